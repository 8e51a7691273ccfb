// `smart bridge`: a run's ROS 2 view live in Foxglove or Lichtblick over the Foxglove WebSocket
// protocol (bridge/, docs/ros2.md "Live in Foxglove"): a read-only DDS watch feeding a
// WebSocket server. Prints {"listening": "ws://ADDR:PORT"} once it listens, runs until
// SIGINT/SIGTERM.
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <iostream>
#include <nlohmann/json.hpp>
#include <thread>

#include "smart/bridge/foxglove_server.hpp"
#include "smart/bridge/ros_watch.hpp"
#include "smart/tools/cli_common.hpp"
#include "smart/tools/commands.hpp"

namespace smart::tools {

namespace {
struct BridgeCliOptions {
  DdsOptions dds;
  uint16_t port = 8765;  // Foxglove's default for a WebSocket connection
  std::string bind = "127.0.0.1";
  std::string ros_namespace;
  std::vector<uint32_t> pose_robots;
};

int run_bridge(const BridgeCliOptions& o) {
  bridge::ServerOptions so;
  so.bind = o.bind;
  so.port = o.port;
  so.latched = {bridge::kMapChannel, bridge::kMarkersChannel};
  bridge::FoxgloveServer server(so, bridge::ros_view_channels(o.ros_namespace, o.pose_robots));
  bridge::RosWatchOptions wo;
  wo.domain = o.dds.domain;
  wo.config = domain_config(o.dds, dds::find_qos_profile(o.dds.qos), "viewer");
  wo.ros_namespace = o.ros_namespace;
  wo.pose_robots = o.pose_robots;
  uint64_t latest_ns = 0;
  bridge::RosWatch watch(
      wo,
      [&](uint32_t channel, uint64_t t_ns, std::string cdr) {
        server.publish(channel, t_ns, std::move(cdr));
        if (channel == bridge::kPosesChannel && t_ns > latest_ns) {  // the fleet's sim time
          latest_ns = t_ns;
          server.time(t_ns);
        }
      },
      [&](std::vector<bridge::Channel> channels, bool latched) {
        server.add_channels(std::move(channels), latched);
      });
  const std::string url = "ws://" + o.bind + ":" + std::to_string(server.port());
  std::cout << nlohmann::json{{"listening", url}}.dump() << std::endl;
  spdlog::info(
      "bridge: the ROS 2 view of domain {}{} at {} (Foxglove: Open connection, "
      "Foxglove WebSocket)",
      o.dds.domain, o.ros_namespace.empty() ? "" : " under " + o.ros_namespace, url);
  install_stop_handlers();
  while (!g_stop_requested.load()) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  return ExitCode::kExitSuccess;
}
}  // namespace

void register_bridge_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<BridgeCliOptions>();
  auto* cmd = app.add_subcommand(
      "bridge",
      "Serve a run's ROS 2 view live to Foxglove or Lichtblick (Foxglove WebSocket protocol), "
      "read-only");
  add_dds_options(cmd, o->dds);
  cmd->add_option("--foxglove-port", o->port, "WebSocket port (0: any free one)")
      ->capture_default_str();
  cmd->add_option("--bind", o->bind,
                  "address to listen on (loopback by default; 0.0.0.0 opens it to the network)")
      ->capture_default_str();
  cmd->add_option("--ros-namespace", o->ros_namespace,
                  "the run's ROS namespace (`smart run --ros-namespace`), e.g. /run_a");
  cmd->add_option("--ros-pose-robots", o->pose_robots,
                  "robots whose /robot_<id>/pose is served too (the run's --ros-pose-robots)")
      ->delimiter(',');
  cmd->callback([&exit_code, o] { exit_code = run_bridge(*o); });
}

}  // namespace smart::tools
