#include "smart/monitor/results.hpp"

#include <dds/version.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <set>
#include <sstream>
#include <stdexcept>
#include <utility>

#ifndef SMART_VERSION
#error "SMART_VERSION comes from the project's version (monitor/CMakeLists.txt)"
#endif

namespace smart::monitor {

namespace {

// Maximal runs of consecutive moves along one heading: what an agent drives without stopping.
std::size_t straight_runs(const ActionPlan& ap) {
  std::size_t runs = 0;
  for (uint32_t r = 0; r < ap.robots(); ++r) {
    bool in_run = false;
    Heading h = Heading::kEast;
    for (uint32_t s = 0; s < ap.count(r); ++s) {
      const Action& a = ap.at(r, s);
      if (a.type != ActionType::kMove) {
        in_run = false;
        continue;
      }
      if (!in_run || a.heading != h) ++runs;
      in_run = true;
      h = a.heading;
    }
  }
  return runs;
}

std::size_t robot_pairs(const ActionPlan& ap, const Adg& adg) {
  std::set<std::pair<uint32_t, uint32_t>> pairs;
  for (uint32_t u = 0; u < adg.nodes(); ++u) {
    for (uint32_t i = adg.out_begin[u]; i < adg.out_begin[u + 1]; ++i) {
      const uint32_t a = ap.actions[u].robot, b = ap.actions[adg.out[i]].robot;
      pairs.insert({std::min(a, b), std::max(a, b)});
    }
  }
  return pairs.size();
}

std::ofstream open_out(const std::filesystem::path& p) {
  std::ofstream out(p);
  if (!out) {
    throw std::runtime_error("cannot write " + p.string() +
                             "; check that the --out folder is writable");
  }
  out.precision(10);
  return out;
}

// Finish time over the motion lower bound, per robot that moves and finished: {median, max}, and
// the bound's AET and makespan.
// The limits the run used (an upload's chosen ones included; issue 26: they appeared nowhere).
nlohmann::json limits_json(const MotionLimits& l, const std::string& robot) {
  return {{"robot", robot},
          {"max_speed_mps", l.max_speed_mps},
          {"max_accel_mps2", l.max_accel_mps2},
          {"max_decel_mps2", l.max_decel_mps2},
          {"max_turn_rate_radps", l.max_turn_rate_radps},
          {"max_angular_accel_radps2", l.max_angular_accel_radps2}};
}

nlohmann::json execution_json(const MonitorResult& r, const RunInfo& info) {
  namespace key = results::summary_key;
  nlohmann::json j = {{key::kMode, r.execution},
                      {key::kSwitches, r.switches.size()},
                      {key::kAnticipated, std::ranges::count_if(r.switches, [](const auto& s) {
                         return s.anticipated;
                       })}};
  if (info.switching) j[key::kOptions] = switch_options_json(*info.switching);
  return j;
}

nlohmann::json motion_bound_json(const MonitorResult& r, const std::vector<double>& bound) {
  std::vector<double> ratio;
  double sum = 0, makespan = 0;
  for (std::size_t i = 0; i < bound.size(); ++i) {
    sum += bound[i];
    makespan = std::max(makespan, bound[i]);
    const double f = i < r.robots.size() ? r.robots[i].finish_time_s : std::nan("");
    if (bound[i] > 0 && !std::isnan(f) && f > 0) ratio.push_back(f / bound[i]);
  }
  std::sort(ratio.begin(), ratio.end());
  const auto n = std::max<double>(1.0, static_cast<double>(bound.size()));
  return {
      {"aet_s", sum / n},
      {"makespan_s", makespan},
      {"finish_over_bound_median",
       ratio.empty() ? nlohmann::json() : nlohmann::json(ratio[ratio.size() / 2])},
      {"finish_over_bound_max", ratio.empty() ? nlohmann::json() : nlohmann::json(ratio.back())}};
}

std::vector<double> bounds_of(const Instance& in, const RunInfo& info) {
  return info.limits ? motion_lower_bounds_s(in.actions, info.cell_m, *info.limits)
                     : std::vector<double>();
}

std::string stats_row(const Instance& in, const MonitorResult& r, const RunInfo& info) {
  double max_t = 0, sum_t = 0;
  long long max_steps = 0, sum_steps = 0;
  for (const auto& m : r.robots) {
    if (std::isnan(m.finish_time_s)) continue;  // done before a resume: unknown
    const auto steps = std::llround(m.finish_time_s / info.control_period_s);
    max_t = std::max(max_t, m.finish_time_s);
    sum_t += m.finish_time_s;
    max_steps = std::max(max_steps, steps);
    sum_steps += steps;
  }
  const auto& a = in.adg.stats;
  std::ostringstream out;
  out.precision(10);
  out << max_steps << "," << sum_steps << "," << max_t << "," << sum_t << "," << in.stats.soc << ","
      << a.type2 << "," << a.type1 << "," << a.nodes << "," << a.moves << "," << a.rotations << ","
      << straight_runs(in.actions) << "," << robot_pairs(in.actions, in.adg) << "," << info.plan
      << "," << r.robots.size() << "\n";
  return out.str();
}

// A robot that has actions and did not finish its last has no finish time.
bool finished(const Instance& in, const MonitorResult& r, uint32_t robot) {
  const uint32_t n = in.actions.count(robot);
  if (n == 0 || r.action_finish_s.empty()) return true;
  return !std::isnan(r.action_finish_s[in.actions.offset[robot] + n - 1]);
}

void create_out_dir(const std::filesystem::path& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) {
    throw std::runtime_error("cannot create the output folder " + dir.string() + ": " +
                             ec.message());
  }
}

// What the robots' reported poses showed (real time): contacts, closest approach, the first
// contact (or null).
// Who sent the samples the monitor refused (issue 25): the sender's participant and what it sent.
nlohmann::json suspects_json(const MonitorResult& r) {
  auto out = nlohmann::json::array();
  for (const auto& s : r.suspected_intruders) {
    out.push_back({{"sender", s.sender}, {"samples", s.samples}, {"first_reason", s.first_reason}});
  }
  return out;
}

nlohmann::json pose_contacts_json(const MonitorResult& r) {
  const auto opt = [](const std::optional<double>& v) {
    return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
  };
  nlohmann::json first = nullptr;
  if (const auto& c = r.first_pose_contact) {
    first = {{"robots", {c->a, c->b}}, {"wall_time_s", c->t_s}, {"gap_m", c->gap_m}};
  }
  return {{"pose_contacts", r.pose_contacts},
          {"pose_min_separation_m", opt(r.pose_min_gap_m)},
          {"first_pose_contact", first}};
}

// What the run cost: peak memory and CPU of the monitor and the sim host, and the machine.
nlohmann::json resources_json(const MonitorResult& r, const RunInfo& info) {
  auto mb = [](const std::optional<double>& v) {
    return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
  };
  nlohmann::json j;
  j["peak_rss_mb"] = {{"monitor", mb(info.monitor_peak_rss_mb)}, {"sim", mb(r.host_peak_rss_mb)}};
  if (!info.machine.empty()) j["machine"] = info.machine;
  j["cpu_s"] = {{"monitor", mb(info.monitor_cpu_s)}, {"sim", mb(info.sim_cpu_s)}};
  if (info.monitor_cpu_s && info.sim_cpu_s && r.sim_time_s > 0) {
    j["cpu_s_per_sim_s"] = (*info.monitor_cpu_s + *info.sim_cpu_s) / r.sim_time_s;
  }
  return j;
}

// How long the instance took to load and check, and the run to start: the wall time from the
// monitor's start to the first report of a host (discovery, world creation, first windows).
nlohmann::json timing_json(const Instance& in, const MonitorResult& r) {
  return {{"build_time_ms", build_time_json(in.timings)},
          {"first_report_wall_s", r.first_progress_wall_s}};
}

}  // namespace

