// `smart export mcap RESULTS_DIR -o FILE`: a results folder as an MCAP recording (record/,
// docs/ros2.md "Recordings"); `smart run --mcap FILE` calls record_run() once its run is over.
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <iostream>
#include <regex>
#include <tuple>

#include "smart/record/export.hpp"
#include "smart/tools/cli_common.hpp"
#include "smart/tools/commands.hpp"
#include "smart/tools/record_run.hpp"

namespace smart::tools {

namespace fs = std::filesystem;

namespace {
// The recording's topics like `mcap info` lists them, one line per robot topic family
// (/robot_<id>/plan: 50 topics), on standard output.
void print_topics(const std::vector<record::McapWriter::ChannelCount>& channels) {
  static const std::regex kRobot("/robot_[0-9]+/");
  std::vector<std::tuple<std::string, std::string, uint64_t, uint64_t>> rows;  // + topics
  for (const auto& c : channels) {
    const std::string topic = std::regex_replace(c.topic, kRobot, "/robot_<id>/");
    if (!rows.empty() && std::get<0>(rows.back()) == topic) {
      std::get<2>(rows.back()) += c.messages;
      ++std::get<3>(rows.back());
    } else {
      rows.emplace_back(topic, c.schema_name, c.messages, 1);
    }
  }
  for (const auto& [topic, type, messages, topics] : rows) {
    std::cout << fmt::format("  {:<28} {:<36} {:>9} msgs{}\n", topic, type, messages,
                             topics > 1 ? fmt::format(" ({} topics)", topics) : "");
  }
}
}  // namespace

void record_run(const fs::path& results_dir, const fs::path& mcap,
                const record::RecorderOptions& options) {
  print_recording(record::export_mcap(results_dir, mcap, options), mcap);
}

record::RecorderOptions run_recorder_options(const MonitorCliOptions& o) {
  record::RecorderOptions r;
  r.ros_namespace = o.sim.ros_namespace;
  r.pose_robots = o.sim.ros_pose_robots;
  return r;
}

void print_recording(const record::ExportReport& report, const fs::path& mcap) {
  for (const auto& note : report.notes) spdlog::warn("{}: {}", mcap.string(), note);
  std::cout << fmt::format("{}: {} messages of {} robots, {:.1f} MB, profile ros2\n", mcap.string(),
                           report.messages, report.robots, static_cast<double>(report.bytes) / 1e6);
  print_topics(report.channels);
  std::cout << fmt::format("  attachments: {} (for `smart serve --open {}`)\n",
                           fmt::join(report.attachments, ", "), mcap.string());
}

void register_record_commands(CLI::App& app, int& exit_code) {
  auto* exp = app.add_subcommand("export", "Convert a run's results for other tools");
  exp->require_subcommand(1);
  struct Args {
    std::string dir, out, ros_namespace;
    std::vector<uint32_t> pose_robots;
    bool uncompressed = false;
  };
  auto args = std::make_shared<Args>();
  auto* mcap = exp->add_subcommand(
      "mcap",
      "Write a results folder as an MCAP file (profile ros2: the ROS 2 view's topics and the "
      "run's own, for Foxglove, Lichtblick and `ros2 bag`; docs/ros2.md)");
  mcap->add_option("RESULTS_DIR", args->dir, "a run's results folder (`smart run --out DIR`)")
      ->required()
      ->check(CLI::ExistingPath);  // a file is named by export_mcap with what to do instead
  mcap->add_option(
      "-o,--out", args->out,
      "the MCAP file (default: RESULTS_DIR/" + std::string(record::kDefaultMcap) + ")");
  mcap->add_option("--ros-namespace", args->ros_namespace,
                   "put the ROS 2 view's topics under this namespace (e.g. /run_a)");
  mcap->add_option("--ros-pose-robots", args->pose_robots,
                   "robots that also get a PoseStamped topic /robot_<id>/pose")
      ->delimiter(',');
  mcap->add_flag("--uncompressed", args->uncompressed, "chunks without zstd");
  mcap->callback([&exit_code, args] {
    record::RecorderOptions o;
    o.ros_namespace = args->ros_namespace;
    o.pose_robots = args->pose_robots;
    o.mcap.compress = !args->uncompressed;
    const fs::path out =
        args->out.empty() ? fs::path(args->dir) / record::kDefaultMcap : fs::path(args->out);
    record_run(args->dir, out, o);
    exit_code = ExitCode::kExitSuccess;
  });
}

}  // namespace smart::tools
