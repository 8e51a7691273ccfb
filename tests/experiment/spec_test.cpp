// The experiment spec, its grid and the results table: pure, no runs.
#include "smart/experiment/spec.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>

namespace smart::experiment {
namespace {

using nlohmann::json;
using ::testing::HasSubstr;

constexpr const char* kSpec = R"(name: scaling
maps: [w.map]
scens: [w-1.scen, w-2.scen]
agents: [10, 100]
plan: {file: paths.txt, axis: rowcol}
robots: [footbot, footbot-smart]
qos: lan
repeats: 2
)";

TEST(Spec, ReadsEveryAxisAndExpandsTheirProduct) {
  const auto s = parse_spec(kSpec, "spec.yaml");
  EXPECT_EQ(s.name, "scaling");
  ASSERT_EQ(s.instances.size(), 2u);  // one map for both scens
  EXPECT_EQ(s.instances[1], (std::pair<std::string, std::string>{"w.map", "w-2.scen"}));
  ASSERT_EQ(s.plans.size(), 1u);
  EXPECT_EQ(s.plans[0].source, PlanSource::kFile);
  EXPECT_EQ(s.plans[0].axis, "rowcol");
  EXPECT_EQ(s.plans[0].name, "paths");
  EXPECT_EQ(s.qos, std::vector<std::string>{"lan"});
  const auto cells = expand(s);
  ASSERT_EQ(cells.size(), 2u * 2 * 2 * 1 * 2);
  EXPECT_EQ(cells[0].key, "0-w-1-n10-footbot-lan-r0");
  EXPECT_EQ(cells.back().key, "1-w-2-n100-footbot-smart-lan-r1");
  std::set<std::string> keys;
  for (const auto& c : cells) keys.insert(c.key);
  EXPECT_EQ(keys.size(), cells.size());  // a folder per cell
}

// `yaml` (as p.yaml) is refused with a message holding `expected`.
void expect_refused(const std::string& yaml, const std::string& expected) {
  try {
    (void)parse_spec(yaml, "p.yaml");
    ADD_FAILURE() << yaml;
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr(expected)) << yaml;
  }
}

TEST(Spec, PlannerAndCommandPlans) {
  auto s =
      parse_spec("name: a\nmaps: [m]\nscens: [s]\nagents: 5\nplan: {planner: builtin}\n", "x.yaml");
  EXPECT_EQ(s.plans.at(0).source, PlanSource::kBuiltin);
  EXPECT_EQ(s.agents, std::vector<std::size_t>{5});
  s = parse_spec(
      "name: a\nmaps: [m]\nscens: [s]\nagents: [5]\nplan: {command: \"p {map} {plan}\"}\n", "x");
  EXPECT_EQ(s.plans.at(0).source, PlanSource::kCommand);
  EXPECT_EQ(s.plans.at(0).text, "p {map} {plan}");
}

TEST(Spec, TheBuiltInPlannerTakesAnAlgorithmThatNamesItsPlans) {
  const auto s = parse_spec(
      "name: a\nmaps: [m]\nscens: [s]\nagents: [5]\n"
      "plans: [{planner: builtin}, {planner: builtin, algorithm: pibt}, "
      "{planner: builtin, algorithm: lacam}]\n",
      "p.yaml");
  ASSERT_EQ(s.plans.size(), 3u);
  EXPECT_EQ(s.plans[0].algorithm, "pp");
  EXPECT_EQ(s.plans[0].name, "builtin");
  EXPECT_EQ(s.plans[1].algorithm, "pibt");
  EXPECT_EQ(s.plans[1].name, "builtin-pibt");
  EXPECT_EQ(s.plans[2].name, "builtin-lacam");
  const std::string head = "name: a\nmaps: [m]\nscens: [s]\nagents: [5]\n";
  expect_refused(head + "plan: {planner: builtin, algorithm: cbs}\n",
                 "p.yaml:5: plan.algorithm: pp (prioritized planning), pibt or lacam");
  expect_refused(head + "plan: {file: x.txt, algorithm: pibt}\n",
                 "only {planner: builtin} takes an algorithm");
}

// Issue 26: planners could not be compared (no planner axis, no planner runtime column).
TEST(Spec, PlansAreAPlannerAxisEachNamedInTheCellsAndTheRows) {
  const auto s = parse_spec(
      "name: a\nmaps: [m]\nscens: [s]\nagents: [5]\nrepeats: 2\n"
      "plans: [{planner: builtin}, {name: lns2, command: \"lns {plan}\", axis: rowcol}]\n",
      "p.yaml");
  ASSERT_EQ(s.plans.size(), 2u);
  EXPECT_EQ(s.plans[0].name, "builtin");
  EXPECT_EQ(s.plans[1].name, "lns2");
  const auto cells = expand(s);
  ASSERT_EQ(cells.size(), 4u);
  EXPECT_EQ(cells[0].key, "0-s-n5-footbot-lan-builtin-r0");
  EXPECT_EQ(cells[3].key, "0-s-n5-footbot-lan-lns2-r1");
  const auto row = result_row(s, cells[3], json::object(), 1.5);
  EXPECT_EQ(row["plan"], "lns2");
  EXPECT_EQ(row["axis"], "rowcol");
  EXPECT_EQ(row["planner_runtime_s"], 1.5);
  EXPECT_FALSE(result_row(s, cells[0], json::object()).contains("planner_runtime_s"));
  for (const auto& [yaml, expected] :
       {std::pair{"plans: [{planner: builtin}, {planner: builtin}]\n",
                  "p.yaml:6: plans[1].name: 'builtin' names two plan sources"},
        {"plans: []\n", "plans: a list"},
        {"plans: [{name: a b, planner: builtin}]\n", "plans[0].name: 1-64"},
        {"plan: {planner: builtin}\nplans: [{planner: builtin}]\n", "not both"}}) {
    expect_refused(std::string("name: a\nmaps: [m]\nscens: [s]\nagents: [5]\nrepeats: 1\n") + yaml,
                   expected);
  }
}

