#include "smart/serve/server.hpp"

#include <httplib.h>
#include <spdlog/spdlog.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <thread>

#include "smart/agent/robot_model.hpp"
#include "smart/common/child_process.hpp"
#include "smart/grid/map_reader.hpp"
#include "smart/grid/problem.hpp"
#include "smart/monitor/instance.hpp"
#include "smart/serve/recording.hpp"
#include "smart/serve/robot_detail.hpp"
#include "smart/serve/run_registry.hpp"

namespace smart::serve {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {
std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void reply(httplib::Response& res, int status, const json& body) {
  res.status = status;
  res.set_content(body.dump(), "application/json");
}

// Problems name the files as the user uploaded them, not the server's scratch paths.
// What a results folder may hold (monitor/results.hpp); nothing else is kept or served.
constexpr const char* kResultFiles[] = {"summary.json", "stats.csv", "robots.csv", "actions.csv",
                                        "states.csv"};
// A run's own files: upload field or summary.json "files" key -> name under the run's folder.
constexpr std::pair<const char*, const char*> kRunFiles[] = {
    {"map", "map.map"}, {"scen", "scen.scen"}, {"plan", "plan.txt"}};

// `names`: scratch path -> the name the user knows the file by.
json problems_json(const std::vector<grid::Problem>& problems,
                   const std::map<std::string, std::string>& names) {
  json out = json::array();
  for (const auto& p : problems) {
    const auto it = names.find(p.source);
    out.push_back({{"file", it == names.end() ? p.source : it->second},
                   {"line", p.line},
                   {"robot", p.robot},
                   {"message", p.message}});
  }
  return out;
}

json problems_json(const std::vector<grid::Problem>& problems, const httplib::Request& req,
                   const fs::path& scratch) {
  std::map<std::string, std::string> names;
  for (const auto& [field, name] : kRunFiles) {
    names[(scratch / name).string()] = req.get_file_value(field).filename;
  }
  return problems_json(problems, names);
}

// The most robots a replayed results folder may have (the largest fleets measured are 10 000).
constexpr uint64_t kMaxReplayRobots = 100000;

bool result_file(const std::string& name) {
  return std::any_of(std::begin(kResultFiles), std::end(kResultFiles),
                     [&](const char* f) { return name == f; });
}

bool plain_name(const std::string& s) {
  return !s.empty() && s.size() <= 64 &&
         s.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789_-") == std::string::npos;
}

// What an upload asks for beyond its files; an error text when a field is wrong.
struct RunRequest {
  std::string axis = "xy";
  std::size_t agents = 0;
  std::string robot = "footbot";
  std::map<std::string, double> limits;  // robot YAML key -> value, from the upload form
  double real_time_factor = 0;           // `smart run --real-time-factor`: 0, as fast as possible
  std::string error;
};

// Uploads run on `smart run`'s default cells (--cell-m 1).
constexpr double kUploadCellM = 1.0;

// The kinodynamic limits an upload may override (robot YAML keys, agent/robot_model.hpp).
constexpr const char* kLimitFields[] = {"max_speed_mps", "max_accel_mps2", "max_turn_rate_radps"};

// The whole text as a finite number, or none.
std::optional<double> finite_number(const std::string& text) {
  double v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(v)) return {};
  return v;
}

void read_limits(const httplib::Request& req, RunRequest& r) {
  for (const char* key : kLimitFields) {
    if (!req.has_file(key) || req.get_file_value(key).content.empty()) continue;
    const auto v = finite_number(req.get_file_value(key).content);
    if (!v || *v <= 0) {
      r.error = std::string(key) + " must be a positive number, e.g. 0.5";
      return;
    }
    r.limits[key] = *v;
  }
}

RunRequest read_fields(const httplib::Request& req, const fs::path& robots_dir) {
  RunRequest r;
  auto field = [&](const char* name) {
    return req.has_file(name) ? std::optional(req.get_file_value(name).content) : std::nullopt;
  };
  for (const char* f : {"plan", "scen", "map"}) {  // the first missing one is named
    if (!req.has_file(f)) r.error = "missing the '" + std::string(f) + "' file field";
  }
  if (auto a = field("axis")) r.axis = *a;
  if (r.axis != "xy" && r.axis != "rowcol") r.error = "axis must be xy or rowcol";
  if (auto n = field("agents")) {
    try {
      const long long v = std::stoll(*n);
      if (v < 0 || v > 100000) throw std::out_of_range(*n);
      r.agents = static_cast<std::size_t>(v);
    } catch (const std::logic_error&) {
      r.error = "agents must be a whole number from 0 (all) to 100000";
    }
  }
  if (auto m = field("robot")) r.robot = *m;
  if (!plain_name(r.robot) || !fs::is_regular_file(robots_dir / (r.robot + ".yaml"))) {
    r.error = "robot must name a model in config/robots, e.g. footbot";
  }
  if (r.error.empty()) read_limits(req, r);
  if (auto f = field("real_time_factor"); f && !f->empty() && r.error.empty()) {
    const auto v = finite_number(*f);
    if (!v || *v < 0 || *v > 1000) {
      r.error = "real_time_factor must be a number from 0 (as fast as possible) to 1000, e.g. 10";
    } else {
      r.real_time_factor = *v;
    }
  }
  return r;
}
}  // namespace

