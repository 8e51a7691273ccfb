#include "uploads.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <variant>

#include "slurp.hpp"
#include "smart/agent/robot_model.hpp"
#include "smart/grid/lorr.hpp"
#include "smart/grid/map_reader.hpp"
#include "smart/grid/problem.hpp"
#include "smart/monitor/results_format.hpp"
#include "smart/planning/generators.hpp"
#include "smart/serve/bounded_json.hpp"
#include "smart/serve/problem_folder.hpp"
#include "smart/serve/recording.hpp"
#include "smart/serve/robot_detail.hpp"
#include "smart/serve/run_store.hpp"

namespace smart::serve::upload {

namespace fs = std::filesystem;
using nlohmann::json;
namespace key = results::summary_key;

namespace {

// Problems name the files as the user uploaded them, not the server's scratch paths.
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

// The instance in a folder of the run's files (map.map, scen.scen, plan.txt), with the ADG
// footprint `smart run` gives its robot (robot.yaml, when there) on the run's cells, so that
// the robot panel's waits are the run's and a robot too wide for the cells is refused here.
monitor::Instance load_files(const fs::path& d, std::size_t agents, const std::string& axis) {
  monitor::InstanceOptions io;
  io.map = d / "map.map";
  io.scen = d / "scen.scen";
  io.plan = d / "plan.txt";
  io.agents = agents;
  io.read.axis = axis == "rowcol" ? grid::AxisOrder::kRowCol : grid::AxisOrder::kXY;
  if (fs::exists(d / "robot.yaml")) {
    const double radius_m = agent::load_robot_model((d / "robot.yaml").string()).radius_m;
    const auto f = monitor::footprint_for(radius_m, kCellM);
    if (!f) {
      throw std::invalid_argument(
          fmt::format("the robot (radius {:g} m) is half a cell ({:g} m) wide or more: robots on "
                      "neighbouring cells would touch; pick a smaller robot model",
                      radius_m, kCellM));
    }
    io.footprint = *f;
  }
  return monitor::load_instance(io);
}

std::map<std::string, std::string> staged_names(const fs::path& staged) {
  std::map<std::string, std::string> names;
  for (const auto& [field, name] : kRunFiles) names[(staged / name).string()] = field;
  return names;
}

// How the plan is read again (axis, robots), from the summary of the run that was made on it.
void write_request(const fs::path& staged, const json& summary) {
  const auto plan = summary.value(key::kPlan, json::object());
  std::ofstream(staged / "request.json") << json{
      {"axis", plan.is_object() ? plan.value(key::kAxis, "xy") : "xy"},
      {"agents", summary.value(key::kRobots,
                               std::size_t{0})}}.dump();
}

}  // namespace

bool plain_name(const std::string& s) {
  return !s.empty() && s.size() <= 64 &&
         s.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789_-") == std::string::npos;
}

namespace {
// kind=lifelong: task_errands, duration_s and seed (each optional, each in its range).
// kind=lorr: the same but task_errands (the problem's tasks are its own), agents 0 for its team.
void read_lifelong(const httplib::Request& req, RunRequest& r, bool lorr) {
  LifelongRequest l;
  const auto number = [&](const char* name, double lo, double hi, double& out) {
    if (!req.has_file(name) || req.get_file_value(name).content.empty()) return;
    const auto v = finite_number(req.get_file_value(name).content);
    if (!v || *v < lo || *v > hi || (std::string(name) != "duration_s" && *v != std::floor(*v))) {
      r.error =
          fmt::format("{} must be {} from {:g} to {:g}", name,
                      std::string(name) == "duration_s" ? "a number" : "a whole number", lo, hi);
      return;
    }
    out = *v;
  };
  double errands = l.task_errands, seed = static_cast<double>(l.seed);
  number("task_errands", 1, 64, errands);
  number("duration_s", 1, 3600, l.duration_s);
  number("seed", 0, 1e9, seed);
  l.task_errands = static_cast<int>(errands);
  l.seed = static_cast<uint64_t>(seed);
  l.folder = lorr;
  if (r.agents == 0 && !lorr) r.error = "agents: a lifelong run needs its fleet size (1 to 100000)";
  r.lifelong = l;
}
}  // namespace

RunRequest read_fields(const httplib::Request& req, const fs::path& robots_dir) {
  RunRequest r;
  auto field = [&](const char* name) {
    return req.has_file(name) ? std::optional(req.get_file_value(name).content) : std::nullopt;
  };
  const auto kind = field("kind").value_or("plan");
  if (kind != "plan" && kind != "lifelong" && kind != "lorr") {
    r.error =
        "kind must be plan (map, scen and plan), lifelong (a map and random tasks) or lorr (a "
        "LoRR problem folder)";
    return r;
  }
  const std::vector<const char*> needed = kind == "plan"
                                              ? std::vector<const char*>{"plan", "scen", "map"}
                                          : kind == "lifelong" ? std::vector<const char*>{"map"}
                                                               : std::vector<const char*>{"folder"};
  for (const char* f : needed) {  // the first missing one is named
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
  if (kind != "plan" && r.error.empty()) read_lifelong(req, r, kind == "lorr");
  return r;
}

// The robot model of the run: the named model with the upload's limits, written next to the
// run's files and checked like any robot YAML (the limits' ranges come from there).
std::optional<json> write_robot(const fs::path& scratch, const fs::path& config_dir,
                                const RunRequest& r) {
  try {
    YAML::Node model = YAML::LoadFile((config_dir / "robots" / (r.robot + ".yaml")).string());
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

namespace {
// A lifelong upload: its map, and room on it for the fleet.
std::optional<json> check_lifelong(const httplib::Request& req, const fs::path& scratch,
                                   const RunRequest& r) {
  std::ofstream(scratch / "map.map", std::ios::binary) << req.get_file_value("map").content;
  try {
    const auto g = grid::parse_map(slurp(scratch / "map.map"), req.get_file_value("map").filename);
    if (g.free_cells() < r.agents) {
      return json{
          {"error", fmt::format("the map has {} free cells for {} robots; give fewer robots",
                                g.free_cells(), r.agents)},
          {"problems", json::array()}};
    }
  } catch (const grid::InputError& e) {
    return json{{"error", "the upload has problems"},
                {"problems", problems_json(e.problems(), {{(scratch / "map.map").string(),
                                                           req.get_file_value("map").filename}})}};
  } catch (const std::exception& e) {
    return json{{"error", e.what()}, {"problems", json::array()}};
  }
  return std::nullopt;
}
// A LoRR problem folder's files under scratch/problem by their paths in the folder (checked
// first: problem_folder.hpp); scratch path -> the path the user knows, or the 400's JSON.
std::variant<std::map<std::string, std::string>, json> stage_folder(const httplib::Request& req,
                                                                    const fs::path& dir) {
  const auto bad = [](std::string what) {
    return json{{"error", std::move(what)}, {"problems", json::array()}};
  };
  const auto [first, last] = req.files.equal_range("folder");
  if (static_cast<std::size_t>(std::distance(first, last)) > kMaxFolderFiles) {
    return bad("the folder has more than " + std::to_string(kMaxFolderFiles) +
               " files: upload the problem's folder only");
  }
  std::map<std::string, std::string> names;
  for (auto it = first; it != last; ++it) {
    const auto& rel = it->second.filename;
    if (auto why = check_folder_path(rel); !why.empty()) return bad(why);
    const auto to = dir / rel;
    if (names.count(to.string())) return bad("the folder has '" + rel + "' twice");
    fs::create_directories(to.parent_path());
    std::ofstream(to, std::ios::binary) << it->second.content;
    names[to.string()] = rel;
  }
  return names;
}

// A file's scratch paths in `text` replaced by the paths the user knows.
std::string as_uploaded(std::string text, const fs::path& dir) {
  const auto prefix = dir.string() + "/";
  for (auto at = text.find(prefix); at != std::string::npos; at = text.find(prefix, at)) {
    text.erase(at, prefix.size());
  }
  return text;
}

// The files the problem names (relative to its own folder) must be files of the upload: an
// uploaded problem naming "/etc/passwd" or "../../x" must not make the server read it.
std::optional<json> check_named_files(const fs::path& dir, const std::string& problem,
                                      const std::map<std::string, std::string>& names) {
  const auto spec = grid::parse_lorr_spec(slurp(dir / problem), problem);
  const auto folder = fs::path(problem).parent_path();
  for (const auto& [field, file] : {std::pair{"mapFile", spec.map_file},
                                    {"agentFile", spec.agent_file},
                                    {"taskFile", spec.task_file}}) {
    const auto path = (folder / file).lexically_normal().string();
    if (!check_folder_path(file).empty() || !names.count((dir / path).string())) {
      return json{{"error", problem + ": " + field + " '" + file +
                                "' is not a file of the uploaded folder; name one of its files, "
                                "relative to the problem (e.g. maps/x.map)"},
                  {"problems", json::array()}};
    }
  }
  return std::nullopt;
}

// A LoRR folder upload: its problem read as `smart run --lifelong` reads it, the fleet no
// larger than its team; its map written as map.map for the viewer.
std::optional<json> check_lorr(const httplib::Request& req, const fs::path& scratch,
                               RunRequest& r) {
  const auto dir = scratch / "problem";
  auto staged = stage_folder(req, dir);
  if (auto* bad = std::get_if<json>(&staged)) return *bad;
  const auto& names = std::get<std::map<std::string, std::string>>(staged);
  std::vector<std::string> paths;
  paths.reserve(names.size());
  for (const auto& [to, rel] : names) paths.push_back(rel);
  const auto named = req.has_file("problem_file") ? req.get_file_value("problem_file").content : "";
  const auto choice = choose_problem(paths, named);
  if (!choice.error.empty()) return json{{"error", choice.error}, {"problems", json::array()}};
  try {
    if (auto bad = check_named_files(dir, choice.problem, names)) return bad;
    const auto lp = grid::load_lorr_problem(dir / choice.problem);
    if (r.agents > lp.starts.size()) {
      return json{{"error", fmt::format("agents: {} has {} robots; give at most that many (0: all)",
                                        choice.problem, lp.starts.size())},
                  {"problems", json::array()}};
    }
    if (r.agents == 0) r.agents = lp.starts.size();
    std::ofstream(scratch / "map.map") << planning::to_movingai_map(lp.grid);
  } catch (const grid::InputError& e) {
    auto problems = problems_json(e.problems(), names);
    for (auto& p : problems) p["file"] = as_uploaded(p["file"].get<std::string>(), dir);
    return json{{"error", "the problem has problems"}, {"problems", problems}};
  } catch (const std::exception& e) {
    return json{{"error", as_uploaded(e.what(), dir)}, {"problems", json::array()}};
  }
  r.lifelong->problem = choice.problem;
  return std::nullopt;
}

}  // namespace

// Writes the upload under a scratch folder and checks it as `smart check-plan` would.
std::optional<json> check_run(const httplib::Request& req, const fs::path& scratch, RunRequest& r) {
  if (r.lifelong && r.lifelong->folder) return check_lorr(req, scratch, r);
  if (r.lifelong) return check_lifelong(req, scratch, r);
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

namespace {
// robots.csv, when given, as the robot panel reads it: rows of this run's robots (a malformed
// one used to make the panel answer 404 later). Throws std::invalid_argument naming the line.
std::optional<std::string> check_robots_csv(const fs::path& csv, uint64_t robots) {
  if (!fs::is_regular_file(csv)) return std::nullopt;
  for (const auto& row : results::parse_robots_csv(slurp(csv))) {
    if (row.robot >= robots) {
      return "robots.csv has a row for robot " + std::to_string(row.robot) +
             " but summary.json has " + std::to_string(robots) +
             " robots; give the files of one run";
    }
  }
  return std::nullopt;
}
}  // namespace

// A staged replay (results/ and the run's files) checked as the viewer will read it; the
// recording is made here once. An error naming the file and line, or nothing.
std::optional<json> check_results(const fs::path& staged) {
  const auto bad = [](std::string what) {
    return json{{"error", std::move(what)}, {"problems", json::array()}};
  };
  const auto r = staged / "results";
  for (const auto f : {results::kSummaryJson, results::kStatesCsv}) {
    if (!fs::is_regular_file(r / f)) return bad("no " + std::string(f) + " in the results");
  }
  json summary;
  try {
    summary = parse_bounded_json(slurp(r / results::kSummaryJson), "summary.json");
  } catch (const std::invalid_argument& e) {
    return bad(e.what());
  }
  if (!summary.is_object() || !summary[key::kRobots].is_number_unsigned() ||
      summary[key::kRobots].get<uint64_t>() > kMaxReplayRobots) {
    return bad(
        "summary.json is not the summary `smart run --out` writes (\"robots\" must be "
        "a whole number up to " +
        std::to_string(kMaxReplayRobots) + ")");
  }
  if (!fs::is_regular_file(staged / "map.map")) {
    const auto named = summary.value(key::kFiles, json::object());
    return bad("no map: give the run's map file (summary.json names " +
               (named.is_object() ? named.value(key::kMap, std::string("none")) : "none") +
               ", not found from here)");
  }
  try {
    (void)grid::parse_map(slurp(staged / "map.map"), "the map");
    const auto states = slurp(r / results::kStatesCsv);
    const auto rows = parse_states_csv(states);
    // The recording holds every robot in every frame: a forged robot id would size it.
    const auto robots = summary[key::kRobots].get<uint64_t>();
    for (std::size_t i = 0; i < rows.size(); ++i) {
      if (rows[i].robot >= robots) {
        return bad("states.csv row " + std::to_string(i + 2) + " names robot " +
                   std::to_string(rows[i].robot) + " but summary.json has " +
                   std::to_string(robots) + " robots; give the files of one run");
      }
    }
    check_recording_size(rows, states.size());
    if (auto wrong = check_robots_csv(r / results::kRobotsCsv, robots)) return bad(*wrong);
    std::ofstream(staged / "recording-v2.smrc", std::ios::binary) << encode_recording(rows);
    if (fs::is_regular_file(staged / "scen.scen") && fs::is_regular_file(staged / "plan.txt")) {
      write_request(staged, summary);
      const auto in = load_run(staged);
      if (fs::is_regular_file(r / results::kActionsCsv)) {
        (void)parse_action_times(slurp(r / results::kActionsCsv), in.actions);
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

// The instance in a run's folder: its files read as request.json says.
monitor::Instance load_run(const fs::path& d) {
  const auto request = json::parse(slurp(d / "request.json"));
  return load_files(d, request.value("agents", std::size_t{0}),
                    request.value("axis", std::string("xy")));
}

std::vector<std::string> run_argv(const ServeOptions& opt, const fs::path& d, const RunRequest& r) {
  std::vector<std::string> argv{opt.smart_exe.string(), "run"};
  if (r.lifelong && !r.lifelong->problem.empty()) {  // a LoRR problem: its map, robots and tasks
    argv.insert(argv.end(), {"--lifelong", (d / "problem" / r.lifelong->problem).string()});
  } else {
    argv.insert(argv.end(), {"--map", (d / "map.map").string()});
  }
  argv.insert(argv.end(), {"--agents", std::to_string(r.agents)});
  if (r.lifelong && !r.lifelong->problem.empty()) {
    argv.insert(argv.end(), {"--duration-s", fmt::format("{:g}", r.lifelong->duration_s), "--seed",
                             std::to_string(r.lifelong->seed)});
  } else if (r.lifelong) {  // random tasks on the map
    argv.insert(argv.end(),
                {"--tasks", "random", "--task-errands", std::to_string(r.lifelong->task_errands),
                 "--duration-s", fmt::format("{:g}", r.lifelong->duration_s), "--seed",
                 std::to_string(r.lifelong->seed)});
  } else {
    argv.insert(argv.end(), {"--scen", (d / "scen.scen").string(), "--plan",
                             (d / "plan.txt").string(), "--axis", r.axis});
  }
  argv.insert(argv.end(), {"--robot", (d / "robot.yaml").string(), "--cell-m",
                           std::to_string(kCellM), "--domain", std::to_string(opt.domain), "--qos",
                           opt.qos, "--out", (d / "results").string(), "--real-time-factor",
                           std::to_string(r.real_time_factor), "--no-progress"});
  return argv;
}

std::string run_name(const httplib::Request& req, const RunRequest& r) {
  if (r.lifelong && !r.lifelong->problem.empty()) return r.lifelong->problem;
  return req.get_file_value("map").filename;
}

json request_json(const RunRequest& r) { return {{"axis", r.axis}, {"agents", r.agents}}; }

std::pair<std::string, std::size_t> replay_entry(const fs::path& staged) {
  const auto summary =
      parse_bounded_json(slurp(staged / "results" / results::kSummaryJson), "summary.json");
  const auto files = summary.value(key::kFiles, json::object());
  const std::string map = files.is_object() ? files.value(key::kMap, "?") : "?";
  return {fs::path(map).filename().string(), summary.value(key::kRobots, std::size_t{0})};
}

}  // namespace smart::serve::upload