TEST(Spec, MistakesNameTheFileLineAndField) {
  const std::pair<const char*, const char*> cases[] = {
      {"name: a b\n", "spec.yaml:1: name"},
      {"name: a\nmaps: [m]\nscens: [s]\nagents: [10, ten]\nplan: {file: p}\n",
       "spec.yaml:4: agents: 'ten' is not a whole number"},
      {"name: a\nmaps: [m, n]\nscens: [s, t, u]\nagents: [1]\nplan: {file: p}\n",
       "spec.yaml:2: maps"},
      {"name: a\nmaps: [m]\nscens: [s]\nagents: [1]\nplan: {file: p, planner: builtin}\n",
       "plan: give exactly one"},
      {"name: a\nmaps: [m]\nscens: [s]\nagents: [1]\nplan: {command: lns2}\n",
       "plan.command: must write {plan}"},
      {"name: a\nmaps: [m]\nscens: [s]\nagents: [1]\nplan: {file: p}\nrepeat: 3\n",
       "spec.yaml:6: repeat: unknown field"},
      {"name: a\nmaps: [m]\nscens: [s]\nagents: [0]\nplan: {file: p}\n",
       "agents: 0 is out of range: fleet sizes"},
      {"name: a\nmaps: [m]\nscens: [s]\nagents: [1]\nplan: {file: p}\nclock: fast\n",
       "spec.yaml:6: clock: lockstep or realtime"},
      {"name: [a\n", "spec.yaml:"},
  };
  for (const auto& [yaml, expected] : cases) {
    try {
      (void)parse_spec(yaml, "spec.yaml");
      ADD_FAILURE() << "accepted: " << yaml;
    } catch (const std::invalid_argument& e) {
      EXPECT_THAT(e.what(), HasSubstr(expected)) << yaml;
    }
  }
}

TEST(Spec, UncertaintySettingsAreAnAxisSeededByTheRepeat) {
  const auto s = parse_spec(
      "name: a\nmaps: [m]\nscens: [s]\nagents: [5]\nplan: {planner: builtin}\nrepeats: 2\n"
      "uncertainty: [{}, {stall_probability: 0.05, stall_s: 2}]\n",
      "u.yaml");
  const auto cells = expand(s);
  ASSERT_EQ(cells.size(), 4u);
  EXPECT_EQ(cells[3].key, "0-s-n5-footbot-lan-u1-r1");
  EXPECT_EQ(uncertainty_flags(s, cells[0]), (std::vector<std::string>{"--seed", "0"}));
  EXPECT_EQ(
      uncertainty_flags(s, cells[3]),
      (std::vector<std::string>{"--stall-probability", "0.05", "--stall-s", "2.0", "--seed", "1"}));
  for (const auto& [yaml, expected] :
       {std::pair{"uncertainty: [{stalls: 1}]\n", "u.yaml:6: uncertainty.stalls: unknown"},
        {"uncertainty: [{stall_probability: 3}]\n", "uncertainty.stall_probability: a number"},
        {"uncertainty: {}\n", "uncertainty: a list"}}) {
    try {
      (void)parse_spec(
          std::string("name: a\nmaps: [m]\nscens: [s]\nagents: [5]\nplan: {planner: builtin}\n") +
              yaml,
          "u.yaml");
      ADD_FAILURE() << yaml;
    } catch (const std::invalid_argument& e) {
      EXPECT_THAT(e.what(), HasSubstr(expected)) << yaml;
    }
  }
}

