# ctest `benchmark_data`: the benchmark data the suite reads is where the build was told it is.
# Tests that need a file of it skip without it (naming the folder); this test fails instead, so a
# checkout without the data cannot pass `make test` on skipped tests.
# Usage: cmake -DDIR=<SMART_BENCHMARKS_DIR> -P check_benchmarks.cmake
foreach(sub maps scens smart-examples lorr-2026)
  if(NOT IS_DIRECTORY "${DIR}/${sub}")
    message(FATAL_ERROR
      "benchmark data missing: no folder ${DIR}/${sub}. Put the shared benchmarks beside the "
      "checkout (../shared/benchmarks) or configure with SMART_BENCHMARKS=<folder> in the "
      "environment (cmake -DSMART_BENCHMARKS_DIR=<folder> on an existing build).")
  endif()
endforeach()
message(STATUS "benchmark data: ${DIR}")
