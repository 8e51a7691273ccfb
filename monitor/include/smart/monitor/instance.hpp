// Contract: loads and checks a whole MAPF instance: map + scenario + plan files -> validated plan,
// actions and ADG. This is the monitor's file edge (it reads files); everything it calls is
// pure. `agents` = 0 takes as many robots as the plan has; N > 0 takes the first N robots of the
// plan and the first N agents of the scenario. `footprint` is the robots' (monitor/adg.hpp). Any
// problem, in any file, throws InputError listing every problem found at that stage.
#pragma once

#include <filesystem>

#include "smart/monitor/action_builder.hpp"
#include "smart/monitor/adg.hpp"
#include "smart/monitor/plan_reader.hpp"
#include "smart/monitor/vocabulary.hpp"

namespace smart::monitor {

struct InstanceOptions {
  std::filesystem::path map;
  std::filesystem::path scen;
  std::filesystem::path plan;
  std::size_t agents = 0;
  PlanReadOptions read;
  Heading initial_heading = Heading::kEast;
  Footprint footprint = Footprint::kHalfCells;  // footprint_for() the robots and cells
};

struct InstanceTimings {
  double read_ms = 0;
  double validate_ms = 0;
  double actions_ms = 0;
  double adg_ms = 0;
  double acyclic_ms = 0;
};

struct Instance {
  Grid grid;
  Scenario scen;
  Plan plan;
  PlanStats stats;
  ActionPlan actions;
  Adg adg;
  InstanceTimings timings;
};

Instance load_instance(const InstanceOptions& options);

}  // namespace smart::monitor