// Issue 29: plain and switchable execution side by side on the same seeds; plain cells keep
// the folders they had before the axis existed.
TEST(Spec, ExecutionsAreAnAxisOnTheSameSeeds) {
  const std::string base =
      "name: a\nmaps: [m]\nscens: [s]\nagents: [5]\nplan: {planner: builtin}\n";
  const auto s = parse_spec(base + "executions: [adg, switchable]\nrepeats: 2\n", "e.yaml");
  const auto cells = expand(s);
  ASSERT_EQ(cells.size(), 4u);
  EXPECT_EQ(cells[0].key, "0-s-n5-footbot-lan-r0");
  EXPECT_EQ(cells[0].execution, "adg");
  EXPECT_EQ(cells[3].key, "0-s-n5-footbot-lan-switchable-r1");
  EXPECT_EQ(cells[3].execution, "switchable");
  EXPECT_EQ(uncertainty_flags(s, cells[1]), uncertainty_flags(s, cells[3]));  // same seed
  EXPECT_EQ(result_row(s, cells[3], nlohmann::json::object())["execution"], "switchable");
  EXPECT_EQ(expand(parse_spec(base, "e.yaml"))[0].execution, "adg");
  try {
    (void)parse_spec(base + "executions: [fast]\n", "e.yaml");
    ADD_FAILURE() << "executions: [fast] was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("e.yaml:6: executions: adg, switchable, switchable-opt or "
                                    "switchable-lookahead"));
  }
  const auto opt = expand(parse_spec(base + "executions: [switchable-opt]\n", "e.yaml"));
  EXPECT_EQ(opt[0].execution, "switchable-opt");
  EXPECT_EQ(opt[0].key, "0-s-n5-footbot-lan-switchable-opt-r0");
  // Lifelong cells switch too (LiveAdg): the axis and the results' execution column.
  const auto l = parse_spec(
      "name: l\nlifelong: {map: m.map}\nagents: [5]\nexecutions: [adg, switchable]\n", "e.yaml");
  const auto lc = expand(l);
  ASSERT_EQ(lc.size(), 2u);
  EXPECT_EQ(lc[1].key, "0-m-n5-footbot-lan-switchable-r0");
  EXPECT_EQ(result_row(l, lc[1], nlohmann::json::object())["execution"], "switchable");
  // Lifelong runs anticipate too (LiveAdg, switchable-opt).
  const auto lo = expand(parse_spec(
      "name: l\nlifelong: {map: m.map}\nagents: [5]\nexecutions: [switchable-opt]\n", "e.yaml"));
  ASSERT_EQ(lo.size(), 1u);
  EXPECT_EQ(lo[0].execution, "switchable-opt");
  // And look ahead (LiveAdg, switchable-lookahead), as plan runs do.
  const auto la = expand(parse_spec(base + "executions: [adg, switchable-lookahead]\n", "e.yaml"));
  ASSERT_EQ(la.size(), 2u);
  EXPECT_EQ(la[1].execution, "switchable-lookahead");
  const auto ll = expand(parse_spec(
      "name: l\nlifelong: {map: m.map}\nagents: [5]\nexecutions: [switchable-lookahead]\n",
      "e.yaml"));
  ASSERT_EQ(ll.size(), 1u);
  EXPECT_EQ(ll[0].execution, "switchable-lookahead");
}

// state_rate_hz: every run of the spec gets `--state-rate-hz` (an experiment of 90 1000-robot
// lifelong runs wrote 6 GB of states.csv); none given, none passed; out of range, named.
TEST(Spec, StateRateHzIsPassedToEveryRunAndCheckedAtItsLine) {
  const std::string base =
      "name: a\nmaps: [m]\nscens: [s]\nagents: [5]\nplan: {planner: builtin}\n";
  EXPECT_TRUE(output_flags(parse_spec(base, "s.yaml")).empty());
  EXPECT_EQ(output_flags(parse_spec(base + "state_rate_hz: 0\n", "s.yaml")),
            (std::vector<std::string>{"--state-rate-hz", "0.0"}));
  EXPECT_EQ(output_flags(parse_spec(base + "state_rate_hz: 2.5\n", "s.yaml")),
            (std::vector<std::string>{"--state-rate-hz", "2.5"}));
  for (const std::string bad : {"-1", "5000", "often"}) {
    try {
      (void)parse_spec(base + "state_rate_hz: " + bad + "\n", "s.yaml");
      ADD_FAILURE() << "accepted state_rate_hz: " << bad;
    } catch (const std::invalid_argument& e) {
      EXPECT_THAT(e.what(), HasSubstr("s.yaml:6: state_rate_hz: '" + bad +
                                      "' is not a number from 0.0 to 1000.0"))
          << bad;
    }
  }
}

// Every spec in examples/experiments/ (the docs' commands) parses and makes a grid.
TEST(Spec, EveryExampleSpecParses) {
  const std::filesystem::path dir =
      std::filesystem::path(SMART_SOURCE_DIR) / "examples/experiments";
  std::size_t specs = 0;
  for (const auto& f : std::filesystem::directory_iterator(dir)) {
    if (f.path().extension() != ".yaml") continue;
    std::ifstream in(f.path());
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    try {
      EXPECT_FALSE(expand(parse_spec(text, f.path().string())).empty()) << f.path();
    } catch (const std::exception& e) {
      ADD_FAILURE() << e.what();
    }
    ++specs;
  }
  EXPECT_GE(specs, 20u);
}

// Chains (`--switch-chain-locations`, issue 29) are an axis of the switching executions of plan
// and lifelong runs, crossed with the commit distance; plain ADG cells run once.
TEST(Spec, SwitchChainLocationsAreAnAxisOfTheSwitchingExecutions) {
  const std::string base =
      "name: a\nmaps: [m]\nscens: [s]\nagents: [5]\nplan: {planner: builtin}\n";
  const auto s =
      parse_spec(base +
                     "executions: [adg, switchable-opt]\nswitch_chain_locations: [1, 8]\n"
                     "switch_commit_actions: [6]\n",
                 "k.yaml");
  const auto cells = expand(s);
  ASSERT_EQ(cells.size(), 3u);
  EXPECT_EQ(cells[0].key, "0-s-n5-footbot-lan-r0");
  EXPECT_EQ(cells[1].key, "0-s-n5-footbot-lan-switchable-opt-c6-k1-r0");
  EXPECT_EQ(execution_flags(cells[2]),
            (std::vector<std::string>{"--execution", "switchable-opt", "--switch-commit-actions",
                                      "6", "--switch-chain-locations", "8"}));
  const auto row = result_row(s, cells[1], nlohmann::json::object());
  EXPECT_EQ(row["switch_chain_locations"], 1);
  EXPECT_FALSE(
      result_row(s, cells[0], nlohmann::json::object()).contains("switch_chain_locations"));
  EXPECT_NE(results_csv({row}).find(",switch_commit_actions,switch_chain_locations,"),
            std::string::npos);
  const auto fails = [](const std::string& text, const std::string& what) {
    try {
      (void)parse_spec(text, "k.yaml");
      ADD_FAILURE() << text << " was accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_THAT(e.what(), HasSubstr(what));
    }
  };
  fails(base + "switch_chain_locations: [2]\n",
        "k.yaml:6: switch_chain_locations: only the switching executions take it");
  fails(base + "executions: [switchable]\nswitch_chain_locations: [65]\n",
        "k.yaml:7: switch_chain_locations: 65 is out of range: from 1 to 64 locations");
  // Lifelong runs chain too (monitor/src/live_adg_chain.cpp).
  const auto lifelong = expand(
      parse_spec("name: l\nlifelong: {map: m.map}\nagents: [5]\nexecutions: [adg, switchable]\n"
                 "switch_chain_locations: [1, 8]\n",
                 "k.yaml"));
  ASSERT_EQ(lifelong.size(), 3u);
  EXPECT_EQ(lifelong[2].chain_locations, 8u);
}

