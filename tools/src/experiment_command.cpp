// `smart experiment SPEC.yaml`: a batch of `smart run`s over a grid (tools/experiment.hpp), up to
// --jobs at once, each in its own DDS domain id and run partition; resumable (a cell whose
// summary.json exists is not run again); a progress line with ETA; results.csv and
// results.jsonl, a row per run. `smart experiment plot RESULTS_DIR`: the figures, drawn by
// tools/plot/experiment_plot.py (Debian's python3-matplotlib).
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <deque>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <thread>

#include "smart/common/child_process.hpp"
#include "smart/grid/text_file.hpp"
#include "smart/monitor/results_format.hpp"
#include "smart/tools/cli_common.hpp"
#include "smart/tools/commands.hpp"
#include "smart/tools/experiment.hpp"

namespace smart::tools {

namespace {
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

struct ExperimentOptions {
  std::string spec, out;
  int jobs = 1;
  int domain = 120;
};

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

struct Experiment {
  ExperimentSpec spec;
  std::vector<ExperimentCell> cells;
  std::vector<std::pair<fs::path, fs::path>> files;  // resolved (map, scen) per instance
  fs::path out, plan_file;
  std::map<std::pair<std::size_t, std::size_t>, fs::path> plans;  // (instance, agents) -> plan

