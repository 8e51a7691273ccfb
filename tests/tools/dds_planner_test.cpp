// tools/dds_planner.hpp: the monitor's end of planning over DDS against real PlannerNodes (real
// DDS, loopback, its own domain): no planner in time, the choice of one and the refusal of a
// second, every reason a window is refused, a stranger's forged reply, a planner that leaves.
#include "smart/tools/dds_planner.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <future>
#include <set>
#include <thread>

#include "support/dds_test_support.hpp"
#include "support/fake_planners.hpp"

namespace smart::tools {
namespace {

using namespace std::chrono_literals;
using test::Served;
using test::stay;
using ::testing::HasSubstr;

const dds::QosProfile& lan() {
  static const auto qos = dds::find_qos_profile("lan");
  return qos;
}

planning::WindowRequest request(grid::Cell a, grid::Cell b, double time_s) {
  planning::WindowRequest r;
  r.start = {a, b};
  r.goals = {{}, {}};
  r.steps = 3;
  r.time_s = time_s;
  return r;
}

DdsPlannerOptions options(double timeout_s) {
  DdsPlannerOptions o;
  o.wait_s = 30;
  o.settle_s = 0.5;
  o.timeout_s = timeout_s;
  return o;
}

lifelong::PlannedWindow plan(DdsPlanner& planner, planning::WindowRequest r) {
  planner.submit(std::move(r));
  auto out = planner.poll();
  EXPECT_TRUE(out.has_value()) << "submit() answers before it returns";
  return out ? *out : lifelong::PlannedWindow{};
}

// Waits until the system clock's millisecond is past `ms` (an announcement's start time).
void after_ms(uint64_t ms) {
  while (static_cast<uint64_t>(std::chrono::duration_cast<std::chrono::milliseconds>(
                                   std::chrono::system_clock::now().time_since_epoch())
                                   .count()) <= ms) {
    std::this_thread::yield();
  }
}

TEST(DdsPlanner, WithoutAPlannerInTimeTheRunIsToldHowToStartOne) {
  dds::Domain domain(test::kDdsPlanner, test::loopback());
  dds::Participant p(domain, "nobody");
  const auto g = test::open_grid_5x4();
  auto o = options(1);
  o.wait_s = 0.3;
  try {
    DdsPlanner planner(p, lan(), g, 2, 3, o);
    FAIL() << "no planner was there";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), HasSubstr("no planner announced itself on run 'nobody', domain " +
                                    std::to_string(test::kDdsPlanner) + " within 0.3 s"));
    EXPECT_THAT(e.what(), HasSubstr("smart planner --domain " + std::to_string(test::kDdsPlanner) +
                                    " --run nobody"));
  }
}

// As a second monitor is refused: the earliest planner plans the run, a later one of the same
// run refuses to and says which planner does; the chosen one serves until the run ends.
TEST(DdsPlanner, TheEarliestPlannerPlansTheRunAndASecondIsRefused) {
  dds::Domain domain(test::kDdsPlannerEarliest, test::loopback());
  const auto g = test::open_grid_5x4();
  auto first = std::make_unique<Served>(domain, "dp", stay, "first");
  after_ms(first->node.info().started_ms);
  Served second(domain, "dp", stay, "second");
  dds::Participant p(domain, "dp");
  {  // Both announcements known to p first (an event, not a guessed wait): the planner's own
     // reader, made on p after, matches both writers at once (discovery under load is slow).
    dds::WireReader<smart_msg_PlannerInfo> probe(p, lan());
    std::set<uint64_t> heard;
    const auto deadline = std::chrono::steady_clock::now() + 60s;
    while (heard.size() < 2) {
      probe.take_each([&](const smart_msg_PlannerInfo& m) { heard.insert(m.planner_id); });
      ASSERT_LT(std::chrono::steady_clock::now(), deadline) << "the planners were never heard";
      std::this_thread::sleep_for(5ms);
    }
  }
  auto o = options(30);
  o.settle_s = 1;
  auto planner = std::make_unique<DdsPlanner>(p, lan(), g, 2, 3, o);
  EXPECT_EQ(planner->chosen().planner_id, first->node.info().planner_id);
  EXPECT_STREQ(planner->chosen().name, "first");
  ASSERT_EQ(second.outcome.wait_for(30s), std::future_status::ready);
  const auto refused = second.outcome.get();
  EXPECT_EQ(refused.end, PlannerNode::End::kRefused);
  EXPECT_THAT(refused.detail,
              HasSubstr("refused: run 'dp' on domain " + std::to_string(test::kDdsPlannerEarliest) +
                        " is planned by planner 'first' (pid "));
  const auto r = request({0, 0}, {4, 3}, 1);
  const auto w = plan(*planner, r);
  EXPECT_EQ(w.error, "");
  EXPECT_EQ(w.paths, stay(r).paths);
  EXPECT_EQ(w.heuristic, "external: first");
  planner.reset();  // the run ends
  ASSERT_EQ(first->outcome.wait_for(30s), std::future_status::ready);
  const auto served = first->outcome.get();
  EXPECT_EQ(served.end, PlannerNode::End::kRunOver);
  EXPECT_EQ(served.windows, 1u);
}

