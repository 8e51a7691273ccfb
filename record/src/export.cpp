#include "smart/record/export.hpp"

#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>

#include "recording_parts.hpp"
#include "smart/agent/robot_model.hpp"
#include "smart/grid/grid.hpp"
#include "smart/grid/map_reader.hpp"
#include "smart/grid/text_file.hpp"
#include "smart/monitor/instance.hpp"
#include "smart/record/import.hpp"

namespace smart::record {

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

constexpr std::size_t kMaxPlanChannels = 60000;

}  // namespace

FileSink::FileSink(const fs::path& path) : path_(path), out_(path, std::ios::binary) {
  if (!out_) throw std::runtime_error(path.string() + ": cannot be written; check the folder");
}

void FileSink::write(std::string_view bytes) {
  out_.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out_) throw std::runtime_error(path_.string() + ": write failed (disk full?)");
  bytes_ += bytes.size();
}

void FileSink::close() {
  out_.close();
  if (!out_) throw std::runtime_error(path_.string() + ": closing failed (disk full?)");
}

namespace {

json read_summary(const fs::path& dir) {
  if (fs::is_regular_file(dir)) {
    throw std::invalid_argument(dir.string() +
                                ": a file, not a results folder; give the folder of "
                                "`smart run --out DIR` (a recording opens with `smart serve "
                                "--open " +
                                dir.string() + "`)");
  }
  const fs::path p = dir / results::kSummaryJson;
  if (!fs::is_regular_file(p)) {
    throw std::invalid_argument(p.string() +
                                ": not found; give the results folder of a finished run "
                                "(`smart run --out DIR`)");
  }
  json s;
  try {
    s = json::parse(grid::read_text_file(p, "summary"));
  } catch (const json::exception& e) {
    throw std::invalid_argument(p.string() + ": " + e.what() + "; it needs \"robots\" (a number)");
  }
  // Checked before any get<size_t>: of a double that is a plain cast, undefined past its range,
  // and of a negative number a huge fleet to allocate.
  const auto robots = s.is_object() ? s.find(results::summary_key::kRobots) : s.end();
  if (robots == s.end() || !robots->is_number_unsigned() ||
      robots->get<uint64_t>() > static_cast<uint64_t>(grid::kMaxRobots)) {
    throw std::invalid_argument(p.string() + ": \"robots\" is " +
                                (robots == s.end() ? std::string("missing") : robots->dump()) +
                                "; it must be the run's robot count, a whole number up to " +
                                std::to_string(grid::kMaxRobots) +
                                " (the summary.json `smart run --out` writes)");
  }
  return s;
}

std::string file_of(const json& summary, const char* key) {
  const auto files = summary.value(results::summary_key::kFiles, json::object());
  const auto it = files.find(key);
  return it != files.end() && it->is_string() ? it->get<std::string>() : std::string();
}

grid::Grid read_map(const fs::path& dir, const json& summary) {
  fs::path map = dir / results::kLifelongMap;
  if (!fs::is_regular_file(map)) map = file_of(summary, results::summary_key::kMap);
  if (map.empty() || !fs::is_regular_file(map)) {
    throw std::invalid_argument((dir / results::kSummaryJson).string() + ": the run's map '" +
                                map.string() +
                                "' cannot be read; put it back where summary.json's "
                                "files.map says");
  }
  return grid::parse_map(grid::read_text_file(map, "map"), map.string());
}

// The run's instance (its plan, ADG), or nothing (with a note) when it cannot be read again.
std::optional<monitor::Instance> read_instance(const json& summary, std::size_t robots,
                                               ExportReport& report) {
  const std::string plan = file_of(summary, results::summary_key::kPlan);
  if (plan.empty()) return std::nullopt;
  try {
    monitor::InstanceOptions io;
    io.map = file_of(summary, results::summary_key::kMap);
    io.scen = file_of(summary, results::summary_key::kScen);
    io.plan = plan;
    io.agents = robots;
    const auto p = summary.value(results::summary_key::kPlan, json::object());
    if (p.is_object() && p.contains(results::summary_key::kAxis)) {
      io.read.axis =
          monitor::parse_axis_order(p.at(results::summary_key::kAxis).get<std::string>());
    }
    if (p.is_object() && p.contains(results::summary_key::kFormat)) {
      io.read.format =
          monitor::parse_plan_format(p.at(results::summary_key::kFormat).get<std::string>());
    }
    return monitor::load_instance(io);
  } catch (const std::exception& e) {
    report.notes.push_back("plans and markers not recorded: the plan " + plan +
                           " cannot be read again (" + e.what() + ")");
    return std::nullopt;
  }
}

// The robots' radius for their markers: the run's robot model, else a fifth of a cell.
double robot_radius_m(const json& summary, double cell_m) {
  try {
    const std::string robot = file_of(summary, results::summary_key::kRobot);
    if (!robot.empty()) return agent::load_robot_model(robot).radius_m;
  } catch (const std::exception&) {
  }
  return 0.2 * cell_m;
}

std::string read_optional(const fs::path& p, const char* what) {
  return fs::is_regular_file(p) ? grid::read_text_file(p, what) : std::string();
}

void add_progress(const fs::path& dir, RunRecorder& rec) {
  const fs::path p = dir / results::kActionsCsv;
  const std::string text = read_optional(p, "actions");
  try {
    results::for_each_action_row(text, [&](const results::ActionRow& row, std::size_t line) {
      if (!row.finish_time_s) return;
      try {
        rec.progress(*row.finish_time_s, row.robot, static_cast<int32_t>(row.action));
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument("line " + std::to_string(line) + ": " + e.what());
      }
    });
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(p.string() + ": " + e.what());
  }
}

void add_events(const fs::path& dir, RunRecorder& rec) {
  const fs::path p = dir / results::kEventsCsv;
  try {
    for (const auto& row : results::parse_events_csv(read_optional(p, "events"))) rec.event(row);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(p.string() + ": " + e.what());
  }
}

void add_states(const fs::path& dir, RunRecorder& rec) {
  const fs::path p = dir / results::kStatesCsv;
  std::ifstream in(p);
  if (!in) throw std::invalid_argument(p.string() + ": not found; the run wrote no robot states");
  std::string line;
  for (std::size_t n = 1; std::getline(in, line); ++n) {
    if (n == 1 || line.empty()) continue;  // the header
    const auto row = results::parse_state_line(line);
    if (!row) {
      throw std::invalid_argument(p.string() + ":" + std::to_string(n) + ": not a state row (" +
                                  std::string(results::kStatesHeader) + "); the file is damaged");
    }
    try {
      rec.state(*row);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(p.string() + ":" + std::to_string(n) + ": " + e.what());
    }
  }
}

std::string media_type(const fs::path& name) {
  const auto ext = name.extension().string();
  return ext == ".json" ? "application/json" : ext == ".csv" ? "text/csv" : "text/plain";
}

// The results files (states.csv is the smart/state channel) and the run's inputs, so that the
// recording opens in the viewer anywhere (import.hpp).
void attach_files(const fs::path& dir, const json& summary, RunRecorder& rec,
                  ExportReport& report) {
  for (const auto name : results::kFiles) {
    if (name == results::kStatesCsv || !fs::is_regular_file(dir / name)) continue;
    rec.attach(name, media_type(name), grid::read_text_file(dir / name, std::string(name).c_str()));
    report.attachments.emplace_back(name);
  }
  if (fs::is_regular_file(dir / results::kLifelongMap)) {
    rec.attach(results::kLifelongMap, "text/plain",
               grid::read_text_file(dir / results::kLifelongMap, "map"));
    report.attachments.emplace_back(results::kLifelongMap);
  }
  for (const char* key : {results::summary_key::kMap, results::summary_key::kScen,
                          results::summary_key::kPlan, results::summary_key::kRobot}) {
    const fs::path file = file_of(summary, key);
    if (file.empty()) continue;
    if (!fs::is_regular_file(file)) {
      report.notes.push_back(std::string("the run's ") + key + " " + file.string() +
                             " is not attached: it cannot be read");
      continue;
    }
    const std::string name =
        std::string(kInputAttachmentPrefix) + key + "/" + file.filename().string();
    rec.attach(name, "text/plain", grid::read_text_file(file, key));
    report.attachments.push_back(name);
  }
}

}  // namespace