struct Server::Impl {
  ServeOptions opt;
  httplib::Server http;
  std::mutex m;
  RunRegistry registry;
  std::map<std::string, std::vector<std::string>> argv;  // queued runs' `smart run` command
  std::map<std::string, common::ChildProcess> children;  // running ones
  uint64_t uploads = 0;
  std::atomic<bool> stopping{false};
  std::map<std::string, std::shared_ptr<const monitor::Instance>> instances;  // loaded on demand
  std::map<std::string, std::shared_ptr<const std::vector<double>>> action_times;  // by node

  explicit Impl(ServeOptions o) : opt(std::move(o)) {}

  fs::path dir(const std::string& id) const { return opt.data_dir / id; }

  // A fresh folder under --data for an upload being checked (renamed to the run's when taken).
  fs::path scratch_dir() {
    std::lock_guard lock(m);
    return opt.data_dir / ("upload-" + std::to_string(++uploads));
  }

  // The instance in a folder of the run's files (map.map, scen.scen, plan.txt), with the ADG
  // footprint `smart run` gives its robot (robot.yaml, when there) on the run's cells, so that
  // the robot panel's waits are the run's and a robot too wide for the cells is refused here.
  static monitor::Instance load_files(const fs::path& d, std::size_t agents,
                                      const std::string& axis) {
    monitor::InstanceOptions io;
    io.map = d / "map.map";
    io.scen = d / "scen.scen";
    io.plan = d / "plan.txt";
    io.agents = agents;
    io.read.axis = axis == "rowcol" ? grid::AxisOrder::kRowCol : grid::AxisOrder::kXY;
    if (fs::exists(d / "robot.yaml")) {
      const double radius_m = agent::load_robot_model((d / "robot.yaml").string()).radius_m;
      const auto f = monitor::footprint_for(radius_m, kUploadCellM);
      if (!f) {
        throw std::invalid_argument(
            fmt::format("the robot (radius {:g} m) is half a cell ({:g} m) wide or more: robots on "
                        "neighbouring cells would touch; pick a smaller robot model",
                        radius_m, kUploadCellM));
      }
      io.footprint = *f;
    }
    return monitor::load_instance(io);
  }

