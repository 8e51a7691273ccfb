// `smart check-plan`: validate a plan against its map and scenario and report plan and ADG
// statistics as JSON (exit 0), or list every problem (exit 1); a file it cannot read: exit 2.
// With --actions (a plain ADG run's actions.csv of this plan): also where that run's waiting
// went (monitor/wait_causes.hpp; docs/execution.md, "What switching can reach").
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <utility>

#include "smart/grid/problem.hpp"
#include "smart/grid/text_file.hpp"
#include "smart/monitor/instance.hpp"
#include "smart/monitor/results.hpp"
#include "smart/monitor/wait_causes.hpp"
#include "smart/serve/robot_detail.hpp"
#include "smart/tools/cli_common.hpp"
#include "smart/tools/commands.hpp"
#include "smart/tools/run_options.hpp"

namespace smart::tools {

namespace {

struct CheckPlanOptions {
  WorldCliOptions world;
  std::string plan;
  std::optional<grid::AxisOrder> axis;
  grid::PlanFormat format = grid::PlanFormat::kAuto;
  std::string actions_csv;  // a plain ADG run's actions.csv: where its waiting went
};

nlohmann::json problems_json(const std::vector<grid::Problem>& problems) {
  auto arr = nlohmann::json::array();
  for (const auto& p : problems) {
    nlohmann::json j = {{"file", p.source}, {"message", p.message}};
    if (p.line > 0) j["line"] = p.line;
    if (p.robot >= 0) j["robot"] = p.robot;
    arr.push_back(j);
  }
  return arr;
}

// The run's waits by cause (wait_causes.hpp), from its actions.csv (`text`) of this plan.
nlohmann::json waits_json(const std::string& actions_csv, const std::string& text,
                          const monitor::Instance& in) {
  std::vector<double> finish_s;
  try {
    finish_s = serve::parse_action_times(text, in.actions);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(actions_csv + ": " + e.what() +
                                "; is it a run of this plan, with the same --agents?");
  }
  const auto w = monitor::wait_causes(
      in.actions, monitor::passing_orders(in.actions, in.grid, in.adg.footprint), finish_s);
  const auto share = [&](double part_s) { return w.total_s > 0 ? part_s / w.total_s : 0.0; };
  return {{"file", actions_csv},
          {"waits", w.waits},
          {"total_s", w.total_s},
          {"on_its_way_s", w.on_its_way_s},
          {"on_its_way_waiting_s", w.on_its_way_waiting_s},
          {"uncommitted_s", w.uncommitted_s},
          {"uncommitted_cycle_s", w.uncommitted_cycle_s},
          {"entering_s", w.entering_s},
          {"at_location_s", w.at_location_s},
          {"on_its_way_share", share(w.on_its_way_s)},
          {"at_location_share", share(w.at_location_s)}};
}

int run_check_plan(const CheckPlanOptions& o) {
  // A file that cannot be read is input to fix (exit 2, as `smart run` says), not an invalid plan.
  for (const auto& [path, what] :
       {std::pair{o.world.map, "map"}, {o.world.scen, "scenario"}, {o.plan, "plan"}}) {
    if (!std::ifstream(path)) {
      throw std::invalid_argument(path + ": cannot open the " + what + " file; check the path");
    }
  }
  const auto io = instance_options(o.world, o.plan, o.axis, o.format);
  // Read first: a run's file that cannot be read is not a problem of the plan.
  const std::string actions =
      o.actions_csv.empty() ? std::string() : grid::read_text_file(o.actions_csv, "actions");
  try {
    const auto in = monitor::load_instance(io);
    nlohmann::json report = {
        {"valid", true},
        {"robots", in.plan.paths.size()},
        {"map", {{"file", o.world.map}, {"width", in.grid.width()}, {"height", in.grid.height()}}},
        {"plan", monitor::plan_json(in.plan, in.stats)},
        {"adg", monitor::adg_json(in.adg.stats)},
        {"build_time_ms", monitor::build_time_json(in.timings)},
    };
    report["plan"]["file"] = o.plan;
    if (!o.actions_csv.empty()) report["waits"] = waits_json(o.actions_csv, actions, in);
    std::cout << report.dump(2) << std::endl;
    return kExitSuccess;
  } catch (const grid::InputError& e) {
    // The JSON has them all; then, last on a terminal (issue 26: the JSON buried the hint), the
    // diagnosis line and the first 50, then a count.
    std::cout << nlohmann::json{{"valid", false},
                                {"problem_count", e.problems().size()},
                                {"problems", problems_json(e.problems())}}
                     .dump(2)
              << std::endl;
    std::cerr << e.what() << "\n" << e.problems().size() << " problem(s) found\n";
    return kExitRunFailed;
  }
}

}  // namespace

void register_check_plan_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<CheckPlanOptions>();
  auto* cmd =
      app.add_subcommand("check-plan",
                         "Validate a MAPF plan against its map and scenario; print plan and ADG "
                         "statistics as JSON (exit 0) or every problem found (exit 1)");
  add_world_options(cmd, o->world);  // --robot, --cell-m: the ADG depends on the footprint
  add_plan_options(cmd, o->plan, o->axis, o->format);
  cmd->add_option("--actions", o->actions_csv,
                  "A plain ADG run's actions.csv of this plan: also print where its waiting "
                  "went (\"waits\": behind robots on their way, entering, at the location)");
  cmd->callback([&exit_code, o] { exit_code = run_check_plan(*o); });
}

}  // namespace smart::tools
