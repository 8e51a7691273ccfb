// `smart agent`: one physical robot (JetBot) joining a run over DDS — the same Agent class as in
// simulation, on the wall clock. With `--i2c emulated` the motor board is the emulated JetBot
// (hw/emulated_jetbot.hpp), which streams its pose to this process as Vicon UDP datagrams.
#include <spdlog/spdlog.h>

#include <chrono>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <thread>

#include "smart/agent/agent.hpp"
#include "smart/agent/agent_node.hpp"
#include "smart/config/yaml_checks.hpp"
#include "smart/hw/emulated_jetbot.hpp"
#include "smart/hw/jetbot_drive.hpp"
#include "smart/hw/ros_pose.hpp"
#include "smart/hw/vicon.hpp"
#include "smart/tools/cli_common.hpp"
#include "smart/tools/commands.hpp"

namespace smart::tools {

namespace {

enum class Backend { kJetbot };
enum class PoseKind { kVicon, kRos };
const EnumNames<Backend> kBackendNames{{"jetbot", Backend::kJetbot}};
const EnumNames<PoseKind> kPoseNames{{"vicon", PoseKind::kVicon}, {"ros", PoseKind::kRos}};

struct AgentOptions {
  DdsOptions dds;
  uint32_t robot_id = 0;
  Backend backend = Backend::kJetbot;
  std::string config = "jetbot";
  std::string i2c;  // default: the robot file's hardware.i2c_device
  PoseKind pose = PoseKind::kVicon;
  std::string vicon_bind = "0.0.0.0";
  std::optional<uint16_t> vicon_port;  // default: 51001, or any free port with --i2c emulated
  std::string vicon_object;  // default: jetbot<id>
  std::string ros_topic;
  double pose_max_age_s = 0.1;
  double period_s = 0.1;
  std::vector<double> emulate_pose;  // x, y, yaw for --i2c emulated
  // Mocap frame -> grid world frame: scale (Vicon mm -> m: 0.001; ROS m: 1), rotation, offset.
  double pose_scale = 0;  // 0: the source's default
  double pose_yaw_offset_rad = 0;
  std::vector<double> pose_offset_m{0, 0};
};

double steady_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// The agent's read/update/write loop on the wall clock until the monitor stops its run (true)
// or a signal arrives (false).
bool control_loop(agent::Agent& robot, agent::AgentNode& node, double period_s) {
  auto next = std::chrono::steady_clock::now();
  double repeated_s = steady_s();
  while (!g_stop_requested.load()) {
    node.take_windows({}, steady_s());
    if (auto c = node.take_monitor_clock(); c && c->stop && c->run_id == robot.run_id()) {
      return true;
    }
    const double now = steady_s();
    robot.step(now);
    node.publish_progress(now);
    if (now - repeated_s >= 1.0) {
      node.republish_progress();
      repeated_s = now;
    }
    if (robot.last_pose().valid) {
      node.publish_state(robot.robot_id(), robot.run_id(), now, robot.last_pose(),
                         robot.last_command());
    }
    next += std::chrono::duration_cast<std::chrono::steady_clock::duration>(
        std::chrono::duration<double>(period_s));
    std::this_thread::sleep_until(next);
  }
  return false;
}

// The robot's pose source; with Vicon also the receiver (an emulated JetBot streams to it).
struct Pose {
  std::unique_ptr<hw::ViconReceiver> vicon;
  std::unique_ptr<agent::PoseSource> source;
  std::string object;  // the Vicon object name
};

Pose open_pose(const AgentOptions& o, const dds::Participant& participant) {
  Pose p;
  p.object = o.vicon_object.empty() ? "jetbot" + std::to_string(o.robot_id) : o.vicon_object;
  hw::ViconTransform transform;
  transform.scale = o.pose_scale > 0 ? o.pose_scale : (o.pose == PoseKind::kVicon ? 0.001 : 1.0);
  transform.yaw_offset_rad = o.pose_yaw_offset_rad;
  transform.x_offset_m = o.pose_offset_m.at(0);
  transform.y_offset_m = o.pose_offset_m.at(1);
  if (o.pose == PoseKind::kVicon) {
    // An emulated JetBot streams to this process's own receiver: any free port, so several
    // emulated agents on one host never fight over the Vicon port.
    const uint16_t port = o.vicon_port.value_or(o.i2c == "emulated" ? 0 : 51001);
    p.vicon = std::make_unique<hw::ViconReceiver>(o.vicon_bind, port, transform,
                                                  std::vector<std::string>{p.object}, steady_s);
    p.source =
        std::make_unique<hw::ViconPoseSource>(*p.vicon, p.object, o.pose_max_age_s, steady_s);
    return p;
  }
  if (o.ros_topic.empty()) {
    throw std::invalid_argument("--pose ros needs --ros-topic, e.g. /vrpn_mocap/jetbot1/pose");
  }
  p.source = std::make_unique<hw::RosPoseSource>(participant, o.ros_topic, transform,
                                                 o.pose_max_age_s, steady_s);
  return p;
}

std::unique_ptr<hw::I2cBus> open_bus(const AgentOptions& o, const hw::JetbotConfig& hwc,
                                     const agent::RobotModel& model, const Pose& pose) {
  if (hwc.i2c_device != "emulated") return std::make_unique<hw::LinuxI2cBus>(hwc.i2c_device);
  if (o.emulate_pose.size() != 3 || !pose.vicon) {
    throw std::invalid_argument("--i2c emulated needs --emulate-pose X,Y,YAW and --pose vicon");
  }
  return std::make_unique<hw::EmulatedJetbot>(
      hwc, model.wheel_base_m,
      agent::Pose2D{o.emulate_pose[0], o.emulate_pose[1], o.emulate_pose[2]}, pose.object,
      pose.vicon->port(), std::max(model.max_accel_mps2, model.max_decel_mps2) * 1.5);
}

nlohmann::json agent_report(const agent::Agent& robot, bool stopped_by_monitor, const Pose& pose) {
  nlohmann::json out = {{"robot_id", robot.robot_id()},
                        {"finished_seq", robot.finished_seq()},
                        {"stopped_by_monitor", stopped_by_monitor},
                        {"watchdog_stops", robot.watchdog_stops()}};
  if (pose.vicon) {
    const auto s = pose.vicon->stats();
    out["vicon"] = {
        {"datagrams", s.datagrams}, {"malformed", s.malformed}, {"unknown_names", s.unknown_names}};
  }
  return out;
}

int run_agent(const AgentOptions& o) {
  const auto path = find_config_file("robots", o.config);
  const auto model = agent::load_robot_model(path);
  auto hwc = hw::parse_jetbot_config(config::read_file(path, "robot"), path);
  if (!o.i2c.empty()) hwc.i2c_device = o.i2c;
  const auto profile = run_qos_profile(o.dds);
  dds::Domain domain(o.dds.domain,
                     domain_config(o.dds, profile, "agent-" + std::to_string(o.robot_id)));
  dds::Participant participant(domain, o.dds.run);
  const Pose pose = open_pose(o, participant);  // first: an emulated JetBot streams to it
  const auto bus = open_bus(o, hwc, model, pose);
  hw::JetbotDrive drive(
      *bus, hwc, [](double s) { std::this_thread::sleep_for(std::chrono::duration<double>(s)); });
  // SIGINT/SIGTERM: outputs off at once from the handler, then a clean shutdown below.
  hw::SignalStop signal_stop(*bus, hwc.address, &g_stop_requested);
  agent::Agent robot({o.robot_id, model, o.period_s, 0.5}, drive, *pose.source);
  agent::AgentNode node(participant, profile);
  node.set_link(profile.link);
  node.host(robot);
  robot.configure();
  robot.activate();
  // A command watchdog beside the control loop: if the loop stalls, the motors stop.
  std::atomic<bool> done{false};
  std::thread watchdog([&] {
    while (!done) {
      drive.poll_watchdog(steady_s());
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  });
  spdlog::info("agent {}: {} on {}, pose from {}, domain {}", o.robot_id, model.name,
               hwc.i2c_device, pose.vicon ? "Vicon UDP " + pose.object : o.ros_topic, o.dds.domain);
  const bool stopped_by_monitor = control_loop(robot, node, o.period_s);
  robot.deactivate();
  done = true;
  watchdog.join();
  std::cout << agent_report(robot, stopped_by_monitor, pose).dump() << std::endl;
  return kExitSuccess;
}

}  // namespace

void register_agent_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<AgentOptions>();
  auto* cmd = app.add_subcommand("agent",
                                 "One physical robot (JetBot) executing its actions "
                                 "from `smart monitor` over DDS");
  add_dds_options(cmd, o->dds);
  cmd->add_option("--robot-id", o->robot_id, "the robot's index in the plan")->required();
  add_enum_option(cmd, "--backend", o->backend, kBackendNames,
                  "the robot's drive (default jetbot)");
  cmd->add_option("--config", o->config, "robot model with a hardware: section (name or file)")
      ->capture_default_str();
  cmd->add_option("--i2c", o->i2c, "I2C device (default from the robot file) or 'emulated'");
  add_enum_option(cmd, "--pose", o->pose, kPoseNames,
                  "vicon (Tracker UDP stream; default) or ros (PoseStamped topic)");
  cmd->add_option("--vicon-bind", o->vicon_bind)->capture_default_str();
  cmd->add_option("--vicon-port", o->vicon_port,
                  "UDP port of the Vicon stream (default 51001; with --i2c emulated any free "
                  "port; 0: any free port)");
  cmd->add_option("--vicon-object", o->vicon_object, "Vicon object name (default jetbot<id>)");
  cmd->add_option("--ros-topic", o->ros_topic, "ROS 2 PoseStamped topic for --pose ros");
  cmd->add_option("--pose-scale", o->pose_scale,
                  "mocap units to metres (default: 0.001 for Vicon mm, 1 for ROS)");
  cmd->add_option("--pose-yaw-offset-rad", o->pose_yaw_offset_rad,
                  "rotation of the mocap frame into the grid frame")
      ->capture_default_str();
  cmd->add_option("--pose-offset-m", o->pose_offset_m,
                  "X,Y of the mocap origin in the grid frame (metres)")
      ->delimiter(',')
      ->expected(2);
  cmd->add_option("--pose-max-age-s", o->pose_max_age_s, "older poses stop the robot")
      ->check(finite_in(0.001, 60.0))
      ->capture_default_str();
  cmd->add_option("--period-s", o->period_s, "control period")
      ->check(finite_in(0.005, 10.0))
      ->capture_default_str();
  cmd->add_option("--emulate-pose", o->emulate_pose, "start pose X Y YAW of an emulated JetBot")
      ->delimiter(',')
      ->expected(3);
  cmd->callback([&exit_code, o] { exit_code = run_agent(*o); });
}

}  // namespace smart::tools
