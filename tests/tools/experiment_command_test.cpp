// `smart experiment` as a command: flags reach the campaign and its errors become exit codes
// (the campaign itself: tests/experiment/campaign_test.cpp).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

#include "support/smart_process.hpp"

namespace smart::test {
namespace {

using namespace std::chrono_literals;
using ::testing::HasSubstr;
namespace fs = std::filesystem;

TEST(ExperimentCommand, ABadSpecExitsWithBadInputNamingTheLine) {
  const auto spec = temp_file("experiment-command.yaml");
  std::ofstream(spec) << "name: x\nmaps: [a.map]\nscens: [a.scen]\nagents: [1]\n"
                         "plan: {planner: builtin}\nclock: fast\n";
  const auto r = run_smart(
      {"experiment", spec.string(), "--out", temp_file("experiment-command-out").string()}, 60s,
      "experiment_command", true);
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_THAT(r.out, HasSubstr(spec.string() + ":6: clock"));
  fs::remove(spec);
}

TEST(ExperimentCommand, PlottingAFolderWithoutResultsExitsWithBadInput) {
  const auto dir = temp_file("experiment-command-empty");
  fs::create_directories(dir);
  const auto r = run_smart({"experiment", "plot", dir.string()}, 60s, "experiment_plot", true);
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_THAT(r.out, HasSubstr("no results.csv in " + dir.string()));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace smart::test
