// From nothing to an executed plan with only `smart` subcommands, on every generated map kind:
// gen-map -> gen-scen -> plan -> check-plan -> run, and gen-map -> gen-walk -> run.
#include <gtest/gtest.h>

#include "support/smart_process.hpp"

namespace smart::test {
namespace {

using namespace std::chrono_literals;

struct Kind {
  const char* name;
  std::vector<std::string> map_args;
  int robots;
};

TEST(Generated, BuiltInPlannerPlansExecuteToSuccessOnEveryMapKind) {
  const std::vector<Kind> kinds = {
      {"warehouse",
       {"warehouse", "--shelf-rows", "4", "--shelf-cols", "3", "--shelf-length", "5", "--margin",
        "3"},
       12},
      {"random", {"random", "--width", "20", "--height", "20", "--obstacles", "0.2"}, 12},
      {"empty", {"empty", "--width", "12", "--height", "12"}, 12},
      {"maze", {"maze", "--width", "21", "--height", "21", "--corridor", "2"}, 6},
  };
  for (const auto& k : kinds) {
    SCOPED_TRACE(k.name);
    const auto map = temp_file(std::string(k.name) + ".map").string();
    const auto scen = temp_file(std::string(k.name) + ".scen").string();
    const auto plan = temp_file(std::string(k.name) + ".plan").string();
    auto gm = k.map_args;
    gm.insert(gm.begin(), "gen-map");
    gm.insert(gm.end(), {"--out", map, "--seed", "3"});
    ASSERT_EQ(run_smart(gm, 30s, "gen_map").code, 0);
    ASSERT_EQ(run_smart({"gen-scen", "--map", map, "--agents", std::to_string(k.robots), "--seed",
                         "5", "--out", scen},
                        30s, "gen_scen")
                  .code,
              0);
    const auto p = run_smart({"plan", "--map", map, "--scen", scen, "--out", plan}, 60s, "plan");
    ASSERT_EQ(p.code, 0) << p.out;
    EXPECT_EQ(p.last_json()["robots"], k.robots);
    const auto check = run_smart(
        {"check-plan", "--map", map, "--scen", scen, "--plan", plan, "--axis", "xy"}, 30s, "check");
    ASSERT_EQ(check.code, 0) << check.out;
    const auto r = run_smart({"run", "--map", map, "--scen", scen, "--plan", plan, "--axis", "xy",
                              "--domain", std::to_string(kRunGenerated), "--no-progress"},
                             120s, "run_generated");
    ASSERT_EQ(r.code, 0) << r.out;
    const auto j = r.last_json();
    EXPECT_TRUE(j["success"].get<bool>());
    EXPECT_EQ(j["collisions"], 0);
    EXPECT_EQ(j["robots"], k.robots);
    for (const auto& f : {map, scen, plan}) std::filesystem::remove(f);
  }
}

// `smart plan --algorithm pibt`: PIBT's long plans (robots following each other, waits, pushes)
// pass check-plan and execute to success with switchable passing orders; so do LaCAM's, under
// switchable-opt; a bad algorithm is a usage error naming the choices.
TEST(Generated, PibtAndLacamPlansExecuteWithSwitchablePassingOrders) {
  const auto map = temp_file("pibt.map").string(), scen = temp_file("pibt.scen").string(),
             plan = temp_file("pibt.plan").string();
  ASSERT_EQ(run_smart({"gen-map", "random", "--width", "16", "--height", "16", "--obstacles", "0.1",
                       "--seed", "4", "--out", map},
                      30s, "pibt_map")
                .code,
            0);
  ASSERT_EQ(run_smart({"gen-scen", "--map", map, "--agents", "30", "--seed", "4", "--out", scen},
                      30s, "pibt_scen")
                .code,
            0);
  const auto bad =
      run_smart({"plan", "--map", map, "--scen", scen, "--algorithm", "cbs", "--out", plan}, 30s,
                "pibt", true);
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.out.find("'cbs' is not one of pp|pibt|lacam"), std::string::npos) << bad.out;
  // Planned by `algorithm`, run with `execution`: every robot home, no collision.
  const auto plan_and_run = [&](const std::string& algorithm, const std::string& execution,
                                int domain) {
    const auto p =
        run_smart({"plan", "--map", map, "--scen", scen, "--algorithm", algorithm, "--out", plan},
                  60s, algorithm);
    ASSERT_EQ(p.code, 0) << p.out;
    EXPECT_EQ(p.last_json()["algorithm"], algorithm);
    const auto r =
        run_smart({"run", "--map", map, "--scen", scen, "--plan", plan, "--axis", "xy",
                   "--execution", execution, "--domain", std::to_string(domain), "--no-progress"},
                  120s, algorithm + "_run");
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_TRUE(r.last_json()["success"].get<bool>());
    EXPECT_EQ(r.last_json()["collisions"], 0);
    EXPECT_EQ(r.last_json()["robots"], 30);
  };
  plan_and_run("pibt", "switchable", kPibtPlanRun);
  plan_and_run("lacam", "switchable-opt", kLacamPlanRun);
  for (const auto& f : {map, scen, plan}) std::filesystem::remove(f);
}

// Random walks (with rotation cycles round 2x2 blocks) of 50 robots on an empty 10x10 map: the
// plan and scenario gen-walk writes pass check-plan and execute without a collision; the same seed
// gives the same files.
TEST(Generated, RandomWalksOfAnySizeAreWrittenAndExecute) {
  const auto map = temp_file("walk.map").string();
  const auto scen = temp_file("walk.scen").string(), scen2 = temp_file("walk2.scen").string();
  const auto plan = temp_file("walk.plan").string(), plan2 = temp_file("walk2.plan").string();
  ASSERT_EQ(run_smart({"gen-map", "empty", "--width", "10", "--height", "10", "--out", map}, 30s,
                      "gen_walk_map")
                .code,
            0);
  const std::vector<std::string> walk{
      "gen-walk", "--map",  map, "--robots",           "50", "--steps",
      "30",       "--seed", "7", "--move-probability", "0.5"};
  auto first = walk, second = walk;
  first.insert(first.end(), {"--out", plan, "--out-scen", scen});
  second.insert(second.end(), {"--out", plan2, "--out-scen", scen2});
  const auto w = run_smart(first, 30s, "gen_walk");
  ASSERT_EQ(w.code, 0) << w.out;
  EXPECT_EQ(w.last_json()["robots"], 50);
  EXPECT_GT(w.last_json()["rotation_cycles"].get<int>(), 0);
  ASSERT_EQ(run_smart(second, 30s, "gen_walk2").code, 0);
  EXPECT_EQ(slurp(plan), slurp(plan2));
  EXPECT_EQ(slurp(scen), slurp(scen2));
  const auto check = run_smart(
      {"check-plan", "--map", map, "--scen", scen, "--plan", plan, "--axis", "xy"}, 30s, "check");
  ASSERT_EQ(check.code, 0) << check.out;
  const auto r = run_smart({"run", "--map", map, "--scen", scen, "--plan", plan, "--axis", "xy",
                            "--domain", std::to_string(kRunWalk), "--no-progress"},
                           120s, "run_walk");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_TRUE(r.last_json()["success"].get<bool>());
  EXPECT_EQ(r.last_json()["collisions"], 0);
  for (const auto& f : {map, scen, scen2, plan, plan2}) std::filesystem::remove(f);
}

}  // namespace
}  // namespace smart::test