// Anticipation's knobs are axes of the executions that read them: the margin and the horizon of
// switchable-opt and the lookahead, the reach of the lookahead alone. An execution that does not
// read a knob runs once (smart run would refuse the flag); a spec whose executions read none is
// refused by the knob's name. Before 2026-12-06 sweeping them took a build of its own.
TEST(Spec, AnticipationKnobsAreAxesOfTheExecutionsThatReadThem) {
  const std::string base =
      "name: a\nmaps: [m]\nscens: [s]\nagents: [5]\nplan: {planner: builtin}\n";
  const auto s = parse_spec(base +
                                "executions: [adg, switchable, switchable-opt, "
                                "switchable-lookahead]\nswitch_margin_s: [0.5, 3]\n"
                                "switch_horizon_actions: 24\nswitch_lookahead_actions: [24, 48]\n",
                            "m.yaml");
  const auto cells = expand(s);
  std::vector<std::string> keys;
  for (const auto& c : cells) keys.push_back(c.key);
  const std::string cell = "0-s-n5-footbot-lan";
  EXPECT_EQ(keys,
            (std::vector<std::string>{
                cell + "-r0", cell + "-switchable-r0", cell + "-switchable-opt-m0.5-h24-r0",
                cell + "-switchable-opt-m3-h24-r0", cell + "-switchable-lookahead-m0.5-h24-a24-r0",
                cell + "-switchable-lookahead-m0.5-h24-a48-r0",
                cell + "-switchable-lookahead-m3-h24-a24-r0",
                cell + "-switchable-lookahead-m3-h24-a48-r0"}));
  EXPECT_EQ(execution_flags(cells[1]), (std::vector<std::string>{"--execution", "switchable"}));
  EXPECT_EQ(execution_flags(cells[5]),
            (std::vector<std::string>{"--execution", "switchable-lookahead", "--switch-margin-s",
                                      "0.5", "--switch-horizon-actions", "24",
                                      "--switch-lookahead-actions", "48"}));
  const auto row = result_row(s, cells[6], nlohmann::json::object());
  EXPECT_EQ(row["switch_margin_s"], 3.0);
  EXPECT_EQ(row["switch_horizon_actions"], 24);
  EXPECT_EQ(row["switch_lookahead_actions"], 24);
  EXPECT_FALSE(result_row(s, cells[1], nlohmann::json::object()).contains("switch_margin_s"));
  EXPECT_NE(results_csv({row}).find(
                ",execution,switch_margin_s,switch_horizon_actions,switch_lookahead_actions,"),
            std::string::npos);
  const auto fails = [&](const std::string& text, const std::string& what) {
    try {
      (void)parse_spec(base + text, "m.yaml");
      ADD_FAILURE() << text << " was accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_THAT(e.what(), HasSubstr(what));
    }
  };
  fails("executions: [adg, switchable]\nswitch_margin_s: [1]\n",
        "m.yaml:7: switch_margin_s: only switchable-opt and switchable-lookahead take it");
  fails("executions: [switchable-opt]\nswitch_lookahead_actions: [48]\n",
        "m.yaml:7: switch_lookahead_actions: only switchable-lookahead takes it");
  fails("executions: [switchable-opt]\nswitch_margin_s: [-1]\n",
        "m.yaml:7: switch_margin_s: '-1' is not a number from 0.0 to 3600.0");
  fails("executions: [switchable-opt]\nswitch_margin_s: []\n",
        "m.yaml:7: switch_margin_s: is empty");
  fails("executions: [switchable-opt]\nswitch_horizon_actions: [0]\n",
        "m.yaml:7: switch_horizon_actions: 0 is out of range: from 1 to 1000 actions");
}

