// `smart run`'s second opinion: a success stands only when the sim hosts' own reports agree.
#include "smart/monitor/sim_reports.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace smart::monitor {
namespace {

using ::testing::HasSubstr;

MonitorResult success(uint64_t robot_contacts = 0, uint64_t wall_contacts = 0) {
  MonitorResult r;
  r.outcome = Outcome::kSuccess;
  r.robot_contacts = robot_contacts;
  r.wall_contacts = wall_contacts;
  return r;
}

results::SimReport report(uint64_t robot, uint64_t wall, bool ok = true) {
  results::SimReport s;
  s.ok = ok;
  s.robot_contacts = robot;
  s.wall_contacts = wall;
  s.error = ok ? "" : "stopped by signal";
  return s;
}

TEST(SimReports, ShardsThatAddUpToWhatTheMonitorWasToldLeaveTheSuccess) {
  auto r = success(0, 0);
  apply_sim_reports(r, {report(0, 0), report(0, 0)});
  EXPECT_EQ(r.outcome, Outcome::kSuccess);
  EXPECT_TRUE(r.error.empty());
}

// Issue 25: the monitor was told 0 collisions by a forged status; sim-0.json counted 7 and 1.
TEST(SimReports, CollisionsTheMonitorWasNotToldOfMakeTheRunUnverified) {
  auto r = success(0, 0);
  apply_sim_reports(r, {report(4, 0), report(3, 1)});
  EXPECT_EQ(r.outcome, Outcome::kUnverified);
  EXPECT_FALSE(r.success());
  EXPECT_THAT(r.error, HasSubstr("own reports count 7 robot-robot and 1 robot-wall collisions, "
                                 "but the status the monitor received said 0 and 0"));
}

TEST(SimReports, AMissingOrFailedReportMakesASuccessUnverifiedNamingTheHost) {
  auto missing = success();
  apply_sim_reports(missing, {report(0, 0), std::string("sim-1.json: no sim report")});
  EXPECT_EQ(missing.outcome, Outcome::kUnverified);
  EXPECT_THAT(missing.error, HasSubstr("sim host 1 left no readable report (sim-1.json"));
  auto failed = success();
  apply_sim_reports(failed, {report(0, 0, false)});
  EXPECT_THAT(failed.error, HasSubstr("sim host 0 reports a failure: stopped by signal"));
}

TEST(SimReports, AFailedRunNeedsNoSecondOpinion) {
  MonitorResult r;
  r.outcome = Outcome::kDeadlock;
  r.error = "deadlock";
  apply_sim_reports(r, {std::string("gone")});
  EXPECT_EQ(r.outcome, Outcome::kDeadlock);
  EXPECT_EQ(r.error, "deadlock");
}

}  // namespace
}  // namespace smart::monitor
