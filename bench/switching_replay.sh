#!/bin/bash
# The cost of switching passing orders counted, not sampled (issue 29, docs/execution.md, "A
# chain's cone walked when it is compared"): the replay bench's whole run of dispatch decisions
# (smart_bench's BM_Execute*: SMART's 1000-robot warehouse plan, a seeded tenth of robots delayed
# each round; bench/adg_bench.cpp) under callgrind with its cache simulation, once with plain
# ADG's tracker and once with each switching execution. Printed for each: the instructions, the
# first-level data-cache misses and the last-level misses of the tracker's progress reports
# (`on_progress`, inclusive: every decision it makes), and an estimate of their cycles, Ir + 10
# L1 misses + 200 LL misses (the Cachegrind manual's "Overview": an L1 miss "around 10 cycles",
# an LL miss "as much as 200"; /usr/share/doc/valgrind/html/cg-manual.html), as a ratio to plain
# ADG's. The same binary gives the same counts on any machine load: what sampling (bench/switching_cost.sh) could not resolve on this VM, whose
# speed drifted by a third within minutes. It measures the tracker alone, in a replay: not the
# monitor's share, which bench/switching_cost.sh samples.
# Usage: bench/switching_replay.sh [OUT_DIR] (SMART_BENCH: the smart_bench binary, default
# build/bin/smart_bench; SMART_BENCHMARKS: the benchmark data; MODES: the benches, space
# separated, default all four). Needs valgrind. About 15-40 s a bench on this machine.
set -euo pipefail
out=${1:-build/switching-replay}
bench_bin=${SMART_BENCH:-build/bin/smart_bench}
export SMART_BENCHMARKS=${SMART_BENCHMARKS:-../shared/benchmarks}
command -v valgrind > /dev/null || {
  echo "switching_replay.sh: valgrind not found; install valgrind" >&2
  exit 2
}
[ -x "$bench_bin" ] || {
  echo "switching_replay.sh: $bench_bin not found; run make build first" >&2
  exit 2
}
mkdir -p "$out"
modes=(ExecutePlainAdg ExecuteSwitchable ExecuteSwitchableOpt ExecuteSwitchableLookahead)
[ -z "${MODES:-}" ] || read -r -a modes <<< "$MODES"
# "Ir D1mr DLmr" of on_progress, inclusive; the tracker's class in the symbol's name.
counts() {
  callgrind_annotate --inclusive=yes --show=Ir,D1mr,DLmr "$1" 2> /dev/null |
    grep -E 'Tracker::on_progress\(' | head -1 |
    awk '{gsub(",", ""); n = 0; for (f = 1; f <= NF && n < 3; f++) if ($f ~ /^[0-9]+$/) v[n++] = $f;
          print v[0], v[1], (n > 2 ? v[2] : 0)}'
}
base=""
printf '%-28s %15s %12s %10s %8s %9s\n' bench instructions L1_misses LL_misses vs_plain switches
for mode in "${modes[@]}"; do
  file="$out/$mode.callgrind"
  valgrind --tool=callgrind --cache-sim=yes --callgrind-out-file="$file" "$bench_bin" \
    --benchmark_filter="^BM_$mode\$" --benchmark_min_time=0.001 > "$out/$mode.out" 2>&1
  read -r ir d1 ll <<< "$(counts "$file")"
  [ -n "${ir:-}" ] || { echo "switching_replay.sh: no on_progress in $file" >&2; exit 1; }
  est=$((ir + 10 * d1 + 200 * ll))
  [ -n "$base" ] || base=$est
  switches=$(grep -o 'switches=[^ ]*' "$out/$mode.out" | head -1 | cut -d= -f2)
  printf '%-28s %15s %12s %10s %8s %9s\n' "$mode" "$ir" "$d1" "$ll" \
    "$(awk -v e="$est" -v b="$base" 'BEGIN {printf "%.2f", e / b}')" "${switches:-?}"
done | tee "$out/counts.txt"
