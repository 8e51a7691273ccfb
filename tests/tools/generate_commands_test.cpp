// `smart plan` as a user runs it: the built-in planner, then plan LNS with the flags it was
// given (a real process; the plan file checked by `smart check-plan`).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "support/monitor_fixtures.hpp"
#include "support/smart_process.hpp"

namespace smart::test {
namespace {

using namespace std::chrono_literals;
using ::testing::HasSubstr;

std::vector<std::string> plan_args(const std::filesystem::path& out) {
  const auto b = benchmarks_dir();
  return {"plan",
          "--map",
          (b / "maps/random-32-32-20.map").string(),
          "--scen",
          (b / "scens/random-32-32-20-random-1.scen").string(),
          "--agents",
          "60",
          "--algorithm",
          "lacam",
          "--out",
          out.string()};
}

// LaCAM's plan, then two passes of neighbourhoods of four robots with at most 2000 expansions
// each: the output says what ran, the sum of costs fell by what LNS saved, and the plan is valid.
TEST(PlanCommand, LnsRunsWithTheNeighbourhoodAndExpansionsItIsGiven) {
  ASSERT_TRUE(std::filesystem::exists(benchmarks_dir()))
      << smart::test::no_benchmarks(benchmarks_dir());
  const auto plain = temp_file("lacam.txt"), improved = temp_file("lacam-lns.txt");
  const auto a = run_smart(plan_args(plain), 60s, "plan_lacam");
  ASSERT_EQ(a.code, 0) << a.out;
  auto args = plan_args(improved);
  args.insert(args.end(),
              {"--lns-passes", "2", "--lns-neighbourhood", "4", "--lns-expansions", "2000"});
  const auto b = run_smart(args, 60s, "plan_lns");
  ASSERT_EQ(b.code, 0) << b.out;
  const auto j = b.last_json();
  EXPECT_EQ(j["lns_passes"], 2);
  EXPECT_EQ(j["lns_neighbourhood"], 4);
  EXPECT_EQ(j["lns_expansions"], 2000);
  EXPECT_GT(j["lns_saved"].get<int>(), 0);
  EXPECT_DOUBLE_EQ(j["soc"].get<double>(),
                   a.last_json()["soc"].get<double>() - j["lns_saved"].get<double>());
  const auto c =
      run_smart({"check-plan", "--map", (benchmarks_dir() / "maps/random-32-32-20.map").string(),
                 "--scen", (benchmarks_dir() / "scens/random-32-32-20-random-1.scen").string(),
                 "--plan", improved.string(), "--axis", "xy", "--agents", "60"},
                60s, "plan_check");
  EXPECT_EQ(c.code, 0) << c.out;
}

TEST(PlanCommand, AnLnsNeighbourhoodOrBudgetOutOfRangeIsBadInput) {
  const auto out = temp_file("never.txt");
  for (const auto& [flag, value] : std::vector<std::pair<std::string, std::string>>{
           {"--lns-neighbourhood", "65"}, {"--lns-expansions", "10"}}) {
    auto args = plan_args(out);
    args.insert(args.end(), {flag, value});
    const auto r = run_smart(args, 60s, "plan_bad", true);
    EXPECT_EQ(r.code, 2) << r.out;
    EXPECT_THAT(r.out, HasSubstr(flag)) << r.out;
  }
}

}  // namespace
}  // namespace smart::test
