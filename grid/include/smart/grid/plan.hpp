// Contract: a MAPF plan as timed grid cells per robot, independent of its file format.
// Times are plan times in MAPF timesteps (one step = one move or wait in the planner's model);
// they strictly increase along a path and may be non-integer (continuous-time plans). A robot
// is at steps[k].cell from steps[k].time until it starts moving to steps[k+1] at that time, and
// after its last step it stays at its goal for good.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "smart/grid/grid.hpp"

namespace smart::grid {

enum class AxisOrder { kXY, kRowCol };
enum class PlanFormat { kAuto, kSmart, kLacam, kYaml };

std::string to_string(AxisOrder a);
std::string to_string(PlanFormat f);

struct PathStep {
  Cell cell;
  double time = 0;  // plan timesteps
  int line = 0;     // source line, for messages
};

struct RobotPath {
  int robot = -1;
  int line = 0;
  std::vector<PathStep> steps;
};

struct Plan {
  std::string source;
  PlanFormat format = PlanFormat::kAuto;
  AxisOrder axis = AxisOrder::kXY;
  bool timed = false;            // times came from the file (else: step index)
  std::vector<RobotPath> paths;  // paths[i].robot == i after parsing
};

struct PlanStats {
  std::size_t robots = 0;
  double soc = 0;       // sum over robots of the arrival time (trailing waits are free)
  double makespan = 0;  // latest arrival time
  std::size_t moves = 0;
  std::size_t waits = 0;
};

// Arrival time: when the robot last changed cell (0 for a robot that never moves).
double arrival_time(const RobotPath& path);
PlanStats plan_stats(const Plan& plan);

}  // namespace smart::grid