void start_recording(RunRecorder& rec, const grid::Grid& map, double cell_m,
                     const monitor::Instance* instance, double robot_radius_m,
                     ExportReport& report) {
  rec.map(map, cell_m);
  // A channel per robot's plan: MCAP's 16-bit channel ids bound them.
  if (instance && report.robots > kMaxPlanChannels) {
    report.notes.push_back("plans and markers not recorded: " + std::to_string(report.robots) +
                           " robots, more plan channels than an MCAP file can hold");
  } else if (instance) {
    rec.plan_view(*instance, cell_m, robot_radius_m);
  }
}

void end_recording(RunRecorder& rec, const fs::path& results_dir, ExportReport& report) {
  attach_files(results_dir, read_summary(results_dir), rec, report);
  rec.finish();
  report.messages = rec.messages();
  report.channels = rec.channel_counts();
}

ExportReport export_mcap(const fs::path& results_dir, const fs::path& out,
                         const RecorderOptions& options) {
  ExportReport report;
  const json summary = read_summary(results_dir);
  report.robots = summary.at(results::summary_key::kRobots).get<std::size_t>();
  const double cell_m = summary.value(results::summary_key::kCellM, 1.0);
  const grid::Grid map = read_map(results_dir, summary);
  const auto instance = read_instance(summary, report.robots, report);
  const fs::path part = out.string() + ".part";
  FileSink sink(part);
  try {
    RunRecorder rec(sink, options, report.robots,
                    summary.value(results::summary_key::kRunId, uint64_t{0}));
    start_recording(rec, map, cell_m, instance ? &*instance : nullptr,
                    robot_radius_m(summary, cell_m), report);
    add_progress(results_dir, rec);
    add_events(results_dir, rec);
    add_states(results_dir, rec);
    end_recording(rec, results_dir, report);
    sink.close();
  } catch (...) {
    std::error_code ec;
    fs::remove(part, ec);
    throw;
  }
  fs::rename(part, out);
  report.bytes = sink.bytes();
  return report;
}

}  // namespace smart::record
