// `smart serve`: the web API and viewer over runs (serve/include/smart/serve/server.hpp).
#include <spdlog/spdlog.h>

#include <cstdlib>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "smart/common/child_process.hpp"
#include "smart/common/install_paths.hpp"
#include "smart/monitor/instance.hpp"
#include "smart/record/import.hpp"
#include "smart/serve/fleet_watch.hpp"
#include "smart/serve/server.hpp"
#include "smart/tools/commands.hpp"
#include "smart/tools/run_options.hpp"
#include "temp_dir.hpp"

namespace smart::tools {

namespace {
struct ServeCliOptions {
  serve::ServeOptions serve;
  DdsOptions dds;
  double max_upload_mb = 64;
  double max_upload_memory_mb = 256;
  std::vector<std::filesystem::path> open;  // results folders or recordings to replay
  bool watch = false;
  // --watch --plan: the watched run's instance (with --map, --scen, --axis, --robot, --cell-m).
  WorldCliOptions world;
  std::string plan, axis;
};

// The watched run's plan, for its robots' paths and Type-2 waits (issue 26: none were shown).
std::shared_ptr<const monitor::Instance> watch_plan(ServeCliOptions& o) {
  if (o.plan.empty()) return nullptr;
  if (!o.watch || o.serve.watch_map.empty() || o.world.scen.empty()) {
    throw std::invalid_argument(
        "--plan is the watched run's: give it with --watch, --map and --scen");
  }
  o.world.map = o.serve.watch_map.string();
  o.world.cell_m = o.serve.watch_cell_m;
  return std::make_shared<const monitor::Instance>(monitor::load_instance(instance_options(
      o.world, o.plan,
      o.axis.empty()
          ? std::nullopt
          : std::optional(o.axis == "xy" ? grid::AxisOrder::kXY : grid::AxisOrder::kRowCol),
      grid::PlanFormat::kAuto)));
}

// --watch: a read-only view of the domain; under --security the keystore's viewer identity.
std::unique_ptr<serve::FleetWatch> start_watch(const ServeCliOptions& o) {
  if (!o.watch) return nullptr;
  serve::WatchOptions w;
  w.domain = o.dds.domain;
  w.qos = dds::find_qos_profile(o.dds.qos);
  w.config = domain_config(o.dds, w.qos, "viewer");
  w.run = o.dds.run_given ? o.dds.run : "";
  auto watch = std::make_unique<serve::FleetWatch>(w);
  spdlog::info("serve: watching {} on domain {}", w.run.empty() ? "every run" : "run " + w.run,
               w.domain);
  return watch;
}

// The user's cache folder (XDG), where uploads and results live unless --data says otherwise.
std::filesystem::path default_data_dir() {
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) {
    return std::filesystem::path(x) / "smart-dds" / "serve";
  }
  if (const char* h = std::getenv("HOME"); h && *h) {
    return std::filesystem::path(h) / ".cache" / "smart-dds" / "serve";
  }
  return std::filesystem::temp_directory_path() / "smart-dds-serve";
}

// A results folder, or a recording made here (record/import.hpp) read back into a scratch folder
// that the server copies from.
std::string open_run(serve::Server& server, const std::filesystem::path& path) {
  if (std::filesystem::is_directory(path)) return server.open_results(path);
  TempDir scratch("smart-open");
  const auto report = record::import_mcap(path, scratch.path() / "results");
  for (const auto& note : report.notes) spdlog::warn("{}: {}", path.string(), note);
  spdlog::info("serve: {}: {} robot states read back", path.string(), report.states);
  try {
    return server.open_results(scratch.path() / "results");
  } catch (const std::runtime_error& e) {
    throw std::invalid_argument(path.string() + ": the run it holds does not check: " + e.what());
  }
}

int serve_runs(ServeCliOptions o) {
  auto& s = o.serve;
  if (s.data_dir.empty()) s.data_dir = default_data_dir();
  s.smart_exe = common::self_executable();
  // The viewer installed beside this executable (<prefix>/share/smart-dds/web) or built next to
  // it (<build>/web-dist), unless --web says otherwise.
  const auto share = common::installed_share_dir();
  for (const auto& dir : {share ? *share / "web" : std::filesystem::path(),
                          s.smart_exe.parent_path().parent_path() / "web-dist"}) {
    if (s.web_dir.empty() && !dir.empty() && std::filesystem::exists(dir / "index.html")) {
      s.web_dir = dir;
    }
  }
  s.config_dir =
      std::filesystem::path(find_config_file("robots", "footbot")).parent_path().parent_path();
  s.max_upload_bytes = static_cast<std::size_t>(o.max_upload_mb * (1 << 20));
  s.max_upload_memory_bytes = static_cast<std::size_t>(o.max_upload_memory_mb * (1 << 20));
  s.domain = o.dds.domain;
  s.qos = o.dds.qos;
  s.watch_plan = watch_plan(o);
  const auto watch = start_watch(o);
  if (watch) s.watch = [&watch](uint64_t run_id) { return watch->snapshot(run_id); };
  serve::Server server(s);
  nlohmann::json opened = nlohmann::json::array();
  for (const auto& path : o.open) opened.push_back(open_run(server, path));
  const int port = server.bind();
  std::cout << nlohmann::json{{"listening", "http://" + s.bind + ":" + std::to_string(port)},
                              {"data", s.data_dir.string()},
                              {"opened", opened}}
            << std::endl;
  install_stop_handlers();
  server.run(g_stop_requested);
  return kExitSuccess;
}
}  // namespace

