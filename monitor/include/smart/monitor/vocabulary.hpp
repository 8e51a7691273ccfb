// Contract: the grid layer's vocabulary (grid/: cells, headings, problems, MovingAI readers, the
// Plan type), named unqualified throughout the monitor core, which is built on it.
#pragma once

#include "smart/grid/action.hpp"
#include "smart/grid/grid.hpp"
#include "smart/grid/map_reader.hpp"
#include "smart/grid/plan.hpp"
#include "smart/grid/problem.hpp"
#include "smart/grid/scen_reader.hpp"
#include "smart/grid/text.hpp"
#include "smart/grid/text_file.hpp"

namespace smart::monitor {

using grid::Action;
using grid::ActionPlan;
using grid::ActionType;
using grid::arrival_time;
using grid::AxisOrder;
using grid::Cell;
using grid::check_scen_against_map;
using grid::excerpt;
using grid::Grid;
using grid::HalfCell;
using grid::Heading;
using grid::heading_of_step;
using grid::InputError;
using grid::parse_double;
using grid::parse_heading;
using grid::parse_int;
using grid::parse_map;
using grid::parse_scen;
using grid::PathStep;
using grid::Plan;
using grid::plan_stats;
using grid::PlanFormat;
using grid::PlanStats;
using grid::Problem;
using grid::read_text_file;
using grid::RobotPath;
using grid::ScenAgent;
using grid::Scenario;
using grid::split;
using grid::split_lines;
using grid::split_whitespace;
using grid::throw_if_any;
using grid::to_string;
using grid::trim;
using grid::WorldPoint;
using grid::yaw_rad;

}  // namespace smart::monitor
