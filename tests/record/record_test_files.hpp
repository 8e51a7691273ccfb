// Test support for record/: a fresh folder per test (named after it and the run's seed), a
// file's bytes, and a two-robot corridor instance on disk.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "smart/monitor/instance.hpp"

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

// A 4x1 corridor in `dir` (m.map, m.scen: robot 0 from (1,0) to (2,0), robot 1 from (0,0) to
// (1,0)) with `plan` (SMART format, x y) as p.txt, loaded as `smart run` would.
inline monitor::Instance corridor_instance(const std::filesystem::path& dir,
                                           const std::string& plan) {
  std::ofstream(dir / "m.map") << "type octile\nheight 1\nwidth 4\nmap\n....\n";
  std::ofstream(dir / "m.scen")
      << "version 1\n0\tm.map\t4\t1\t1\t0\t2\t0\t1\n0\tm.map\t4\t1\t0\t0\t1\t0\t1\n";
  std::ofstream(dir / "p.txt") << plan;
  monitor::InstanceOptions io;
  io.map = dir / "m.map";
  io.scen = dir / "m.scen";
  io.plan = dir / "p.txt";
  io.agents = 2;
  io.read.axis = grid::AxisOrder::kXY;
  return monitor::load_instance(io);
}

}  // namespace smart::record::test