  std::vector<std::string> run_argv(const std::string& id, const RunRequest& r) const {
    const auto d = dir(id);
    return {opt.smart_exe.string(),
            "run",
            "--map",
            (d / "map.map").string(),
            "--scen",
            (d / "scen.scen").string(),
            "--plan",
            (d / "plan.txt").string(),
            "--axis",
            r.axis,
            "--agents",
            std::to_string(r.agents),
            "--robot",
            (d / "robot.yaml").string(),
            "--cell-m",
            std::to_string(kUploadCellM),
            "--domain",
            std::to_string(opt.domain),
            "--qos",
            opt.qos,
            "--out",
            (d / "results").string(),
            "--real-time-factor",
            std::to_string(r.real_time_factor),
            "--no-progress"};
  }

  // The robot model of the run: the named model with the upload's limits, written next to the
  // run's files and checked like any robot YAML (the limits' ranges come from there).
  std::optional<json> write_robot(const fs::path& scratch, const RunRequest& r) {
    try {
      YAML::Node model = YAML::LoadFile((opt.config_dir / "robots" / (r.robot + ".yaml")).string());
      for (const auto& [key, value] : r.limits) model[key] = value;
      YAML::Emitter out;
      out << model;
      std::ofstream(scratch / "robot.yaml") << out.c_str();
      (void)agent::parse_robot_model(out.c_str(), "the upload's robot limits");
      return std::nullopt;
    } catch (const std::exception& e) {
      return json{{"error", e.what()}, {"problems", json::array()}};
    }
  }

  // Writes the upload under a scratch folder and checks it as `smart check-plan` would.
  std::optional<json> check_upload(const httplib::Request& req, const fs::path& scratch,
                                   const RunRequest& r) {
    fs::create_directories(scratch);
    for (const auto& [field, name] : kRunFiles) {
      std::ofstream(scratch / name, std::ios::binary) << req.get_file_value(field).content;
    }
    try {
      (void)load_files(scratch, r.agents, r.axis);
      return std::nullopt;
    } catch (const grid::InputError& e) {
      return json{{"error", "the upload has problems"},
                  {"problems", problems_json(e.problems(), req, scratch)}};
    } catch (const std::exception& e) {
      return json{{"error", e.what()}, {"problems", json::array()}};
    }
  }

  void post_run(const httplib::Request& req, httplib::Response& res) {
    const RunRequest r = read_fields(req, opt.config_dir / "robots");
    if (!r.error.empty()) return reply(res, 400, {{"error", r.error}, {"problems", json::array()}});
    const fs::path scratch = scratch_dir();
    fs::create_directories(scratch);
    auto bad = write_robot(scratch, r);  // first: the upload is checked with its robot
    if (!bad) bad = check_upload(req, scratch, r);
    if (bad) {
      fs::remove_all(scratch);
      return reply(res, 400, *bad);
    }
    std::lock_guard lock(m);
    const auto id = registry.add(req.get_file_value("map").filename, r.agents);
    fs::rename(scratch, dir(id));
    std::ofstream(dir(id) / "request.json") << json{{"axis", r.axis}, {"agents", r.agents}}.dump();
    argv[id] = run_argv(id, r);
    reply(res, 200, {{"id", id}});
  }

