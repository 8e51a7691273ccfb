#include "smart/record/live_recording.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "record_test_files.hpp"
#include "smart/record/export.hpp"

namespace smart::record {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

using test::slurp;

// Robot 0 drives (1,0) -> (2,0); robot 1 follows into (1,0) a step later: a 4x1 corridor run,
// its files on disk as `smart run` would have them.
class LiveRecordingTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::fresh_test_dir("smart_live_");
    fs::create_directories(dir_ / "results");
    in_ = test::corridor_instance(
        dir_, "Agent 0:(1,0,0)->(2,0,1)->(2,0,2)\nAgent 1:(0,0,0)->(0,0,1)->(1,0,2)\n");
    write(
        "results/summary.json",
        R"({"robots": 2, "cell_m": 1.0, "run_id": 9, "plan": {"axis": "xy"}, "files": {"map": ")" +
            (dir_ / "m.map").string() + R"(", "scen": ")" + (dir_ / "m.scen").string() +
            R"(", "plan": ")" + (dir_ / "p.txt").string() + R"("}})");
  }
  void TearDown() override { fs::remove_all(dir_); }
  void write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
  }
  LiveRecordingSetup setup() {
    return {dir_ / "live.mcap", {}, 9, &in_, 1.0, 0.2 * 1.0};  // export's radius without a robot
  }
  // The rows as the run's files hold them, for the export.
  void write_results(const std::vector<results::StateRow>& states,
                     const std::vector<results::ActionRow>& actions) {
    std::string s(results::kStatesHeader), a(results::kActionsHeader);
    s += '\n';
    a += '\n';
    for (const auto& r : states) results::append_row(s, r);
    for (const auto& r : actions) results::append_row(a, r);
    write("results/states.csv", s);
    write("results/actions.csv", a);
  }
  fs::path dir_;
  monitor::Instance in_;
};

results::StateRow at(double t, uint32_t robot, double x) {
  return {t, robot, x, 0.0, 0.1234567890123, 0.5, 0, 0.25, 0.75, 1};
}

// A row as the monitor's states.csv writer hands it over.
void tell(LiveRecording& live, const results::StateRow& row) {
  std::string line;
  results::append_row(line, row);
  live.state(line);
}

TEST_F(LiveRecordingTest, IsTheFileTheExportMakesOfTheRunsResults) {
  // Rows as a monitor hears them: progress before and after states of its time (within the lag),
  // numbers with more digits than the files keep.
  const std::vector<results::StateRow> states = {
      at(0.5, 0, 1), at(0.5, 1, 0), at(1.0, 0, 1.5000000000001),
      at(1.0, 1, 0), at(1.5, 0, 2), at(1.5, 1, 0.5),
      at(2.0, 0, 2), at(2.0, 1, 1), at(4.5, 0, 2),
      at(4.5, 1, 1)};
  LiveRecording live(setup());
  tell(live, states[0]);
  tell(live, states[1]);
  live.action_finished(0, 0, 0.7000000000001);
  tell(live, states[2]);
  tell(live, states[3]);
  tell(live, states[4]);
  live.action_finished(1, 0, 1.2);  // told after states at 1.5: within the 2 s lag
  live.action_finished(0, 1, 1.2);
  for (std::size_t i = 5; i < 8; ++i) tell(live, states[i]);
  live.action_finished(1, 1, 2.0);  // after the states of its time, 2 s before 4.5
  tell(live, states[8]);
  tell(live, states[9]);
  write_results(states, {{0, 0, results::ActionType::kMove, 0.7000000000001},
                         {0, 1, results::ActionType::kMove, 1.2},
                         {1, 0, results::ActionType::kMove, 1.2},
                         {1, 1, results::ActionType::kMove, 2.0}});
  const auto report = live.finish(dir_ / "results");
  const auto exported = export_mcap(dir_ / "results", dir_ / "export.mcap", {});
  EXPECT_EQ(report.messages, exported.messages);
  EXPECT_EQ(report.bytes, fs::file_size(dir_ / "live.mcap"));
  EXPECT_EQ(slurp(dir_ / "live.mcap"), slurp(dir_ / "export.mcap"));
  EXPECT_FALSE(fs::exists(dir_ / "live.mcap.part"));
}

TEST_F(LiveRecordingTest, ProgressHeardLaterThanTheLagIsRecordedNotLost) {
  LiveRecording live(setup());
  tell(live, at(0.5, 0, 1));
  tell(live, at(10, 0, 2));
  live.action_finished(0, 0, 0.7);  // 9.3 s late: the state at 0.5 was written already
  write_results({at(0.5, 0, 1), at(10, 0, 2)}, {});
  const auto report = live.finish(dir_ / "results");
  // map, 2 plans, 2 RobotState, 2 x (PoseArray + TFMessage + MarkerArray), 1 Progress.
  EXPECT_EQ(report.messages, 1u + 2u + 2u + 6u + 1u);
}

TEST_F(LiveRecordingTest, ARowOutsideTheFleetFailsAtFinishAndLeavesNoFile) {
  LiveRecording live(setup());
  tell(live, at(0.5, 5, 1));
  write_results({}, {});
  try {
    (void)live.finish(dir_ / "results");
    ADD_FAILURE() << "finish() took a state of robot 5 in a fleet of 2";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("names robot 5 but the fleet has 2 robots"));
  }
  EXPECT_FALSE(fs::exists(dir_ / "live.mcap"));
  EXPECT_FALSE(fs::exists(dir_ / "live.mcap.part"));
}

TEST_F(LiveRecordingTest, ARunThatEndsWithoutFinishLeavesNoFile) {
  {
    LiveRecording live(setup());
    tell(live, at(0.5, 0, 1));
    EXPECT_TRUE(fs::exists(dir_ / "live.mcap.part"));
  }
  EXPECT_FALSE(fs::exists(dir_ / "live.mcap.part"));
  EXPECT_FALSE(fs::exists(dir_ / "live.mcap"));
}

}  // namespace
}  // namespace smart::record
