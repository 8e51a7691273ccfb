#include "smart/lifelong/window_planner.hpp"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <utility>

#include "smart/planning/guide_paths.hpp"

namespace smart::lifelong {

namespace {
std::size_t budget_bytes(const BuiltinPlannerOptions& o) {
  return static_cast<std::size_t>(o.distance_budget_mb * 1048576.0);
}

std::unique_ptr<planning::GoalHeuristic> make_heuristic(const grid::Grid& grid,
                                                        const BuiltinPlannerOptions& o,
                                                        planning::DistanceCache& tables) {
  if (planning::choose_heuristic(o.heuristic, grid, o.robots, budget_bytes(o)) ==
      planning::HeuristicKind::kTables) {
    return std::make_unique<planning::TableHeuristic>(tables);
  }
  return std::make_unique<planning::GuidePaths>(grid);
}
// Every robot's current goal and a quarter more for the goals that come back soon: the cache
// fills in the run's first minutes and then stays (a table per goal cell ever seen would grow
// for hours on a warehouse); none given: the budget alone bounds it.
std::size_t tables_for(std::size_t robots) {
  return robots == 0 ? SIZE_MAX : robots + robots / 4 + 16;
}

}  // namespace

BuiltinPlanner::BuiltinPlanner(const grid::Grid& grid, const BuiltinPlannerOptions& options,
                               std::function<double()> wall_ms)
    : wall_ms_(std::move(wall_ms)),
      distances_(grid, budget_bytes(options), tables_for(options.robots)),
      heuristic_(make_heuristic(grid, options, distances_)),
      pibt_(grid, *heuristic_, options.seed),
      lns_passes_(options.lns_passes),
      lns_(grid, distances_,
           planning::WindowLnsOptions{.passes = std::max(1, options.lns_passes)}) {}

void BuiltinPlanner::submit(planning::WindowRequest request) {
  PlannedWindow out;
  const double w0 = wall_ms_ ? wall_ms_() : 0;
  try {
    auto window = pibt_.plan(request);
    if (lns_passes_ > 0) lns_.improve(request, window);
    out.paths = std::move(window.paths);
  } catch (const std::invalid_argument& e) {
    out.error = e.what();
  }
  out.wall_ms = wall_ms_ ? wall_ms_() - w0 : 0;
  out.distance_tables = distances_.tables();
  out.heuristic = heuristic_->name();
  out.heuristic_mb = static_cast<double>(heuristic_->memory_bytes()) / 1048576.0;
  answer_ = std::move(out);
}

std::optional<PlannedWindow> BuiltinPlanner::poll() { return std::exchange(answer_, std::nullopt); }

FallbackPlanner::FallbackPlanner(std::unique_ptr<WindowPlanner> first,
                                 std::unique_ptr<WindowPlanner> second)
    : first_(std::move(first)), second_(std::move(second)) {}

void FallbackPlanner::submit(planning::WindowRequest request) {
  first_->submit(request);
  auto first = first_->poll();
  if (!first) throw std::logic_error("FallbackPlanner: the first planner must answer in submit()");
  if (first->error.empty()) {
    answer_ = std::move(first);
    return;
  }
  second_->submit(std::move(request));
  answer_ = second_->poll();
  if (!answer_)
    throw std::logic_error("FallbackPlanner: the second planner must answer in submit()");
  answer_->replaced = first->error;
  answer_->wall_ms += first->wall_ms;
}

std::optional<PlannedWindow> FallbackPlanner::poll() {
  return std::exchange(answer_, std::nullopt);
}

ThreadedPlanner::ThreadedPlanner(std::unique_ptr<WindowPlanner> inner) : inner_(std::move(inner)) {}

ThreadedPlanner::~ThreadedPlanner() {
  if (answer_.valid()) answer_.wait();
}

void ThreadedPlanner::submit(planning::WindowRequest request) {
  if (answer_.valid()) {
    throw std::logic_error("ThreadedPlanner: a request is still being planned; poll() it first");
  }
  answer_ = std::async(std::launch::async, [this, r = std::move(request)]() mutable {
    inner_->submit(std::move(r));
    auto out = inner_->poll();
    if (!out) throw std::logic_error("ThreadedPlanner: the inner planner must answer in submit()");
    return std::move(*out);
  });
}

std::optional<PlannedWindow> ThreadedPlanner::poll() {
  if (!answer_.valid() || answer_.wait_for(std::chrono::seconds(0)) != std::future_status::ready) {
    return std::nullopt;
  }
  try {
    return answer_.get();
  } catch (const std::exception& e) {
    PlannedWindow failed;
    failed.error = std::string("the planner failed: ") + e.what();
    return failed;
  }
}

}  // namespace smart::lifelong
