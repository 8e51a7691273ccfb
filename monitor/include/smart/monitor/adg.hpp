// Contract: the Action Dependency Graph (Hönig et al. 2019; SMART §IV-B).
// Nodes are the actions of an ActionPlan (node id = offset[robot] + seq).
// - Type-1 edges: each robot's action k -> k+1 (implicit, not stored).
// - Type-2 edges: at each location L (cell or edge midpoint), the robots' occupancy intervals
//   sorted by plan arrival time; for consecutive intervals of different robots i then j, the
//   action by which i leaves L -> the action by which j enters L. This is the transitive
//   reduction of the all-pairs rule (every earlier visitor -> every later one) and costs
//   O(A log A) instead of O(A^2); stats.type2_all_pairs counts what the full rule would add.
// build_adg() reports, as Problems, a later visitor at a location where a robot is parked for
// good and two robots starting at one location (invalid plans). check_acyclic() runs Kahn's
// algorithm iteratively and on a cycle names the robots and locations on it.
#pragma once

#include <cstdint>
#include <vector>

#include "smart/monitor/action_builder.hpp"
#include "smart/monitor/vocabulary.hpp"

namespace smart::monitor {

struct AdgStats {
  std::size_t nodes = 0;
  std::size_t type1 = 0;
  std::size_t type2 = 0;
  std::size_t type2_all_pairs = 0;
  std::size_t moves = 0;
  std::size_t rotations = 0;
  std::size_t locations = 0;  // distinct locations visited
};

struct Adg {
  // Type-2 edges in compressed sparse rows, both directions.
  std::vector<uint32_t> out_begin;  // nodes + 1
  std::vector<uint32_t> out;
  std::vector<uint32_t> in_begin;  // nodes + 1
  std::vector<uint32_t> in;
  AdgStats stats;

  std::size_t nodes() const { return out_begin.empty() ? 0 : out_begin.size() - 1; }
};

// `source` names the plan in Problems. Problems found are appended to `problems`.
Adg build_adg(const ActionPlan& actions, const Grid& grid, const std::string& source,
              std::vector<Problem>& problems);

std::vector<Problem> check_acyclic(const Adg& adg, const ActionPlan& actions,
                                   const std::string& source);

}  // namespace smart::monitor
