#include "smart/record/import.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <limits>
#include <sstream>

#include "record_test_files.hpp"
#include "smart/dds/topics.hpp"
#include "smart/record/cdr.hpp"
#include "smart/record/export.hpp"

namespace smart::record {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

using test::slurp;

class ImportMcap : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::fresh_test_dir("smart_import_");
    fs::create_directories(dir_ / "run");
  }
  void TearDown() override { fs::remove_all(dir_); }
  void write(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }
  std::string error_of(const fs::path& mcap, const ImportOptions& o = {}) {
    try {
      (void)import_mcap(mcap, dir_ / "back", o);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  }
  // A recording made by hand: the given attachments and RobotStates.
  fs::path hand_made(const std::vector<std::pair<std::string, std::string>>& attachments,
                     const std::vector<smart_msg_RobotState>& states, bool state_channel = true) {
    StringSink sink;
    McapWriter w(sink, {});
    const auto s = w.add_schema("smart::msg::RobotState", "omgidl", "");
    const auto c = w.add_channel({s, state_channel ? smart_msg_TOPIC_STATE : "other", "cdr"});
    for (const auto& [name, data] : attachments) w.attach(name, "text/plain", data);
    for (const auto& st : states) w.write(c, 1, 1, cdr_bytes(st));
    w.finish();
    fs::path p = dir_ / "hand.mcap";
    write(p, sink.bytes());
    return p;
  }
  fs::path dir_;
};

TEST_F(ImportMcap, AnExportedRunComesBackAsItsResultsFolder) {
  const fs::path run = dir_ / "run";
  write(dir_ / "tiny.map", "type octile\nheight 2\nwidth 3\nmap\n...\n.@.\n");
  write(run / "summary.json", R"({"robots": 2, "cell_m": 1.0, "run_id": 5, "files": {"map": ")" +
                                  (dir_ / "tiny.map").string() + R"("}})");
  const std::string states =
      "t_s,robot,x_m,y_m,yaw_rad,v_mps,omega_radps,left_mps,right_mps,queue\n"
      "0.5,0,0,0,0,0,0,0,0,1\n0.5,1,2,0,1.570796327,0.1234567891,0,-0.5,0.5,1\n"
      "1,0,1,0,0,0,0,0,0,0\n";
  write(run / "states.csv", states);
  write(run / "actions.csv", "robot,action,type,finish_time_s\n0,0,move,1\n1,0,move,\n");
  (void)export_mcap(run, dir_ / "run.mcap", {});

  const auto report = import_mcap(dir_ / "run.mcap", dir_ / "back");
  EXPECT_EQ(report.states, 3u);
  EXPECT_TRUE(report.notes.empty());
  EXPECT_EQ(slurp(dir_ / "back" / "states.csv"), states);
  EXPECT_EQ(slurp(dir_ / "back" / "actions.csv"), slurp(run / "actions.csv"));
  const fs::path map = dir_ / "back" / "inputs" / "map" / "tiny.map";
  EXPECT_EQ(slurp(map), slurp(dir_ / "tiny.map"));
  EXPECT_THAT(slurp(dir_ / "back" / "summary.json"), HasSubstr(fs::absolute(map).string()));
  EXPECT_THAT(slurp(dir_ / "back" / "summary.json"), HasSubstr("\"run_id\": 5"));
}

TEST_F(ImportMcap, AttachmentNamesCannotLeaveTheFolder) {
  const auto mcap = hand_made({{"summary.json", "{}"},
                               {"../evil", "x"},
                               {"input/map/../../evil", "y"},
                               {"input/secrets/a", "z"}},
                              {smart_msg_RobotState{}});
  const auto report = import_mcap(mcap, dir_ / "back");
  EXPECT_FALSE(fs::exists(dir_ / "evil"));
  EXPECT_EQ(slurp(dir_ / "back" / "inputs" / "map" / "_.._evil"), "y");
  EXPECT_FALSE(fs::exists(dir_ / "back" / "inputs" / "secrets"));
  ASSERT_EQ(report.notes.size(), 2u);
  EXPECT_THAT(report.notes[0], HasSubstr("attachment '_evil' skipped"));
}

TEST_F(ImportMcap, ARecordingMadeElsewhereIsRefusedByName) {
  EXPECT_THAT(error_of(hand_made({}, {smart_msg_RobotState{}})),
              HasSubstr("hand.mcap: no summary.json attachment; it was not recorded by"));
  EXPECT_THAT(error_of(hand_made({{"summary.json", "{}"}}, {}, false)),
              HasSubstr("no smart/state channel"));
  EXPECT_THAT(error_of(hand_made({{"summary.json", "[1]"}}, {smart_msg_RobotState{}})),
              HasSubstr("summary.json is not a JSON object"));
  EXPECT_THAT(error_of(hand_made({{"summary.json", "{}"}, {"summary.json", "{}"}}, {})),
              HasSubstr("attachment summary.json appears twice"));
}

TEST_F(ImportMcap, AStateThatIsNotFiniteOrNotARobotStateIsNamed) {
  smart_msg_RobotState s{};
  s.robot_id = 3;
  s.pose.x_m = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THAT(error_of(hand_made({{"summary.json", "{}"}}, {smart_msg_RobotState{}, s})),
              HasSubstr("smart/state message 2 (log time 1 ns): robot 3 has a number that is not "
                        "finite"));
  StringSink sink;
  McapWriter w(sink, {});
  const auto c = w.add_channel(
      {w.add_schema("smart::msg::RobotState", "omgidl", ""), smart_msg_TOPIC_STATE, "cdr"});
  w.attach("summary.json", "application/json", "{}");
  w.write(c, 1, 1, std::string("\x00\x01\x00\x00short", 9));
  w.finish();
  write(dir_ / "short.mcap", sink.bytes());
  EXPECT_THAT(error_of(dir_ / "short.mcap"), HasSubstr("the CDR payload does not hold this type"));
}

TEST_F(ImportMcap, StatesBeyondTheLimitAreRefused) {
  const auto mcap = hand_made({{"summary.json", "{}"}}, std::vector<smart_msg_RobotState>(100));
  EXPECT_THAT(error_of(mcap, {.limits = {}, .max_states_bytes = 1000}),
              HasSubstr("more than 1000 bytes"));
  EXPECT_EQ(import_mcap(mcap, dir_ / "ok").states, 100u);
}

}  // namespace
}  // namespace smart::record