// The lookahead's window search is an axis of switchable-lookahead from 0 (off) to 6 pairs, in
// the folder name (-w) and results.csv, in plan and lifelong runs.
TEST(Spec, WindowPairsAreAnAxisOfTheLookahead) {
  const std::string base =
      "name: a\nmaps: [m]\nscens: [s]\nagents: [5]\nplan: {planner: builtin}\n";
  const auto s = parse_spec(
      base + "executions: [adg, switchable-lookahead]\nswitch_window_pairs: [0, 3]\n", "w.yaml");
  const auto cells = expand(s);
  ASSERT_EQ(cells.size(), 3u);
  EXPECT_EQ(cells[1].key, "0-s-n5-footbot-lan-switchable-lookahead-w0-r0");
  EXPECT_EQ(cells[2].key, "0-s-n5-footbot-lan-switchable-lookahead-w3-r0");
  EXPECT_EQ(execution_flags(cells[2]),
            (std::vector<std::string>{"--execution", "switchable-lookahead",
                                      "--switch-window-pairs", "3"}));
  EXPECT_EQ(result_row(s, cells[1], nlohmann::json::object())["switch_window_pairs"], 0);
  EXPECT_FALSE(result_row(s, cells[0], nlohmann::json::object()).contains("switch_window_pairs"));
  const auto fails = [&](const std::string& text, const std::string& what) {
    try {
      (void)parse_spec(text, "w.yaml");
      ADD_FAILURE() << text << " was accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_THAT(e.what(), HasSubstr(what));
    }
  };
  fails(base + "executions: [switchable-opt]\nswitch_window_pairs: [3]\n",
        "w.yaml:7: switch_window_pairs: only switchable-lookahead takes it");
  fails(base + "executions: [switchable-lookahead]\nswitch_window_pairs: [7]\n",
        "w.yaml:7: switch_window_pairs: 7 is out of range: from 0 (off) to 6 pairs");
  // Lifelong runs too (LiveAdg's window search).
  const auto lifelong =
      expand(parse_spec("name: l\nlifelong: {map: m.map}\nagents: [5]\nexecutions: "
                        "[switchable-lookahead]\nswitch_window_pairs: [3]\n",
                        "w.yaml"));
  ASSERT_EQ(lifelong.size(), 1u);
  EXPECT_EQ(lifelong[0].window_pairs, 3u);
}

// Regression (2026-12-06): a margin was written into the folder name with six significant
// digits, so margins that differ past the sixth shared one folder and one run.
TEST(Spec, MarginsThatDifferPastTheSixthDigitGetFoldersOfTheirOwn) {
  const auto cells =
      expand(parse_spec("name: a\nmaps: [m]\nscens: [s]\nagents: [5]\nplan: {planner: builtin}\n"
                        "executions: [switchable-opt]\nswitch_margin_s: [0.1234567, 0.1234568]\n",
                        "m.yaml"));
  ASSERT_EQ(cells.size(), 2u);
  EXPECT_EQ(cells[0].key, "0-s-n5-footbot-lan-switchable-opt-m0.1234567-r0");
  EXPECT_EQ(cells[1].key, "0-s-n5-footbot-lan-switchable-opt-m0.1234568-r0");
}

// Regression (2026-12-06): a value listed twice in an axis (agents: [5, 5]) made two cells of
// one key, run twice into one folder with two rows in results.csv; robots or qos files of one
// stem did the same. Each is refused at its line, naming the value.
TEST(Spec, AValueListedTwiceInAnAxisIsRefusedAtItsLine) {
  const std::string base = "name: a\nmaps: [m, m]\nscens: [s, t]\nplan: {planner: builtin}\n";
  const std::pair<std::string, std::string> cases[] = {
      {"agents: [5,\n  5]\n", "m.yaml:6: agents: '5' is listed twice; list each value once"},
      {"agents: [5]\nrobots: [a/footbot.yaml, b/footbot.yaml]\n",
       "m.yaml:6: robots: 'footbot' is listed twice"},
      {"agents: [5]\nqos: [lan, lan]\n", "m.yaml:6: qos: 'lan' is listed twice"},
      {"agents: [5]\nexecutions: [adg, switchable, adg]\n", "executions: 'adg' is listed twice"},
      {"agents: [5]\nexecutions: [switchable-opt]\nswitch_margin_s: [1, 1.0]\n",
       "m.yaml:7: switch_margin_s: '1' is listed twice"},
      {"agents: [5]\nexecutions: [switchable]\nswitch_commit_actions: [4, 4]\n",
       "switch_commit_actions: '4' is listed twice"},
      {"agents: [5]\nuncertainty: [{}, {stall_s: 1}, {stall_s: 1.0}]\n",
       "m.yaml:6: uncertainty: '{\"stall_s\":1.0}' is listed twice"},
  };
  for (const auto& [extra, expected] : cases) {
    try {
      (void)parse_spec(base + extra, "m.yaml");
      ADD_FAILURE() << "accepted: " << extra;
    } catch (const std::invalid_argument& e) {
      EXPECT_THAT(e.what(), HasSubstr(expected)) << extra;
    }
  }
  // Scens of one map, and that map given once per scen, stay as they were.
  EXPECT_EQ(expand(parse_spec(base + "agents: [5, 6]\n", "m.yaml")).size(), 4u);
  const auto lifelong = [](const std::string& line) {
    return "name: l\nlifelong: {map: w.map, duration_s: 10, " + line + "}\nagents: [4]\n";
  };
  EXPECT_THROW((void)parse_spec(lifelong("replan_period_s: [1, 1]"), "l.yaml"),
               std::invalid_argument);
  EXPECT_THROW((void)parse_spec(lifelong("lookahead: [4, 4]"), "l.yaml"), std::invalid_argument);
  EXPECT_EQ(expand(parse_spec(lifelong("lookahead: [4, 8]"), "l.yaml")).size(), 2u);
}

