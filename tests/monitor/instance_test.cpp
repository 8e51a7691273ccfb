#include "smart/monitor/instance.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "smart/grid/problem.hpp"
#include "support/monitor_fixtures.hpp"

namespace smart::monitor {
namespace {

using ::testing::HasSubstr;

InstanceOptions smart_example(const std::string& plan, AxisOrder axis) {
  const auto b = test::benchmarks_dir();
  InstanceOptions o;
  if (plan.starts_with("scen_1")) {
    o.map = b / "maps/warehouse-10-20-10-2-1.map";
    o.scen = b / "scens/warehouse-10-20-10-2-1-random-1.scen";
  } else {
    o.map = b / "maps/random-32-32-20.map";
    o.scen = b / "scens/random-32-32-20-random-1.scen";
  }
  o.plan = b / "smart-examples" / plan;
  o.read.axis = axis;
  return o;
}

class SmartExamples : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(std::filesystem::exists(test::benchmarks_dir()))
        << smart::test::no_benchmarks(test::benchmarks_dir());
  }
};

// SOC and makespan as found by the independent checker in smart-examples/PROVENANCE.md.
TEST_F(SmartExamples, EveryExamplePlanLoadsWithTheDocumentedCosts) {
  struct Expected {
    const char* plan;
    AxisOrder axis;
    std::size_t robots;
    double soc, makespan;
  };
  for (const auto& e : {Expected{"example_paths_xy.txt", AxisOrder::kXY, 50, 1241, 48},
                        Expected{"example_paths_yx.txt", AxisOrder::kRowCol, 50, 1241, 48},
                        Expected{"scen_1_paths.txt", AxisOrder::kRowCol, 500, 66548, 278},
                        Expected{"scen_1_1000_paths.txt", AxisOrder::kRowCol, 1000, 133391, 312}}) {
    const auto in = load_instance(smart_example(e.plan, e.axis));
    EXPECT_EQ(in.plan.paths.size(), e.robots) << e.plan;
    EXPECT_DOUBLE_EQ(in.stats.soc, e.soc) << e.plan;
    EXPECT_DOUBLE_EQ(in.stats.makespan, e.makespan) << e.plan;
    EXPECT_EQ(in.adg.stats.nodes, in.actions.actions.size());
    EXPECT_LT(in.adg.stats.type2, in.adg.stats.type2_all_pairs) << e.plan;
  }
}

TEST_F(SmartExamples, AgentsTakesTheFirstNRobots) {
  auto o = smart_example("scen_1_paths.txt", AxisOrder::kRowCol);
  o.agents = 100;
  const auto in = load_instance(o);
  EXPECT_EQ(in.plan.paths.size(), 100u);
  EXPECT_EQ(in.scen.agents.size(), 100u);
  o.agents = 501;
  EXPECT_THROW(load_instance(o), InputError);
}

TEST_F(SmartExamples, WrongAxisIsRejectedWithAHint) {
  try {
    load_instance(smart_example("scen_1_paths.txt", AxisOrder::kXY));
    FAIL();
  } catch (const InputError& e) {
    EXPECT_THAT(e.problems()[0].message, HasSubstr("pass --axis rowcol"));
  }
}

TEST_F(SmartExamples, MissingFileIsAnInputError) {
  auto o = smart_example("example_paths_xy.txt", AxisOrder::kXY);
  o.plan = "/nonexistent/plan.txt";
  EXPECT_THROW(load_instance(o), InputError);
}

}  // namespace
}  // namespace smart::monitor
