// A whole run over a lossy link (the protocol-loss-test QoS profile drops 20 % of every
// process's sent packets): no action is lost or duplicated, and in lock-step the transport's
// losses change no number; a modelled lossy link (sim-lossy-wifi), whose losses cost sim time,
// still succeeds, later.
#include <gtest/gtest.h>

#include "support/smart_process.hpp"

namespace smart::test {
namespace {

using namespace std::chrono_literals;

TEST(LossyRun, TwentyPercentPacketLossChangesNothingInLockStep) {
  const auto map = temp_file("lossy.map").string();
  const auto scen = temp_file("lossy.scen").string();
  const auto plan = temp_file("lossy.plan").string();
  ASSERT_EQ(run_smart({"gen-map", "empty", "--width", "9", "--height", "9", "--out", map}, 30s,
                      "lossy_map")
                .code,
            0);
  ASSERT_EQ(run_smart({"gen-scen", "--map", map, "--agents", "8", "--seed", "4", "--out", scen},
                      30s, "lossy_scen")
                .code,
            0);
  ASSERT_EQ(
      run_smart({"plan", "--map", map, "--scen", scen, "--out", plan}, 60s, "lossy_plan").code, 0);
  auto run = [&](const std::string& qos, int domain) {
    std::vector<std::string> args{"run",
                                  "--map",
                                  map,
                                  "--scen",
                                  scen,
                                  "--plan",
                                  plan,
                                  "--axis",
                                  "xy",
                                  "--qos",
                                  qos,
                                  "--domain",
                                  std::to_string(domain),
                                  "--no-progress"};
    const auto r = run_smart(args, 120s, "lossy_run_" + qos);
    EXPECT_EQ(r.code, 0) << qos << ":\n" << r.out;
    return r.last_json();
  };
  const auto clean = run("lan", kLossyRunClean);
  const auto lossy = run("protocol-loss-test", kLossyRun);
  ASSERT_TRUE(lossy["success"].get<bool>()) << lossy.dump(2);
  EXPECT_EQ(lossy["finished_actions"], lossy["total_actions"]);
  EXPECT_EQ(lossy["rejected_progress"], 0);  // no duplicated or out-of-order progress accepted
  EXPECT_EQ(lossy["collisions"], 0);
  for (const char* key : {"aet_s", "makespan_s", "sim_time_s", "finished_actions", "stops",
                          "min_separation_m", "waiting_time_s"}) {
    EXPECT_EQ(lossy[key], clean[key]) << key;
  }
  // The modelled link: the same run, its losses and delays now on the sim clock.
  const auto modelled = run("sim-lossy-wifi", kLossyRun);
  EXPECT_TRUE(modelled["success"].get<bool>()) << modelled.dump(2);
  EXPECT_EQ(modelled["collisions"], 0);
  EXPECT_GT(modelled["makespan_s"].get<double>(), clean["makespan_s"].get<double>());
  for (const auto& f : {map, scen, plan}) std::filesystem::remove(f);
}

}  // namespace
}  // namespace smart::test
