// Contract: the Action Dependency Graph (Hönig et al. 2019; SMART §IV-B).
// Nodes are the actions of an ActionPlan (node id = offset[robot] + seq).
// - Type-1 edges: each robot's action k -> k+1 (implicit, not stored).
// - Type-2 edges: at each location L, the robots' occupancy intervals
//   sorted by plan arrival time; for consecutive intervals of different robots i then j, the
//   action by which i leaves L -> the action by which j enters L. This is the transitive
//   reduction of the all-pairs rule (every earlier visitor -> every later one) and costs
//   O(A log A) instead of O(A^2); stats.type2_all_pairs counts what the full rule would add.
// What a location is depends on the robots' footprint against the cell (Footprint below).
// build_adg() reports, as Problems, a later visitor at a location where a robot is parked for
// good and two robots starting at one location (invalid plans). check_acyclic() runs Kahn's
// algorithm iteratively and on a cycle names the robots and locations on it.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "smart/monitor/action_builder.hpp"
#include "smart/monitor/results_format.hpp"
#include "smart/monitor/switching.hpp"
#include "smart/monitor/vocabulary.hpp"

namespace smart::monitor {

// Which positions of two robots exclude each other:
// - kHalfCells (SMART §IV-B): cell centres and edge midpoints are separate locations. A robot on
//   an edge midpoint may be half a cell from one on the next cell's centre, so this is safe only
//   for robots no wider than a quarter cell (4·radius <= cell); followers keep half a cell apart.
// - kCells: the locations are cells; a robot on an edge midpoint (or moving to or from one) holds
//   both cells the edge joins. Positions of robots holding disjoint cells are at least one cell
//   apart, so this is safe for robots narrower than half a cell (2·radius < cell), such as
//   JetBots (radius 0.09 m) on the SMART paper's 0.3 m lab grid (§V-B). Followers keep a whole
//   cell apart, and robots that follow each other round a loop deadlock (check_acyclic names it).
enum class Footprint : uint8_t { kHalfCells, kCells };

// The least restrictive footprint that is safe for robots of `radius_m` on cells of `cell_m`;
// nothing when a robot is half a cell wide or more (neighbouring robots would touch).
std::optional<Footprint> footprint_for(double radius_m, double cell_m);
std::string to_string(Footprint f);  // "half cells" or "cells"

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
  Footprint footprint = Footprint::kHalfCells;

  std::size_t nodes() const { return out_begin.empty() ? 0 : out_begin.size() - 1; }
};

// Every location's passing order: the robots' stays there (entered by action `enter`, left by
// `leave`; kNoAction: its start, or never left) in the order build_adg chains them, consecutive
// stays of different robots being its Type-2 edges (leave -> next enter). What switchable
// execution reorders (switchable_tracker.hpp).
inline constexpr uint32_t kNoAction = 0xffffffffu;
struct Stay {
  uint32_t robot = 0;
  uint32_t enter = kNoAction;
  uint32_t leave = kNoAction;
};
struct PassingOrders {
  std::vector<uint32_t> begin;  // per location (half-cell index) + 1: its stays' range
  std::vector<Stay> stays;
};
PassingOrders passing_orders(const ActionPlan& actions, const Grid& grid,
                             Footprint footprint = Footprint::kHalfCells);

// The ADG whose Type-2 edges `orders` give: consecutive stays of different robots at a location,
// leave -> next enter (stays without either are skipped). For passing_orders() these are
// build_adg's edges; after apply_switches(), a switchable run's edges as they ended.
Adg adg_of_orders(const PassingOrders& orders, const ActionPlan& actions, Footprint footprint);

// Replays a switchable run's switches (switchable_tracker.hpp; switches.csv) in order on the
// plan's passing orders: each puts `first`'s stay directly before `second`'s at its location,
// where second's came directly before it: the pair of stays the switch names by their entries
// (PassingSwitch::first_enter, second_enter) or, where it names none (files written before
// those were), the first pair whose `first` stay was not yet entered at the switch time
// (`finish_s` by node, NaN: never finished; empty: the first pair).
// Returns how many switches matched no pair (skipped: e.g. a results folder of another plan).
std::size_t apply_switches(PassingOrders& orders, const std::vector<PassingSwitch>& switches,
                           const std::vector<double>& finish_s = {});

// A switch as a switches.csv row (results_format.hpp SwitchRow): its location in cells of `grid`
// (.5 on an edge midpoint), its stays by the seqs of their entering actions in `actions` (none
// when null: a lifelong run's, whose actions are no fixed plan). And rows back as switches of
// the plan `actions` (apply_switches): a row off the map, or naming a seq the robot does not
// have, matches no pair there.
results::SwitchRow switch_row(const Grid& grid, const ActionPlan* actions, const PassingSwitch& s);
std::vector<PassingSwitch> passing_switches(const Grid& grid, const ActionPlan& actions,
                                            const std::vector<results::SwitchRow>& rows);

// `source` names the plan in Problems. Problems found are appended to `problems`.
Adg build_adg(const ActionPlan& actions, const Grid& grid, const std::string& source,
              std::vector<Problem>& problems, Footprint footprint = Footprint::kHalfCells);

std::vector<Problem> check_acyclic(const Adg& adg, const ActionPlan& actions,
                                   const std::string& source);

}  // namespace smart::monitor