nlohmann::json build_time_json(const InstanceTimings& t) {
  return {{"read", t.read_ms},       {"validate", t.validate_ms},
          {"actions", t.actions_ms}, {"adg", t.adg_ms},
          {"acyclic", t.acyclic_ms}, {"adg_total", t.actions_ms + t.adg_ms + t.acyclic_ms}};
}

nlohmann::json adg_json(const AdgStats& a) {
  return {{"nodes", a.nodes},        {"type1", a.type1},
          {"type2", a.type2},        {"type2_all_pairs", a.type2_all_pairs},
          {"moves", a.moves},        {"rotations", a.rotations},
          {"locations", a.locations}};
}

nlohmann::json plan_json(const Plan& plan, const PlanStats& st) {
  return {{"soc", st.soc},      {"makespan", st.makespan},          {"moves", st.moves},
          {"waits", st.waits},  {"format", to_string(plan.format)}, {"axis", to_string(plan.axis)},
          {"timed", plan.timed}};
}

namespace {
// The fields a run has only sometimes: the limits and motion bound, uncertainty, link, a resume.
nlohmann::json when_known_json(const Instance& in, const MonitorResult& r, const RunInfo& info) {
  nlohmann::json j = nlohmann::json::object();
  if (info.limits) {
    j["motion_bound"] = motion_bound_json(r, bounds_of(in, info));
    j["limits"] = limits_json(*info.limits, info.robot_model);
  }
  if (!info.uncertainty.is_null()) j["uncertainty"] = info.uncertainty;
  if (!info.link.is_null()) j["link"] = info.link;
  if (r.resumed) {
    j["resumed"] = {{"at_s", r.resumed_at_s},
                    {"finished_before", r.finished_before_resume},
                    {"robots_done_before", r.robots_done_before_resume}};
  }
  return j;
}
// AET and makespan: known once every action finished, whatever the verdict (a run with a
// collision still has an AET worth reporting), except for robots done before a resume.
nlohmann::json times_json(const MonitorResult& r) {
  double sum = 0, makespan = 0, waiting = 0;
  uint64_t stops = 0;
  bool times_known = r.finished_actions == r.total_actions;
  for (const auto& m : r.robots) {
    waiting += m.waiting_time_s;
    stops += m.stops;
    if (std::isnan(m.finish_time_s)) {
      times_known = false;
      continue;
    }
    sum += m.finish_time_s;
    makespan = std::max(makespan, m.finish_time_s);
  }
  const double n = std::max<double>(1.0, static_cast<double>(r.robots.size()));
  const auto known = [times_known](double v) {
    return times_known ? nlohmann::json(v) : nlohmann::json(nullptr);
  };
  nlohmann::json wait = {{"mean", waiting / n}, {"total", waiting}};
  if (r.waiting_by_cause_s) {
    for (std::size_t c = 0; c < kWaitCauses; ++c) {
      wait["by_cause"][to_string(static_cast<WaitCause>(c))] = (*r.waiting_by_cause_s)[c];
    }
  }
  return {{"aet_s", known(sum / n)},
          {"makespan_s", known(makespan)},
          {"waiting_time_s", std::move(wait)},
          {"stops", stops}};
}

// What the run did: its verdict, contacts, progress and the samples it refused.
nlohmann::json outcome_json(const MonitorResult& r) {
  return {
      {"success", r.success()},
      {results::summary_key::kOutcome, to_string(r.outcome)},
      {"robots", r.robots.size()},
      {"sim_time_s", r.sim_time_s},
      {"wall_time_s", r.wall_time_s},
      {"sim_speed", r.wall_time_s > 0 ? r.sim_time_s / r.wall_time_s : 0.0},
      {"collisions", r.robot_contacts},
      {"first_collision", r.first_collision ? nlohmann::json::array({r.first_collision->first,
                                                                     r.first_collision->second})
                                            : nlohmann::json(nullptr)},
      {"goal_tolerance_m", r.goal_tolerance_m},
      {"robots_off_goal", r.off_goal},
      {"robots_goal_unverified", r.goal_unverified},
      {"wall_contacts", r.wall_contacts},
      {"min_separation_m", r.min_gap_m ? nlohmann::json(*r.min_gap_m) : nlohmann::json(nullptr)},
      {"sim_status_received", r.have_sim_status},
      {"deadlock", r.outcome == Outcome::kDeadlock},
      {"stalled", r.outcome == Outcome::kStalled},
      {"sim_lost", r.outcome == Outcome::kHostLost},
      {"error", r.error},
      {"finished_actions", r.finished_actions},
      {"total_actions", r.total_actions},
      {"rejected_progress", r.rejected_progress},
      {"rejected_samples", r.rejected_samples},
      {"rejected_examples", r.rejected_examples},
      {"suspected_intruders", suspects_json(r)},
      {"run_id", r.run_id},
      {"first_report_wall_s", r.first_progress_wall_s},
  };
}

// Where the run came from: its run, seed, clock, hosts, QoS, files and versions.
nlohmann::json origin_json(const RunInfo& info) {
  return {
      {"run", info.run},
      {"seed", info.seed},
      {"clock", info.clock},
      {"sim_hosts", info.sim_hosts},
      {"sim_handovers",
       info.sim_handovers ? nlohmann::json(*info.sim_handovers) : nlohmann::json()},
      {"qos", info.qos},
      {"cell_m", info.cell_m},
      {"files",
       {{"map", info.map}, {"scen", info.scen}, {"plan", info.plan}, {"robot", info.robot}}},
      {"versions", {{"smart_dds", SMART_VERSION}, {"cyclonedds", DDS_VERSION}}},
  };
}
}  // namespace

