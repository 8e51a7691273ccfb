// The run option sets: parsed straight into library types, and `smart run`'s sim child
// command line generated from the struct reads back as the same options.
#include "smart/tools/run_options.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <spdlog/spdlog.h>

namespace smart::tools {
namespace {

using ::testing::HasSubstr;

void parse_sim(SimCliOptions& o, std::vector<std::string> args) {
  CLI::App app;
  add_common_run_options(&app, o);
  add_sim_host_options(&app, o);
  app.add_option("--external-robots", o.external)->delimiter(',');
  std::reverse(args.begin(), args.end());  // CLI11 takes the words last to first
  app.parse(args);
}

TEST(RunOptions, EnumsAreParsedIntoTheirTypes) {
  SimCliOptions o;
  parse_sim(o, {"--map", "m.map", "--scen", "s.scen", "--clock", "realtime", "--initial-heading",
                "south", "--network", "network"});
  EXPECT_EQ(o.clock, sim::ClockMode::kRealtime);
  EXPECT_EQ(o.world.heading, grid::Heading::kSouth);
  EXPECT_EQ(o.dds.network, Network::kNetwork);
}

TEST(RunOptions, AnUnknownEnumNameIsAParseErrorListingTheNames) {
  SimCliOptions o;
  try {
    parse_sim(o, {"--map", "m", "--scen", "s", "--clock", "sometimes"});
    FAIL() << "parsed";
  } catch (const CLI::ParseError& e) {
    EXPECT_THAT(e.what(), HasSubstr("'sometimes' is not one of lockstep|realtime"));
  }
}

// Regressions from fuzzing the flags: `--cell-m nan` passed CLI::Range and crashed Simbody
// later; NaN and negative timeouts and rates were accepted; `--agents -5` wrapped. (A state
// rate of 0 is allowed since issue 13: only the final states.)
TEST(RunOptions, NonFiniteNegativeAndZeroValuesAreParseErrors) {
  for (const std::vector<std::string>& bad : {std::vector<std::string>{"--cell-m", "nan"},
                                              {"--cell-m", "inf"},
                                              {"--timeout-s", "-1"},
                                              {"--timeout-s", "nan"},
                                              {"--state-rate-hz", "-1"},
                                              {"--agents", "-5"},
                                              {"--agents", "0"}}) {
    SimCliOptions o;
    std::vector<std::string> args{"--map", "m", "--scen", "s"};
    args.insert(args.end(), bad.begin(), bad.end());
    EXPECT_THROW(parse_sim(o, args), CLI::ParseError) << bad[0] << " " << bad[1];
  }
  SimCliOptions o;
  parse_sim(o, {"--map", "m", "--scen", "s", "--cell-m", "0.5", "--agents", "3"});
  EXPECT_EQ(o.world.cell_m, 0.5);
  EXPECT_EQ(o.world.agents, 3u);
}

TEST(RunOptions, TheSimChildsArgvReadsBackAsTheSameOptions) {
  SimCliOptions o;
  parse_sim(o, {"--map",
                "maps/a b.map",
                "--scen",
                "x.scen",
                "--agents",
                "17",
                "--cell-m",
                "0.3",
                "--initial-heading",
                "west",
                "--robot",
                "jetbot",
                "--clock",
                "realtime",
                "--state-rate-hz",
                "0.7",
                "--timeout-s",
                "12.5",
                "--system-capacity",
                "8",
                "--threads",
                "1",
                "--real-time-factor",
                "2.5",
                "--ros-pose-robots",
                "1,4",
                "--external-robots",
                "2",
                "--domain",
                "33",
                "--qos",
                "wifi",
                "--network",
                "network",
                "--run",
                "exp-1.b_2"});
  spdlog::set_level(spdlog::level::warn);
  const auto argv = sim_argv("/bin/smart", o);
  spdlog::set_level(spdlog::level::info);
  ASSERT_GE(argv.size(), 4u);
  EXPECT_EQ(argv[0], "/bin/smart");
  EXPECT_EQ(argv[1], "--log-level");  // the child logs at the parent's level
  EXPECT_EQ(argv[2], "warning");
  EXPECT_EQ(argv[3], "sim");
  SimCliOptions back;
  parse_sim(back, std::vector<std::string>(argv.begin() + 4, argv.end()));
  EXPECT_EQ(back.world.map, "maps/a b.map");
  EXPECT_EQ(back.world.agents, 17u);
  EXPECT_EQ(back.world.cell_m, 0.3);  // exactly: the text reads back as the same double
  EXPECT_EQ(back.world.heading, grid::Heading::kWest);
  EXPECT_EQ(back.world.robot, "jetbot");
  EXPECT_EQ(back.clock, sim::ClockMode::kRealtime);
  EXPECT_EQ(back.state_rate_hz, 0.7);
  EXPECT_EQ(back.timeout_s, 12.5);
  EXPECT_EQ(back.system_capacity, 8);
  EXPECT_EQ(back.threads, 1);
  EXPECT_EQ(back.real_time_factor, 2.5);
  EXPECT_EQ(back.ros_pose_robots, (std::vector<uint32_t>{1, 4}));
  EXPECT_EQ(back.external, (std::vector<uint32_t>{2}));
  EXPECT_EQ(back.dds.domain, 33);
  EXPECT_EQ(back.dds.qos, "wifi");
  EXPECT_EQ(back.dds.network, Network::kNetwork);
  EXPECT_EQ(back.dds.run, "exp-1.b_2");
  EXPECT_TRUE(back.dds.run_given);
}

TEST(RunOptions, ARealTimeFactorPacesLockstepAndIsRefusedWithTheRealtimeClock) {
  SimCliOptions o;
  parse_sim(o, {"--map", "m", "--scen", "s", "--real-time-factor", "10"});
  EXPECT_EQ(sim_host_options(o).real_time_factor, 10);
  EXPECT_THROW(parse_sim(o, {"--map", "m", "--scen", "s", "--real-time-factor", "-1"}),
               CLI::ParseError);
  SimCliOptions rt;
  parse_sim(rt, {"--map", "m", "--scen", "s", "--clock", "realtime", "--real-time-factor", "10"});
  try {
    (void)sim_host_options(rt);
    FAIL() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("drop --real-time-factor or use --clock lockstep"));
  }
}

TEST(RunOptions, MonitorOptionsCarryTheRunPolicy) {
  MonitorCliOptions o;
  CLI::App app;
  add_monitor_options(&app, o);
  std::vector<std::string> args{"--map",
                                "m",
                                "--scen",
                                "s",
                                "--plan",
                                "p",
                                "--axis",
                                "rowcol",
                                "--window-cap",
                                "5",
                                "--stall-timeout-s",
                                "9",
                                "--clock",
                                "realtime",
                                "--max-sim-time-s",
                                "100",
                                "--format",
                                "lacam"};
  std::reverse(args.begin(), args.end());
  app.parse(args);
  const auto mo = monitor_options(o);
  EXPECT_FALSE(mo.run.lockstep);
  EXPECT_EQ(mo.run.window_cap, 5u);
  EXPECT_EQ(mo.run.stall_timeout_s, 9.0);
  EXPECT_EQ(mo.run.max_sim_time_s, 100.0);
  EXPECT_EQ(mo.run.run_id, 0u);  // derived from the wall clock when the run starts
  const auto io = instance_options(o.sim.world, o.plan, o.axis, o.format);
  EXPECT_EQ(io.read.axis, grid::AxisOrder::kRowCol);
  EXPECT_EQ(io.read.format, grid::PlanFormat::kLacam);
}

// --execution and the switching flags become the tracker's options: chains of 8 locations by
// default, one location at a time with --switch-chain-locations 1, none past 64.
// A plan run's monitor options from `--execution execution` and the flags of `extra`.
monitor::SupervisorConfig parse_execution(const std::string& execution,
                                          const std::vector<std::string>& extra) {
  MonitorCliOptions o;
  CLI::App app;
  add_monitor_options(&app, o);
  std::vector<std::string> args{"--map", "m",      "--scen", "s",           "--plan",
                                "p",     "--axis", "xy",     "--execution", execution};
  args.insert(args.end(), extra.begin(), extra.end());
  std::reverse(args.begin(), args.end());
  app.parse(args);
  return monitor_options(o).run;
}

TEST(RunOptions, SwitchingFlagsBecomeTheTrackersOptions) {
  const auto parse = [](const std::vector<std::string>& extra) {
    return parse_execution("switchable", extra);
  };
  EXPECT_TRUE(parse({}).switchable);
  EXPECT_EQ(parse({}).switch_options.chain_locations, 8u);
  const auto one = parse({"--switch-chain-locations", "1", "--switch-commit-actions", "2"});
  EXPECT_EQ(one.switch_options.chain_locations, 1u);
  EXPECT_EQ(one.switch_options.commit_actions, 2u);
  EXPECT_THROW(parse({"--switch-chain-locations", "0"}), CLI::ParseError);
  EXPECT_THROW(parse({"--switch-chain-locations", "65"}), CLI::ParseError);
}

// Regression: `--execution adg --switch-commit-actions 2` ran plain ADG and ignored the flag
// without a word, so a user comparing commit distances got one plain run per value. Plain ADG
// reads neither switching flag and now refuses each by name; every switching execution takes
// them.
TEST(RunOptions, PlainAdgRefusesTheCommitAndChainFlagsItDoesNotRead) {
  for (const std::string flag : {"--switch-commit-actions", "--switch-chain-locations"}) {
    try {
      parse_execution("adg", {flag, "2"});
      ADD_FAILURE() << "plain ADG took " << flag;
    } catch (const std::invalid_argument& e) {
      EXPECT_THAT(e.what(), testing::HasSubstr(flag + ": only --execution switchable,"));
    }
    for (const std::string execution : {"switchable-opt", "switchable-lookahead"}) {
      const auto s = parse_execution(execution, {flag, "2"}).switch_options;
      EXPECT_EQ(flag == "--switch-commit-actions" ? s.commit_actions : s.chain_locations, 2u)
          << execution << " " << flag;
    }
  }
  EXPECT_EQ(parse_execution("switchable", {}).switch_options.commit_actions, 6u);
  EXPECT_FALSE(parse_execution("adg", {}).switchable);
}

// Anticipation's knobs reach the tracker: the margin goes to the margin the execution reads
// (switchable-opt's own, the lookahead's), the horizon to both, the reach to the lookahead; an
// execution that does not read a knob refuses it by name rather than ignoring it.
TEST(RunOptions, AnticipationKnobsReachTheExecutionThatReadsThem) {
  const auto parse = [](const std::string& execution, const std::vector<std::string>& extra) {
    return parse_execution(execution, extra).switch_options;
  };
  const monitor::SwitchOptions defaults;
  const auto opt =
      parse("switchable-opt", {"--switch-margin-s", "3", "--switch-horizon-actions", "24"});
  EXPECT_EQ(opt.margin_s, 3.0);
  EXPECT_EQ(opt.lookahead_margin_s, defaults.lookahead_margin_s);
  EXPECT_EQ(opt.horizon_actions, 24u);
  EXPECT_EQ(opt.lookahead_actions, 0u);
  const auto look = parse("switchable-lookahead",
                          {"--switch-margin-s", "2.5", "--switch-lookahead-actions", "48"});
  EXPECT_EQ(look.lookahead_margin_s, 2.5);
  EXPECT_EQ(look.margin_s, defaults.margin_s);
  EXPECT_EQ(look.lookahead_actions, 48u);
  EXPECT_EQ(look.horizon_actions, defaults.horizon_actions);
  EXPECT_EQ(parse("switchable-lookahead", {}).lookahead_actions, monitor::kDefaultLookaheadActions);
  try {
    parse("switchable", {"--switch-margin-s", "3"});
    ADD_FAILURE() << "switchable took a margin it does not read";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), testing::HasSubstr("--switch-margin-s: only --execution switchable-opt"));
  }
  EXPECT_THROW(parse("switchable-opt", {"--switch-lookahead-actions", "48"}),
               std::invalid_argument);
  EXPECT_THROW(parse("adg", {"--switch-horizon-actions", "24"}), std::invalid_argument);
  EXPECT_THROW(parse("switchable-opt", {"--switch-margin-s", "-1"}), CLI::ParseError);
  EXPECT_THROW(parse("switchable-lookahead", {"--switch-lookahead-actions", "0"}), CLI::ParseError);
  // The window search (SwitchOptions::window_pairs): off unless told, the lookahead's alone,
  // at most kMaxWindowPairs.
  EXPECT_EQ(look.window_pairs, 0u);
  EXPECT_EQ(parse("switchable-lookahead", {"--switch-window-pairs", "3"}).window_pairs, 3u);
  EXPECT_THROW(parse("switchable-opt", {"--switch-window-pairs", "3"}), std::invalid_argument);
  EXPECT_THROW(parse("switchable-lookahead", {"--switch-window-pairs", "7"}), CLI::ParseError);
  // Lifelong runs read it too (LiveAdg's window search).
  MonitorCliOptions lifelong;
  lifelong.execution = MonitorCliOptions::Execution::kSwitchableLookahead;
  lifelong.switch_window_pairs = 3;
  lifelong.sim.source.tasks = "random";
  EXPECT_EQ(switch_options(lifelong).window_pairs, 3u);
}

}  // namespace
}  // namespace smart::tools
