#include "smart/record/export.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

#include "record_test_files.hpp"

namespace smart::record {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

class ExportMcap : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::fresh_test_dir("smart_export_");
    write("tiny.map", "type octile\nheight 2\nwidth 3\nmap\n...\n.@.\n");
    write("summary.json", R"({"robots": 2, "cell_m": 1.0, "run_id": 5, "files": {"map": ")" +
                              (dir_ / "tiny.map").string() + R"("}})");
    write("states.csv",
          "t_s,robot,x_m,y_m,yaw_rad,v_mps,omega_radps,left_mps,right_mps,queue\n"
          "0.5,0,0,0,0,0,0,0,0,1\n0.5,1,2,0,0,0,0,0,0,1\n1,0,1,0,0,0,0,0,0,0\n");
  }
  void TearDown() override { fs::remove_all(dir_); }
  void write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
  }
  std::string error_of(const fs::path& out) {
    try {
      (void)export_mcap(dir_, out, {});
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  }
  fs::path dir_;
};

TEST_F(ExportMcap, WritesTheMapStatesAndFleetOfAResultsFolder) {
  const auto report = export_mcap(dir_, dir_ / "run.mcap", {});
  // map, 3 RobotState, PoseArray + TFMessage at 0.5 and at 1.
  EXPECT_EQ(report.messages, 1u + 3u + 4u);
  EXPECT_EQ(report.robots, 2u);
  EXPECT_EQ(report.bytes, fs::file_size(dir_ / "run.mcap"));
  EXPECT_FALSE(fs::exists(dir_ / "run.mcap.part"));
  EXPECT_TRUE(report.notes.empty());
}

TEST_F(ExportMcap, ADamagedStatesRowIsNamedByLineAndLeavesNoFile) {
  write("states.csv", "t_s,robot,x_m,y_m,yaw_rad\n0.5,0,0,0,0\n0.5,1,2\n");
  EXPECT_THAT(error_of(dir_ / "run.mcap"), HasSubstr("states.csv:3: not a state row"));
  EXPECT_FALSE(fs::exists(dir_ / "run.mcap"));
  EXPECT_FALSE(fs::exists(dir_ / "run.mcap.part"));
}

TEST_F(ExportMcap, ARobotOutsideTheFleetIsNamed) {
  write("states.csv", "t_s,robot,x_m,y_m,yaw_rad\n0.5,4,0,0,0\n");
  EXPECT_THAT(error_of(dir_ / "run.mcap"),
              HasSubstr("states.csv:2: recording: a state row names robot 4 but the fleet has 2"));
}

TEST_F(ExportMcap, AMissingMapOrSummaryIsNamedWithWhatToDo) {
  fs::remove(dir_ / "tiny.map");
  EXPECT_THAT(error_of(dir_ / "run.mcap"), HasSubstr("put it back where summary.json's files.map"));
  fs::remove(dir_ / "summary.json");
  EXPECT_THAT(error_of(dir_ / "run.mcap"), HasSubstr("summary.json: not found"));
}

// "robots" was read with get<size_t>: 1e30 was a cast past its range (undefined), -1 a fleet of
// 2^64 - 1 robots to allocate.
TEST_F(ExportMcap, RegressionARobotCountThatIsNoWholeNumberIsNamedNotCast) {
  for (const std::string bad : {"1e30", "-1", "2.5", "\"two\"", "20000000"}) {
    write("summary.json", R"({"robots": )" + bad + "}");
    EXPECT_THAT(error_of(dir_ / "run.mcap"),
                ::testing::AllOf(HasSubstr("summary.json: \"robots\" is "),
                                 HasSubstr("it must be the run's robot count")))
        << bad;
  }
  write("summary.json", "[1]");
  EXPECT_THAT(error_of(dir_ / "run.mcap"), HasSubstr("\"robots\" is missing"));
}

TEST_F(ExportMcap, APlanThatCannotBeReadAgainIsANoteNotAFailure) {
  write("summary.json",
        R"({"robots": 2, "files": {"map": ")" + (dir_ / "tiny.map").string() +
            R"(", "plan": "/nonexistent/plan.txt", "scen": "/nonexistent/s.scen"}})");
  const auto report = export_mcap(dir_, dir_ / "run.mcap", {});
  ASSERT_EQ(report.notes.size(), 3u);
  EXPECT_THAT(report.notes[0], HasSubstr("plans and markers not recorded"));
  // Nor can they be attached for the viewer (import.hpp).
  EXPECT_THAT(report.notes[1], HasSubstr("the run's scen /nonexistent/s.scen is not attached"));
  EXPECT_THAT(report.notes[2], HasSubstr("the run's plan /nonexistent/plan.txt is not attached"));
}

}  // namespace
}  // namespace smart::record
