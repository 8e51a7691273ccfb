// Contract: `smart serve`'s HTTP edge (cpp-httplib, Debian): a small JSON API over runs that
// execute as real `smart run` processes (monitor + sim host over DDS, each in its own run
// partition), at most max_running at once, the rest queued.
//   POST /api/runs               multipart: map, scen, plan (files); axis (xy|rowcol), agents,
//                                robot (a model name), max_speed_mps, max_accel_mps2,
//                                max_turn_rate_radps (overrides of the model's limits, checked
//                                against its ranges), real_time_factor (0 or none: as fast as
//                                possible; e.g. 10 to watch it live; `smart run
//                                --real-time-factor`). Runs on 1 m cells; the plan is checked
//                                with the robot's ADG footprint there (a robot half a cell wide
//                                is refused). 200 {"id"}; 400 {"error", "problems":
//                                [{file, line, robot, message}]} as `smart check-plan` lists them
//   GET  /api/runs               [{id, state, map, robots}]
//   GET  /api/runs/{id}          {id, state, error, summary (summary.json, once done)}
//   GET  /api/runs/{id}/recording the run's poses in the SMRC format (recording.hpp)
//   GET  /api/runs/{id}/map      the run's MovingAI map text
//   GET  /api/runs/{id}/robots/{r} planned path, actions, Type-2 partners (robot_detail.hpp)
//                                and robots.csv's finish/waiting time
//   GET  /api/runs/{id}/live     Server-Sent Events, about 4 a second until the run ended:
//                                {"state", "t_s", "poses": [[x_m, y_m, yaw_rad], ...], "status":
//                                [moving|waiting|idle per robot], "queue": [...], "progress":
//                                {"t_s", "finished", "total"} once the run has finished one,
//                                "finished": [actions finished per robot] once known}
//   GET  /api/robots             the robot models offered, with their limits
//   GET  /api/watch              (--watch) the runs live on the DDS domain and the newest one's
//                                robots (fleet_watch.hpp, watch_board.hpp); ?run_id= picks one
//   GET  /api/watch/live         the same as Server-Sent Events, about 4 a second
//   GET  /api/runs/{id}/marks    every robot's start and goal from the run's plan
//   (robot_detail.hpp) GET  /api/watch/map          the map given with --watch (MovingAI text) GET
//   /api/watch/robots/{r}   with --plan: robot r's path and actions with their Type-2
//                                predecessors (robot_detail.hpp, no times); /api/watch then also
//                                has "total_actions"
//   POST /api/results            a `smart run --out` folder (fields "files") and the run's map
//                                (scen, plan optional) to replay; 400 names the bad file/line
//   GET  /api/runs/{id}/progress finished actions over time (actions.csv)
//   GET  /api/runs/{id}/results/{name} a results file as a download (summary.json, stats.csv,
//                                robots.csv, actions.csv, states.csv; nothing else)
//   GET  /...                    the web app's built files (web_dir), when given
// Files live only under data_dir/<id>/ with fixed names; ids come from RunRegistry and anything
// else in a URL is a 404, so no request reads or writes outside data_dir. Uploads are bounded
// (max_upload_bytes). A run that fails or crashes is recorded as failed; the server goes on.
#pragma once

#include <atomic>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "smart/monitor/instance.hpp"

namespace smart::serve {

struct ServeOptions {
  std::string bind = "127.0.0.1";
  int port = 8080;  // 0: any free port (bind() returns it)
  std::filesystem::path data_dir;
  std::filesystem::path web_dir;     // empty: API only
  std::filesystem::path smart_exe;   // the `smart` executable that runs each run
  std::filesystem::path config_dir;  // robot models offered (config/robots)
  std::size_t max_running = 1;
  std::size_t max_upload_bytes = 64u << 20;
  // What all uploads being read at once may hold (upload_budget.hpp); past it: 503.
  std::size_t max_upload_memory_bytes = 256u << 20;
  // Bounds no client may exceed (issue 25: 8 slow connections or 8 open live streams froze the
  // API; the run queue was unbounded): request threads, live streams open at once, runs queued.
  std::size_t threads = 64;
  std::size_t max_live_streams = 16;
  std::size_t max_queued = 32;
  int read_timeout_s = 5;
  // Write endpoints (uploads) need "Authorization: Bearer <token>" when set; bound beyond
  // loopback without one, they are refused.
  std::string token;
  int domain = 0;
  std::string qos = "lan";
  // --watch: what is live on the domain (run_id 0: the newest), and the map to draw it on.
  std::function<nlohmann::json(uint64_t run_id)> watch;
  std::filesystem::path watch_map;
  double watch_cell_m = 1.0;
  // The watched run's plan (--watch --plan), for robots' paths and whom they wait for now.
  std::shared_ptr<const monitor::Instance> watch_plan;
};

class Server {
 public:
  explicit Server(ServeOptions options);
  ~Server();
  // Adds a finished run from a `smart run --out` folder (summary.json, states.csv) to replay;
  // copies it under data_dir. Throws std::runtime_error naming a missing file. Returns its id.
  std::string open_results(const std::filesystem::path& results_dir);
  // Binds the socket; returns the port. Throws std::runtime_error naming bind:port on failure.
  int bind();
  // Serves until stop is set (checked every 100 ms); runs still going are stopped.
  void run(const std::atomic<bool>& stop);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace smart::serve
