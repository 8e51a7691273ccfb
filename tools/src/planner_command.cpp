// `smart planner`: the built-in lifelong planner (PIBT, lifelong/window_planner.hpp) as a process
// of its own, serving one run's windows over DDS (tools/planner_node.hpp) until the run ends.
#include <spdlog/spdlog.h>

#include <algorithm>
#include <memory>

#include "smart/dds/participant.hpp"
#include "smart/tools/cli_common.hpp"
#include "smart/tools/commands.hpp"
#include "smart/tools/planner_node.hpp"
#include "smart/tools/run_key.hpp"
#include "smart/tools/run_options.hpp"

namespace smart::tools {

namespace {

struct PlannerCliOptions {
  DdsOptions dds;
  std::string name = "pibt";
  uint64_t seed = 1;
  double distance_budget_mb = 1024;
  planning::HeuristicKind heuristic = planning::HeuristicKind::kAuto;
  int lns_passes = 0;
};

int run_planner(const PlannerCliOptions& o) {
  const auto profile = run_qos_profile(o.dds);
  dds::Domain domain(o.dds.domain, domain_config(o.dds, profile, "planner"));
  dds::Participant participant(domain, o.dds.run);
  prove_member(participant, o.dds, "planner");
  PlannerNode node(participant, profile, o.name, [&o](const grid::Grid& grid, std::size_t robots) {
    return std::make_unique<lifelong::BuiltinPlanner>(
        grid, lifelong::BuiltinPlannerOptions{o.distance_budget_mb, o.seed, o.heuristic, robots,
                                              o.lns_passes});
  });
  const auto out = node.serve(g_stop_requested);
  switch (out.end) {
    case PlannerNode::End::kRefused:
      spdlog::error("planner: {}", out.detail);
      return kExitRunFailed;
    case PlannerNode::End::kRunOver:
      spdlog::info("planner: the run is over after {} windows", out.windows);
      return kExitSuccess;
    case PlannerNode::End::kStopped:
      spdlog::info("planner: stopped after {} windows", out.windows);
      return kExitSuccess;
  }
  return kExitSuccess;
}

}  // namespace

void register_planner_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<PlannerCliOptions>();
  auto* cmd = app.add_subcommand(
      "planner",
      "Plan a lifelong run's windows over DDS with the built-in planner, as a process of its own "
      "(the run waits for it with --planner external; docs/planner-protocol.md)");
  add_dds_options(cmd, o->dds);
  cmd->add_option("--name", o->name, "the name the run records for this planner")
      ->check([](const std::string& s) {
        const bool ok = s.size() <= 64 && std::all_of(s.begin(), s.end(), [](char c) {
                          return c >= 0x20 && c <= 0x7e;
                        });
        return ok ? std::string() : std::string("at most 64 printable ASCII characters");
      })
      ->capture_default_str();
  cmd->add_option("--seed", o->seed, "PIBT's tie-breaking seed")->capture_default_str();
  cmd->add_option("--distance-budget-mb", o->distance_budget_mb,
                  "memory for the planner's distance tables (as `smart run --lifelong`)")
      ->check(finite_in(16.0, 1e6))
      ->capture_default_str();
  add_enum_option(cmd, "--heuristic", o->heuristic, kHeuristicNames,
                  "how the planner ranks moves (as `smart run --lifelong`)")
      ->capture_default_str();
  cmd->add_option("--window-lns-passes", o->lns_passes,
                  "rounds of replanning each robot in PIBT's window (as `smart run --lifelong`)")
      ->check(CLI::Range(0, 16))
      ->capture_default_str();
  cmd->callback([&exit_code, o] {
    install_stop_handlers();
    exit_code = run_planner(*o);
  });
}

}  // namespace smart::tools