// What the fake planner answers, by the request's time: each a reason to refuse the window.
lifelong::PlannedWindow bad_window(const planning::WindowRequest& r) {
  auto w = stay(r);
  switch (static_cast<int>(r.time_s)) {
    case 1:
      w.paths[1][0] = {3, 3};  // not its cut cell (4,3)
      break;
    case 2:
      w.paths[1][1] = w.paths[1][2] = w.paths[1][3] = {0, 0};  // onto robot 0
      break;
    case 3:
      w.paths[0][1] = {2, 0};  // two cells in one step
      break;
    case 4:
      w.paths[1][1] = {5, 3};  // off the 5x4 map
      break;
    case 5:
      for (auto& path : w.paths) path.pop_back();  // a step short
      break;
    case 6:
      w.paths.clear();
      w.error = "goal walled in";
      break;
    default:
      break;
  }
  return w;
}

TEST(DdsPlanner, EveryBadWindowIsRefusedWithTheReason) {
  dds::Domain domain(test::kDdsPlannerBadWindows, test::loopback());
  const auto g = test::open_grid_5x4();
  Served served(domain, "bad", bad_window);
  dds::Participant p(domain, "bad");
  DdsPlanner planner(p, lan(), g, 2, 3, options(30));
  const std::vector<std::pair<planning::WindowRequest, std::string>> cases{
      {request({0, 0}, {4, 3}, 1), "robot 1 starts at (x=3,y=3), not at its cut cell (x=4,y=3)"},
      {request({0, 0}, {1, 0}, 2), "robots 0 and 1 collide at (x=0,y=0) at step 1"},
      {request({0, 0}, {4, 3}, 3), "jumps from (x=0,y=0) to (x=2,y=0)"},
      {request({0, 0}, {4, 3}, 4), "leaves the map at (x=5,y=3)"},
      {request({0, 0}, {4, 3}, 5), "malformed: steps 2 where the request asked for 3"},
      {request({0, 0}, {4, 3}, 6), "the planner's error: goal walled in"},
  };
  uint64_t window = 0;
  for (const auto& [r, why] : cases) {
    const auto w = plan(planner, r);
    EXPECT_THAT(w.error,
                HasSubstr("--planner external window " + std::to_string(++window) + " refused: "));
    EXPECT_THAT(w.error, HasSubstr(why));
    EXPECT_TRUE(w.paths.empty());
  }
  const auto ok = plan(planner, request({0, 0}, {4, 3}, 7));  // and then a good one is taken
  EXPECT_EQ(ok.error, "");
  EXPECT_EQ(ok.paths.size(), 2u);
}

TEST(DdsPlanner, ALateReplyIsRefusedAndTheRunGoesOn) {
  dds::Domain domain(test::kDdsPlannerLate, test::loopback());
  const auto g = test::open_grid_5x4();
  std::promise<void> release;
  auto released = release.get_future().share();
  Served served(domain, "late", [released](const planning::WindowRequest& r) {
    released.wait_for(60s);  // answers once the test lets it (bounded: a failed test ends)
    return stay(r);
  });
  dds::Participant p(domain, "late");
  DdsPlanner planner(p, lan(), g, 2, 3, options(0.3));
  const auto w = plan(planner, request({0, 0}, {4, 3}, 1));
  EXPECT_THAT(w.error, HasSubstr("window 1 refused: late: no reply within 0.3 s "
                                 "(--planner-timeout-s); robots stop at the cut"));
  EXPECT_GE(w.wall_ms, 300);
  release.set_value();
}