// The commit distance of switching (`--switch-commit-actions`) is an axis of the switching
// executions only: plain ADG cells run once, on the same seeds.
TEST(Spec, SwitchCommitActionsAreAnAxisOfTheSwitchingExecutions) {
  const std::string base =
      "name: a\nmaps: [m]\nscens: [s]\nagents: [5]\nplan: {planner: builtin}\n";
  const auto s =
      parse_spec(base + "executions: [adg, switchable]\nswitch_commit_actions: [2, 6]\n", "c.yaml");
  const auto cells = expand(s);
  ASSERT_EQ(cells.size(), 3u);
  EXPECT_EQ(cells[0].key, "0-s-n5-footbot-lan-r0");
  EXPECT_EQ(execution_flags(cells[0]), (std::vector<std::string>{"--execution", "adg"}));
  EXPECT_EQ(cells[1].key, "0-s-n5-footbot-lan-switchable-c2-r0");
  EXPECT_EQ(execution_flags(cells[2]), (std::vector<std::string>{"--execution", "switchable",
                                                                 "--switch-commit-actions", "6"}));
  EXPECT_EQ(uncertainty_flags(s, cells[0]), uncertainty_flags(s, cells[2]));
  const auto row = result_row(s, cells[1], nlohmann::json::object());
  EXPECT_EQ(row["switch_commit_actions"], 2);
  EXPECT_FALSE(result_row(s, cells[0], nlohmann::json::object()).contains("switch_commit_actions"));
  EXPECT_NE(results_csv({row}).find(",execution,switch_commit_actions,"), std::string::npos);
  // Lifelong runs switch with it too.
  const auto l =
      expand(parse_spec("name: l\nlifelong: {map: m.map}\nagents: [5]\nexecutions: [switchable]\n"
                        "switch_commit_actions: 3\n",
                        "c.yaml"));
  ASSERT_EQ(l.size(), 1u);
  EXPECT_EQ(l[0].commit_actions, 3u);
  const auto fails = [&](const std::string& text, const std::string& what) {
    try {
      (void)parse_spec(base + text, "c.yaml");
      ADD_FAILURE() << text << " was accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_THAT(e.what(), HasSubstr(what));
    }
  };
  fails("switch_commit_actions: [2]\n",
        "c.yaml:6: switch_commit_actions: only the switching executions take it; add switchable");
  fails("executions: [switchable]\nswitch_commit_actions: [0]\n",
        "c.yaml:7: switch_commit_actions: 0 is out of range: from 1 to 1000 actions");
  fails("executions: [switchable]\nswitch_commit_actions: [two]\n",
        "c.yaml:7: switch_commit_actions: 'two' is not a whole number");
}

// Issue 28: lifelong runs as an experiment: the map (or a LoRR problem), team sizes, planners
// (built in or a pipe command), replanning periods and delays are the axes.
constexpr const char* kLifelongSpec = R"(name: ll
lifelong:
  map: random-32-32-20.map
  duration_s: 30
  task_errands: 1
  replan_period_s: [1, 2.5]
agents: [10, 20]
planners: [{planner: builtin}, {name: greedy, command: "python3 g.py"}]
uncertainty: [{}, {delay_probability: 0.01, delay_max_s: 2}]
repeats: 2
)";

TEST(Spec, ALifelongSpecHasTeamSizesPlannersPeriodsAndDelaysAsAxes) {
  const auto s = parse_spec(kLifelongSpec, "ll.yaml");
  ASSERT_TRUE(s.lifelong.has_value());
  EXPECT_EQ(s.lifelong->map, "random-32-32-20.map");
  EXPECT_DOUBLE_EQ(s.lifelong->duration_s, 30);
  EXPECT_EQ(s.lifelong->task_errands, 1);
  EXPECT_EQ(s.lifelong->replan_period_s, (std::vector<double>{1, 2.5}));
  ASSERT_EQ(s.plans.size(), 2u);
  EXPECT_EQ(s.plans[0].source, PlanSource::kBuiltin);
  EXPECT_EQ(s.plans[1].source, PlanSource::kCommand);
  EXPECT_EQ(s.plans[1].text, "python3 g.py");
  const auto cells = expand(s);
  ASSERT_EQ(cells.size(), 2u * 2 * 2 * 2 * 2);
  EXPECT_EQ(cells[0].key, "0-random-32-32-20-n10-footbot-lan-builtin-u0-p0-r0");
  EXPECT_EQ(cells.back().key, "0-random-32-32-20-n20-footbot-lan-greedy-u1-p1-r1");
  EXPECT_EQ(cells.back().period, 1u);
  EXPECT_EQ(uncertainty_flags(s, cells.back()),
            (std::vector<std::string>{"--delay-max-s", "2.0", "--delay-probability", "0.01",
                                      "--seed", "1"}));
  const auto row = result_row(s, cells.back(), {{"lifelong", {{"throughput_per_min", 12.5}}}});
  EXPECT_EQ(row["replan_period_s"], 2.5);
  EXPECT_EQ(row["plan"], "greedy");
  EXPECT_EQ(row["map"], "random-32-32-20");
  EXPECT_EQ(row["lifelong.throughput_per_min"], 12.5);
  EXPECT_FALSE(row.contains("axis"));  // no plan file to read
  const auto csv = results_csv({row});
  EXPECT_THAT(csv, HasSubstr("clock,execution,replan_period_s,lifelong.throughput_per_min\n"));
}

