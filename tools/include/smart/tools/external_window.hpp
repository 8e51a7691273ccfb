// Contract: one window asked of an external planner (a pipe, tools/pipe_planner.hpp, or DDS,
// tools/dds_planner.hpp), the same way for both: timed on the steady clock; a refusal worded
// "<flag> window N refused: <why>" and logged once (a planner already gone is not logged again).
#pragma once

#include <spdlog/spdlog.h>

#include <chrono>
#include <cstdint>
#include <string>
#include <utility>

#include "smart/lifelong/window_planner.hpp"

namespace smart::tools {

// exchange(out) asks for the window and answers why not ("" when out.paths is the window);
// `gone`: why the planner answers no more ("" while it may).
template <class Exchange>
lifelong::PlannedWindow external_window(const std::string& flag, uint64_t window,
                                        std::string heuristic, const std::string& gone,
                                        Exchange&& exchange) {
  lifelong::PlannedWindow out;
  out.heuristic = std::move(heuristic);
  const auto t0 = std::chrono::steady_clock::now();
  const bool was_gone = !gone.empty();  // `gone` may be set by this very exchange: said then
  out.error = was_gone ? gone : exchange(out);
  out.wall_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  if (!out.error.empty()) {
    out.paths.clear();
    out.error = flag + " window " + std::to_string(window) + " refused: " + out.error;
    if (!was_gone) spdlog::warn("{}", out.error);
  }
  return out;
}

}  // namespace smart::tools
