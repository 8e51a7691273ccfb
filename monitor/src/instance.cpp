#include "smart/monitor/instance.hpp"

#include <chrono>

#include "smart/monitor/plan_validator.hpp"
#include "smart/monitor/vocabulary.hpp"

namespace smart::monitor {

namespace {
using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}
}  // namespace

Instance load_instance(const InstanceOptions& o) {
  Instance in;
  auto t0 = Clock::now();
  in.grid = parse_map(read_text_file(o.map, "map"), o.map.string());
  in.plan = parse_plan(read_text_file(o.plan, "plan"), o.plan.string(), o.read);
  if (o.agents > 0) {
    if (in.plan.paths.size() < o.agents) {
      throw InputError({{o.plan.string(), 0, -1,
                         "--agents " + std::to_string(o.agents) + " but the plan has only " +
                             std::to_string(in.plan.paths.size()) + " robots; lower --agents"}});
    }
    in.plan.paths.resize(o.agents);
  }
  in.scen = parse_scen(read_text_file(o.scen, "scenario"), o.scen.string(), in.plan.paths.size());
  in.timings.read_ms = ms_since(t0);

  t0 = Clock::now();
  auto problems = check_scen_against_map(in.scen, in.grid);
  auto plan_problems = validate_plan(in.plan, in.grid, &in.scen);
  problems.insert(problems.end(), plan_problems.begin(), plan_problems.end());
  throw_if_any(std::move(problems));
  in.stats = plan_stats(in.plan);
  in.timings.validate_ms = ms_since(t0);

  t0 = Clock::now();
  in.actions = build_actions(in.plan, o.initial_heading);
  in.timings.actions_ms = ms_since(t0);

  t0 = Clock::now();
  std::vector<Problem> adg_problems;
  in.adg = build_adg(in.actions, in.grid, in.plan.source, adg_problems, o.footprint);
  throw_if_any(std::move(adg_problems));
  in.timings.adg_ms = ms_since(t0);

  t0 = Clock::now();
  throw_if_any(check_acyclic(in.adg, in.actions, in.plan.source));
  in.timings.acyclic_ms = ms_since(t0);
  return in;
}

}  // namespace smart::monitor