nlohmann::json switch_options_json(const SwitchOptions& o) {
  return {{"commit_actions", o.commit_actions},
          {"search_budget", o.search_budget},
          {"anticipate", o.anticipate},
          {"margin_s", o.margin_s},
          {"horizon_actions", o.horizon_actions},
          {"lookahead_actions", o.lookahead_actions},
          {"lookahead_nodes", o.lookahead_nodes},
          {"lookahead_first_nodes", o.lookahead_first_nodes},
          {"lookahead_margin_s", o.lookahead_margin_s},
          {"chain_locations", o.chain_locations},
          {"window_pairs", o.window_pairs}};
}

nlohmann::json run_summary_json(const MonitorResult& r, const RunInfo& info) {
  auto j = outcome_json(r);
  j.update(times_json(r));
  j.update(origin_json(info));
  j.update(pose_contacts_json(r));
  j[results::summary_key::kExecution] = execution_json(r, info);
  j.update(resources_json(r, info));
  if (info.limits) j["limits"] = limits_json(*info.limits, info.robot_model);
  if (!info.uncertainty.is_null()) j["uncertainty"] = info.uncertainty;
  if (!info.link.is_null()) j["link"] = info.link;
  return j;
}

nlohmann::json summary_json(const Instance& in, const MonitorResult& r, const RunInfo& info) {
  auto j = run_summary_json(r, info);
  j["plan"] = plan_json(in.plan, in.stats);
  j["adg"] = adg_json(in.adg.stats);
  j.update(timing_json(in, r));
  j.update(when_known_json(in, r, info));
  return j;
}