// The commit cut's look-ahead (`smart run --lookahead`, actions kept per robot) is an axis of a
// lifelong grid: each value its own cells (and folders, "-l4"), passed to smart run, a column
// of its own, so that plain ADG pairs with switching at the same look-ahead.
TEST(Spec, ALifelongGridTakesTheCommitCutsLookaheadAsAnAxis) {
  const auto s = parse_spec(
      "name: l\nlifelong: {map: m.map, lookahead: [4, 8]}\nagents: [10]\n"
      "executions: [adg, switchable-opt]\n",
      "l.yaml");
  EXPECT_EQ(s.lifelong->lookahead, (std::vector<uint32_t>{4, 8}));
  const auto cells = expand(s);
  ASSERT_EQ(cells.size(), 4u);
  EXPECT_EQ(cells[0].key, "0-m-n10-footbot-lan-l4-r0");
  EXPECT_EQ(cells[1].key, "0-m-n10-footbot-lan-l4-switchable-opt-r0");
  EXPECT_EQ(cells[3].key, "0-m-n10-footbot-lan-l8-switchable-opt-r0");
  EXPECT_EQ(cells[3].lookahead, 8u);
  const auto row = result_row(s, cells[3], {{"lifelong", {{"lookahead", 8}}}});
  EXPECT_EQ(row["lookahead"], 8);
  EXPECT_THAT(results_csv({row}), HasSubstr("execution,replan_period_s,lookahead,"));
  // Without it, no flag, no column, the folders as before.
  const auto plain = parse_spec("name: l\nlifelong: {map: m.map}\nagents: [10]\n", "l.yaml");
  EXPECT_EQ(expand(plain).at(0).key, "0-m-n10-footbot-lan-r0");
  EXPECT_EQ(expand(plain).at(0).lookahead, 0u);
  EXPECT_FALSE(result_row(plain, expand(plain).at(0), json::object()).contains("lookahead"));
}

// The built-in planner's windows made better by LNS (`smart run --window-lns-passes`) is a
// planner of the planner axis, so a grid compares PIBT's windows with and without it.
TEST(Spec, ALifelongBuiltinPlannerTakesWindowLnsPasses) {
  const auto s = parse_spec(
      "name: l\nlifelong: {map: m.map}\nagents: [10]\n"
      "planners: [{planner: builtin}, {name: lns, planner: builtin, window_lns_passes: 2}]\n",
      "l.yaml");
  ASSERT_EQ(s.plans.size(), 2u);
  EXPECT_EQ(s.plans[0].lns_passes, 0);
  EXPECT_EQ(s.plans[1].lns_passes, 2);
  EXPECT_EQ(expand(s).at(1).key, "0-m-n10-footbot-lan-lns-r0");
  const std::string head = "name: l\nlifelong: {map: m.map}\nagents: [10]\nplanners: ";
  expect_refused(head + "[{command: \"p {plan}\", window_lns_passes: 1}]\n",
                 "p.yaml:4: planners[0].window_lns_passes: only {planner: builtin}");
  expect_refused(head + "[{planner: builtin, window_lns_passes: 17}]\n",
                 "planners[0].window_lns_passes: 17 is out of range: rounds run from 0");
  expect_refused(head + "[{planner: builtin, window_lns_passes: [1, 2]}]\n",
                 "one whole number, e.g. 1");
}

// `smart plan --lns-passes` for a built-in planner's one-shot plans; a plan file has none.
TEST(Spec, ABuiltinPlannerTakesLnsPasses) {
  const auto s = parse_spec(
      "name: p\nmaps: [m.map]\nscens: [s.scen]\nagents: [10]\n"
      "plans: [{planner: builtin, algorithm: lacam}, {name: lns, planner: builtin, algorithm: "
      "lacam, lns_passes: 4}, {name: lns8, planner: builtin, algorithm: lacam, lns_passes: 4, "
      "lns_neighbourhood: 8, lns_expansions: 400000}]\n",
      "p.yaml");
  ASSERT_EQ(s.plans.size(), 3u);
  EXPECT_EQ(s.plans[0].lns_passes, 0);
  EXPECT_EQ(s.plans[1].lns_passes, 4);
  EXPECT_EQ(s.plans[1].lns_neighbourhood, 1);
  EXPECT_EQ(s.plans[1].algorithm, "lacam");
  EXPECT_EQ(s.plans[2].lns_neighbourhood, 8);
  EXPECT_EQ(s.plans[1].lns_expansions, 0);
  EXPECT_EQ(s.plans[2].lns_expansions, 400000);
  expect_refused(
      "name: p\nmaps: [m.map]\nscens: [s.scen]\nagents: [10]\n"
      "plan: {planner: builtin, lns_neighbourhood: 4}\n",
      "p.yaml:5: plan.lns_neighbourhood: only with lns_passes");
  expect_refused(
      "name: p\nmaps: [m.map]\nscens: [s.scen]\nagents: [10]\n"
      "plan: {planner: builtin, lns_passes: 2, lns_neighbourhood: 65}\n",
      "plan.lns_neighbourhood");
  expect_refused(
      "name: p\nmaps: [m.map]\nscens: [s.scen]\nagents: [10]\n"
      "plan: {planner: builtin, lns_passes: 2, lns_expansions: 99}\n",
      "plan.lns_expansions");
  expect_refused(
      "name: p\nmaps: [m.map]\nscens: [s.scen]\nagents: [10]\n"
      "plan: {file: a.txt, lns_passes: 1}\n",
      "p.yaml:5: plan.lns_passes: only {planner: builtin} takes it");
}

