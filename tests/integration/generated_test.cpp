// From nothing to an executed plan with only `smart` subcommands, on every generated map kind:
// gen-map -> gen-scen -> plan -> check-plan -> run.
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

}  // namespace
}  // namespace smart::test
