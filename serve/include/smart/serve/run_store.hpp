// Contract: the runs of a `smart serve` on disk, under its data folder: each run a folder <id>/
// holding the run's files (map.map, scen.scen, plan.txt, robot.yaml, request.json: how the plan is
// read again), results/ (monitor/results_format.hpp), run.out (`smart run`'s output) and the
// cached recording. Uploads are staged in fresh scratch folders and become runs whole (a rename)
// or not at all (discard). Queued runs start as `smart run` processes, at most max_running at
// once, and are collected when they end (done: exit 0 or 1 with a summary; failed otherwise,
// naming run.out). What the robot panel needs (a run's instance, its actions' finish times) is
// loaded once and kept. Ids come from RunRegistry: a URL's text is a path here only after
// is_run_id(). Thread-safe: HTTP handlers and the tending loop call it concurrently.
// Restarts (issue 26): one server per data folder (an exclusive lock on <data>/.lock, held while
// the store lives; a second server is refused naming the folder); the store adopts the runs a
// previous server left (entry.json beside each run: map name and robots; done when its
// summary.json is there, else failed as interrupted), continues their ids, and removes half-
// written uploads. A surprise in the folder (a file where a run folder should be, an unreadable
// entry) is skipped with a warning, never fatal; a new run never lands on an existing name.
#pragma once

#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "smart/common/child_process.hpp"
#include "smart/monitor/instance.hpp"
#include "smart/serve/run_registry.hpp"

namespace smart::serve {

// A run's files under its folder: upload field or summary.json "files" key -> file name.
inline constexpr std::pair<const char*, const char*> kRunFiles[] = {
    {"map", "map.map"}, {"scen", "scen.scen"}, {"plan", "plan.txt"}};

class RunStore {
 public:
  // Throws std::runtime_error when another server holds the data folder or it cannot be made.
  explicit RunStore(std::filesystem::path data_dir);
  ~RunStore();  // stops the runs still going

  std::filesystem::path dir(const std::string& id) const { return data_dir_ / id; }
  // A results file of a run (results_format.hpp names).
  std::filesystem::path results_file(const std::string& id, std::string_view name) const;
  // A fresh, empty scratch folder for an upload being checked.
  std::filesystem::path stage();
  // The staged folder becomes a queued run; `argv(id)` is its `smart run` command.
  std::string add_queued(const std::filesystem::path& staged, const std::string& map_name,
                         std::size_t robots,
                         const std::function<std::vector<std::string>(const std::string&)>& argv);
  // The staged folder becomes a finished run (a replay).
  std::string add_done(const std::filesystem::path& staged, const std::string& map_name,
                       std::size_t robots);

  std::optional<RunEntry> entry(const std::string& id) const;  // none: not a run here
  std::size_t queued() const;                                  // runs waiting to start
  std::vector<RunEntry> list() const;

  // The run's instance, loaded once by `load` from its folder.
  using Loader = std::function<monitor::Instance(const std::filesystem::path& run_dir)>;
  std::shared_ptr<const monitor::Instance> instance(const std::string& id, const Loader& load);
  // When each action of a finished run finished (actions.csv), by node; empty while it runs or
  // when it wrote none.
  std::shared_ptr<const std::vector<double>> action_times(const std::string& id,
                                                          const monitor::Instance& in);

  // The ADG a switchable run ended with (robot_detail.hpp ended_adg, from switches.csv); null
  // for any other run. Throws std::invalid_argument naming a malformed switches.csv row.
  std::shared_ptr<const monitor::Adg> ended_adg(const std::string& id, const monitor::Instance& in);

  // Starts what may start, collects what ended.
  void tend(std::size_t max_running);
  void stop_all();

 private:
  void lock_data_dir();
  void adopt_previous();
  // A fresh id whose folder does not exist yet (registry_.add or add_done); under m_.
  std::string fresh_id(const std::string& map_name, std::size_t robots, bool done);

  std::filesystem::path data_dir_;
  int lock_fd_ = -1;
  mutable std::mutex m_;
  RunRegistry registry_;
  uint64_t staged_ = 0;
  std::map<std::string, std::vector<std::string>> argv_;  // queued runs' command
  std::map<std::string, common::ChildProcess> children_;  // running ones
  std::map<std::string, std::shared_ptr<const monitor::Instance>> instances_;
  std::map<std::string, std::shared_ptr<const std::vector<double>>> action_times_;
  std::map<std::string, std::shared_ptr<const monitor::Adg>> ended_adgs_;
};

}  // namespace smart::serve
