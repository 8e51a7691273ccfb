#include "smart/experiment/campaign.hpp"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <thread>
#include <tuple>
#include <utility>
#include <vector>

#include "smart/common/child_process.hpp"
#include "smart/common/install_paths.hpp"
#include "smart/dds/qos_profile.hpp"
#include "smart/experiment/spec.hpp"
#include "smart/grid/text_file.hpp"
#include "smart/monitor/results_format.hpp"

namespace smart::experiment {

namespace {
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// A file named in the spec: as given, next to the spec, or in $SMART_BENCHMARKS/<kind>/.
fs::path resolve(const std::string& name, const fs::path& spec_dir, const char* kind) {
  std::vector<fs::path> places{name, spec_dir / name};
  if (const char* b = std::getenv("SMART_BENCHMARKS"); b && *b) {
    places.push_back(fs::path(b) / kind / name);
  }
  std::string looked;
  for (const auto& p : places) {
    if (fs::is_regular_file(p)) return fs::absolute(p);
    looked += (looked.empty() ? "" : ", ") + p.string();
  }
  throw std::invalid_argument("experiment: " + name + " not found (looked at " + looked +
                              "); give a path, or set SMART_BENCHMARKS");
}

std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

struct Campaign {
  Spec spec;
  std::vector<Cell> cells;
  std::vector<std::pair<fs::path, fs::path>> files;  // resolved (map, scen) per instance
  fs::path out, smart;
  std::vector<fs::path> plan_files;  // resolved, per spec.plans entry (empty: made here)
  // (instance, agents, plan source) -> the plan file made, and its planner's wall seconds
  std::map<std::tuple<std::size_t, std::size_t, std::size_t>, std::pair<fs::path, double>> plans;