  fs::path cell_dir(const ExperimentCell& c) const { return out / "cells" / c.key; }
  bool done(const ExperimentCell& c) const {
    std::ifstream in(cell_dir(c) / results::kSummaryJson);
    return in && nlohmann::json::parse(in, nullptr, false).is_object();
  }
};

// The plan of (instance, agents): the spec's file, or made once by the built-in planner or the
// spec's command into <out>/plans/.
fs::path make_plan(Experiment& e, std::size_t instance, std::size_t agents) {
  if (e.spec.plan_source == PlanSource::kFile) return e.plan_file;
  const auto key = std::make_pair(instance, agents);
  if (auto it = e.plans.find(key); it != e.plans.end()) return it->second;
  const auto plan =
      e.out / "plans" / (std::to_string(instance) + "-n" + std::to_string(agents) + ".txt");
  fs::create_directories(plan.parent_path());
  const auto& [map, scen] = e.files[instance];
  if (!fs::exists(plan)) {
    std::vector<std::string> argv;
    if (e.spec.plan_source == PlanSource::kBuiltin) {
      argv = {common::self_executable().string(),
              "plan",
              "--map",
              map.string(),
              "--scen",
              scen.string(),
              "--agents",
              std::to_string(agents),
              "--out",
              plan.string()};
    } else {
      std::string cmd = e.spec.plan;
      for (const auto& [k, v] : {std::pair{"{map}", shell_quote(map.string())},
                                 {"{scen}", shell_quote(scen.string())},
                                 {"{agents}", std::to_string(agents)},
                                 {"{plan}", shell_quote(plan.string())}}) {
        for (std::size_t at; (at = cmd.find(k)) != std::string::npos;)
          cmd.replace(at, strlen(k), v);
      }
      argv = {"/bin/sh", "-c", cmd};
    }
    const int rc = common::ChildProcess(argv, plan.string() + ".log")
                       .wait(std::chrono::hours(24))
                       .value_or(-1);
    if (rc != 0 || !fs::exists(plan)) {
      throw std::runtime_error("experiment: planning " + std::to_string(agents) + " robots of " +
                               scen.string() + " failed (exit code " + std::to_string(rc) +
                               "); see " + plan.string() + ".log");
    }
  }
  return e.plans[key] = plan;
}

std::vector<std::string> run_argv(Experiment& e, const ExperimentCell& c, int domain) {
  const auto& [map, scen] = e.files[c.instance];
  std::vector<std::string> argv{common::self_executable().string(),
                                "--log-level",
                                "error",
                                "run",
                                "--map",
                                map.string(),
                                "--scen",
                                scen.string(),
                                "--plan",
                                make_plan(e, c.instance, c.agents).string(),
                                "--axis",
                                e.spec.axis,
                                "--agents",
                                std::to_string(c.agents),
                                "--robot",
                                c.robot,
                                "--qos",
                                c.qos,
                                "--clock",
                                e.spec.clock,
                                "--domain",
                                std::to_string(domain),
                                "--out",
                                e.cell_dir(c).string(),
                                "--no-progress"};
  const auto flags = uncertainty_flags(e.spec, c);
  argv.insert(argv.end(), flags.begin(), flags.end());
  return argv;
}

std::string eta_text(double s) {
  const auto m = static_cast<long>(s / 60);
  return std::to_string(m) + "m" + std::to_string(static_cast<long>(s) % 60) + "s";
}
}  // namespace

namespace {
struct Slot {
  std::optional<common::ChildProcess> child;
  const ExperimentCell* cell = nullptr;
  Clock::time_point started;
};

struct Tally {
  std::size_t total = 0, finished = 0, errors = 0;
  double busy_s = 0;  // wall seconds of finished runs
};

void progress_line(const Tally& t, std::size_t running, int jobs) {
  const std::size_t left = t.total - t.finished;
  const double eta = t.finished ? t.busy_s / double(t.finished) * double(left) / jobs : 0;
  std::string bar(20, '.');
  for (std::size_t i = 0; i < 20 * t.finished / std::max<std::size_t>(t.total, 1); ++i)
    bar[i] = '#';
  std::cerr << "\rexperiment: [" << bar << "] " << t.finished << "/" << t.total << " runs, "
            << running << " running" << (t.finished ? ", ETA " + eta_text(eta) : "") << "   "
            << std::flush;
}

// A slot's run ended: counted, and a failure to produce a summary is named with its log.
void collect(Experiment& e, Slot& s, int rc, Tally& t, bool tty) {
  t.busy_s += std::chrono::duration<double>(Clock::now() - s.started).count();
  ++t.finished;
  if (!e.done(*s.cell)) {
    ++t.errors;
    std::cerr << (tty ? "\n" : "") << "experiment: " << s.cell->key
              << " wrote no summary (exit code " << rc << "); see "
              << (e.cell_dir(*s.cell) / "run.log").string() << "\n";
  } else if (!tty) {
    std::cerr << "experiment: " << t.finished << "/" << t.total << " " << s.cell->key << "\n";
  }
  s.child.reset();
}

Tally run_cells(Experiment& e, const ExperimentOptions& o) {
  std::deque<const ExperimentCell*> todo;
  for (const auto& c : e.cells) {
    if (!e.done(c)) todo.push_back(&c);
  }
  if (todo.size() < e.cells.size()) {
    std::cerr << "experiment: " << e.cells.size() - todo.size() << " of " << e.cells.size()
              << " runs already done (skipped)\n";
  }
  Tally t;
  t.total = todo.size();
  std::vector<Slot> slots(static_cast<std::size_t>(o.jobs));
  const bool tty = ::isatty(STDERR_FILENO) != 0;
  for (std::size_t running = 0; (!todo.empty() || running > 0) && !g_stop_requested.load();) {
    running = 0;
    for (std::size_t i = 0; i < slots.size(); ++i) {
      auto& s = slots[i];
      if (s.child) {
        if (const auto rc = s.child->wait(std::chrono::milliseconds(0))) collect(e, s, *rc, t, tty);
      }
      if (!s.child && !todo.empty()) {
        s.cell = todo.front();
        todo.pop_front();
        fs::create_directories(e.cell_dir(*s.cell));
        s.child.emplace(run_argv(e, *s.cell, o.domain + static_cast<int>(i)),
                        e.cell_dir(*s.cell) / "run.log");
        s.started = Clock::now();
      }
      running += s.child ? 1 : 0;
    }
    if (tty) progress_line(t, running, o.jobs);
    if (running > 0) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  if (tty) std::cerr << "\n";
  return t;
}

// results.csv and results.jsonl from every cell that has a summary.
std::size_t write_results(const Experiment& e) {
  std::vector<nlohmann::json> rows;
  std::ofstream jsonl(e.out / "results.jsonl");
  for (const auto& c : e.cells) {
    std::ifstream in(e.cell_dir(c) / results::kSummaryJson);
    const auto summary = nlohmann::json::parse(in, nullptr, false);
    if (!in || !summary.is_object()) continue;
    rows.push_back(result_row(e.spec, c, summary));
    jsonl << rows.back().dump() << "\n";
  }
  std::ofstream(e.out / "results.csv") << results_csv(rows);
  return rows.size();
}

Experiment load_experiment(const ExperimentOptions& o) {
  Experiment e;
  e.spec = parse_experiment_spec(grid::read_text_file(o.spec, "experiment spec"), o.spec);
  const auto spec_dir = fs::path(o.spec).parent_path();
  for (const auto& [map, scen] : e.spec.instances) {
    auto map_file = resolve(map, spec_dir, "maps");  // named first when both are missing
    e.files.emplace_back(std::move(map_file), resolve(scen, spec_dir, "scens"));
  }
  if (e.spec.plan_source == PlanSource::kFile) {
    e.plan_file = resolve(e.spec.plan, spec_dir, "smart-examples");
  }
  for (const auto& robot : e.spec.robots) (void)find_config_file("robots", robot);
  for (const auto& q : e.spec.qos) (void)dds::find_qos_profile(q);
  e.out = o.out.empty() ? fs::path("experiments") / e.spec.name : fs::path(o.out);
  e.cells = expand(e.spec);
  fs::create_directories(e.out);
  fs::copy_file(o.spec, e.out / "spec.yaml", fs::copy_options::overwrite_existing);
  return e;
}

int run_experiment(const ExperimentOptions& o) {
  if (o.domain + o.jobs > 231) {
    std::cerr << "experiment: --domain " << o.domain << " + --jobs " << o.jobs
              << " passes 230, the largest domain id; lower either\n";
    return kExitBadInput;
  }
  Experiment e;
  try {
    e = load_experiment(o);
  } catch (const std::exception& ex) {
    std::cerr << ex.what() << "\n";
    return kExitBadInput;
  }
  install_stop_handlers();
  const auto t = run_cells(e, o);
  const auto rows = write_results(e);
  std::cout << nlohmann::json{{"experiment", e.spec.name},
                              {"runs", e.cells.size()},
                              {"skipped", e.cells.size() - t.total},  // done before (resumed)
                              {"with_results", rows},
                              {"errors", t.errors},
                              {"stopped", g_stop_requested.load()},
                              {"results", (e.out / "results.csv").string()}}
            << std::endl;
  return rows == e.cells.size() ? kExitSuccess : kExitRunFailed;
}

// The figures: python3 with tools/plot/experiment_plot.py (matplotlib, Debian).
int plot_experiment(const std::string& results_dir, const std::string& out) {
  const fs::path script = fs::path(SMART_SOURCE_DIR) / "tools" / "plot" / "experiment_plot.py";
  if (!fs::is_regular_file(fs::path(results_dir) / "results.csv")) {
    std::cerr << "experiment plot: no results.csv in " << results_dir
              << "; give the folder `smart experiment` wrote\n";
    return kExitBadInput;
  }
  const auto dir = out.empty() ? (fs::path(results_dir) / "figures").string() : out;
  const int rc = common::ChildProcess({"/usr/bin/python3", script.string(), results_dir, dir})
                     .wait(std::chrono::minutes(10))
                     .value_or(-1);
  if (rc != 0) {
    std::cerr << "experiment plot: " << script.string() << " failed (exit code " << rc
              << "); is python3-matplotlib installed (scripts/install-deps.sh)?\n";
    return kExitSystem;
  }
  return kExitSuccess;
}
}  // namespace

void register_experiment_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<ExperimentOptions>();
  auto* cmd = app.add_subcommand(
      "experiment", "A batch of runs over a grid from a spec (YAML); resumable; results.csv");
  cmd->add_option("spec", o->spec, "the experiment spec (tools/include/smart/tools/experiment.hpp)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--out", o->out, "results folder (default: experiments/<name>)");
  cmd->add_option("--jobs", o->jobs, "runs at once (each in its own DDS domain id)")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  cmd->add_option("--domain", o->domain, "first DDS domain id (one per job)")
      ->check(CLI::Range(0, 230))
      ->capture_default_str();
  auto p = std::make_shared<std::pair<std::string, std::string>>();
  auto* plot = cmd->add_subcommand("plot", "Figures (PNG and SVG) from an experiment's results");
  plot->add_option("results", p->first, "the folder `smart experiment` wrote")->required();
  plot->add_option("--out", p->second, "where the figures go (default: RESULTS/figures)");
  plot->callback([&exit_code, p] { exit_code = plot_experiment(p->first, p->second); });
  cmd->callback([cmd, plot, o, &exit_code] {
    if (plot->parsed()) return;
    if (o->spec.empty()) throw CLI::RequiredError("spec (or the plot subcommand)");
    exit_code = run_experiment(*o);
  });
}

}  // namespace smart::tools
