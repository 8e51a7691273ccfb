// examples/lab-7-jetbots end to end, as a lab would run it without robots: its script plans the
// lab, runs one real-time trial with 7 `smart agent --i2c emulated --emulate-realistic`
// processes at 40 Hz (motor dead band and lag, Vicon latency and noise) and the same plan in the
// Simbody sim on 0.3 m cells, and writes the results table. Real processes, own domain.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "support/smart_process.hpp"

namespace smart::test {
namespace {

using namespace std::chrono_literals;

TEST(LabExample, SevenEmulatedJetbotsCompleteTheLabPlanAndTheTableIsWritten) {
  const auto out = temp_file("lab_example");
  const auto script = std::string(SMART_SOURCE_DIR) + "/examples/lab-7-jetbots/run-emulated.sh";
  common::ChildProcess run({"/usr/bin/env", "SMART=" + smart_exe().string(), "/bin/sh", script, "1",
                            out.string(), std::to_string(kLabExample)},
                           temp_file("lab_example.log"));
  ASSERT_EQ(run.wait(110s).value_or(-1), 0) << slurp(temp_file("lab_example.log"));
  std::istringstream trials(slurp(out / "trials.csv"));
  std::string header, row;
  std::getline(trials, header);
  ASSERT_TRUE(std::getline(trials, row)) << slurp(out / "trials.csv");
  std::vector<std::string> f;
  std::stringstream cells(row);
  for (std::string c; std::getline(cells, c, ',');) f.push_back(c);
  ASSERT_EQ(f.size(), 8u) << row;
  EXPECT_EQ(f[3], "True") << row;
  EXPECT_EQ(f[4], f[5]) << "every action finished: " << row;
  EXPECT_EQ(f[5], "108");
  // On the paper's 0.3 m cells the emulated robots' reported poses never overlap (regression:
  // with half-cell locations the sim saw 5 contacts; run_test.cpp RunWideRobots).
  EXPECT_EQ(f[6], "0") << row;
  EXPECT_GT(std::stod(f[7]), 0.0) << row;
  const auto sim = summary_in(slurp(out / "sim.json"));
  EXPECT_TRUE(sim["success"].get<bool>());
  EXPECT_EQ(sim["collisions"], 0);
  // Real robots (emulated) are slower than the ideal sim: lag, dead band, noisy poses.
  EXPECT_GT(std::stod(f[1]), sim["aet_s"].get<double>());
  EXPECT_NE(slurp(out / "table.md").find("7 emulated JetBots"), std::string::npos);
  std::filesystem::remove_all(out);
  std::filesystem::remove(temp_file("lab_example.log"));
}

}  // namespace
}  // namespace smart::test
