// `smart experiment SPEC.yaml` and `smart experiment plot RESULTS`: flags into
// experiment::CampaignOptions (experiment/campaign.hpp: the grid's runs, resumable, results.csv),
// the report as one JSON line on stdout. Bad input (std::invalid_argument) exits 2 through main's
// printer, a failed plan or plotter 3, a campaign with cells missing results 1.
#include <unistd.h>

#include <iostream>

#include "smart/common/child_process.hpp"
#include "smart/experiment/campaign.hpp"
#include "smart/tools/cli_common.hpp"
#include "smart/tools/commands.hpp"

namespace smart::tools {

namespace {

struct ExperimentOptions {
  std::string spec, out;
  int jobs = 1;
  int domain = experiment::CampaignOptions{}.first_domain;
};

int run_experiment(const ExperimentOptions& o) {
  experiment::CampaignOptions c;
  c.spec = o.spec;
  c.out = o.out;
  c.jobs = o.jobs;
  c.first_domain = o.domain;
  c.smart = common::self_executable();
  c.progress_bar = ::isatty(STDERR_FILENO) != 0;
  c.stop = &g_stop_requested;
  install_stop_handlers();
  const auto report = experiment::run_campaign(c, std::cerr);
  std::cout << report.to_json() << std::endl;
  return report.complete() ? kExitSuccess : kExitRunFailed;
}

}  // namespace

void register_experiment_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<ExperimentOptions>();
  auto* cmd = app.add_subcommand(
      "experiment", "A batch of runs over a grid from a spec (YAML); resumable; results.csv");
  cmd->add_option("spec", o->spec,
                  "the experiment spec (experiment/include/smart/experiment/spec.hpp)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--out", o->out, "results folder (default: experiments/<name>)");
  cmd->add_option("--jobs", o->jobs, "runs at once (each in its own DDS domain id)")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  cmd->add_option("--domain", o->domain,
                  "first DDS domain id (one per job; the default stays below the tests' ids)")
      ->check(CLI::Range(0, 230))
      ->capture_default_str();
  auto p = std::make_shared<std::pair<std::string, std::string>>();
  auto* plot = cmd->add_subcommand(
      "plot", "Figures (PNG, SVG, PDF; figures.json: the data shown) from an experiment's results");
  plot->add_option("results", p->first, "the folder `smart experiment` wrote")->required();
  plot->add_option("--out", p->second, "where the figures go (default: RESULTS/figures)");
  plot->callback([&exit_code, p] {
    experiment::plot_campaign(p->first, p->second);
    exit_code = kExitSuccess;
  });
  cmd->callback([cmd, plot, o, &exit_code] {
    if (plot->parsed()) return;
    if (o->spec.empty()) throw CLI::RequiredError("spec (or the plot subcommand)");
    exit_code = run_experiment(*o);
  });
}

}  // namespace smart::tools
