// A campaign as a researcher runs it: a tiny spec of real runs (1 and 2 robots, two repeats), two
// at once, each a real `smart run`; resumed after a cell's result is removed; then its figures.
#include "smart/experiment/campaign.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <atomic>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "support/monitor_fixtures.hpp"
#include "support/smart_process.hpp"

namespace smart::test {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

class Campaign : public ::testing::Test {
 protected:
  void SetUp() override {
    b_ = benchmarks_dir();
    ASSERT_TRUE(fs::exists(b_)) << smart::test::no_benchmarks(b_);
    dir_ = temp_file("experiment");
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path write_spec(const std::string& extra = "") const {
    auto spec = dir_ / "spec.yaml";
    std::ofstream(spec) << "name: tiny\nmaps: [" << (b_ / "maps/random-32-32-20.map").string()
                        << "]\nscens: [" << (b_ / "scens/random-32-32-20-random-1.scen").string()
                        << "]\nagents: [1, 2]\nplan: {file: "
                        << (b_ / "smart-examples/example_paths_xy.txt").string()
                        << ", axis: xy}\nrepeats: 2\n"
                        << extra;
    return spec;
  }
  experiment::CampaignReport run(const fs::path& spec, int domain = kExperiment,
                                 const std::atomic<bool>* stop = nullptr) {
    experiment::CampaignOptions o;
    o.spec = spec;
    o.out = dir_ / "out";
    o.jobs = 2;
    o.first_domain = domain;
    o.smart = smart_exe();
    o.stop = stop;
    log_.str("");
    return experiment::run_campaign(o, log_);
  }
  std::ostringstream log_;
  fs::path b_, dir_;
};

std::vector<std::string> lines_of(const fs::path& p) {
  std::ifstream in(p);
  std::vector<std::string> out;
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

// Regression (2026-12-06): the first id defaulted to 120, a test's own, so a campaign run beside
// `make test` shared that test's discovery traffic. The ids of a campaign of two jobs (the
// documented `--jobs 2`) are now below every test's.
TEST(CampaignDefaults, ItsDefaultDomainsStayBelowEveryTestsOwn) {
  const experiment::CampaignOptions o;
  EXPECT_GE(o.first_domain, 0);
  EXPECT_LT(o.first_domain + 2 - 1, kLowestTestDomain);
}

TEST_F(Campaign, RunsTheGridWritesOneRowPerRunAndResumesWhereItStopped) {
  const auto spec = write_spec();
  auto r = run(spec);
  ASSERT_TRUE(r.complete()) << log_.str();
  EXPECT_EQ(r.runs, 4u);
  EXPECT_EQ(r.with_results, 4u);
  EXPECT_EQ(r.skipped, 0u);
  EXPECT_EQ(r.errors, 0u);
  EXPECT_EQ(r.results, dir_ / "out" / "results.csv");
  const auto rows = lines_of(dir_ / "out" / "results.csv");
  ASSERT_EQ(rows.size(), 5u);
  EXPECT_THAT(rows[0], ::testing::StartsWith("cell,map,scen,agents,robot,qos,uncertainty,repeat,"));
  EXPECT_THAT(rows[0], HasSubstr("aet_s"));
  EXPECT_THAT(rows[1], ::testing::StartsWith("0-random-32-32-20-random-1-n1-footbot-lan-r0,"));
  EXPECT_THAT(rows[4], HasSubstr(",2,footbot,lan,{},1,"));
  for (std::size_t i = 1; i < rows.size(); ++i) EXPECT_THAT(rows[i], HasSubstr(",true,")) << i;
  EXPECT_EQ(lines_of(dir_ / "out" / "results.jsonl").size(), 4u);
  // Resume: a removed result is made again, the others are not touched.
  const auto cells = dir_ / "out" / "cells";
  const auto kept = cells / "0-random-32-32-20-random-1-n1-footbot-lan-r0" / "summary.json";
  const auto kept_time = fs::last_write_time(kept);
  fs::remove(cells / "0-random-32-32-20-random-1-n2-footbot-lan-r1" / "summary.json");
  // And a run stopped before its end (Ctrl-C: its summary written as it ended, outcome
  // "stopped") is no result: no row, and the resumed campaign runs it again.
  const auto stopped = cells / "0-random-32-32-20-random-1-n2-footbot-lan-r0" / "summary.json";
  auto summary = nlohmann::json::parse(slurp(stopped));
  summary["outcome"] = "stopped";
  summary["success"] = false;
  std::ofstream(stopped) << summary.dump();
  const std::atomic<bool> stop_now{true};  // the grid with nothing run: results.csv rewritten
  r = run(spec, kExperiment, &stop_now);
  EXPECT_EQ(r.with_results, 2u);
  EXPECT_FALSE(r.complete());
  EXPECT_EQ(lines_of(dir_ / "out" / "results.csv").size(), 3u);
  r = run(spec);
  ASSERT_TRUE(r.complete()) << log_.str();
  EXPECT_EQ(r.skipped, 2u);
  EXPECT_EQ(r.with_results, 4u);
  EXPECT_EQ(fs::last_write_time(kept), kept_time);
  EXPECT_EQ(nlohmann::json::parse(slurp(stopped))["outcome"], "success");
  EXPECT_EQ(lines_of(dir_ / "out" / "results.csv").size(), 5u);
  // The figures, as PNG, SVG and PDF, and the data they show (tests/experiment/
  // experiment_plot_test.py checks that data against results.csv).
  experiment::plot_campaign(dir_ / "out", {});
  for (const char* name : {"sim_speed", "aet_makespan", "memory", "success"}) {
    const auto png = slurp(dir_ / "out" / "figures" / (std::string(name) + ".png"));
    ASSERT_GT(png.size(), 1000u) << name;
    EXPECT_EQ(png.substr(1, 3), "PNG") << name;
    EXPECT_THAT(slurp(dir_ / "out" / "figures" / (std::string(name) + ".svg")), HasSubstr("<svg"));
    EXPECT_EQ(slurp(dir_ / "out" / "figures" / (std::string(name) + ".pdf")).substr(0, 4), "%PDF");
  }
  const auto shown = nlohmann::json::parse(slurp(dir_ / "out" / "figures" / "figures.json"));
  const auto& aet = shown["figures"]["aet_makespan"]["panels"][0];
  ASSERT_EQ(aet["series"].size(), 1u);               // nothing varies but the fleet size
  EXPECT_EQ(aet["series"][0]["points"][0]["n"], 2);  // two repeats
  EXPECT_EQ(aet["xticklabels"], nlohmann::json::array({"1", "2"}));
  // The table: one row per fleet size, its two repeats folded into one (identical in lock-step).
  const auto table = lines_of(dir_ / "out" / "figures" / "table.md");
  ASSERT_EQ(table.size(), 4u);
  EXPECT_THAT(table[2], HasSubstr("| 1 | example_paths_xy | footbot | lan |"));
  EXPECT_THAT(table[2], HasSubstr("| 2 | 2/2 |"));
}

// Any planner as a command: {map} {scen} {agents} {plan} are filled in (quoted), the plan is
// made once into <out>/plans/ and then executed.
TEST_F(Campaign, APlannerCommandMakesThePlanThatIsRun) {
  const auto spec = dir_ / "command.yaml";
  std::ofstream(spec) << "name: cmd\nmaps: [" << (b_ / "maps/random-32-32-20.map").string()
                      << "]\nscens: [" << (b_ / "scens/random-32-32-20-random-1.scen").string()
                      << "]\nagents: [2]\nplan: {command: \"test -f {map} && test -f {scen} && "
                      << "test {agents} = 2 && cp "
                      << (b_ / "smart-examples/example_paths_xy.txt").string()
                      << " {plan}\", axis: xy}\n";
  const auto r = run(spec, kExperimentCommand);
  ASSERT_TRUE(r.complete()) << log_.str();
  EXPECT_EQ(r.with_results, 1u);
  EXPECT_TRUE(fs::exists(dir_ / "out" / "plans" / "0-n2.txt"));
  const auto row = lines_of(dir_ / "out" / "results.csv").at(1);
  EXPECT_THAT(row, HasSubstr(",command,xy,lockstep,"));
  // The planner's wall seconds follow, kept beside the plan for a resumed campaign.
  const auto runtime = std::stod(row.substr(row.find(",lockstep,adg,") + 14));
  EXPECT_GT(runtime, 0.0);
  EXPECT_LT(runtime, 600.0);
  EXPECT_TRUE(fs::exists(dir_ / "out" / "plans" / "0-n2.txt.runtime_s"));
}

// Regression (found 2026-11-27): a planner's error went to the terminal, and the log the
// message pointed to was empty. Its last lines are in the message now, and in the log.
TEST_F(Campaign, APlannerThatFailsIsNamedWithItsErrorAndNothingRuns) {
  const auto spec = dir_ / "too-many.yaml";
  std::ofstream(spec) << "name: many\nmaps: [" << (b_ / "maps/random-32-32-20.map").string()
                      << "]\nscens: [" << (b_ / "scens/random-32-32-20-random-1.scen").string()
                      << "]\nagents: [5000]\nplan: {planner: builtin}\n";
  const std::string said = "asked for 5000 agents but the file has 409; lower --agents";
  EXPECT_THAT(
      [&] { run(spec, kExperimentPlannerFails); },
      ::testing::ThrowsMessage<std::runtime_error>(::testing::AllOf(
          HasSubstr("planner builtin on 5000 robots of "), HasSubstr("(exit code 2): "),
          HasSubstr(said), HasSubstr("; see " + (dir_ / "out/plans/0-n5000.txt.log").string()))));
  EXPECT_THAT(slurp(dir_ / "out" / "plans" / "0-n5000.txt.log"), HasSubstr(said));
  EXPECT_FALSE(fs::exists(dir_ / "out" / "results.csv"));  // no run
}

// A planner's output is untrusted: one line of 50 000 characters, then failure. The message
// shows how the line ended, cut to 240 characters; the log keeps all of it. (`# {plan}`: the
// spec asks every command to name its plan file.)
TEST_F(Campaign, AFailingPlannersFloodOfOutputIsCutInTheMessage) {
  const auto spec = dir_ / "flood.yaml";
  std::ofstream(spec)
      << "name: flood\nmaps: [" << (b_ / "maps/random-32-32-20.map").string() << "]\nscens: ["
      << (b_ / "scens/random-32-32-20-random-1.scen").string()
      << "]\nagents: [2]\nplan: {command: \"yes x | head -c 100000 | "
      << "tr -d '[:space:]' >&2; echo ' and then it ended' >&2; exit 3 # {plan}\"}\n";
  std::string said;
  try {
    run(spec, kExperimentPlannerFloods);
  } catch (const std::runtime_error& e) {
    said = e.what();
  }
  EXPECT_THAT(said, HasSubstr("(exit code 3): ...xxxx"));
  EXPECT_THAT(said, HasSubstr("xxxx and then it ended; see "));
  EXPECT_LT(said.size(), 800u) << said.substr(0, 300);
  EXPECT_EQ(fs::file_size(dir_ / "out" / "plans" / "0-n2.txt.log"), 50000u + 19u);
}

// Issue 28: a lifelong experiment runs `smart run --tasks random` per cell with its team size,
// planner and seed, and the figures show throughput against team size and over time.
TEST_F(Campaign, ALifelongExperimentMeasuresThroughputOverSeeds) {
  const auto spec = dir_ / "lifelong.yaml";
  std::ofstream(spec) << "name: ll\nlifelong:\n  map: "
                      << (b_ / "maps/random-32-32-20.map").string()
                      << "\n  duration_s: 30\n  task_errands: 1\nagents: [4, 8]\nrepeats: 2\n";
  const auto r = run(spec, kExperimentLifelong);
  ASSERT_TRUE(r.complete()) << log_.str();
  EXPECT_EQ(r.with_results, 4u);
  const auto rows = lines_of(dir_ / "out" / "results.csv");
  ASSERT_EQ(rows.size(), 5u);
  EXPECT_THAT(rows[0], HasSubstr(",clock,execution,replan_period_s,"));
  EXPECT_THAT(rows[0], HasSubstr("lifelong.throughput_per_min"));
  EXPECT_THAT(rows[1], ::testing::StartsWith("0-random-32-32-20-n4-footbot-lan-r0,"
                                             "random-32-32-20,,4,footbot,lan,{},0,builtin,"
                                             "lockstep,adg,1.0,"));
  for (const char* cell :
       {"0-random-32-32-20-n4-footbot-lan-r0", "0-random-32-32-20-n8-footbot-lan-r1"}) {
    const auto summary =
        nlohmann::json::parse(slurp(dir_ / "out" / "cells" / cell / "summary.json"));
    EXPECT_EQ(summary["lifelong"]["duration_s"], 30.0) << cell;
    EXPECT_EQ(summary["lifelong"]["planner"]["via"], "process") << cell;
    EXPECT_TRUE(fs::exists(dir_ / "out" / "cells" / cell / "throughput.csv")) << cell;
  }
  experiment::plot_campaign(dir_ / "out", {});
  const auto shown = nlohmann::json::parse(slurp(dir_ / "out" / "figures" / "figures.json"));
  const auto& tp = shown["figures"]["throughput"]["panels"][0];
  EXPECT_EQ(tp["field"], "lifelong.throughput_per_min");
  ASSERT_EQ(tp["series"].size(), 1u);
  ASSERT_EQ(tp["series"][0]["points"].size(), 2u);  // 4 and 8 robots, each over two seeds
  EXPECT_EQ(tp["series"][0]["points"][1]["x"], 8.0);
  EXPECT_EQ(tp["series"][0]["points"][1]["n"], 2);
  const auto& over_time = shown["figures"]["throughput_time"]["panels"];
  ASSERT_EQ(over_time.size(), 4u);  // tasks finished and last minute's, for 4 and 8 robots
  EXPECT_EQ(over_time[0]["match"]["agents"], "4");
  for (const char* name : {"throughput", "throughput_time"}) {
    EXPECT_EQ(slurp(dir_ / "out" / "figures" / (std::string(name) + ".png")).substr(1, 3), "PNG");
  }
  EXPECT_THAT(slurp(dir_ / "out" / "figures" / "table.md"), HasSubstr("throughput (tasks/min)"));
}

// The commit cut's look-ahead axis reaches smart run: the run's own summary says it kept that
// many actions per robot.
TEST_F(Campaign, ALifelongLookaheadAxisIsPassedToEachRun) {
  const auto spec = dir_ / "lookahead.yaml";
  std::ofstream(spec) << "name: la\nlifelong:\n  map: "
                      << (b_ / "maps/random-32-32-20.map").string()
                      << "\n  duration_s: 10\n  lookahead: [3, 5]\nagents: [4]\n";
  const auto r = run(spec, kExperimentLookahead);
  ASSERT_TRUE(r.complete()) << log_.str();
  EXPECT_EQ(r.with_results, 2u);
  const auto rows = lines_of(dir_ / "out" / "results.csv");
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_THAT(rows[0], HasSubstr(",replan_period_s,lookahead,"));
  for (const auto& [cell, kept] : {std::pair{"0-random-32-32-20-n4-footbot-lan-l3-r0", 3},
                                   std::pair{"0-random-32-32-20-n4-footbot-lan-l5-r0", 5}}) {
    const auto summary =
        nlohmann::json::parse(slurp(dir_ / "out" / "cells" / cell / "summary.json"));
    EXPECT_EQ(summary["lifelong"]["lookahead"], kept) << cell;
  }
}

// A built-in planner with window LNS passes reaches smart run: the run's summary says so.
TEST_F(Campaign, ALifelongPlannersWindowLnsPassesArePassedToItsRuns) {
  const auto spec = dir_ / "lns.yaml";
  std::ofstream(spec) << "name: lns\nlifelong:\n  map: "
                      << (b_ / "maps/random-32-32-20.map").string()
                      << "\n  duration_s: 10\nagents: [6]\nplanners: [{planner: builtin}, "
                         "{name: lns, planner: builtin, window_lns_passes: 1}]\n";
  const auto r = run(spec, kExperimentWindowLns);
  ASSERT_TRUE(r.complete()) << log_.str();
  EXPECT_EQ(r.with_results, 2u);
  for (const auto& [cell, passes] : {std::pair{"0-random-32-32-20-n6-footbot-lan-builtin-r0", 0},
                                     std::pair{"0-random-32-32-20-n6-footbot-lan-lns-r0", 1}}) {
    const auto summary =
        nlohmann::json::parse(slurp(dir_ / "out" / "cells" / cell / "summary.json"));
    EXPECT_EQ(summary["lifelong"]["planner"]["lns_passes"], passes) << cell;
    EXPECT_TRUE(summary["success"].get<bool>()) << cell;
  }
}

// A built-in planner's lns_passes, lns_neighbourhood and lns_expansions reach `smart plan`: its
// log says how many rounds it ran, with how many robots together and how many expansions each,
// and what they saved; the plan runs.
TEST_F(Campaign, ABuiltinPlannersLnsPassesArePassedToSmartPlan) {
  const auto spec = dir_ / "plan-lns.yaml";
  std::ofstream(spec) << "name: pl\nmaps: [" << (b_ / "maps/random-32-32-20.map").string()
                      << "]\nscens: [" << (b_ / "scens/random-32-32-20-random-1.scen").string()
                      << "]\nagents: [40]\nplan: {planner: builtin, algorithm: lacam, "
                         "lns_passes: 2, lns_neighbourhood: 4, lns_expansions: 3000}\n";
  const auto r = run(spec, kExperimentPlanLns);
  ASSERT_TRUE(r.complete()) << log_.str();
  EXPECT_EQ(r.with_results, 1u);
  const auto said = slurp(dir_ / "out" / "plans" / "0-n40.txt.log");
  EXPECT_THAT(said, HasSubstr("\"lns_passes\":2")) << said;
  EXPECT_THAT(said, HasSubstr("\"lns_neighbourhood\":4")) << said;
  EXPECT_THAT(said, HasSubstr("\"lns_expansions\":3000")) << said;
  EXPECT_THAT(said, HasSubstr("\"algorithm\":\"lacam\"")) << said;
}

TEST_F(Campaign, BadInputIsNamedBeforeAnythingRuns) {
  EXPECT_THAT([&] { run(write_spec("clock: fast\n")); },
              ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("spec.yaml:")));
  const auto missing = dir_ / "nope.yaml";
  std::ofstream(missing) << "name: x\nmaps: [no-such.map]\nscens: [s]\nagents: [1]\n"
                            "plan: {planner: builtin}\n";
  EXPECT_THAT([&] { run(missing); },
              ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("no-such.map not found")));
  EXPECT_THAT([&] { run(write_spec("robots: [no-such-robot]\n")); },
              ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("no-such-robot")));
  EXPECT_THAT([&] { run(write_spec(), 230); },
              ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("0-230")));
  EXPECT_FALSE(fs::exists(dir_ / "out" / "results.csv"));
}

TEST_F(Campaign, PlottingAFolderWithoutResultsIsBadInput) {
  EXPECT_THAT([&] { experiment::plot_campaign(dir_, {}); },
              ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("no results.csv")));
}

}  // namespace
}  // namespace smart::test
