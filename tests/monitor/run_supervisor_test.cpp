// The run supervisor driven by scripted event sequences: no DDS, no threads, no sleeps.
#include "smart/monitor/run_supervisor.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <tuple>

#include "support/monitor_fixtures.hpp"

namespace smart::monitor {
namespace {

using ::testing::HasSubstr;

// Robot 0 drives (1,0) -> (2,0); robot 1 follows into (1,0) a step later, so robot 1's second
// half-move waits for robot 0 to leave (1,0) (a Type-2 edge). Two half-moves each, no rotation.
Instance corridor() {
  Instance in;
  in.grid = test::grid_of({"...."});
  in.plan = test::plan_of({{{1, 0}, {2, 0}, {2, 0}}, {{0, 0}, {0, 0}, {1, 0}}});
  in.scen = test::scen_of(in.plan, in.grid);
  in.actions = build_actions(in.plan, Heading::kEast);
  std::vector<Problem> problems;
  in.adg = build_adg(in.actions, in.grid, "fixture", problems);
  return in;
}

struct FakeWriter : RunWriter {
  std::map<uint32_t, ExecutionTracker::Window> windows;  // the latest per robot
  std::vector<wire::Tick> answers;
  int window_writes = 0;
  void publish_window(uint32_t robot, uint64_t, ExecutionTracker::Window w) override {
    windows[robot] = w;
    ++window_writes;
  }
  void answer_tick(const wire::Tick& a) override { answers.push_back(a); }
  std::vector<std::tuple<uint32_t, uint32_t, double>> finished;  // robot, seq, time
  void action_finished(uint32_t robot, uint32_t seq, double t_s) override {
    finished.emplace_back(robot, seq, t_s);
  }
};

constexpr uint64_t kRun = 7;

SupervisorConfig lockstep_config() {
  SupervisorConfig c;
  c.run_id = kRun;
  c.domain_id = 42;
  c.timeout_s = 5;
  c.stall_timeout_s = 10;
  return c;
}

wire::Tick tick(uint64_t k, uint64_t sync_total) {
  return {kRun, k, 0.1 * double(k), sync_total, false};
}

struct Scripted {
  Instance in = corridor();
  FakeWriter out;
  RunSupervisor sup;
  explicit Scripted(SupervisorConfig c = lockstep_config()) : sup(in, c, out) {}
};

TEST(RunSupervisor, StartPublishesEveryWindowAndTheFirstTickIsAnsweredWithTheirSum) {
  Scripted r;
  r.sup.start(0);
  ASSERT_EQ(r.out.windows.size(), 2u);
  EXPECT_EQ(r.out.windows[0].end, 2u);  // robot 0 may do everything
  EXPECT_EQ(r.out.windows[1].end, 1u);  // robot 1 waits for robot 0 to leave (1,0)
  r.sup.on_clock(tick(0, 0), 0.1);
  ASSERT_EQ(r.out.answers.size(), 1u);
  EXPECT_EQ(r.out.answers[0].tick, 0u);
  EXPECT_EQ(r.out.answers[0].sync_total, 3u);
  EXPECT_FALSE(r.out.answers[0].stop);
}

// Runs the corridor to success, progress before or after the tick that announces it.
void drive_to_success(Scripted& r, bool progress_first) {
  r.sup.start(0);
  r.sup.on_clock(tick(0, 0), 0);
  auto step = [&](uint64_t k, uint64_t total, ProgressEvent p) {
    if (progress_first) r.sup.on_progress(p, 0);
    r.sup.on_clock(tick(k, total), 0);
    if (!progress_first) r.sup.on_progress(p, 0);
  };
  step(5, 2, {0, kRun, 1});
  EXPECT_EQ(r.out.windows[1].end, 2u);  // robot 0 left (1,0): robot 1 may enter
  step(9, 4, {1, kRun, 1});
  EXPECT_TRUE(r.out.answers.back().stop);
}

MonitorResult run_to_success(bool progress_first) {
  Scripted r;
  drive_to_success(r, progress_first);
  return r.sup.result();
}

TEST(RunSupervisor, SuccessTimesEveryRobotAtTheTickThatAnnouncedItsProgress) {
  for (bool progress_first : {true, false}) {
    const auto res = run_to_success(progress_first);
    EXPECT_EQ(res.outcome, Outcome::kSuccess);
    EXPECT_TRUE(res.success());
    EXPECT_DOUBLE_EQ(res.robots[0].finish_time_s, 0.5);
    EXPECT_DOUBLE_EQ(res.robots[1].finish_time_s, 0.9);
    EXPECT_EQ(res.finished_actions, 4u);
    EXPECT_DOUBLE_EQ(res.sim_time_s, 0.9);
  }
}

TEST(RunSupervisor, EveryActionIsTimedAtTheTickThatAnnouncedIt) {
  Scripted r;
  r.sup.start(0);
  r.sup.on_clock(tick(0, 0), 0);
  r.sup.on_clock(tick(3, 1), 0);
  r.sup.on_progress({0, kRun, 0}, 0);  // robot 0's first half-move at 0.3 s
  EXPECT_TRUE(std::isnan(r.sup.result().action_finish_s[1]));
  r.sup.on_clock(tick(5, 2), 0);
  r.sup.on_progress({0, kRun, 1}, 0);
  r.sup.on_clock(tick(9, 4), 0);
  r.sup.on_progress({1, kRun, 1}, 0);  // robot 1's two at once at 0.9 s
  EXPECT_THAT(r.sup.result().action_finish_s,
              ::testing::Pointwise(::testing::DoubleEq(), {0.1 * 3, 0.1 * 5, 0.1 * 9, 0.1 * 9}));
  // The writer heard each action once, as it was timed (a live recording's progress).
  using F = std::tuple<uint32_t, uint32_t, double>;
  EXPECT_EQ(r.out.finished,
            (std::vector<F>{{0, 0, 0.1 * 3}, {0, 1, 0.1 * 5}, {1, 0, 0.1 * 9}, {1, 1, 0.1 * 9}}));
}

TEST(RunSupervisor, ATickIsAnsweredOnlyWhenItsProgressAddsUp) {
  Scripted r;
  r.sup.start(0);
  r.sup.on_clock(tick(0, 0), 0);
  r.sup.on_clock(tick(3, 2), 0);  // announces two finished actions
  EXPECT_EQ(r.out.answers.size(), 1u);
  r.sup.on_progress({0, kRun, 0}, 0);
  EXPECT_EQ(r.out.answers.size(), 1u);
  r.sup.on_progress({0, kRun, 1}, 0);
  ASSERT_EQ(r.out.answers.size(), 2u);
  EXPECT_EQ(r.out.answers[1].tick, 3u);
}

TEST(RunSupervisor, DuplicateStaleForeignAndOutOfRangeProgressChangeNothing) {
  Scripted r;
  r.sup.start(0);
  r.sup.on_clock(tick(0, 0), 0);
  r.sup.on_progress({1, kRun, 1}, 0);  // not enqueued yet: robot 0 is still in (1,0)
  // Rejected at once: no honest host reports an action before it was sent, and held it would
  // keep the tick from adding up.
  EXPECT_EQ(r.sup.result().rejected_progress, 1u);
  r.sup.on_progress({0, kRun, 0}, 0);
  EXPECT_EQ(r.sup.result().finished_actions, 0u);  // lock-step: held until its tick
  r.sup.on_clock(tick(1, 1), 0);
  ASSERT_EQ(r.out.answers.size(), 2u);
  const int writes = r.out.window_writes;
  r.sup.on_progress({0, kRun, 0}, 0);      // duplicate
  r.sup.on_progress({0, kRun, -1}, 0);     // older
  r.sup.on_progress({1, kRun + 1, 0}, 0);  // another run
  r.sup.on_progress({9, kRun, 0}, 0);      // no such robot
  r.sup.on_clock(tick(2, 1), 0);
  EXPECT_EQ(r.out.answers.size(), 3u);
  EXPECT_EQ(r.out.window_writes, writes);
  EXPECT_EQ(r.sup.result().finished_actions, 1u);
  EXPECT_EQ(r.sup.result().rejected_progress, 2u);
  const auto notes = r.sup.take_notes();
  ASSERT_EQ(notes.size(), 2u);
  EXPECT_THAT(notes[0], HasSubstr("only actions below 1 were enqueued"));
  EXPECT_THAT(notes[1], HasSubstr("robot 9 does not exist"));
  EXPECT_TRUE(r.sup.take_notes().empty());
}

TEST(RunSupervisor, LateTicksAreIgnoredAndARepeatedTickIsAnsweredAgain) {
  Scripted r;
  r.sup.start(0);
  r.sup.on_clock(tick(0, 0), 0);
  r.sup.on_progress({0, kRun, 0}, 0);
  r.sup.on_clock(tick(4, 1), 0);
  ASSERT_EQ(r.out.answers.size(), 2u);
  r.sup.on_clock(tick(2, 0), 0);  // reordered: older than the last answer
  EXPECT_EQ(r.out.answers.size(), 2u);
  r.sup.on_clock(tick(4, 1), 0);  // the sim re-announced: the answer may have been missed
  EXPECT_EQ(r.out.answers.size(), 3u);
  EXPECT_EQ(r.out.answers[2].tick, 4u);
}

// Regression (Sharded.SmartsWarehousePlanIsIdenticalOnOneTwoAndFourShards, "the sim host went
// silent for 30 s" at tick 0 on a loaded machine): a sim shard other than the lead whose clock
// reader matched after the monitor answered tick 0 never got the answer (the clock keeps no
// history) and cannot announce again; it waited, and the lead for it. The monitor now sends its
// last answer again, the same sample, while no newer tick comes.
TEST(RunSupervisor, TheLastAnswerGoesOutAgainWhileNoNewerTickComes) {
  auto c = lockstep_config();
  c.reanswer_s = 0.5;
  Scripted r(c);
  r.sup.start(0);
  r.sup.on_clock(tick(0, 0), 1.0);
  ASSERT_EQ(r.out.answers.size(), 1u);
  r.sup.poll(1.4);
  EXPECT_EQ(r.out.answers.size(), 1u);
  r.sup.poll(1.6);
  ASSERT_EQ(r.out.answers.size(), 2u);
  EXPECT_EQ(r.out.answers[1].tick, r.out.answers[0].tick);
  EXPECT_EQ(r.out.answers[1].sync_total, r.out.answers[0].sync_total);
  EXPECT_EQ(r.out.answers[1].run_id, kRun);
  r.sup.poll(2.0);
  EXPECT_EQ(r.out.answers.size(), 2u);  // once a period
  r.sup.on_progress({0, kRun, 0}, 2.05);
  r.sup.on_clock(tick(4, 1), 2.1);  // the fleet stepped: its tick is answered, not the old one
  ASSERT_EQ(r.out.answers.size(), 3u);
  EXPECT_EQ(r.out.answers[2].tick, 4u);
  r.sup.poll(2.5);
  EXPECT_EQ(r.out.answers.size(), 3u);
  EXPECT_FALSE(r.sup.over());
  // Without a period (scripted runs, 0), never.
  Scripted quiet;
  quiet.sup.start(0);
  quiet.sup.on_clock(tick(0, 0), 1.0);
  quiet.sup.poll(4.0);
  EXPECT_EQ(quiet.out.answers.size(), 1u);
}

TEST(RunSupervisor, ClockOfAnotherRunIsIgnoredAndRunZeroIsTaken) {
  Scripted r;
  r.sup.start(0);
  r.sup.on_clock({kRun + 1, 0, 0, 0, false}, 0);
  EXPECT_TRUE(r.out.answers.empty());
  r.sup.on_clock({0, 0, 0, 0, false}, 0);  // a sim that has no window yet does not know the run
  EXPECT_EQ(r.out.answers.size(), 1u);
}

TEST(RunSupervisor, DeadlockWhenNoRobotHasAnActionItMayExecute) {
  Scripted r;
  // A dependency cycle between the robots' first actions (nodes 0 and 2).
  r.in.adg.out_begin = r.in.adg.in_begin = {0, 1, 1, 2, 2};
  r.in.adg.out = r.in.adg.in = {2, 0};
  RunSupervisor sup(r.in, lockstep_config(), r.out);
  sup.start(0);
  sup.on_clock(tick(0, 0), 0);
  EXPECT_EQ(sup.result().outcome, Outcome::kDeadlock);
  EXPECT_THAT(sup.result().error, HasSubstr("4 actions remain"));
  EXPECT_TRUE(r.out.answers.back().stop);
}

TEST(RunSupervisor, StalledAfterStallTimeoutOfSimTimeWithoutAFinishedAction) {
  Scripted r;
  r.sup.start(0);
  r.sup.on_clock(tick(0, 0), 0);
  r.sup.on_clock(tick(100, 0), 1);  // 10.0 s: not yet past
  EXPECT_FALSE(r.sup.over());
  r.sup.on_clock(tick(101, 0), 1);
  EXPECT_EQ(r.sup.result().outcome, Outcome::kStalled);
  EXPECT_THAT(r.sup.result().error, HasSubstr("no action finished for 10"));
}

TEST(RunSupervisor, TimeLimitPastMaxSimTime) {
  auto c = lockstep_config();
  c.max_sim_time_s = 0.25;
  Scripted r(c);
  r.sup.start(0);
  r.sup.on_clock(tick(0, 0), 0);
  r.sup.on_progress({0, kRun, 0}, 0);
  r.sup.on_clock(tick(3, 1), 0);
  EXPECT_EQ(r.sup.result().outcome, Outcome::kTimeLimit);
  EXPECT_THAT(r.sup.result().error, HasSubstr("time limit"));
}

TEST(RunSupervisor, NoSimHostWithinTimeoutNamesTheDomain) {
  Scripted r;
  r.sup.start(0);
  r.sup.poll(4.9);
  EXPECT_FALSE(r.sup.over());
  r.sup.poll(5.1);
  EXPECT_EQ(r.sup.result().outcome, Outcome::kHostLost);
  EXPECT_THAT(r.sup.result().error, HasSubstr("no sim host joined domain 42"));
}

// Start-up lasts until the tick after the sim's first step (wire::kLastJoinTick), as the sim
// shards wait: CI stop 52's four-shard run was lost 30 s after tick 0 while the shards would
// have waited four times as long for each other's first step.
TEST(RunSupervisor, ASimHostStartedHereHasTheJoinTimeoutUntilItsFirstStepThenTheUsualOne) {
  auto c = lockstep_config();
  c.join_timeout_s = 20;
  Scripted r(c);
  r.sup.start(0);
  r.sup.poll(19.9);
  EXPECT_FALSE(r.sup.over());
  r.sup.on_clock(tick(0, 0), 19.9);
  r.sup.poll(39.8);
  EXPECT_FALSE(r.sup.over()) << "the first step is start-up too";
  r.sup.on_clock(tick(1, 0), 39.8);
  r.sup.poll(44.7);
  EXPECT_FALSE(r.sup.over());
  r.sup.poll(44.9);
  EXPECT_EQ(r.sup.result().outcome, Outcome::kHostLost);
  EXPECT_THAT(r.sup.result().error, HasSubstr("went silent for 5"));
  EXPECT_THAT(r.sup.result().error, HasSubstr("after tick 1"));
}

TEST(RunSupervisor, ASimSilentThroughItsFirstStepIsLostAfterTheJoinTimeoutNamingTheTick) {
  auto c = lockstep_config();
  c.join_timeout_s = 20;
  Scripted r(c);
  r.sup.start(0);
  r.sup.on_clock(tick(0, 0), 1);
  r.sup.poll(20.9);
  EXPECT_FALSE(r.sup.over());
  r.sup.poll(21.1);
  EXPECT_EQ(r.sup.result().outcome, Outcome::kHostLost);
  EXPECT_THAT(r.sup.result().error, HasSubstr("went silent for 20"));
  EXPECT_THAT(r.sup.result().error, HasSubstr("after tick 0 (answered)"));
}

TEST(RunSupervisor, LockstepSimThatGoesSilentOrLeavesIsLost) {
  Scripted silent;
  silent.sup.start(0);
  silent.sup.on_clock(tick(0, 0), 1);
  silent.sup.poll(5.9);
  EXPECT_FALSE(silent.sup.over());
  silent.sup.poll(6.1);
  EXPECT_THAT(silent.sup.result().error, HasSubstr("went silent"));

  Scripted left;
  left.sup.start(0);
  left.sup.on_hosts_matched(1, 0.5);
  left.sup.on_clock(tick(0, 0), 1);
  left.sup.on_hosts_matched(1, 1.5);
  EXPECT_FALSE(left.sup.over());
  left.sup.on_hosts_matched(0, 2);
  EXPECT_EQ(left.sup.result().outcome, Outcome::kHostLost);
  EXPECT_THAT(left.sup.result().error, HasSubstr("the sim host left"));
}

TEST(RunSupervisor, HostFailureAndStopEndTheRunAndFinishSendsTheStop) {
  Scripted failed;
  failed.sup.start(0);
  failed.sup.on_host_failure("the sim process exited with code 3");
  failed.sup.stop("later reasons do not replace the first");
  EXPECT_EQ(failed.sup.result().outcome, Outcome::kHostLost);
  EXPECT_EQ(failed.sup.result().error, "the sim process exited with code 3");

  Scripted stopped;
  stopped.sup.start(0);
  stopped.sup.on_clock(tick(0, 0), 0);
  stopped.sup.stop("stopped by signal");
  stopped.sup.finish(2.5);
  EXPECT_EQ(stopped.sup.result().outcome, Outcome::kStopped);
  ASSERT_FALSE(stopped.out.answers.empty());
  EXPECT_TRUE(stopped.out.answers.back().stop);
  EXPECT_EQ(stopped.out.answers.back().tick, 0u);
  EXPECT_DOUBLE_EQ(stopped.sup.result().wall_time_s, 2.5);
}

TEST(RunSupervisor, RealTimeTakesProgressAtWallTimeAndTracksEachRobotsHost) {
  auto c = lockstep_config();
  c.lockstep = false;
  Scripted r(c);
  r.sup.start(0);
  EXPECT_TRUE(r.sup.wants_progress());
  r.sup.on_hosts_matched(1, 0.2);
  r.sup.on_progress({0, kRun, 1}, 1.5);
  r.sup.poll(1.5);
  EXPECT_DOUBLE_EQ(r.sup.result().robots[0].finish_time_s, 1.5);
  EXPECT_TRUE(r.sup.on_state({1, kRun}, 3.0));
  EXPECT_FALSE(r.sup.on_state({1, kRun + 1}, 3.0));  // another run's robot says nothing
  r.sup.poll(7.9);
  EXPECT_FALSE(r.sup.over());  // robot 1 was heard at 3.0; robot 0 is done
  r.sup.poll(8.1);
  EXPECT_EQ(r.sup.result().outcome, Outcome::kHostLost);
  EXPECT_THAT(r.sup.result().error, HasSubstr("robot 1: nothing heard from its host"));
}

TEST(RunSupervisor, RealTimePosesOfThisRunAreWatchedForContactsWithoutFailingTheRun) {
  auto c = lockstep_config();
  c.lockstep = false;
  c.robot_radius_m = 0.09;
  Scripted r(c);
  r.sup.start(0);
  r.sup.on_state({0, kRun, 1.0, 0.0}, 1.0);
  r.sup.on_state({1, kRun + 1, 1.1, 0.0}, 1.0);  // another run's robot: not compared
  EXPECT_FALSE(r.sup.result().pose_min_gap_m);
  r.sup.on_state({1, kRun, 1.25, 0.0}, 1.02);
  EXPECT_NEAR(*r.sup.result().pose_min_gap_m, 0.07, 1e-12);
  r.sup.on_state({1, kRun, 1.1, 0.0}, 1.04);
  EXPECT_EQ(r.sup.result().pose_contacts, 1u);
  ASSERT_TRUE(r.sup.result().first_pose_contact);
  EXPECT_DOUBLE_EQ(r.sup.result().first_pose_contact->t_s, 1.04);
  EXPECT_FALSE(r.sup.over());
  // Lock-step runs leave contacts to the sim host's physics.
  Scripted lockstep;
  lockstep.sup.on_state({0, kRun, 1.0, 0.0}, 1.0);
  lockstep.sup.on_state({1, kRun, 1.0, 0.0}, 1.0);
  EXPECT_EQ(lockstep.sup.result().pose_contacts, 0u);
  EXPECT_FALSE(lockstep.sup.result().pose_min_gap_m);
}

TEST(RunSupervisor, SimStatusOfThisRunOrRunZeroIsTaken) {
  Scripted r;
  r.sup.on_sim_status({kRun + 1, 5, 5, 0.1, 10});
  EXPECT_FALSE(r.sup.result().have_sim_status);
  r.sup.on_sim_status({0, 1, 2, 0.3, 20});
  r.sup.on_sim_status({kRun, 1, 2, 1e9, 15});
  EXPECT_TRUE(r.sup.result().have_sim_status);
  EXPECT_EQ(r.sup.result().robot_contacts, 1u);
  EXPECT_EQ(r.sup.result().wall_contacts, 2u);
  EXPECT_DOUBLE_EQ(*r.sup.result().min_gap_m, 0.3);  // 1e9: no gap measured
  EXPECT_DOUBLE_EQ(*r.sup.result().host_peak_rss_mb, 20);
}

TEST(RunSupervisor, ResumeReachesTheFixpointWhateverOrderProgressCameIn) {
  Scripted r;
  // Robot 1's last action waited for robot 0: reported first, it is taken on the second pass.
  const auto error = r.sup.resume({{1, 99, 1}, {0, 99, 0}, {0, 99, 1}, {0, 99, 0}});
  ASSERT_EQ(error, "");
  const auto& res = r.sup.result();
  EXPECT_TRUE(res.resumed);
  EXPECT_EQ(res.run_id, 99u);
  EXPECT_EQ(res.finished_before_resume, 4u);
  EXPECT_EQ(res.robots_done_before_resume, 2u);
  EXPECT_TRUE(std::isnan(res.robots[0].finish_time_s));
  EXPECT_EQ(r.sup.take_notes().size(), 1u);
  r.sup.start(0);
  r.sup.on_clock({99, 40, 4.0, 4, false}, 0);
  EXPECT_EQ(res.outcome, Outcome::kSuccess);
  EXPECT_DOUBLE_EQ(res.resumed_at_s, 4.0);
  EXPECT_EQ(r.out.answers.back().sync_total, 4u);  // the hosts hold what was finished
}

TEST(RunSupervisor, ResumeRefusesProgressThatDoesNotFitThePlan) {
  Scripted too_many;
  EXPECT_THAT(too_many.sup.resume({{5, 99, 0}}), HasSubstr("progress for robot 5"));
  EXPECT_EQ(too_many.sup.result().outcome, Outcome::kHostLost);
  Scripted two_runs;
  EXPECT_THAT(two_runs.sup.resume({{0, 99, 0}, {1, 98, 0}}), HasSubstr("two runs (99 and 98)"));
  Scripted not_allowed;  // robot 1 entered (1,0) while robot 0 was still there
  EXPECT_THAT(not_allowed.sup.resume({{1, 99, 1}}),
              HasSubstr("robot 1 reports action 1 finished, which this plan's dependency"));
  Scripted nothing;
  EXPECT_THAT(nothing.sup.resume({}), HasSubstr("report no progress yet"));
}

// The corridor's goals in the world frame (cell 1 m, one row): robot 0 (2,0), robot 1 (1,0).
TEST(RunSupervisor, SuccessMeansEveryRobotSeenAtItsGoalAfterItFinished) {
  Scripted r;
  drive_to_success(r, true);
  r.sup.finish(1);
  r.sup.on_state({0, kRun, 2.05, 0.02}, 1);  // within a quarter cell
  r.sup.on_state({1, kRun, 0.9, -0.1}, 1);
  r.sup.conclude();
  EXPECT_EQ(r.sup.result().outcome, Outcome::kSuccess);
  EXPECT_DOUBLE_EQ(r.sup.result().goal_tolerance_m, 0.25);
  EXPECT_TRUE(r.sup.result().off_goal.empty());
  EXPECT_TRUE(r.sup.result().goal_unverified.empty());
}

TEST(RunSupervisor, ForgedProgressThatFinishesARobotAwayFromItsGoalIsNotSuccess) {
  Scripted r;
  drive_to_success(r, false);
  r.sup.finish(1);
  r.sup.on_state({0, kRun, 2.0, 0.0}, 1);
  r.sup.on_state({1, kRun, 0.0, 0.0}, 1);      // still at its start: it never drove
  r.sup.on_state({1, kRun + 1, 1.0, 0.0}, 1);  // another run's sample does not count
  r.sup.conclude();
  EXPECT_EQ(r.sup.result().outcome, Outcome::kOffGoal);
  EXPECT_FALSE(r.sup.result().success());
  EXPECT_THAT(r.sup.result().off_goal, ::testing::ElementsAre(1u));
  EXPECT_THAT(r.sup.result().error, HasSubstr("robots 1 were last seen more than 0.25"));
}

TEST(RunSupervisor, APoseSeenOnlyBeforeTheRobotFinishedLeavesItUnverifiedNotFailed) {
  Scripted r;
  r.sup.start(0);
  r.sup.on_state({1, kRun, 0.0, 0.0}, 0);  // before it moved; its final state was lost
  r.sup.on_clock(tick(0, 0), 0);
  r.sup.on_clock(tick(5, 2), 0);
  r.sup.on_progress({0, kRun, 1}, 0);
  r.sup.on_clock(tick(9, 4), 0);
  r.sup.on_progress({1, kRun, 1}, 0);
  r.sup.finish(1);
  r.sup.on_state({0, kRun, 2.0, 0.0}, 1);
  r.sup.conclude();
  EXPECT_EQ(r.sup.result().outcome, Outcome::kSuccess);
  EXPECT_THAT(r.sup.result().goal_unverified, ::testing::ElementsAre(1u));
}

TEST(RunSupervisor, ACollisionMakesACompleteRunFailAndNamesTheRobots) {
  Scripted r;
  drive_to_success(r, true);
  r.sup.finish(1);
  r.sup.on_state({0, kRun, 2.0, 0.0}, 1);
  r.sup.on_state({1, kRun, 1.0, 0.0}, 1);
  r.sup.on_sim_status({kRun, 1, 0, 0.0, 10, 1, 0});
  r.sup.conclude();
  EXPECT_EQ(r.sup.result().outcome, Outcome::kCollision);
  EXPECT_THAT(r.sup.result().error, HasSubstr("1 robot-robot collisions, first robots 1 and 0"));
}

// Issue 25, "a false success": an intruder's stronger SimStatus writer hid the sim's status and
// the run ended `success: true` while the sim counted 7 collisions.
TEST(RunSupervisor, ASimulatedRunWithoutTheSimsFinalStatusIsUnverifiedNotASuccess) {
  auto c = lockstep_config();
  c.require_sim_status = true;
  Scripted none(c);
  drive_to_success(none, true);
  none.sup.finish(1);
  EXPECT_FALSE(none.sup.has_final_sim_status());
  none.sup.conclude();
  EXPECT_EQ(none.sup.result().outcome, Outcome::kUnverified);
  EXPECT_FALSE(none.sup.result().success());
  EXPECT_THAT(none.sup.result().error, HasSubstr("no status from the run's sim host"));
  // A status from before the last tick (0.9 s) is not the sim's last word: a contact may follow.
  Scripted early(c);
  drive_to_success(early, true);
  early.sup.on_sim_status({kRun, 0, 0, 0.5, 10, -1, -1, 0.5});
  early.sup.finish(1);
  EXPECT_FALSE(early.sup.has_final_sim_status());
  early.sup.conclude();
  EXPECT_EQ(early.sup.result().outcome, Outcome::kUnverified);
  EXPECT_THAT(early.sup.result().error, HasSubstr("the sim host's status at the run's end"));
  Scripted final_word(c);
  drive_to_success(final_word, true);
  final_word.sup.finish(1);
  final_word.sup.on_sim_status({kRun, 0, 0, 0.5, 10, -1, -1, 0.9});
  EXPECT_TRUE(final_word.sup.has_final_sim_status());
  final_word.sup.conclude();
  EXPECT_EQ(final_word.sup.result().outcome, Outcome::kSuccess);
}

TEST(RunSupervisor, RealTimePoseContactsFailACompleteRunNamingTheRobots) {
  auto c = lockstep_config();
  c.lockstep = false;
  c.robot_radius_m = 0.09;
  c.timeout_s = 100;
  Scripted r(c);
  r.sup.start(0);
  r.sup.on_hosts_matched(1, 0);
  r.sup.on_state({0, kRun, 1.0, 0.0}, 1.0);
  r.sup.on_state({1, kRun, 1.1, 0.0}, 1.02);  // 0.08 m overlap
  r.sup.on_progress({0, kRun, 1}, 2);
  r.sup.on_progress({1, kRun, 1}, 3);
  r.sup.poll(3);
  ASSERT_EQ(r.sup.result().outcome, Outcome::kSuccess);
  r.sup.finish(3);
  r.sup.on_state({0, kRun, 2.0, 0.0}, 3);
  r.sup.on_state({1, kRun, 1.0, 0.0}, 3);
  r.sup.conclude();
  EXPECT_EQ(r.sup.result().outcome, Outcome::kCollision);
  EXPECT_THAT(r.sup.result().error,
              HasSubstr("reported poses show 1 contact(s), first robots 0 and 1 at 1.02"));
}

TEST(RunSupervisor, ConcludeLeavesAFailedRunAsItIs) {
  Scripted r;
  r.sup.start(0);
  r.sup.stop("stopped by signal");
  r.sup.finish(1);
  r.sup.on_sim_status({kRun, 3, 0, 0.0, 10, 0, 1});
  r.sup.conclude();
  EXPECT_EQ(r.sup.result().outcome, Outcome::kStopped);
  EXPECT_EQ(r.sup.result().error, "stopped by signal");
}

TEST(RunSupervisor, OutcomeNames) {
  EXPECT_EQ(to_string(Outcome::kCollision), "collision");
  EXPECT_EQ(to_string(Outcome::kOffGoal), "not at goal");
  EXPECT_EQ(to_string(Outcome::kSuccess), "success");
  EXPECT_EQ(to_string(Outcome::kHostLost), "host lost");
  EXPECT_EQ(to_string(Outcome::kTimeLimit), "time limit");
  EXPECT_EQ(to_string(Outcome::kUnverified), "unverified");
}

// A lifelong run (execution.hpp) as the supervisor sees it: one robot whose graph grows by a
// half-move each time time passes 1 s more, complete after 3 s; no final goal.
struct GrowingExecution final : Execution {
  std::vector<grid::Action> actions;
  uint32_t finished_ = 0;
  double next_s = 0, now_s = 0;
  std::vector<std::pair<double, std::vector<uint32_t>>> calls;  // on_time's time and `sent`
  double period_s = 1;                                          // grows once this much time passed
  std::optional<WaitCause> cause_told = {};  // why it says its robot waits (nullopt: not told)
  std::size_t robots() const override { return 1; }
  ProgressUpdate on_progress(uint32_t, int64_t seq, double) override {
    if (seq < int64_t{finished_}) return {ProgressResult::kStale, "old", {}};
    if (seq >= int64_t(actions.size())) return {ProgressResult::kRejected, "never sent", {}};
    finished_ = static_cast<uint32_t>(seq + 1);
    return {ProgressResult::kAdvanced, "", {0}};
  }
  std::vector<uint32_t> on_time(double t, const std::vector<uint32_t>& sent) override {
    calls.emplace_back(t, sent);
    now_s = t;
    if (t < next_s) return {};
    next_s = t + period_s;
    const auto seq = static_cast<uint32_t>(actions.size());
    actions.push_back({0, seq, grid::ActionType::kRotate, grid::Heading::kEast, {}, {}, t, t});
    return {0};
  }
  ActionWindowRange window(uint32_t, uint32_t cap) const override {
    return {finished_, std::min<uint32_t>(uint32_t(actions.size()), finished_ + cap)};
  }
  uint32_t finished(uint32_t) const override { return finished_; }
  uint32_t enqueued(uint32_t) const override { return uint32_t(actions.size()); }
  uint32_t known(uint32_t) const override { return uint32_t(actions.size()); }
  const grid::Action& action(uint32_t, uint32_t seq) const override { return actions[seq]; }
  bool robot_done(uint32_t) const override { return false; }
  std::size_t finished_total() const override { return finished_; }
  std::size_t total() const override { return actions.size(); }
  bool complete() const override { return now_s >= 3; }
  bool deadlocked() const override { return false; }
  bool lifelong() const override { return true; }
  std::optional<WaitCause> wait_cause(uint32_t) const override { return cause_told; }
};

TEST(RunSupervisor, ALifelongExecutionGrowsAsTimePassesAndSucceedsWhenItsDurationIsOver) {
  GrowingExecution exec;
  FakeWriter out;
  RunSupervisor sup(exec, lockstep_config(), out);
  sup.start(0);
  sup.on_clock({kRun, 0, 0.0, 0, false}, 0);
  ASSERT_EQ(out.answers.size(), 1u);
  EXPECT_EQ(out.answers[0].sync_total, 1u) << "the window grown at t=0 is sent before the answer";
  ASSERT_EQ(exec.calls.size(), 1u);
  EXPECT_EQ(exec.calls[0].second, (std::vector<uint32_t>{0})) << "nothing was sent before";
  sup.on_progress({0, kRun, 0}, 0);
  sup.on_clock({kRun, 1, 1.0, 1, false}, 0);  // the action finished: the graph grows again
  EXPECT_EQ(exec.calls.back().second, (std::vector<uint32_t>{1}));
  EXPECT_EQ(out.answers.back().sync_total, 2u);
  EXPECT_FALSE(sup.over());
  sup.on_progress({0, kRun, 1}, 0);
  sup.on_clock({kRun, 2, 3.0, 2, false}, 0);
  EXPECT_TRUE(sup.over());
  EXPECT_TRUE(out.answers.back().stop);
  sup.on_sim_status({kRun, 0, 0, 1.0, 10, -1, -1, 3.0});
  sup.finish(0);
  sup.conclude();
  EXPECT_EQ(sup.result().outcome, Outcome::kSuccess) << sup.result().error;
  EXPECT_TRUE(sup.result().goal_unverified.empty()) << "a lifelong run has no final goals";
  EXPECT_NE(sup.resume({}), "") << "a lifelong run is not resumed";
}

// A robot that finished its action and has none until the graph grows 2 s later waits 1 s at
// the tick of 1 s; the execution says why, so the supervisor counts that second there.
TEST(RunSupervisor, TheWaitingIsSplitByTheCauseTheExecutionTells) {
  for (const auto told : {std::optional<WaitCause>{}, std::optional{WaitCause::kNoAction}}) {
    GrowingExecution exec;
    exec.period_s = 2;
    exec.cause_told = told;
    FakeWriter out;
    RunSupervisor sup(exec, lockstep_config(), out);
    sup.start(0);
    sup.on_clock({kRun, 0, 0.0, 0, false}, 0);
    sup.on_progress({0, kRun, 0}, 0);
    sup.on_clock({kRun, 1, 1.0, 1, false}, 0);  // nothing new: it waited 1 s
    sup.on_clock({kRun, 2, 2.0, 1, false}, 0);  // it grew: no longer waiting
    EXPECT_EQ(sup.result().robots[0].waiting_time_s, 1.0);
    if (!told) {
      EXPECT_FALSE(sup.result().waiting_by_cause_s) << "an execution that does not tell";
      continue;
    }
    ASSERT_TRUE(sup.result().waiting_by_cause_s);
    const auto& by_cause = *sup.result().waiting_by_cause_s;
    for (std::size_t c = 0; c < kWaitCauses; ++c) {
      EXPECT_EQ(by_cause[c], c == std::size_t(WaitCause::kNoAction) ? 1.0 : 0.0)
          << to_string(WaitCause(c));
    }
  }
}

// Asking every tick cost 15 % of the monitor at 1000 robots: a robot is asked when it begins to
// wait and then every 0.5 s of sim time, its waiting going to the cause it told last.
TEST(RunSupervisor, AWaitingRobotIsAskedWhyWhenItBeginsAndEveryHalfSecondAfter) {
  GrowingExecution exec;
  exec.period_s = 10;
  exec.cause_told = WaitCause::kNoAction;
  FakeWriter out;
  RunSupervisor sup(exec, lockstep_config(), out);
  sup.start(0);
  sup.on_clock({kRun, 0, 0.0, 0, false}, 0);
  sup.on_progress({0, kRun, 0}, 0);
  sup.on_clock({kRun, 1, 1.0, 1, false}, 0);  // began waiting: no action (1 s)
  exec.cause_told = WaitCause::kAtLocation;
  sup.on_clock({kRun, 2, 1.25, 1, false}, 0);  // not asked yet
  sup.on_clock({kRun, 3, 1.5, 1, false}, 0);   // asked again: at the location
  sup.on_clock({kRun, 4, 1.75, 1, false}, 0);
  ASSERT_TRUE(sup.result().waiting_by_cause_s);
  const auto& by_cause = *sup.result().waiting_by_cause_s;
  EXPECT_DOUBLE_EQ(by_cause[std::size_t(WaitCause::kNoAction)], 1.25);
  EXPECT_DOUBLE_EQ(by_cause[std::size_t(WaitCause::kAtLocation)], 0.5);
  EXPECT_DOUBLE_EQ(sup.result().robots[0].waiting_time_s, 1.75);
}

// Robots with ten actions each, all enqueued; it keeps the order progress reached it in.
struct RecordingExecution final : Execution {
  std::vector<uint32_t> done = std::vector<uint32_t>(3, 0);
  std::vector<std::pair<uint32_t, int64_t>> calls;  // robot, finished_seq
  grid::Action rotate{};
  std::size_t robots() const override { return done.size(); }
  ProgressUpdate on_progress(uint32_t r, int64_t seq, double) override {
    calls.emplace_back(r, seq);
    if (seq < int64_t{done[r]}) return {ProgressResult::kStale, "old", {}};
    done[r] = static_cast<uint32_t>(seq + 1);
    return {ProgressResult::kAdvanced, "", {r}};
  }
  ActionWindowRange window(uint32_t r, uint32_t) const override { return {done[r], 10}; }
  uint32_t finished(uint32_t r) const override { return done[r]; }
  uint32_t enqueued(uint32_t) const override { return 10; }
  uint32_t known(uint32_t) const override { return 10; }
  const grid::Action& action(uint32_t, uint32_t) const override { return rotate; }
  bool robot_done(uint32_t) const override { return false; }
  std::size_t finished_total() const override { return done[0] + done[1] + done[2]; }
  std::size_t total() const override { return 30; }
  bool complete() const override { return false; }
  bool deadlocked() const override { return false; }
};

// Bug: a lookahead run on the LoRR game problem did not reproduce in lock-step (seed 0: 356 068.5
// then 359 289.7 s of waiting): each report reached the execution as it arrived, and what a
// switchable execution decides depends on the order. Now a tick's progress reaches it once it
// adds up, in robot order, each robot's newest report once, whatever order and split it came in.
TEST(RunSupervisor, LockstepProgressOrderDidNotReproduceALookaheadRun) {
  const std::vector<std::vector<ProgressEvent>> arrivals = {
      {{2, kRun, 0}, {0, kRun, 0}, {0, kRun, 1}, {1, kRun, 2}},
      {{1, kRun, 2}, {0, kRun, 0}, {2, kRun, 0}, {0, kRun, 1}},
      {{0, kRun, 1}, {2, kRun, 0}, {1, kRun, 0}, {1, kRun, 2}}};
  for (const bool tick_first : {true, false}) {
    for (const auto& arrival : arrivals) {
      RecordingExecution exec;
      FakeWriter out;
      RunSupervisor sup(exec, lockstep_config(), out);
      sup.start(0);
      sup.on_clock({kRun, 0, 0.0, 0, false}, 0);
      if (tick_first) sup.on_clock({kRun, 1, 0.1, 6, false}, 0);
      for (std::size_t i = 0; i < arrival.size(); ++i) {
        sup.on_progress(arrival[i], 0);
        if (i + 1 < arrival.size()) {
          EXPECT_TRUE(exec.calls.empty()) << "taken before it adds up";
        }
      }
      if (!tick_first) sup.on_clock({kRun, 1, 0.1, 6, false}, 0);
      using Call = std::pair<uint32_t, int64_t>;
      EXPECT_EQ(exec.calls, (std::vector<Call>{{0, 1}, {1, 2}, {2, 0}}));
      ASSERT_EQ(out.answers.size(), 2u);
      EXPECT_EQ(out.answers[1].tick, 1u);
      sup.on_progress({0, kRun, 0}, 0);  // a stale report after its tick: nothing
      EXPECT_EQ(exec.calls.size(), 3u);
    }
  }
}

}  // namespace
}  // namespace smart::monitor