// Issue 25's rule for planners: a participant that is not the chosen planner, though it reads
// the request and answers it first with the chosen planner's id, is filtered out before the
// reader (it can neither be taken nor displace the real reply) and counted.
TEST(DdsPlanner, AStrangersForgedReplyIsFilteredOutAndTheChosenPlannersIsTaken) {
  dds::Domain domain(test::kDdsPlannerForged, test::loopback());
  const auto g = test::open_grid_5x4();
  std::promise<void> release;
  auto released = release.get_future().share();
  Served served(domain, "forged", [released](const planning::WindowRequest& r) {
    released.wait_for(60s);
    return stay(r);
  });
  dds::Participant stranger(domain, "forged");
  dds::WireReader<smart_msg_PlanRequest> overheard(stranger, lan());
  dds::WireWriter<smart_msg_PlanReply> forger(stranger, lan());
  dds::Participant p(domain, "forged");
  DdsPlanner planner(p, lan(), g, 2, 3, options(30));
  ASSERT_TRUE(forger.wait_for_readers(1, 30s));  // the monitor's reply reader
  const auto r = request({0, 0}, {4, 3}, 1);
  auto answer = std::async(std::launch::async, [&] { return plan(planner, r); });
  std::optional<std::pair<uint64_t, uint64_t>> asked;  // run id, window
  const auto deadline = std::chrono::steady_clock::now() + 30s;
  while (!asked) {
    overheard.take_each([&](const smart_msg_PlanRequest& m) { asked.emplace(m.run_id, m.window); });
    ASSERT_LT(std::chrono::steady_clock::now(), deadline) << "the request was never overheard";
    std::this_thread::sleep_for(2ms);
  }
  auto forged_paths = stay(r).paths;
  forged_paths[0][1] = forged_paths[0][2] = forged_paths[0][3] = {1, 0};
  wire::PlanReplyBuffer forged;
  forged.set_paths(planner.chosen().planner_id, asked->first, asked->second, forged_paths);
  forger.write(forged.view());
  ASSERT_TRUE(forger.wait_for_acks(30s));  // in the monitor's hands before the real one
  release.set_value();
  ASSERT_EQ(answer.wait_for(60s), std::future_status::ready);
  const auto w = answer.get();
  EXPECT_EQ(w.error, "");
  EXPECT_EQ(w.paths, stay(r).paths);
  EXPECT_EQ(planner.rejections().counts().at(smart_msg_TOPIC_PLAN_REPLY).size(), 1u);
  EXPECT_EQ(planner.rejections().total(), 1u);
}

TEST(DdsPlanner, APlannerThatLeavesHasEveryLaterWindowRefusedAtOnce) {
  dds::Domain domain(test::kDdsPlannerLeaves, test::loopback());
  const auto g = test::open_grid_5x4();
  auto served = std::make_unique<Served>(domain, "gone", stay, "leaver");
  dds::Participant p(domain, "gone");
  DdsPlanner planner(p, lan(), g, 2, 3, options(30));
  EXPECT_EQ(plan(planner, request({0, 0}, {4, 3}, 1)).error, "");
  served.reset();  // the planner process ends
  const auto w = plan(planner, request({0, 0}, {4, 3}, 2));
  EXPECT_THAT(w.error, HasSubstr("window 2 refused: planner 'leaver' (pid "));
  EXPECT_THAT(w.error, HasSubstr("left the run; no more windows from it"));
  const auto again = plan(planner, request({0, 0}, {4, 3}, 3));
  EXPECT_THAT(again.error, HasSubstr("window 3 refused: planner 'leaver'"));
  EXPECT_LT(again.wall_ms, 1000);  // at once, not after the timeout
}

}  // namespace
}  // namespace smart::tools