  // A staged replay (results/ and the run's files) checked as the viewer will read it; the
  // recording is made here once. An error naming the file and line, or nothing.
  std::optional<json> check_results(const fs::path& staged) {
    const auto bad = [](std::string what) {
      return json{{"error", std::move(what)}, {"problems", json::array()}};
    };
    const auto r = staged / "results";
    for (const char* f : {"summary.json", "states.csv"}) {
      if (!fs::is_regular_file(r / f)) return bad(std::string("no ") + f + " in the results");
    }
    const auto summary = json::parse(slurp(r / "summary.json"), nullptr, false);
    if (!summary.is_object() || !summary["robots"].is_number_unsigned() ||
        summary["robots"].get<uint64_t>() > kMaxReplayRobots) {
      return bad(
          "summary.json is not the summary `smart run --out` writes (\"robots\" must be "
          "a whole number up to " +
          std::to_string(kMaxReplayRobots) + ")");
    }
    if (!fs::is_regular_file(staged / "map.map")) {
      const auto named = summary.value("files", json::object());
      return bad("no map: give the run's map file (summary.json names " +
                 (named.is_object() ? named.value("map", std::string("none")) : "none") +
                 ", not found from here)");
    }
    try {
      (void)grid::parse_map(slurp(staged / "map.map"), "the map");
      const auto rows = parse_states_csv(slurp(r / "states.csv"));
      // The recording holds every robot in every frame: a forged robot id would size it.
      const auto robots = summary["robots"].get<uint64_t>();
      for (std::size_t i = 0; i < rows.size(); ++i) {
        if (rows[i].robot >= robots) {
          return bad("states.csv row " + std::to_string(i + 2) + " names robot " +
                     std::to_string(rows[i].robot) + " but summary.json has " +
                     std::to_string(robots) + " robots; give the files of one run");
        }
      }
      std::ofstream(staged / "recording-v2.smrc", std::ios::binary) << encode_recording(rows);
      if (fs::is_regular_file(staged / "scen.scen") && fs::is_regular_file(staged / "plan.txt")) {
        write_request(staged, summary);
        const auto in = load(staged);
        if (fs::is_regular_file(r / "actions.csv")) {
          (void)parse_action_times(slurp(r / "actions.csv"), in.actions);
        }
      }
    } catch (const grid::InputError& e) {
      return json{{"error", "the run's files have problems"},
                  {"problems", problems_json(e.problems(), staged_names(staged))}};
    } catch (const std::exception& e) {
      return bad(e.what());
    }
    return std::nullopt;
  }

  static std::map<std::string, std::string> staged_names(const fs::path& staged) {
    std::map<std::string, std::string> names;
    for (const auto& [field, name] : kRunFiles) names[(staged / name).string()] = field;
    return names;
  }

  // How the plan is read again (axis, robots), from the summary of the run that was made on it.
  static void write_request(const fs::path& staged, const json& summary) {
    const auto plan = summary.value("plan", json::object());
    std::ofstream(staged / "request.json") << json{
        {"axis", plan.is_object() ? plan.value("axis", "xy") : "xy"},
        {"agents",
         summary.value("robots", std::size_t{0})}}.dump();
  }

  // A checked replay becomes a done run.
  std::string adopt(const fs::path& staged) {
    const auto summary = json::parse(slurp(staged / "results" / "summary.json"));
    const auto files = summary.value("files", json::object());
    const std::string map = files.is_object() ? files.value("map", "?") : "?";
    std::lock_guard lock(m);
    const auto id = registry.add_done(fs::path(map).filename().string(),
                                      summary.value("robots", std::size_t{0}));
    fs::rename(staged, dir(id));
    return id;
  }

  // POST /api/results: a results folder (fields "files", many) with the run's map (and scen and
  // plan for the robot panel), replayed like --open.
  void post_results(const httplib::Request& req, httplib::Response& res) {
    const fs::path scratch = scratch_dir();
    fs::create_directories(scratch / "results");
    const auto [first, last] = req.files.equal_range("files");
    for (auto it = first; it != last; ++it) {
      const auto name = fs::path(it->second.filename).filename().string();
      if (result_file(name)) std::ofstream(scratch / "results" / name) << it->second.content;
    }
    for (const auto& [field, name] : kRunFiles) {
      if (req.has_file(field)) std::ofstream(scratch / name) << req.get_file_value(field).content;
    }
    if (auto bad = check_results(scratch)) {
      fs::remove_all(scratch);
      return reply(res, 400, *bad);
    }
    reply(res, 200, {{"id", adopt(scratch)}});
  }

