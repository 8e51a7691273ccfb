// `smart check-plan`: validate a plan against its map and scenario and report plan and ADG
// statistics as JSON (exit 0), or list every problem (exit 1); a file it cannot read: exit 2.
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <utility>

#include "smart/grid/problem.hpp"
#include "smart/monitor/instance.hpp"
#include "smart/monitor/results.hpp"
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

int run_check_plan(const CheckPlanOptions& o) {
  // A file that cannot be read is input to fix (exit 2, as `smart run` says), not an invalid plan.
  for (const auto& [path, what] :
       {std::pair{o.world.map, "map"}, {o.world.scen, "scenario"}, {o.plan, "plan"}}) {
    if (!std::ifstream(path)) {
      throw std::invalid_argument(path + ": cannot open the " + what + " file; check the path");
    }
  }
  const auto io = instance_options(o.world, o.plan, o.axis, o.format);
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
  cmd->callback([&exit_code, o] { exit_code = run_check_plan(*o); });
}

}  // namespace smart::tools