  fs::path cell_dir(const Cell& c) const { return out / "cells" / c.key; }
  // The cell's summary.json, or a discarded value when there is none or it does not parse.
  nlohmann::json summary(const Cell& c) const {
    std::ifstream in(cell_dir(c) / results::kSummaryJson);
    if (!in) return nlohmann::json(nlohmann::json::value_t::discarded);
    return nlohmann::json::parse(in, nullptr, false);
  }
  bool done(const Cell& c) const { return ran_to_its_end(summary(c)); }
};

// The words that make the plan of (map, scen, agents) into `plan`.
std::vector<std::string> plan_argv(const Campaign& c, const PlanSpec& source, const fs::path& map,
                                   const fs::path& scen, std::size_t agents, const fs::path& plan) {
  if (source.source == PlanSource::kBuiltin) {
    std::vector<std::string> argv{
        c.smart.string(), "plan",           "--map",    map.string(),
        "--scen",         scen.string(),    "--agents", std::to_string(agents),
        "--algorithm",    source.algorithm, "--out",    plan.string()};
    if (source.lns_passes > 0) {
      argv.insert(argv.end(), {"--lns-passes", std::to_string(source.lns_passes),
                               "--lns-neighbourhood", std::to_string(source.lns_neighbourhood)});
      if (source.lns_expansions > 0) {
        argv.insert(argv.end(), {"--lns-expansions", std::to_string(source.lns_expansions)});
      }
    }
    return argv;
  }
  std::string cmd = source.text;
  for (const auto& [k, v] : {std::pair{"{map}", shell_quote(map.string())},
                             {"{scen}", shell_quote(scen.string())},
                             {"{agents}", std::to_string(agents)},
                             {"{plan}", shell_quote(plan.string())}}) {
    for (std::size_t at; (at = cmd.find(k)) != std::string::npos;) cmd.replace(at, strlen(k), v);
  }
  return {"/bin/sh", "-c", cmd};
}

// ": " and the last lines (up to kLines) of a log's last kBytes, each cut to its last kWidth
// characters, joined by " | "; or nothing. Bounded: a planner may print anything, megabytes on
// one line or binary, and the message only has to show how it ended.
std::string log_tail(const fs::path& log) {
  constexpr std::size_t kLines = 3, kBytes = 4096, kWidth = 240;
  std::ifstream in(log, std::ios::binary | std::ios::ate);
  const auto size = static_cast<std::size_t>(std::max<std::streamoff>(0, in.tellg()));
  const std::size_t from = size > kBytes ? size - kBytes : 0;
  std::string text(size - from, '\0');
  in.seekg(static_cast<std::streamoff>(from));
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  std::deque<std::string> last;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    if (line.empty()) continue;
    last.push_back(line.size() > kWidth ? "..." + line.substr(line.size() - kWidth) : line);
    if (last.size() > kLines) last.pop_front();
  }
  std::string out;
  for (const auto& line : last) out += (out.empty() ? ": " : " | ") + line;
  return out;
}

// The planner's wall seconds, kept beside its plan so a resumed campaign reports them too.
std::optional<double> read_runtime(const fs::path& plan) {
  std::ifstream in(plan.string() + ".runtime_s");
  double s = 0;
  return in >> s ? std::optional<double>(s) : std::nullopt;
}

// The plan of (instance, agents, plan source): the spec's file, or made once by the built-in
// planner or the spec's command into <out>/plans/, timed.
std::pair<fs::path, std::optional<double>> make_plan(Campaign& c, const Cell& cell) {
  const auto& source = c.spec.plans.at(cell.plan);
  if (source.source == PlanSource::kFile) return {c.plan_files.at(cell.plan), std::nullopt};
  const auto key = std::make_tuple(cell.instance, cell.agents, cell.plan);
  if (auto it = c.plans.find(key); it != c.plans.end()) return it->second;
  const auto plan = c.out / "plans" /
                    (std::to_string(cell.instance) + "-n" + std::to_string(cell.agents) +
                     (c.spec.plans.size() > 1 ? "-" + source.name : "") + ".txt");
  fs::create_directories(plan.parent_path());
  const auto& [map, scen] = c.files[cell.instance];
  if (!fs::exists(plan) || !read_runtime(plan)) {
    const auto t0 = Clock::now();
    // stderr into the log too (dup'd after stdout's file is opened): the error the message
    // points to is there (the log was empty when the planner refused with an error).
    const int rc = common::ChildProcess(plan_argv(c, source, map, scen, cell.agents, plan),
                                        plan.string() + ".log", {{STDOUT_FILENO, STDERR_FILENO}})
                       .wait(std::chrono::hours(24))
                       .value_or(-1);
    if (rc != 0 || !fs::exists(plan)) {
      throw std::runtime_error(
          "experiment: planner " + source.name + " on " + std::to_string(cell.agents) +
          " robots of " + scen.string() + " failed (exit code " + std::to_string(rc) + ")" +
          log_tail(plan.string() + ".log") + "; see " + plan.string() + ".log");
    }
    std::ofstream(plan.string() + ".runtime_s")
        << std::chrono::duration<double>(Clock::now() - t0).count() << "\n";
  }
  return c.plans[key] = {plan, *read_runtime(plan)};
}

// A lifelong cell: its task stream, duration, replanning period, look-ahead and planner.
std::vector<std::string> lifelong_argv(const Campaign& c, const Cell& cell) {
  const auto& l = *c.spec.lifelong;
  const auto& source = c.files[cell.instance].first.string();
  std::vector<std::string> argv;
  if (l.problem.empty()) {
    argv = {"--tasks", "random", "--map", source, "--agents", std::to_string(cell.agents)};
  } else {
    argv = {"--lifelong", source};
  }
  if (l.task_errands) argv.insert(argv.end(), {"--task-errands", std::to_string(*l.task_errands)});
  argv.insert(argv.end(), {"--duration-s", nlohmann::json(l.duration_s).dump(), "--replan-period-s",
                           nlohmann::json(l.replan_period_s.at(cell.period)).dump()});
  if (cell.lookahead != 0) argv.insert(argv.end(), {"--lookahead", std::to_string(cell.lookahead)});
  const auto& planner = c.spec.plans.at(cell.plan);
  if (planner.source == PlanSource::kCommand) {
    argv.insert(argv.end(), {"--planner-cmd", planner.text});
  }
  if (planner.lns_passes > 0) {
    argv.insert(argv.end(), {"--window-lns-passes", std::to_string(planner.lns_passes)});
  }
  return argv;
}

std::vector<std::string> run_argv(Campaign& c, const Cell& cell, int domain) {
  if (c.spec.lifelong) {
    std::vector<std::string> argv{c.smart.string(), "--log-level", "error", "run"};
    const auto what = lifelong_argv(c, cell);
    argv.insert(argv.end(), what.begin(), what.end());
    argv.insert(argv.end(),
                {"--robot", cell.robot, "--qos", cell.qos, "--clock", c.spec.clock, "--domain",
                 std::to_string(domain), "--out", c.cell_dir(cell).string(), "--no-progress"});
    const auto execution = execution_flags(cell);
    argv.insert(argv.end(), execution.begin(), execution.end());
    const auto flags = uncertainty_flags(c.spec, cell);
    argv.insert(argv.end(), flags.begin(), flags.end());
    const auto output = output_flags(c.spec);
    argv.insert(argv.end(), output.begin(), output.end());
    return argv;
  }
  const auto& [map, scen] = c.files[cell.instance];
  std::vector<std::string> argv{c.smart.string(), "--log-level",
                                "error",          "run",
                                "--map",          map.string(),
                                "--scen",         scen.string(),
                                "--plan",         make_plan(c, cell).first.string(),
                                "--axis",         c.spec.plans.at(cell.plan).axis,
                                "--agents",       std::to_string(cell.agents),
                                "--robot",        cell.robot,
                                "--qos",          cell.qos,
                                "--clock",        c.spec.clock,
                                "--domain",       std::to_string(domain),
                                "--out",          c.cell_dir(cell).string(),
                                "--no-progress"};
  const auto execution = execution_flags(cell);
  argv.insert(argv.end(), execution.begin(), execution.end());
  const auto flags = uncertainty_flags(c.spec, cell);
  argv.insert(argv.end(), flags.begin(), flags.end());
  const auto output = output_flags(c.spec);
  argv.insert(argv.end(), output.begin(), output.end());
  return argv;
}

std::string eta_text(double s) {
  const auto m = static_cast<long>(s / 60);
  return std::to_string(m) + "m" + std::to_string(static_cast<long>(s) % 60) + "s";
}

struct Slot {
  std::optional<common::ChildProcess> child;
  const Cell* cell = nullptr;
  Clock::time_point started;
};

struct Tally {
  std::size_t total = 0, finished = 0, errors = 0;
  double busy_s = 0;  // wall seconds of finished runs
};

void progress_bar(std::ostream& log, const Tally& t, std::size_t running, int jobs) {
  const std::size_t left = t.total - t.finished;
  const double eta = t.finished ? t.busy_s / double(t.finished) * double(left) / jobs : 0;
  std::string bar(20, '.');
  for (std::size_t i = 0; i < 20 * t.finished / std::max<std::size_t>(t.total, 1); ++i)
    bar[i] = '#';
  log << "\rexperiment: [" << bar << "] " << t.finished << "/" << t.total << " runs, " << running
      << " running" << (t.finished ? ", ETA " + eta_text(eta) : "") << "   " << std::flush;
}

// A slot's run ended: counted, and a failure to produce a summary is named with its log.
void collect(const Campaign& c, Slot& s, int rc, Tally& t, bool bar, std::ostream& log) {
  t.busy_s += std::chrono::duration<double>(Clock::now() - s.started).count();
  ++t.finished;
  const auto summary = c.summary(*s.cell);
  if (!summary.is_object()) {
    ++t.errors;
    log << (bar ? "\n" : "") << "experiment: " << s.cell->key << " wrote no summary (exit code "
        << rc << "); see " << (c.cell_dir(*s.cell) / "run.log").string() << "\n";
  } else if (!ran_to_its_end(summary)) {
    ++t.errors;
    log << (bar ? "\n" : "") << "experiment: " << s.cell->key
        << " was stopped before its end (a signal?): not a result; running the experiment again "
           "runs it again; see "
        << (c.cell_dir(*s.cell) / "run.log").string() << "\n";
  } else if (!bar) {
    log << "experiment: " << t.finished << "/" << t.total << " " << s.cell->key << "\n";
  }
  s.child.reset();
}

std::deque<const Cell*> cells_to_run(const Campaign& c, std::ostream& log) {
  std::deque<const Cell*> todo;
  for (const auto& cell : c.cells) {
    if (!c.done(cell)) todo.push_back(&cell);
  }
  if (todo.size() < c.cells.size()) {
    log << "experiment: " << c.cells.size() - todo.size() << " of " << c.cells.size()
        << " runs already done (skipped)\n";
  }
  return todo;
}

Tally run_cells(Campaign& c, const CampaignOptions& o, std::ostream& log) {
  auto todo = cells_to_run(c, log);
  Tally t;
  t.total = todo.size();
  std::vector<Slot> slots(static_cast<std::size_t>(o.jobs));
  const auto stopped = [&o] { return o.stop != nullptr && o.stop->load(); };
  for (std::size_t running = 0; (!todo.empty() || running > 0) && !stopped();) {
    running = 0;
    for (std::size_t i = 0; i < slots.size(); ++i) {
      auto& s = slots[i];
      if (s.child) {
        if (const auto rc = s.child->wait(std::chrono::milliseconds(0))) {
          collect(c, s, *rc, t, o.progress_bar, log);
        }
      }
      if (!s.child && !todo.empty()) {
        s.cell = todo.front();
        todo.pop_front();
        fs::create_directories(c.cell_dir(*s.cell));
        s.child.emplace(run_argv(c, *s.cell, o.first_domain + static_cast<int>(i)),
                        c.cell_dir(*s.cell) / "run.log");
        s.started = Clock::now();
      }
      running += s.child ? 1 : 0;
    }
    if (o.progress_bar) progress_bar(log, t, running, o.jobs);
    // Children are polled: ChildProcess waits on one child at a time.
    if (running > 0) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  if (o.progress_bar) log << "\n";
  return t;
}

// results.csv and results.jsonl from every cell that has a summary.
std::size_t write_results(Campaign& c) {
  std::vector<nlohmann::json> rows;
  std::ofstream jsonl(c.out / "results.jsonl");
  for (const auto& cell : c.cells) {
    const auto summary = c.summary(cell);
    if (!ran_to_its_end(summary)) continue;
    const auto runtime_s =
        c.spec.lifelong ? std::nullopt : std::optional<double>(make_plan(c, cell).second);
    rows.push_back(result_row(c.spec, cell, summary, runtime_s));
    jsonl << rows.back().dump() << "\n";
  }
  std::ofstream(c.out / "results.csv") << results_csv(rows);
  return rows.size();
}

// Robot and QoS names as `smart run` looks them up; bad input named before anything runs.
void check_names(const Spec& spec) {
  try {
    for (const auto& robot : spec.robots) (void)dds::find_config_file("robots", robot);
    for (const auto& q : spec.qos) (void)dds::find_qos_profile(q);
  } catch (const std::exception& e) {
    throw std::invalid_argument(std::string("experiment: ") + e.what());
  }
}

Campaign load_campaign(const CampaignOptions& o) {
  if (o.jobs < 1 || o.first_domain < 0 || o.first_domain + o.jobs > 231) {
    throw std::invalid_argument("experiment: domain " + std::to_string(o.first_domain) +
                                " + jobs " + std::to_string(o.jobs) +
                                " must stay within 0-230, the domain ids; lower either");
  }
  Campaign c;
  c.smart = o.smart;
  c.spec = parse_spec(grid::read_text_file(o.spec.string(), "experiment spec"), o.spec.string());
  const auto spec_dir = o.spec.parent_path();
  for (const auto& [map, scen] : c.spec.instances) {
    if (c.spec.lifelong) {  // a map, or a LoRR problem ($SMART_BENCHMARKS/lorr-2026/...)
      const bool problem = !c.spec.lifelong->problem.empty();
      c.files.emplace_back(resolve(map, spec_dir, problem ? "lorr-2026" : "maps"), fs::path());
      continue;
    }
    auto map_file = resolve(map, spec_dir, "maps");  // named first when both are missing
    c.files.emplace_back(std::move(map_file), resolve(scen, spec_dir, "scens"));
  }
  for (const auto& p : c.spec.plans) {
    c.plan_files.push_back(
        p.source == PlanSource::kFile ? resolve(p.text, spec_dir, "smart-examples") : fs::path());
  }
  check_names(c.spec);
  c.out = o.out.empty() ? fs::path("experiments") / c.spec.name : o.out;
  c.cells = expand(c.spec);
  fs::create_directories(c.out);
  fs::copy_file(o.spec, c.out / "spec.yaml", fs::copy_options::overwrite_existing);
  return c;
}
}  // namespace

nlohmann::json CampaignReport::to_json() const {
  return {{"experiment", name},           {"runs", runs},     {"skipped", skipped},
          {"with_results", with_results}, {"errors", errors}, {"stopped", stopped},
          {"results", results.string()}};
}

CampaignReport run_campaign(const CampaignOptions& options, std::ostream& log) {
  auto c = load_campaign(options);
  const auto t = run_cells(c, options, log);
  CampaignReport r;
  r.name = c.spec.name;
  r.runs = c.cells.size();
  r.skipped = c.cells.size() - t.total;
  r.with_results = write_results(c);
  r.errors = t.errors;
  r.stopped = options.stop != nullptr && options.stop->load();
  r.results = c.out / "results.csv";
  return r;
}

void plot_campaign(const fs::path& results_dir, fs::path out_dir) {
  // Installed beside the executable (<prefix>/share/smart-dds), else the source tree's.
  const auto share = common::installed_share_dir();
  const fs::path script =
      share && fs::exists(*share / "experiment_plot.py")
          ? *share / "experiment_plot.py"
          : fs::path(SMART_SOURCE_DIR) / "experiment" / "plot" / "experiment_plot.py";
  if (!fs::is_regular_file(results_dir / "results.csv")) {
    throw std::invalid_argument("experiment plot: no results.csv in " + results_dir.string() +
                                "; give the folder `smart experiment` wrote");
  }
  if (out_dir.empty()) out_dir = results_dir / "figures";
  const int rc = common::ChildProcess(
                     {"/usr/bin/python3", script.string(), results_dir.string(), out_dir.string()})
                     .wait(std::chrono::minutes(10))
                     .value_or(-1);
  if (rc != 0) {
    throw std::runtime_error("experiment plot: " + script.string() + " failed (exit code " +
                             std::to_string(rc) +
                             "); is python3-matplotlib installed (scripts/install-deps.sh)?");
  }
}

}  // namespace smart::experiment