StatesCsvWriter::StatesCsvWriter(const std::filesystem::path& dir) {
  create_out_dir(dir);
  out_ = open_out(dir / results::kStatesCsv);
  out_ << results::kStatesHeader << '\n';
}

void StatesCsvWriter::add(const StateRow& s) {
  std::string line;
  line.reserve(128);
  results::append_row(line, s);
  add_line(line);
}

void StatesCsvWriter::add_line(std::string_view line) {
  out_ << line;
  ++rows_;
}

ProgressCsvWriter::ProgressCsvWriter(const std::filesystem::path& dir) {
  create_out_dir(dir);
  out_ = open_out(dir / results::kProgressCsv);
  out_ << results::kProgressHeader << '\n' << std::flush;
}

void ProgressCsvWriter::add(const results::ProgressRow& r) {
  std::string line;
  results::append_row(line, r);
  out_ << line << std::flush;
}

void write_finished_csv(const std::filesystem::path& dir, const std::vector<uint32_t>& finished) {
  const auto file = dir / results::kFinishedCsv;
  const auto aside = dir / (std::string(results::kFinishedCsv) + ".new");
  {
    auto out = open_out(aside);
    out << results::finished_csv(finished);
  }
  std::filesystem::rename(aside, file);
}

namespace {
// One row per robot: finish and waiting time, stops, actions, the motion lower bound.
void write_robots_csv(const std::filesystem::path& dir, const Instance& in, const MonitorResult& r,
                      const RunInfo& info) {
  std::string text(results::kRobotsHeader);
  text.push_back('\n');
  const auto bound = bounds_of(in, info);
  for (uint32_t i = 0; i < r.robots.size(); ++i) {
    const auto& m = r.robots[i];
    results::RobotRow row{i, std::nullopt, m.waiting_time_s, m.stops, m.actions, std::nullopt};
    if (!std::isnan(m.finish_time_s) && finished(in, r, i)) row.finish_time_s = m.finish_time_s;
    if (i < bound.size()) row.lower_bound_s = bound[i];
    results::append_row(text, row);
  }
  open_out(dir / results::kRobotsCsv) << text;
}

// One row per action in ADG order: who, which, what, and when it finished on the sim clock
// (empty: never finished, or before a resume).
void write_actions_csv(const std::filesystem::path& dir, const Instance& in,
                       const MonitorResult& r) {
  std::string text(results::kActionsHeader);
  text.push_back('\n');
  for (std::size_t node = 0; node < in.actions.actions.size(); ++node) {
    const auto& a = in.actions.actions[node];
    results::ActionRow row{a.robot, a.seq,
                           a.type == grid::ActionType::kMove ? results::ActionType::kMove
                                                             : results::ActionType::kRotate,
                           std::nullopt};
    if (node < r.action_finish_s.size() && !std::isnan(r.action_finish_s[node])) {
      row.finish_time_s = r.action_finish_s[node];
    }
    results::append_row(text, row);
  }
  open_out(dir / results::kActionsCsv) << text;
}
}  // namespace

