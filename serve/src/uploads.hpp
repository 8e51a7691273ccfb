// Internal to `smart serve`: what an upload must be before it becomes a run, decided on its staged
// folder. A run upload (POST /api/runs): its fields (RunRequest), its robot model with the
// upload's limits (robot.yaml), its plan checked as `smart check-plan` checks it, with the robot's
// ADG footprint on the run's 1 m cells. A results upload (POST /api/results, --open): checked as
// the viewer will read it (summary, states, map, and the plan files when given), its recording
// made once. Each check answers the 400's JSON {error, problems: [{file, line, robot, message}]}
// naming the files as the user knows them, or nothing.
#pragma once

#include <httplib.h>

#include <cstddef>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "smart/monitor/instance.hpp"
#include "smart/serve/server.hpp"

namespace smart::serve::upload {

// Uploads run on `smart run`'s default cells (--cell-m 1).
inline constexpr double kCellM = 1.0;
// The most robots a replayed results folder may have (the largest fleets measured are 10 000).
inline constexpr uint64_t kMaxReplayRobots = 100000;

// A name of lower-case letters, digits, '_' and '-' (robot models; nothing else becomes a path).
bool plain_name(const std::string& s);

// What a run upload asks for beyond its files; `error` names the first wrong field.
// A lifelong run from the form (issue 28): random tasks on the uploaded map, no scen or plan.
// Or a LoRR problem folder (kind=lorr): the problem JSON's path inside the uploaded folder,
// which is staged under the run's folder as problem/ (problem_folder.hpp).
struct LifelongRequest {
  int task_errands = 1;     // errands per task (random tasks)
  double duration_s = 120;  // sim seconds
  uint64_t seed = 1;
  bool folder = false;  // kind=lorr
  std::string problem;  // set by check_run: `smart run --lifelong problem/<this>`
};
struct RunRequest {
  std::optional<LifelongRequest> lifelong;  // set: `smart run --tasks random` on the map
  std::string axis = "xy";
  std::size_t agents = 0;
  std::string robot = "footbot";
  std::map<std::string, double> limits;  // robot YAML key -> value, from the upload form
  double real_time_factor = 0;           // `smart run --real-time-factor`: 0, as fast as possible
  std::string error;
};
RunRequest read_fields(const httplib::Request& req, const std::filesystem::path& robots_dir);

// robot.yaml in `staged`: the named model of config_dir/robots with the upload's limits.
std::optional<nlohmann::json> write_robot(const std::filesystem::path& staged,
                                          const std::filesystem::path& config_dir,
                                          const RunRequest& r);
// The upload's files written into `staged` and checked; a LoRR folder's problem and fleet size
// are set in `r` (agents 0: the problem's team).
std::optional<nlohmann::json> check_run(const httplib::Request& req,
                                        const std::filesystem::path& staged, RunRequest& r);
// The name the run list shows for an accepted run upload.
std::string run_name(const httplib::Request& req, const RunRequest& r);
// request.json of a run: how its plan is read again (a lifelong run has none: no plan files).
nlohmann::json request_json(const RunRequest& r);
// The `smart run` command of a run in `run_dir`.
std::vector<std::string> run_argv(const ServeOptions& opt, const std::filesystem::path& run_dir,
                                  const RunRequest& r);

// A staged replay: results/ and the run's files; its recording is written next to them.
std::optional<nlohmann::json> check_results(const std::filesystem::path& staged);
// The name the run list shows for a staged replay, and its fleet size (from summary.json).
std::pair<std::string, std::size_t> replay_entry(const std::filesystem::path& staged);

// The instance of a run folder: its files read as request.json says.
monitor::Instance load_run(const std::filesystem::path& run_dir);

}  // namespace smart::serve::upload