  // GET /api/runs/{id}/results/{name}: a results file as a download, streamed from disk.
  void get_result_file(const std::string& id, const std::string& name, httplib::Response& res) {
    const auto path = dir(id) / "results" / name;
    if (!entry(id) || !result_file(name) || !fs::is_regular_file(path)) {
      return reply(res, 404, {{"error", "no " + name + " in the results of " + id}});
    }
    res.set_header("Content-Disposition", "attachment; filename=\"" + id + "-" + name + "\"");
    auto in = std::make_shared<std::ifstream>(path, std::ios::binary);
    res.set_content_provider(
        fs::file_size(path), name.ends_with(".json") ? "application/json" : "text/csv",
        [in](size_t offset, size_t length, httplib::DataSink& sink) {
          std::vector<char> buf(std::min<size_t>(length, 1 << 16));
          in->seekg(static_cast<std::streamoff>(offset));
          in->read(buf.data(), static_cast<std::streamsize>(buf.size()));
          return in->gcount() > 0 && sink.write(buf.data(), static_cast<size_t>(in->gcount()));
        });
  }

  json entry_json(const RunEntry& e) const {
    return {{"id", e.id},
            {"state", to_string(e.state)},
            {"map", e.map_name},
            {"robots", e.robots},
            {"error", e.error}};
  }

  void get_run(const std::string& id, httplib::Response& res) {
    const auto e = entry(id);
    if (!e) return reply(res, 404, {{"error", "no run " + id}});
    json j = entry_json(*e);
    const auto summary = dir(id) / "results" / "summary.json";
    if (e->state == RunState::kDone && fs::exists(summary))
      j["summary"] = json::parse(slurp(summary));
    j["files"] = json::array();
    for (const char* f : kResultFiles) {
      if (e->state == RunState::kDone && fs::exists(dir(id) / "results" / f))
        j["files"].push_back(f);
    }
    reply(res, 200, j);
  }

  void get_recording(const std::string& id, httplib::Response& res) {
    const auto e = entry(id);
    const auto states = dir(id) / "results" / "states.csv";
    if (!e || e->state != RunState::kDone || !fs::exists(states)) {
      return reply(res, 404, {{"error", "no recording of " + id + " (yet)"}});
    }
    const auto cached = dir(id) / "recording-v2.smrc";
    if (!fs::exists(cached)) {
      std::ofstream(cached, std::ios::binary) << encode_recording(parse_states_csv(slurp(states)));
    }
    res.set_content(slurp(cached), "application/octet-stream");
  }

  std::optional<RunEntry> entry(const std::string& id) {
    std::lock_guard lock(m);
    return is_run_id(id) ? registry.get(id) : std::nullopt;
  }

