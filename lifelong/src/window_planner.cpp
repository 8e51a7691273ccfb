#include "smart/lifelong/window_planner.hpp"

#include <chrono>
#include <stdexcept>

namespace smart::lifelong {

BuiltinPlanner::BuiltinPlanner(const grid::Grid& grid, double distance_budget_mb, uint64_t seed,
                               std::function<double()> wall_ms)
    : grid_(grid),
      wall_ms_(std::move(wall_ms)),
      distances_(grid, static_cast<std::size_t>(distance_budget_mb * 1048576.0)),
      pibt_(grid, distances_, seed) {}

void BuiltinPlanner::submit(planning::WindowRequest request) {
  PlannedWindow out;
  const double w0 = wall_ms_ ? wall_ms_() : 0;
  try {
    out.paths = pibt_.plan(request).paths;
  } catch (const std::invalid_argument& e) {
    out.error = e.what();
  }
  out.wall_ms = wall_ms_ ? wall_ms_() - w0 : 0;
  out.distance_tables = distances_.tables();
  out.distance_tables_mb = static_cast<double>(distances_.tables()) *
                           static_cast<double>(grid_.width()) *
                           static_cast<double>(grid_.height()) * sizeof(int32_t) / 1048576.0;
  answer_ = std::move(out);
}

std::optional<PlannedWindow> BuiltinPlanner::poll() {
  auto out = std::move(answer_);
  answer_.reset();
  return out;
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