void register_serve_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<ServeCliOptions>();
  auto* cmd = app.add_subcommand(
      "serve", "HTTP API (and web viewer) to upload, run and replay runs: smart run per upload");
  cmd->add_option("--bind", o->serve.bind, "address to listen on")->capture_default_str();
  cmd->add_option("--port", o->serve.port, "port (0: any free port, printed)")
      ->check(CLI::Range(0, 65535))
      ->capture_default_str();
  cmd->add_option("--data", o->serve.data_dir,
                  "folder for uploads and results (default: ~/.cache/smart-dds/serve)");
  cmd->add_option("--web", o->serve.web_dir, "built web app to serve at / (web/dist)")
      ->check(CLI::ExistingDirectory);
  cmd->add_option("--open", o->open,
                  "a `smart run --out` folder or a `smart run --mcap` recording to replay "
                  "(repeatable)")
      ->check(CLI::ExistingPath);
  cmd->add_option("--max-runs", o->serve.max_running, "runs executing at once; the rest queue")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  cmd->add_option("--max-upload-mb", o->max_upload_mb, "largest upload accepted")
      ->check(finite_in(0.001, 4096))
      ->capture_default_str();
  cmd->add_option("--max-upload-memory-mb", o->max_upload_memory_mb,
                  "memory all uploads being read at once may hold; past it uploads get 503 "
                  "(retry later)")
      ->check(finite_in(0.001, 65536))
      ->capture_default_str();
  cmd->add_flag("--watch", o->watch,
                "also show what is live on the DDS domain (every run, or --run NAME), read-only: "
                "simulated and physical robots alike");
  cmd->add_option("--map", o->serve.watch_map, "the map to draw a watched run on (--watch)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--cell-m", o->serve.watch_cell_m, "the watched run's cell size (--watch)")
      ->check(finite_in(0.01, 100))
      ->capture_default_str();
  cmd->add_option("--scen", o->world.scen, "the watched run's scenario (--watch --plan)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--plan", o->plan,
                  "the watched run's plan: robots' paths and whom they wait for (--watch)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--axis", o->axis, "the plan's axis order, xy or rowcol (--watch --plan)")
      ->check(CLI::IsMember({"xy", "rowcol"}));
  cmd->add_option("--robot", o->world.robot, "the watched run's robot model (--watch --plan)")
      ->capture_default_str();
  cmd->add_option("--agents,--robots", o->world.agents,
                  "the watched run's robots: the first N of the plan (--watch --plan; 0: all)");
  cmd->add_option("--token", o->serve.token,
                  "secret that uploads must send (\"Authorization: Bearer TOKEN\"; the viewer: "
                  "open it with #token=TOKEN); needed for uploads when --bind is not loopback")
      ->envname("SMART_SERVE_TOKEN");
  add_dds_options(cmd, o->dds);
  cmd->callback([o, &exit_code] { exit_code = serve_runs(*o); });
}

}  // namespace smart::tools