  // One event per call, paced; the stream ends after the event that shows the run ended.
  bool live_event(const std::string& id, PoseTail& tail, std::uintmax_t& offset,
                  httplib::DataSink& sink) {
    const auto e = entry(id);
    const auto states = dir(id) / "results" / "states.csv";
    std::ifstream in(states, std::ios::binary);
    if (in && in.seekg(static_cast<std::streamoff>(offset))) {
      std::string chunk((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      offset += chunk.size();
      tail.feed(chunk);
    }
    json poses = json::array();
    for (const auto& p : tail.latest()) poses.push_back({p.x_m, p.y_m, p.yaw_rad});
    const std::string state(to_string(e->state));
    const auto msg =
        "data: " + json{{"state", state}, {"t_s", tail.time_s()}, {"poses", poses}}.dump() + "\n\n";
    if (!sink.write(msg.data(), msg.size())) return false;
    if (e->state == RunState::kDone || e->state == RunState::kFailed) {
      sink.done();
      return true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(250));
    return true;
  }

  void get_live(const std::string& id, httplib::Response& res) {
    if (!entry(id)) return reply(res, 404, {{"error", "no run " + id}});
    auto tail = std::make_shared<PoseTail>();
    auto offset = std::make_shared<std::uintmax_t>(0);
    res.set_chunked_content_provider("text/event-stream",
                                     [this, id, tail, offset](size_t, httplib::DataSink& sink) {
                                       return live_event(id, *tail, *offset, sink);
                                     });
  }

  // The instance in a run's folder: its files read as request.json says.
  static monitor::Instance load(const fs::path& d) {
    const auto request = json::parse(slurp(d / "request.json"));
    return load_files(d, request.value("agents", std::size_t{0}),
                      request.value("axis", std::string("xy")));
  }

  // The run's instance (plan, actions, ADG), loaded once from its files and request.json.
  std::shared_ptr<const monitor::Instance> instance(const std::string& id) {
    {
      std::lock_guard lock(m);
      if (auto it = instances.find(id); it != instances.end()) return it->second;
    }
    auto in = std::make_shared<const monitor::Instance>(load(dir(id)));
    std::lock_guard lock(m);
    return instances.emplace(id, std::move(in)).first->second;
  }

  // When each action of a finished run finished (actions.csv), by node; empty while it runs or
  // when the run wrote none.
  std::shared_ptr<const std::vector<double>> times(const std::string& id,
                                                   const monitor::Instance& in) {
    {
      std::lock_guard lock(m);
      if (auto it = action_times.find(id); it != action_times.end()) return it->second;
    }
    const auto csv = dir(id) / "results" / "actions.csv";
    const auto e = entry(id);
    if (!e || e->state != RunState::kDone || !fs::exists(csv)) {
      return std::make_shared<const std::vector<double>>();
    }
    auto t =
        std::make_shared<const std::vector<double>>(parse_action_times(slurp(csv), in.actions));
    std::lock_guard lock(m);
    return action_times.emplace(id, std::move(t)).first->second;
  }

  // Finished actions over time (the stats panel's plot), from actions.csv.
  void get_progress(const std::string& id, httplib::Response& res) {
    const auto e = entry(id);
    if (!e || !fs::exists(dir(id) / "request.json")) {
      return reply(res, 404, {{"error", "no finished actions of " + id + " (no plan files)"}});
    }
    try {
      reply(res, 200, finished_curve(*times(id, *instance(id))));
    } catch (const std::exception& ex) {
      reply(res, 404, {{"error", ex.what()}});
    }
  }

  // robots.csv's row of `robot` as JSON (finish and waiting time, stops, lower bound), if the
  // run wrote one; an empty field (not finished, bound unknown) is null.
  json robot_results(const std::string& id, uint32_t robot) const {
    std::ifstream in(dir(id) / "results" / "robots.csv");
    std::string line;
    const auto number = [](const std::string& text) {
      double v = 0;
      const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
      return ec == std::errc() && end == text.data() + text.size() ? json(v) : json();
    };
    for (std::getline(in, line); std::getline(in, line);) {
      std::istringstream row(line);
      std::string cell[6];
      for (auto& c : cell) std::getline(row, c, ',');
      if (cell[0] == std::to_string(robot)) {
        return {{"finish_time_s", number(cell[1])},
                {"waiting_time_s", number(cell[2])},
                {"stops", number(cell[3])},
                {"lower_bound_s", number(cell[5])}};
      }
    }
    return json::object();
  }

  void get_robot(const std::string& id, const std::string& robot_text, httplib::Response& res) {
    const auto e = entry(id);
    if (!e || !fs::exists(dir(id) / "request.json") ||
        robot_text.find_first_not_of("0123456789") != std::string::npos || robot_text.size() > 7) {
      return reply(res, 404, {{"error", "no robot " + robot_text + " in " + id}});
    }
    try {
      const auto robot = static_cast<uint32_t>(std::stoul(robot_text));
      const auto in = instance(id);
      json j = robot_detail(*in, robot, summary_cell_m(id), *times(id, *in));
      j["results"] = robot_results(id, robot);
      reply(res, 200, j);
    } catch (const std::exception& ex) {
      reply(res, 404, {{"error", ex.what()}});
    }
  }

  double summary_cell_m(const std::string& id) const {
    const auto s = dir(id) / "results" / "summary.json";
    return fs::exists(s) ? json::parse(slurp(s)).value("cell_m", 1.0) : 1.0;
  }

  // GET /api/robots: the robot models an upload may name, with their limits (the form's
  // sliders start there).
  void get_robots(httplib::Response& res) const {
    json out = json::array();
    std::vector<fs::path> files;
    for (const auto& e : fs::directory_iterator(opt.config_dir / "robots")) {
      if (e.path().extension() == ".yaml" && plain_name(e.path().stem().string())) {
        files.push_back(e.path());
      }
    }
    std::sort(files.begin(), files.end());
    for (const auto& f : files) {
      try {
        const auto m = agent::load_robot_model(f.string());
        out.push_back({{"name", f.stem().string()},
                       {"max_speed_mps", m.max_speed_mps},
                       {"max_accel_mps2", m.max_accel_mps2},
                       {"max_turn_rate_radps", m.max_turn_rate_radps}});
      } catch (const std::exception& e) {
        spdlog::warn("serve: robot model {} not offered: {}", f.string(), e.what());
      }
    }
    reply(res, 200, out);
  }

  // --watch: the board as JSON, once or as a stream (until the page goes away).
  void watch_routes() {
    const auto run_of = [](const httplib::Request& req) -> uint64_t {
      const auto v = req.get_param_value("run_id");
      uint64_t id = 0;
      std::from_chars(v.data(), v.data() + v.size(), id);
      return id;
    };
    http.Get("/api/watch", [this, run_of](const auto& req, auto& res) {
      if (!opt.watch)
        return reply(res, 404, {{"error", "not watching: start smart serve --watch"}});
      auto j = opt.watch(run_of(req));
      j["cell_m"] = opt.watch_cell_m;
      reply(res, 200, j);
    });
    http.Get("/api/watch/map", [this](const auto&, auto& res) {
      if (opt.watch_map.empty()) return reply(res, 404, {{"error", "no map: give --map"}});
      res.set_content(slurp(opt.watch_map), "text/plain");
    });
    http.Get("/api/watch/live", [this, run_of](const auto& req, auto& res) {
      if (!opt.watch)
        return reply(res, 404, {{"error", "not watching: start smart serve --watch"}});
      const uint64_t run = run_of(req);
      res.set_chunked_content_provider("text/event-stream", [this, run](size_t, auto& sink) {
        if (stopping.load()) return false;  // the server is going down: end the stream
        const auto msg = "data: " + opt.watch(run).dump() + "\n\n";
        if (!sink.write(msg.data(), msg.size())) return false;
        std::this_thread::sleep_for(std::chrono::milliseconds(250));
        return true;
      });
    });
  }

  void routes() {
    // Without TCP_NODELAY (cpp-httplib's default is off) Nagle's algorithm and delayed ACKs held
    // static files back: three.js (0.7 MB) took 1.9 s over loopback, 0.1 s with it.
    http.set_tcp_nodelay(true);
    watch_routes();
    http.Get("/api/robots", [this](const auto&, auto& res) { get_robots(res); });
    http.set_payload_max_length(opt.max_upload_bytes);
    http.Post("/api/runs", [this](const auto& req, auto& res) { post_run(req, res); });
    http.Get("/api/runs", [this](const auto&, auto& res) {
      json list = json::array();
      std::lock_guard lock(m);
      for (const auto& e : registry.list()) list.push_back(entry_json(e));
      reply(res, 200, list);
    });
    http.Get(R"(/api/runs/([^/]+))",
             [this](const auto& req, auto& res) { get_run(req.matches[1], res); });
    http.Get(R"(/api/runs/([^/]+)/recording)",
             [this](const auto& req, auto& res) { get_recording(req.matches[1], res); });
    http.Get(R"(/api/runs/([^/]+)/map)", [this](const auto& req, auto& res) {
      const std::string id = req.matches[1];
      if (!entry(id) || !fs::exists(dir(id) / "map.map")) {
        return reply(res, 404, {{"error", "no map of " + id}});
      }
      res.set_content(slurp(dir(id) / "map.map"), "text/plain");
    });
    http.Get(R"(/api/runs/([^/]+)/robots/([^/]+))", [this](const auto& req, auto& res) {
      get_robot(req.matches[1], req.matches[2], res);
    });
    http.Post("/api/results", [this](const auto& req, auto& res) { post_results(req, res); });
    http.Get(R"(/api/runs/([^/]+)/progress)",
             [this](const auto& req, auto& res) { get_progress(req.matches[1], res); });
    http.Get(R"(/api/runs/([^/]+)/results/([^/]+))", [this](const auto& req, auto& res) {
      get_result_file(req.matches[1], req.matches[2], res);
    });
    http.Get(R"(/api/runs/([^/]+)/live)",
             [this](const auto& req, auto& res) { get_live(req.matches[1], res); });
    if (!opt.web_dir.empty()) http.set_mount_point("/", opt.web_dir.string());
  }

  // Starts what may start, collects what ended.
  void tend_runs() {
    std::lock_guard lock(m);
    for (const auto& id : registry.start_ready(opt.max_running)) {
      children.emplace(id, common::ChildProcess(argv.at(id), dir(id) / "run.out"));
      spdlog::info("serve: {} started", id);
    }
    for (auto it = children.begin(); it != children.end();) {
      const auto rc = it->second.wait(std::chrono::milliseconds(0));
      if (!rc) {
        ++it;
        continue;
      }
      const bool summary = fs::exists(dir(it->first) / "results" / "summary.json");
      const bool ok = (*rc == 0 || *rc == 1) && summary;
      registry.finish(it->first, ok,
                      ok ? ""
                         : "smart run exited with code " + std::to_string(*rc) + "; see " +
                               (dir(it->first) / "run.out").string());
      spdlog::info("serve: {} ended (exit code {})", it->first, *rc);
      it = children.erase(it);
    }
  }
};

Server::Server(ServeOptions options) : impl_(std::make_unique<Impl>(std::move(options))) {
  fs::create_directories(impl_->opt.data_dir);
  impl_->routes();
}

Server::~Server() = default;

std::string Server::open_results(const fs::path& results) {
  auto& I = *impl_;
  const fs::path scratch = I.scratch_dir();
  fs::create_directories(scratch / "results");
  for (const char* f : kResultFiles) {
    if (fs::is_regular_file(results / f)) fs::copy_file(results / f, scratch / "results" / f);
  }
  // The files the run was made on, when still where summary.json says (for the robot panel).
  json files = json::object();
  if (fs::is_regular_file(results / "summary.json")) {
    files = json::parse(slurp(results / "summary.json"), nullptr, false).value("files", files);
  }
  for (const auto& [key, name] : kRunFiles) {
    const fs::path src = files.is_object() ? files.value(key, std::string()) : std::string();
    if (!src.empty() && fs::is_regular_file(src)) fs::copy_file(src, scratch / name);
  }
  if (auto bad = I.check_results(scratch)) {
    fs::remove_all(scratch);
    throw std::runtime_error("--open " + results.string() + ": " + bad->value("error", "") +
                             "; give a folder written by `smart run --out`");
  }
  return I.adopt(scratch);
}

int Server::bind() {
  auto& I = *impl_;
  const int port = I.opt.port == 0
                       ? I.http.bind_to_any_port(I.opt.bind)
                       : (I.http.bind_to_port(I.opt.bind, I.opt.port) ? I.opt.port : -1);
  if (port < 0) {
    throw std::runtime_error("cannot listen on " + I.opt.bind + ":" + std::to_string(I.opt.port) +
                             "; is the port taken? choose another with --port");
  }
  return port;
}

void Server::run(const std::atomic<bool>& stop) {
  auto& I = *impl_;
  std::thread listener([&] { I.http.listen_after_bind(); });
  while (!stop.load()) {
    I.tend_runs();
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  I.stopping = true;
  I.http.stop();
  listener.join();
  std::lock_guard lock(I.m);
  I.children.clear();  // ChildProcess stops what still runs
}

}  // namespace smart::serve