TEST(Spec, ALorrProblemBringsItsTeam) {
  const auto s =
      parse_spec("name: lorr\nlifelong: {problem: maze.domain/maze-example_40.json}\n", "l.yaml");
  ASSERT_EQ(s.agents, std::vector<std::size_t>{0});
  EXPECT_EQ(s.plans.at(0).name, "builtin");
  const auto cells = expand(s);
  ASSERT_EQ(cells.size(), 1u);
  EXPECT_EQ(cells[0].key, "0-maze-example_40-n0-footbot-lan-r0");
  EXPECT_EQ(result_row(s, cells[0], {{"robots", 40}})["agents"], 40);
}

TEST(Spec, LifelongMistakesNameTheFileLineAndField) {
  const auto error = [](const std::string& text) {
    try {
      (void)parse_spec(text, "ll.yaml");
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_THAT(error("name: a\nlifelong: {map: m, problem: p}\nagents: [1]\n"),
              HasSubstr("ll.yaml:2: lifelong: give map (random tasks on it) or problem"));
  EXPECT_THAT(error("name: a\nlifelong: {problem: p.json}\nagents: [5]\n"),
              HasSubstr("ll.yaml:3: agents: a LoRR problem brings its team; drop agents"));
  EXPECT_THAT(error("name: a\nlifelong: {map: m}\nagents: [1]\nmaps: [x]\n"),
              HasSubstr("ll.yaml:4: maps: a lifelong experiment has no plan files"));
  EXPECT_THAT(error("name: a\nlifelong: {map: m, replan_period_s: [0]}\nagents: [1]\n"),
              HasSubstr("lifelong.replan_period_s: '0' is not a number from 0.05 to 3600"));
  EXPECT_THAT(
      error("name: a\nlifelong: {map: m, lookahead: [0]}\nagents: [1]\n"),
      HasSubstr("ll.yaml:2: lifelong.lookahead: 0 is out of range: from 1 to 1000 actions"));
  EXPECT_THAT(error("name: a\nlifelong: {map: m, lookahead: [four]}\nagents: [1]\n"),
              HasSubstr("lifelong.lookahead: 'four' is not a whole number"));
  EXPECT_THAT(error("name: a\nlifelong: {map: m, windows: 3}\nagents: [1]\n"),
              HasSubstr("lifelong.windows: unknown; the fields are map or problem"));
  EXPECT_THAT(error("name: a\nlifelong: {map: m}\nagents: [1]\nplanners: [{planner: lacam}]\n"),
              HasSubstr("planners[0].planner: the only planner inside is 'builtin'"));
  EXPECT_THAT(error("name: a\nmaps: [m]\nscens: [s]\nagents: [1]\nplan: {planner: builtin}\n"
                    "planners: [{planner: builtin}]\n"),
              HasSubstr("planners: only with lifelong:"));
  EXPECT_THAT(error("name: a\nlifelong: {map: m}\nagents: [1]\nuncertainty: [{delay_s: 1}]\n"),
              HasSubstr("delay_probability, delay_rate_hz, delay_min_s, delay_max_s"));
}

TEST(ExperimentResults, ARowHasTheParametersAndEverySummaryFieldFlattened) {
  const auto s = parse_spec(kSpec, "spec.yaml");
  const auto cells = expand(s);
  const auto summary = json::parse(
      R"({"success": true, "aet_s": 12.5, "adg": {"type2": 7}, "robots_off_goal": [3, 4],
          "machine": "x, y"})");
  const auto row = result_row(s, cells[1], summary);
  EXPECT_EQ(row["robot"], "footbot");
  EXPECT_EQ(row["repeat"], 1);
  EXPECT_EQ(row["agents"], 10);
  EXPECT_EQ(row["adg.type2"], 7);
  EXPECT_EQ(row["robots_off_goal"], "[3,4]");
  auto other = row;
  other.erase("aet_s");
  other["extra"] = "q\"uote";
  const auto csv = results_csv({row, other});
  EXPECT_THAT(csv, ::testing::StartsWith("cell,map,scen,agents,robot,qos,uncertainty,repeat,plan,"
                                         "axis,clock,execution,planner_runtime_s,"
                                         "adg.type2,aet_s,extra,machine,"));
  EXPECT_THAT(csv, HasSubstr(",lockstep,adg,,7,12.5,,\"x, y\","));  // no runtime (a file); no extra
  EXPECT_THAT(csv, HasSubstr(",7,,\"q\"\"uote\",\"x, y\","));       // row 2: no AET
}

// Regression: a campaign stopped with Ctrl-C (or a run killed by a signal) left the running cells'
// summaries, written as the runs ended early (outcome "stopped"); a resumed campaign took them as
// done and results.csv held the truncated runs as results.
TEST(Results, ARunStoppedBeforeItsEndIsNoResult) {
  using nlohmann::json;
  EXPECT_TRUE(ran_to_its_end(json{{"outcome", "success"}, {"success", true}}));
  EXPECT_TRUE(ran_to_its_end(json{{"outcome", "deadlock"}, {"success", false}}));  // it ended
  EXPECT_TRUE(ran_to_its_end(json{{"success", true}}));  // a summary from before the outcome
  EXPECT_FALSE(ran_to_its_end(json{{"outcome", "stopped"}, {"success", false}}));
  EXPECT_FALSE(ran_to_its_end(json(json::value_t::discarded)));  // none, or it did not parse
  EXPECT_FALSE(ran_to_its_end(json::array()));
}

}  // namespace
}  // namespace smart::experiment
