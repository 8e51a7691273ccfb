// Test support for record/: a fresh folder per test (named after it and the run's seed) and a
// file's bytes.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace smart::record::test {

inline std::filesystem::path fresh_test_dir(const std::string& prefix) {
  const auto* unit = ::testing::UnitTest::GetInstance();
  auto dir =
      std::filesystem::temp_directory_path() /
      (prefix + std::to_string(unit->random_seed()) + "_" + unit->current_test_info()->name());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace smart::record::test
