// Lifelong planners for the tests of planning over DDS: a WindowPlanner that answers with a
// function of the request, and a PlannerNode serving on its own participant and thread.
#pragma once

#include <gtest/gtest.h>

#include <atomic>
#include <functional>
#include <future>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "smart/grid/grid.hpp"
#include "smart/lifelong/window_planner.hpp"
#include "smart/tools/planner_node.hpp"

namespace smart::test {

// A planner that answers with `answer(request)`.
class FakePlanner final : public lifelong::WindowPlanner {
 public:
  using Answer = std::function<lifelong::PlannedWindow(const planning::WindowRequest&)>;
  explicit FakePlanner(Answer answer) : answer_(std::move(answer)) {}
  void submit(planning::WindowRequest request) override { out_ = answer_(request); }
  std::optional<lifelong::PlannedWindow> poll() override { return std::exchange(out_, {}); }

 private:
  Answer answer_;
  std::optional<lifelong::PlannedWindow> out_;
};

// A 5 x 4 map without obstacles.
inline grid::Grid open_grid_5x4() { return grid::Grid(5, 4, std::vector<uint8_t>(20, 0)); }

// Every robot stays where it is.
inline lifelong::PlannedWindow stay(const planning::WindowRequest& r) {
  lifelong::PlannedWindow w;
  for (const auto c : r.start) w.paths.emplace_back(static_cast<std::size_t>(r.steps) + 1, c);
  return w;
}

// A PlannerNode named `name` in run `run`, serving from construction until destruction (or
// until serve() ends: `outcome`).
struct Served {
  Served(dds::Domain& domain, const std::string& run, FakePlanner::Answer answer,
         const std::string& name = "fake")
      : p(domain, run),
        node(p, dds::find_qos_profile("lan"), name,
             [answer](const grid::Grid&, std::size_t) {
               return std::make_unique<FakePlanner>(answer);
             }),
        outcome(std::async(std::launch::async, [this] { return node.serve(stop); })) {}
  ~Served() {
    stop = true;
    if (outcome.valid()) outcome.wait();
  }
  Served(const Served&) = delete;
  Served& operator=(const Served&) = delete;
  dds::Participant p;
  tools::PlannerNode node;
  std::atomic<bool> stop{false};
  std::future<tools::PlannerNode::Outcome> outcome;
};

}  // namespace smart::test
