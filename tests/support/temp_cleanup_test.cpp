// support/temp_cleanup.cpp: what a test process made with temp_file() (a file, a folder with
// files in it) is gone once the process has exited, and stays with SMART_KEEP_TEST_FILES=1.
// The process is this binary run again for the probe test alone.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "smart/common/child_process.hpp"
#include "support/dds_test_support.hpp"

namespace smart::test {
namespace {

using namespace std::chrono_literals;

// Makes a file and a folder with a file in it, and prints their paths (read by the test below,
// which runs it in a process of its own; run with the others it cleans up after itself too).
TEST(TempCleanupProbe, MakesAFileAndAFolder) {
  const auto file = temp_file("cleanup_probe.txt"), dir = temp_file("cleanup_probe_dir");
  std::ofstream(file) << "x";
  std::filesystem::create_directories(dir / "inner");
  std::ofstream(dir / "inner" / "f") << "y";
  ASSERT_TRUE(std::filesystem::exists(file));
  ASSERT_TRUE(std::filesystem::exists(dir / "inner" / "f"));
  std::cout << "PROBE " << file.string() << "\nPROBE " << dir.string() << "\n";
}

// The probe's paths, run with `env` settings (its exit code checked).
std::vector<std::filesystem::path> run_probe(const std::vector<std::string>& env,
                                             const std::string& tag) {
  const auto out = temp_file("cleanup_" + tag + ".out");
  std::vector<std::string> argv{"/usr/bin/env"};
  argv.insert(argv.end(), env.begin(), env.end());
  argv.insert(argv.end(), {common::self_executable().string(),
                           "--gtest_filter=TempCleanupProbe.MakesAFileAndAFolder"});
  common::ChildProcess probe(argv, out);
  const auto rc = probe.wait(60s * kSlowdown);
  EXPECT_EQ(rc, 0);
  std::ifstream in(out);
  std::vector<std::filesystem::path> paths;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("PROBE ", 0) == 0) paths.emplace_back(line.substr(6));
  }
  EXPECT_EQ(paths.size(), 2u);
  return paths;
}

TEST(TempCleanup, WhatATestProcessMadeIsGoneWhenItExitsUnlessKept) {
  for (const auto& p : run_probe({"-u", "SMART_KEEP_TEST_FILES"}, "removed")) {
    EXPECT_FALSE(std::filesystem::exists(p)) << p;
  }
  const auto kept = run_probe({"SMART_KEEP_TEST_FILES=1"}, "kept");
  for (const auto& p : kept) {
    EXPECT_TRUE(std::filesystem::exists(p)) << p;
    std::filesystem::remove_all(p);
  }
}

}  // namespace
}  // namespace smart::test
