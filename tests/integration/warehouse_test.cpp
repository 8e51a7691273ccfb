// SMART's 500-robot warehouse plan (scen_1_paths.txt: (row,col), untimed) executed to success.
// About 790 s of sim time: roughly 75 s of wall time on 2 cores (label `long`).
#include <gtest/gtest.h>

#include "support/monitor_fixtures.hpp"
#include "support/smart_process.hpp"

namespace smart::test {
namespace {

using namespace std::chrono_literals;

TEST(Warehouse, SmartFiveHundredRobotPlanSucceedsWithoutCollisions) {
  const auto b = benchmarks_dir();
  ASSERT_TRUE(std::filesystem::exists(b)) << smart::test::no_benchmarks(b);
  const auto r =
      run_smart({"run", "--map", (b / "maps/warehouse-10-20-10-2-1.map").string(), "--scen",
                 (b / "scens/warehouse-10-20-10-2-1-random-1.scen").string(), "--plan",
                 (b / "smart-examples/scen_1_paths.txt").string(), "--axis", "rowcol", "--domain",
                 std::to_string(kRunWarehouse500), "--no-progress"},
                600s, "run_500");
  ASSERT_EQ(r.code, 0) << r.out;
  const auto j = r.last_json();
  EXPECT_TRUE(j["success"].get<bool>());
  EXPECT_EQ(j["robots"], 500);
  EXPECT_EQ(j["collisions"], 0);
  EXPECT_EQ(j["finished_actions"], j["total_actions"]);
  EXPECT_EQ(j["plan"]["soc"], 66548.0);
}

}  // namespace
}  // namespace smart::test
