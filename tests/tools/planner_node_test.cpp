// tools/planner_node.hpp: the planner's end of planning over DDS, driven by a hand-written
// monitor side (real DDS, loopback, its own domain): it announces itself, plans the requests of
// the run that names it, answers a bad request with the reason, refuses a run that names another
// planner, and ends when the run's problem goes.
#include "smart/tools/planner_node.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <future>
#include <thread>

#include "support/dds_test_support.hpp"
#include "support/fake_planners.hpp"

namespace smart::tools {
namespace {

using namespace std::chrono_literals;
using test::FakePlanner;
using test::Served;
using test::stay;
using ::testing::HasSubstr;

planning::WindowRequest request_of_two() {
  planning::WindowRequest r;
  r.start = {{0, 0}, {4, 3}};
  r.goals = {{{2, 0}}, {}};
  r.heading = {grid::Heading::kEast, grid::Heading::kNorth};
  r.steps = 3;
  r.time_s = 4;
  return r;
}

// The monitor's side by hand.
struct MonitorSide {
  explicit MonitorSide(dds::Domain& domain)
      : p(domain, "pn"), problem(p, qos), request(p, qos), reply(p, qos), info(p, qos) {}
  dds::Participant p;
  dds::QosProfile qos = dds::find_qos_profile("lan");
  dds::WireWriter<smart_msg_PlanProblem> problem;
  dds::WireWriter<smart_msg_PlanRequest> request;
  dds::WireReader<smart_msg_PlanReply> reply;
  dds::WireReader<smart_msg_PlannerInfo> info;

  // The first announcement heard.
  smart_msg_PlannerInfo announcement() {
    const auto deadline = std::chrono::steady_clock::now() + 30s;
    for (;;) {
      std::optional<smart_msg_PlannerInfo> heard;
      info.take_each([&](const smart_msg_PlannerInfo& m) { heard = m; });
      if (heard) return *heard;
      EXPECT_LT(std::chrono::steady_clock::now(), deadline) << "no planner announced itself";
      if (std::chrono::steady_clock::now() >= deadline) return {};
      std::this_thread::sleep_for(2ms);
    }
  }
  // The reply to `window`, checked and converted by the test.
  std::pair<std::string, std::vector<std::vector<grid::Cell>>> reply_to(uint64_t window) {
    const auto deadline = std::chrono::steady_clock::now() + 30s;
    for (;;) {
      std::optional<std::pair<std::string, std::vector<std::vector<grid::Cell>>>> got;
      reply.take_each([&](const smart_msg_PlanReply& r) {
        if (r.window == window) got.emplace(r.error, wire::paths_of(r));
      });
      if (got) return *got;
      if (std::chrono::steady_clock::now() >= deadline) return {"no reply", {}};
      std::this_thread::sleep_for(2ms);
    }
  }
};

TEST(PlannerNode, AnnouncesItselfThenPlansTheRequestsOfTheRunThatNamesIt) {
  dds::Domain domain(test::kPlannerNode, test::loopback());
  MonitorSide monitor(domain);
  Served served(domain, "pn", stay);
  const auto me = monitor.announcement();
  EXPECT_EQ(me.planner_id, served.node.info().planner_id);
  EXPECT_STREQ(me.name, "fake");
  EXPECT_EQ(me.pid, static_cast<int32_t>(getpid()));
  wire::PlanProblemBuffer problem(11, me, test::open_grid_5x4(), 2, 3);
  monitor.problem.write(problem.view());
  wire::PlanRequestBuffer request;
  for (uint64_t window = 1; window <= 2; ++window) {
    request.set(11, me.planner_id, window, 0.1, request_of_two());
    monitor.request.write(request.view());
    const auto [error, paths] = monitor.reply_to(window);
    EXPECT_EQ(error, "");
    EXPECT_EQ(paths, stay(request_of_two()).paths);
  }
}

TEST(PlannerNode, ABadRequestOrThePlannersFailureIsAnsweredWithTheReason) {
  dds::Domain domain(test::kPlannerNodeBadRequest, test::loopback());
  MonitorSide monitor(domain);
  Served served(domain, "pn", [](const planning::WindowRequest& r) {
    lifelong::PlannedWindow w;
    if (r.time_s > 100) w.error = "goal walled in";
    return r.time_s > 100 ? w : stay(r);
  });
  const auto me = monitor.announcement();
  wire::PlanProblemBuffer problem(11, me, test::open_grid_5x4(), 2, 3);
  monitor.problem.write(problem.view());
  auto bad = request_of_two();
  bad.start[1] = {5, 3};  // off the 5x4 map
  wire::PlanRequestBuffer request;
  request.set(11, me.planner_id, 1, 0.1, bad);
  monitor.request.write(request.view());
  auto [error, paths] = monitor.reply_to(1);
  EXPECT_EQ(error, "request refused by the planner: robot 1: start (x=5,y=3) is off the 5x4 map");
  EXPECT_TRUE(paths.empty());
  auto late = request_of_two();
  late.time_s = 200;
  request.set(11, me.planner_id, 2, 0.1, late);
  monitor.request.write(request.view());
  std::tie(error, paths) = monitor.reply_to(2);
  EXPECT_EQ(error, "goal walled in");
}

TEST(PlannerNode, ARunThatNamesAnotherPlannerIsRefusedNamingIt) {
  dds::Domain domain(test::kPlannerNodeOtherPlanner, test::loopback());
  MonitorSide monitor(domain);
  Served served(domain, "pn", stay);
  (void)monitor.announcement();
  smart_msg_PlannerInfo other{};
  other.planner_id = served.node.info().planner_id + 2;
  other.pid = 77;
  other.started_ms = 1;
  std::snprintf(other.name, sizeof(other.name), "lacam");
  std::snprintf(other.host, sizeof(other.host), "lab-2");
  wire::PlanProblemBuffer problem(11, other, test::open_grid_5x4(), 2, 3);
  monitor.problem.write(problem.view());
  ASSERT_EQ(served.outcome.wait_for(30s), std::future_status::ready);
  const auto out = served.outcome.get();
  EXPECT_EQ(out.end, PlannerNode::End::kRefused);
  EXPECT_EQ(out.detail,
            "refused: run 'pn' on domain " + std::to_string(test::kPlannerNodeOtherPlanner) +
                " is planned by planner 'lacam' (pid 77 on lab-2); stop that planner, or start "
                "this one with another --run");
}

TEST(PlannerNode, ServingEndsWhenTheRunsProblemGoes) {
  dds::Domain domain(test::kPlannerNodeProblemGoes, test::loopback());
  auto monitor = std::make_unique<MonitorSide>(domain);
  Served served(domain, "pn", stay);
  const auto me = monitor->announcement();
  wire::PlanProblemBuffer problem(11, me, test::open_grid_5x4(), 2, 3);
  monitor->problem.write(problem.view());
  wire::PlanRequestBuffer request;
  request.set(11, me.planner_id, 1, 0.1, request_of_two());
  monitor->request.write(request.view());
  EXPECT_EQ(monitor->reply_to(1).first, "");
  monitor.reset();  // the monitor leaves: its problem is disposed
  ASSERT_EQ(served.outcome.wait_for(30s), std::future_status::ready);
  const auto out = served.outcome.get();
  EXPECT_EQ(out.end, PlannerNode::End::kRunOver);
  EXPECT_EQ(out.windows, 1u);
}

}  // namespace
}  // namespace smart::tools
