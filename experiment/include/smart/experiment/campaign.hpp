// Contract: an experiment run as a campaign of `smart run` processes (the edge around spec.hpp).
// - run_campaign(): reads the spec, resolves every file it names (as given, next to the spec, or
//   in $SMART_BENCHMARKS/<maps|scens|smart-examples>/), checks its robot and QoS names, copies it
//   to OUT/spec.yaml, makes each (instance, agents) plan once into OUT/plans/ (the spec's file, the
//   built-in planner or the spec's command), runs up to `jobs` cells at once, each in its own DDS
//   domain id (first_domain + slot) and folder OUT/cells/<key>/ (run.log, the results folder), and
//   writes OUT/results.csv and OUT/results.jsonl, a row per cell with a summary (spec.hpp).
//   Resumable: a cell whose summary.json parses is not run again, unless its run was stopped
//   before its end (ran_to_its_end, spec.hpp: such a summary is no result and no row). Once
//   `stop` is set (SIGINT), the running cells are ended (SIGTERM: each writes what it has, as
//   stopped) and none is started; the next campaign of the spec runs them again.
// - plot_campaign(): the figures (PNG, SVG, PDF and figures.json, the data each shows) of OUT by
//   experiment/plot/experiment_plot.py (python3-matplotlib, Debian).
// Errors: std::invalid_argument for bad input (spec, files it names, options: the command's exit
// code 2), std::runtime_error when a plan or the plotter fails (exit code 3). A cell that fails
// is counted and named with its log, never fatal.
#pragma once

#include <atomic>
#include <cstddef>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>

namespace smart::experiment {

struct CampaignOptions {
  std::filesystem::path spec;
  std::filesystem::path out;  // default: experiments/<name>
  int jobs = 1;
  // first_domain + jobs - 1 must be at most 230. 10: below the tests' ids (44-230,
  // tests/support/dds_test_support.hpp), so a campaign beside `make test` shares no discovery.
  int first_domain = 10;
  std::filesystem::path smart;  // the `smart` executable that plans and runs the cells
  bool progress_bar = false;    // a redrawn bar with ETA (a terminal); else a line per cell
  const std::atomic<bool>* stop = nullptr;
};

struct CampaignReport {
  std::string name;
  std::size_t runs = 0;          // cells of the grid
  std::size_t skipped = 0;       // done before (resumed)
  std::size_t with_results = 0;  // rows of results.csv
  std::size_t errors = 0;        // cells run now that wrote no summary
  bool stopped = false;
  std::filesystem::path results;  // results.csv

  bool complete() const { return with_results == runs; }
  nlohmann::json to_json() const;
};

// `log`: progress and each failed cell with its log file.
CampaignReport run_campaign(const CampaignOptions& options, std::ostream& log);

// out_dir empty: RESULTS/figures.
void plot_campaign(const std::filesystem::path& results_dir, std::filesystem::path out_dir);

}  // namespace smart::experiment
