// Regression tests from fuzzing the readers' file edge: a directory given as a file got a parse
// error, and `--plan /dev/zero` read without bound (a bare std::bad_alloc).
#include "smart/grid/text_file.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "smart/grid/problem.hpp"

namespace smart::grid {
namespace {

using ::testing::HasSubstr;

std::string file_error_of(const std::filesystem::path& p) {
  try {
    read_text_file(p, "plan");
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(TextFile, ADirectoryIsNamedAsSuch) {
  EXPECT_THAT(file_error_of(std::filesystem::temp_directory_path()),
              HasSubstr("is a directory, not a plan file"));
}

TEST(TextFile, AnEndlessDeviceIsRefusedAtTheLimit) {
  EXPECT_THAT(file_error_of("/dev/zero"), HasSubstr("the plan file is larger than 256 MiB"));
}

}  // namespace
}  // namespace smart::grid