void append_stats(const std::filesystem::path& file, const Instance& in, const MonitorResult& r,
                  const RunInfo& info) {
  std::error_code ec;
  const bool fresh =
      !std::filesystem::exists(file, ec) || std::filesystem::file_size(file, ec) == 0;
  std::ofstream out(file, std::ios::app);
  if (!out) {
    throw std::runtime_error("cannot append to the stats file " + file.string() +
                             "; check the folder exists and is writable");
  }
  if (fresh) out << results::kStatsHeader << '\n';
  out << stats_row(in, r, info);
}

void write_switches_csv(const std::filesystem::path& dir, const Grid& grid,
                        const ActionPlan* actions, const std::vector<PassingSwitch>& switches) {
  std::string text(results::kSwitchesHeader);
  text += '\n';
  for (const auto& s : switches) results::append_row(text, switch_row(grid, actions, s));
  open_out(dir / results::kSwitchesCsv) << text;
}

SwitchesCsvWriter::SwitchesCsvWriter(const std::filesystem::path& dir) {
  create_out_dir(dir);
  out_ = open_out(dir / results::kSwitchesCsv);
  out_ << results::kSwitchesHeader << '\n' << std::flush;
}

void SwitchesCsvWriter::add(const results::SwitchRow& row) {
  std::string line;
  results::append_row(line, row);
  out_ << line << std::flush;
}

void write_results(const std::filesystem::path& dir, const Instance& in, const MonitorResult& r,
                   const RunInfo& info) {
  create_out_dir(dir);
  open_out(dir / results::kSummaryJson) << summary_json(in, r, info).dump(2) << "\n";
  open_out(dir / results::kStatsCsv) << results::kStatsHeader << '\n' << stats_row(in, r, info);
  write_robots_csv(dir, in, r, info);
  write_actions_csv(dir, in, r);
  if (r.execution != "adg") write_switches_csv(dir, in.grid, &in.actions, r.switches);
}

}  // namespace smart::monitor
