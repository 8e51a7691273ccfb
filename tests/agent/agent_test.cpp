#include "smart/agent/agent.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "support/fake_robot.hpp"
#include "support/robot_models.hpp"

namespace smart::agent {
namespace {

constexpr double kStep_s = 0.1;

// Half-moves along +x from x=0: seq k goes from k/2 to (k+1)/2 metres.
std::vector<AgentAction> east_half_moves(uint32_t first, uint32_t last) {
  std::vector<AgentAction> w;
  for (uint32_t s = first; s <= last; ++s) {
    w.push_back({s, ActionKind::kMove, 0.5 * s, 0, 0.5 * (s + 1), 0, 0});
  }
  return w;
}

struct Drive {
  test::FakeRobot robot;
  Agent agent;
  std::vector<int64_t> finished;  // after each step
  std::vector<double> speed;      // commanded forward speed after each step
  explicit Drive(const RobotModel& m)
      : robot(m.wheel_base_m), agent({7, m, kStep_s, 0.5}, robot, robot) {}
  void steps(int n) {
    for (int i = 0; i < n; ++i) {
      agent.step(robot.time());
      robot.advance(kStep_s);
      finished.push_back(agent.finished_seq());
      speed.push_back(to_twist(agent.last_command(), wheel_base_m).linear_mps);
    }
  }
  double wheel_base_m = 0.14;
};

TEST(Agent, MergedRunReportsEveryHalfMoveInOrderWithoutStopping) {
  Drive r(test::footbot_model());
  EXPECT_TRUE(r.agent.activate().ok());
  ASSERT_EQ(r.agent.on_window(1, east_half_moves(0, 5)), ActionQueue::Result::kAccepted);
  r.steps(300);
  ASSERT_EQ(r.agent.finished_seq(), 5);
  EXPECT_NEAR(r.robot.pose().x_m, 3.0, 0.02);
  // Progress only grows, one action at a time or more, and covers every seq.
  for (std::size_t i = 1; i < r.finished.size(); ++i) EXPECT_GE(r.finished[i], r.finished[i - 1]);
  // Between the first and last half-move the robot never stops (one merged run).
  std::size_t first = 0, last = 0;
  for (std::size_t i = 0; i < r.finished.size(); ++i) {
    if (r.finished[i] >= 0 && first == 0) first = i;
    if (r.finished[i] >= 4 && last == 0) last = i;
  }
  ASSERT_GT(last, first);
  for (std::size_t i = first; i <= last; ++i) EXPECT_GT(r.speed[i], 0.05) << "step " << i;
  EXPECT_EQ(r.agent.queue_length(), 0u);
  EXPECT_EQ(r.agent.executing_seq(), -1);
}

// Execution uncertainty: a certain stall holds a robot at rest for stall_s before its action;
// a speed factor below 1 makes it slower; both are the same for the same seed.
TEST(Agent, AStallHoldsTheRobotAtRestForStallSecondsThenItDrives) {
  auto m = test::footbot_model();
  m.uncertainty.stall_probability = 1.0;
  m.uncertainty.stall_s = 2.0;
  Drive r(m);
  EXPECT_TRUE(r.agent.activate().ok());
  ASSERT_EQ(r.agent.on_window(1, east_half_moves(0, 1)), ActionQueue::Result::kAccepted);
  r.steps(19);  // 1.9 s: still stalled
  EXPECT_TRUE(r.agent.stalled());
  EXPECT_NEAR(r.robot.pose().x_m, 0.0, 1e-9);
  r.steps(200);
  EXPECT_EQ(r.agent.finished_seq(), 1);
  EXPECT_EQ(r.agent.stalls(), 1u) << "a stall only from rest: the merged run does not stall";
}

// A delay event stops a moving robot where it is (between cells), braking within its limits,
// for the event's duration; then it drives on and finishes its actions (LoRR 2026 delays).
TEST(Agent, ADelayEventStopsAMovingRobotMidEdgeThenItDrivesOn) {
  auto m = test::footbot_model();
  m.uncertainty.seed = 3;
  m.uncertainty.delay_probability = 0.05;
  m.uncertainty.delay_min_s = 2.0;
  m.uncertainty.delay_max_s = 2.0;
  Drive r(m);
  EXPECT_TRUE(r.agent.activate().ok());
  ASSERT_EQ(r.agent.on_window(1, east_half_moves(0, 7)), ActionQueue::Result::kAccepted);
  bool stopped_mid_edge = false, was_moving = false;
  for (int i = 0; i < 600 && r.agent.finished_seq() < 7; ++i) {
    const bool delayed_before = r.agent.delayed();
    r.steps(1);
    if (!delayed_before && r.agent.delayed() && r.speed.size() > 1 &&
        r.speed[r.speed.size() - 2] > 0.1) {
      was_moving = true;  // an event began while the robot drove
    }
    const double x = r.robot.pose().x_m;
    const double off_grid = std::abs(x / 0.5 - std::round(x / 0.5)) * 0.5;
    if (was_moving && r.agent.delayed() && std::abs(r.speed.back()) < 1e-6 && off_grid > 0.05) {
      stopped_mid_edge = true;
    }
  }
  EXPECT_TRUE(was_moving) << "seed 3 should start a delay while the robot drives";
  EXPECT_TRUE(stopped_mid_edge) << "a delayed robot stops where it is, between half-cells";
  EXPECT_EQ(r.agent.finished_seq(), 7) << "after its delays the robot finishes its actions";
  EXPECT_GE(r.agent.delays(), 1u);
}

// Issue 28 (LoRR output's delayIntervals): the intervals delay_intervals() computes from the
// seed alone are the delays an agent stepped every 0.1 s lives, tick for tick.
TEST(Agent, DelayIntervalsAreTheDelaysTheAgentLives) {
  auto m = test::footbot_model();
  m.uncertainty.seed = 5;
  m.uncertainty.delay_probability = 0.05;
  m.uncertainty.delay_min_s = 0.3;
  m.uncertainty.delay_max_s = 1.55;
  Drive r(m);
  EXPECT_TRUE(r.agent.activate().ok());
  ASSERT_EQ(r.agent.on_window(1, east_half_moves(0, 7)), ActionQueue::Result::kAccepted);
  constexpr int64_t kTicks = 600;
  std::vector<bool> lived;
  for (int64_t k = 0; k < kTicks; ++k) {
    r.steps(1);  // the agent's update at tick k
    lived.push_back(r.agent.delayed());
  }
  const auto intervals = delay_intervals(m.uncertainty, 7, kTicks);
  ASSERT_GE(intervals.size(), 5u);
  EXPECT_EQ(intervals.size(), r.agent.delays());
  std::vector<bool> computed(kTicks, false);
  for (const auto& [from, to] : intervals) {
    ASSERT_LT(from, to);
    for (int64_t k = from; k < std::min(to, kTicks); ++k)
      computed[static_cast<std::size_t>(k)] = true;
  }
  for (int64_t k = 0; k < kTicks; ++k) {
    EXPECT_EQ(computed[static_cast<std::size_t>(k)], lived[static_cast<std::size_t>(k)])
        << "tick " << k;
  }
  EXPECT_TRUE(delay_intervals(Uncertainty{}, 7, kTicks).empty());
}

TEST(Agent, ASpeedFactorBelowOneSlowsTheRobotDeterministically) {
  auto m = test::footbot_model();
  m.max_speed_mps = 0.5;
  m.max_accel_mps2 = 5.0;
  m.max_decel_mps2 = 5.0;
  const auto top = [&](uint64_t seed) {
    auto mm = m;
    mm.uncertainty.speed_sigma = 0.3;
    mm.uncertainty.seed = seed;
    Drive r(mm);
    EXPECT_TRUE(r.agent.activate().ok());
    (void)r.agent.on_window(1, east_half_moves(0, 9));
    r.steps(40);
    double v = 0;
    for (double s : r.speed) v = std::max(v, s);
    return v;
  };
  const double factor = speed_factor({0, 0, 0.3, 0, 3}, 7);
  ASSERT_LT(factor, 0.999) << "seed 3 gives robot 7 a factor below 1";
  EXPECT_NEAR(top(3), 0.5 * factor, 0.01);
  EXPECT_DOUBLE_EQ(top(3), top(3));
}

TEST(Agent, EachHalfMoveIsFinishedWhenTheRobotPassesItsEnd) {
  Drive r(test::footbot_model());
  EXPECT_TRUE(r.agent.activate().ok());
  r.agent.on_window(1, east_half_moves(0, 3));
  for (int i = 0; i < 300; ++i) {
    r.agent.step(r.robot.time());
    const double x = r.robot.pose().x_m;
    const int64_t f = r.agent.finished_seq();
    // Finished seq k means the robot got past (k+1)/2 m, less the final tolerance.
    if (f >= 0) {
      EXPECT_GE(x, 0.5 * (f + 1) - 0.011) << "finished " << f << " at x=" << x;
    }
    r.robot.advance(kStep_s);
  }
  EXPECT_EQ(r.agent.finished_seq(), 3);
}

TEST(Agent, DuplicatedAndOutOfOrderWindowsCauseNoDuplicateExecution) {
  Drive r(test::footbot_model());
  EXPECT_TRUE(r.agent.activate().ok());
  r.agent.on_window(3, east_half_moves(0, 3));
  r.steps(10);
  r.agent.on_window(3, east_half_moves(0, 3));  // duplicate
  r.agent.on_window(3, east_half_moves(0, 1));  // older, out of order
  r.agent.on_window(3, east_half_moves(2, 5));  // overlapping extension
  r.steps(300);
  EXPECT_EQ(r.agent.finished_seq(), 5);
  EXPECT_NEAR(r.robot.pose().x_m, 3.0, 0.02) << "executing a half-move twice would overshoot";
}

TEST(Agent, RotationThenMove) {
  Drive r(test::footbot_model());
  EXPECT_TRUE(r.agent.activate().ok());
  std::vector<AgentAction> w{{0, ActionKind::kRotate, 0, 0, 0, 0, M_PI / 2},
                             {1, ActionKind::kMove, 0, 0, 0, 0.5, M_PI / 2},
                             {2, ActionKind::kMove, 0, 0.5, 0, 1.0, M_PI / 2}};
  r.agent.on_window(1, w);
  r.steps(300);
  EXPECT_EQ(r.agent.finished_seq(), 2);
  EXPECT_NEAR(r.robot.pose().y_m, 1.0, 0.02);
  EXPECT_NEAR(r.robot.pose().x_m, 0.0, 0.02);
}

TEST(Agent, StalePoseStopsTheWheelsAtOnce) {
  Drive r(test::footbot_model());
  EXPECT_TRUE(r.agent.activate().ok());
  r.agent.on_window(1, east_half_moves(0, 9));
  r.steps(30);
  ASSERT_GT(std::abs(r.agent.last_command().left_mps), 0.1);
  const int stops_before = r.robot.stops;
  r.robot.freeze_stamp_at(r.robot.time() - 1.0);  // pose a second old
  r.agent.step(r.robot.time() + 1.0);
  EXPECT_TRUE(r.agent.pose_stale());
  EXPECT_EQ(r.agent.watchdog_stops(), 1u);
  EXPECT_EQ(r.robot.stops, stops_before + 1);
  EXPECT_EQ(r.robot.commands.back().left_mps, 0.0);
  EXPECT_EQ(r.robot.commands.back().right_mps, 0.0);
  r.robot.valid = false;  // no pose at all: still stopped
  r.agent.step(r.robot.time());
  EXPECT_EQ(r.robot.commands.back().left_mps, 0.0);
}

// Regression: every `smart agent --backend ros2` robot reported one watchdog stop, counted while
// its odometry had not arrived yet.
TEST(Agent, WaitingForTheFirstPoseIsNotAWatchdogStop) {
  Drive r(test::footbot_model());
  EXPECT_TRUE(r.agent.activate().ok());
  r.robot.valid = false;
  r.agent.step(0.0);
  EXPECT_TRUE(r.agent.pose_stale());
  EXPECT_EQ(r.agent.watchdog_stops(), 0u);
  EXPECT_EQ(r.robot.commands.back().left_mps, 0.0);
  r.robot.valid = true;
  r.agent.on_window(1, east_half_moves(0, 1));
  r.steps(5);
  EXPECT_FALSE(r.agent.pose_stale());
  r.robot.valid = false;  // lost after it had been seen: a stop
  r.agent.step(r.robot.time());
  EXPECT_EQ(r.agent.watchdog_stops(), 1u);
}

TEST(Agent, LifecycleOnlyActiveAgentsMoveAndDeactivateStops) {
  Drive r(test::footbot_model());
  r.agent.on_window(1, east_half_moves(0, 1));
  r.agent.step(0.0);
  EXPECT_TRUE(r.robot.commands.empty());
  EXPECT_TRUE(r.agent.configure().ok());
  EXPECT_EQ(r.robot.configured, 1);
  EXPECT_EQ(r.agent.state(), LifecycleState::kInactive);
  r.agent.step(0.0);
  EXPECT_TRUE(r.robot.commands.empty());
  EXPECT_TRUE(r.agent.activate().ok());
  r.steps(5);
  EXPECT_FALSE(r.robot.commands.empty());
  EXPECT_TRUE(r.agent.deactivate().ok());
  EXPECT_EQ(r.robot.deactivated, 1);
  EXPECT_EQ(r.robot.commands.back().left_mps, 0.0);
  EXPECT_EQ(r.agent.state(), LifecycleState::kInactive);
}

TEST(Agent, ADriveThatFailsToConfigureLeavesTheAgentUnconfiguredAndNamesTheRobot) {
  Drive r(test::footbot_model());
  r.robot.configure_answer = LifecycleResult::error("motor driver did not answer");
  const auto a = r.agent.activate();
  EXPECT_EQ(a.code, CallbackReturn::kError);
  EXPECT_EQ(a.message, "robot 7: motor driver did not answer");
  EXPECT_EQ(r.agent.state(), LifecycleState::kUnconfigured);
  EXPECT_EQ(r.robot.activated, 0) << "never activated after a failed configure";
  r.robot.configure_answer = LifecycleResult::success();  // the device answers now: retry
  EXPECT_TRUE(r.agent.activate().ok());
  EXPECT_EQ(r.agent.state(), LifecycleState::kActive);
}

TEST(Agent, AFailedActivationKeepsTheAgentInactiveSoItNeverMoves) {
  Drive r(test::footbot_model());
  r.robot.activate_answer = LifecycleResult::failure("not yet");
  r.agent.on_window(1, east_half_moves(0, 1));
  EXPECT_EQ(r.agent.activate().code, CallbackReturn::kFailure);
  EXPECT_EQ(r.agent.state(), LifecycleState::kInactive);
  r.steps(5);
  EXPECT_TRUE(r.robot.commands.empty());
}

}  // namespace
}  // namespace smart::agent
