// `smart agent`: physical robots joining a run over DDS — the same Agent class as in simulation,
// on the wall clock.
// - --backend jetbot: one JetBot (PCA9685 over i2c-dev). With `--i2c emulated` the motor board
//   is the emulated JetBot (hw/emulated_jetbot.hpp), which streams its pose to this process as
//   Vicon UDP datagrams.
// - --backend ros2: one or several ROS 2 diff-drive bases (--robot-ids 0-9), each driven through
//   cmd_vel and located by its odometry (or a mocap PoseStamped) in its namespace; one process,
//   one DDS participant, one AgentNode for all of them.
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
#include "smart/hw/ros_twist_drive.hpp"
#include "smart/hw/vicon.hpp"
#include "smart/tools/cli_common.hpp"
#include "smart/tools/commands.hpp"

namespace smart::tools {

namespace {

enum class Backend { kJetbot, kRos2 };
enum class PoseKind { kDefault, kVicon, kRos, kOdom };
const EnumNames<Backend> kBackendNames{{"jetbot", Backend::kJetbot}, {"ros2", Backend::kRos2}};
const EnumNames<PoseKind> kPoseNames{
    {"vicon", PoseKind::kVicon}, {"ros", PoseKind::kRos}, {"odom", PoseKind::kOdom}};

struct AgentOptions {
  DdsOptions dds;
  std::optional<uint32_t> robot_id;
  std::string robot_ids;  // "0-9,12"
  Backend backend = Backend::kJetbot;
  std::string config;  // default: jetbot, or turtlebot3-burger for ros2
  std::string i2c;     // default: the robot file's hardware.i2c_device
  PoseKind pose = PoseKind::kDefault;
  std::string vicon_bind = "0.0.0.0";
  std::optional<uint16_t> vicon_port;  // default: 51001, or any free port with --i2c emulated
  std::string vicon_object;            // default: jetbot<id>
  std::string ros_topic;               // --pose ros: PoseStamped topic; "{id}" is the robot's index
  std::string ros_namespace{dds::kRosNamespacePattern};
  double pose_max_age_s = 0.1;
  double period_s = 0.1;
  std::vector<double> emulate_pose;  // x, y, yaw for --i2c emulated
  std::string pose_transform;        // mocap/odometry frame -> grid frame (smart calibrate)
};

double steady_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// One robot this process drives: its backend, its pose source and its agent.
struct Robot {
  std::unique_ptr<agent::DriveBackend> drive;
  std::unique_ptr<agent::PoseSource> pose;
  std::unique_ptr<agent::Agent> agent;
};

bool stopped_by(const std::optional<wire::Tick>& clock, const std::vector<Robot>& robots) {
  if (!clock || !clock->stop) return false;
  return std::any_of(robots.begin(), robots.end(),
                     [&](const Robot& r) { return clock->run_id == r.agent->run_id(); });
}

// The agents' read/update/write loop on the wall clock until the monitor stops their run (true)
// or a signal arrives (false).
bool control_loop(std::vector<Robot>& robots, agent::AgentNode& node, double period_s) {
  auto next = std::chrono::steady_clock::now();
  double repeated_s = steady_s();
  while (!g_stop_requested.load()) {
    node.take_windows({}, steady_s());
    if (stopped_by(node.take_monitor_clock(), robots)) return true;
    const double now = steady_s();
    for (auto& r : robots) r.agent->step(now);
    node.publish_progress(now);
    if (now - repeated_s >= 1.0) {
      node.republish_progress();
      repeated_s = now;
    }
    for (const auto& r : robots) {
      const auto& a = *r.agent;
      if (a.last_pose().valid) {
        node.publish_state(a.robot_id(), a.run_id(), now, a.last_pose(), a.last_command());
      }
    }
    next += std::chrono::duration_cast<std::chrono::steady_clock::duration>(
        std::chrono::duration<double>(period_s));
    std::this_thread::sleep_until(next);
  }
  return false;
}

// "{id}" in a topic or file pattern is the robot's index.
std::string with_id(std::string pattern, uint32_t robot) {
  const auto at = pattern.find("{id}");
  if (at != std::string::npos) pattern.replace(at, 4, std::to_string(robot));
  return pattern;
}

// Robot `id`'s transform file (odometry starts where each robot stood: one file per robot).
geometry::FrameTransform pose_transform(const AgentOptions& o, PoseKind kind, uint32_t id) {
  if (!o.pose_transform.empty()) {
    return geometry::load_frame_transform(with_id(o.pose_transform, id));
  }
  return kind == PoseKind::kVicon ? hw::vicon_millimetres() : geometry::FrameTransform{};
}

std::vector<uint32_t> robot_ids(const AgentOptions& o) {
  if (o.robot_id.has_value() == !o.robot_ids.empty()) {
    throw std::invalid_argument(
        "give the robots as --robot-id K or --robot-ids LIST (e.g. 0-9,12)");
  }
  const auto ids = o.robot_id ? std::vector<uint32_t>{*o.robot_id} : parse_id_ranges(o.robot_ids);
  if (o.backend == Backend::kJetbot && ids.size() != 1) {
    throw std::invalid_argument("--backend jetbot drives one robot per process: use --robot-id");
  }
  return ids;
}

// Hosts `robots` on one AgentNode, runs them until the monitor stops their run (true) or a
// signal arrives (false), and brings their wheels to zero.
bool execute(const dds::QosProfile& profile, const dds::Participant& participant,
             std::vector<Robot>& robots, double period_s) {
  agent::AgentNode node(participant, profile);
  node.set_link(profile.link);
  for (auto& r : robots) {
    node.host(*r.agent);
    r.agent->configure();
    r.agent->activate();
  }
  const bool stopped_by_monitor = control_loop(robots, node, period_s);
  for (auto& r : robots) r.agent->deactivate();
  return stopped_by_monitor;
}

nlohmann::json robot_report(const agent::Agent& robot) {
  return {{"robot_id", robot.robot_id()},
          {"finished_seq", robot.finished_seq()},
          {"watchdog_stops", robot.watchdog_stops()}};
}

// ---- JetBot: one robot, PCA9685 over i2c-dev (or emulated), Vicon or ROS 2 mocap poses. ----

// The robot's pose source; with Vicon also the receiver (an emulated JetBot streams to it).
struct Pose {
  std::unique_ptr<hw::ViconReceiver> vicon;
  std::unique_ptr<agent::PoseSource> source;
  std::string object;  // the Vicon object name
};

Pose open_jetbot_pose(const AgentOptions& o, uint32_t id, const dds::Participant& participant) {
  Pose p;
  const PoseKind kind = o.pose == PoseKind::kDefault ? PoseKind::kVicon : o.pose;
  p.object = o.vicon_object.empty() ? "jetbot" + std::to_string(id) : o.vicon_object;
  const auto transform = pose_transform(o, kind, id);
  if (kind == PoseKind::kVicon) {
    // An emulated JetBot streams to this process's own receiver: any free port, so several
    // emulated agents on one host never fight over the Vicon port.
    const uint16_t port = o.vicon_port.value_or(o.i2c == "emulated" ? 0 : 51001);
    p.vicon = std::make_unique<hw::ViconReceiver>(o.vicon_bind, port, transform,
                                                  std::vector<std::string>{p.object}, steady_s);
    p.source =
        std::make_unique<hw::ViconPoseSource>(*p.vicon, p.object, o.pose_max_age_s, steady_s);
    return p;
  }
  if (kind != PoseKind::kRos || o.ros_topic.empty()) {
    throw std::invalid_argument(
        "a JetBot's pose comes from --pose vicon, or --pose ros with --ros-topic, e.g. "
        "/vrpn_mocap/jetbot1/pose");
  }
  p.source = std::make_unique<hw::RosPoseSource>(participant, with_id(o.ros_topic, id), transform,
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

int run_jetbot(const AgentOptions& o, uint32_t id, const std::string& robot_file,
               const dds::QosProfile& profile, const dds::Participant& participant) {
  const auto model = agent::load_robot_model(robot_file);
  auto hwc = hw::parse_jetbot_config(config::read_file(robot_file, "robot"), robot_file);
  if (!o.i2c.empty()) hwc.i2c_device = o.i2c;
  const Pose pose =
      open_jetbot_pose(o, id, participant);  // first: an emulated JetBot streams to it
  const auto bus = open_bus(o, hwc, model, pose);
  auto drive = std::make_unique<hw::JetbotDrive>(
      *bus, hwc, [](double s) { std::this_thread::sleep_for(std::chrono::duration<double>(s)); });
  // SIGINT/SIGTERM: outputs off at once from the handler, then a clean shutdown below.
  hw::SignalStop signal_stop(*bus, hwc.address, &g_stop_requested);
  auto* jetbot = drive.get();
  std::vector<Robot> robots(1);
  robots[0].agent = std::make_unique<agent::Agent>(agent::AgentConfig{id, model, o.period_s, 0.5},
                                                   *drive, *pose.source);
  robots[0].drive = std::move(drive);
  // A command watchdog beside the control loop: if the loop stalls, the motors stop.
  std::atomic<bool> done{false};
  std::thread watchdog([&] {
    while (!done) {
      jetbot->poll_watchdog(steady_s());
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  });
  spdlog::info("agent {}: {} on {}, pose from {}, domain {}", id, model.name, hwc.i2c_device,
               pose.vicon ? "Vicon UDP " + pose.object : o.ros_topic, o.dds.domain);
  const bool stopped_by_monitor = execute(profile, participant, robots, o.period_s);
  done = true;
  watchdog.join();
  auto report = robot_report(*robots[0].agent);
  report["stopped_by_monitor"] = stopped_by_monitor;
  if (pose.vicon) {
    const auto s = pose.vicon->stats();
    report["vicon"] = {
        {"datagrams", s.datagrams}, {"malformed", s.malformed}, {"unknown_names", s.unknown_names}};
  }
  std::cout << report.dump() << std::endl;
  return kExitSuccess;
}

// ---- ROS 2 diff-drive bases: cmd_vel out, odometry (or mocap PoseStamped) in. ----

int run_ros2(const AgentOptions& o, const std::vector<uint32_t>& ids, const std::string& robot_file,
             const dds::QosProfile& profile, const dds::Participant& participant) {
  const auto model = agent::load_robot_model(robot_file);
  const PoseKind kind = o.pose == PoseKind::kDefault ? PoseKind::kOdom : o.pose;
  if (kind == PoseKind::kVicon || (kind == PoseKind::kRos && o.ros_topic.empty())) {
    throw std::invalid_argument(
        "a ROS 2 robot's pose comes from --pose odom (<ns>/odom) or --pose ros with --ros-topic "
        "(\"{id}\" is the robot's index, e.g. /vrpn_mocap/robot_{id}/pose)");
  }
  std::vector<Robot> robots;
  std::vector<hw::RosPoseSource*> sources;
  std::vector<hw::RosTwistDrive*> drives;
  for (const uint32_t id : ids) {
    const auto ns = dds::ros_namespace(o.ros_namespace, id);
    Robot r;
    auto drive = std::make_unique<hw::RosTwistDrive>(participant, ns, model.wheel_base_m);
    auto pose = std::make_unique<hw::RosPoseSource>(
        participant, kind == PoseKind::kOdom ? dds::ros_odom_topic(ns) : with_id(o.ros_topic, id),
        pose_transform(o, kind, id), o.pose_max_age_s, steady_s,
        kind == PoseKind::kOdom ? hw::RosPoseSource::Message::kOdometry
                                : hw::RosPoseSource::Message::kPoseStamped);
    drives.push_back(drive.get());
    sources.push_back(pose.get());
    r.agent = std::make_unique<agent::Agent>(agent::AgentConfig{id, model, o.period_s, 0.5}, *drive,
                                             *pose);
    r.drive = std::move(drive);
    r.pose = std::move(pose);
    robots.push_back(std::move(r));
  }
  spdlog::info("agent: {} ROS 2 robot(s) ({}), cmd_vel on {}, domain {}", robots.size(), model.name,
               drives.front()->topic(), o.dds.domain);
  const bool stopped_by_monitor = execute(profile, participant, robots, o.period_s);
  nlohmann::json report = {{"stopped_by_monitor", stopped_by_monitor},
                           {"robots", nlohmann::json::array()}};
  for (std::size_t i = 0; i < robots.size(); ++i) {
    auto r = robot_report(*robots[i].agent);
    r["cmd_vel_writes"] = drives[i]->commands();
    r["pose_samples"] = sources[i]->samples();
    report["robots"].push_back(r);
  }
  std::cout << report.dump() << std::endl;
  return kExitSuccess;
}

int run_agent(const AgentOptions& o) {
  const auto ids = robot_ids(o);
  const std::string config =
      !o.config.empty() ? o.config : (o.backend == Backend::kRos2 ? "turtlebot3-burger" : "jetbot");
  const auto robot_file = find_config_file("robots", config);
  const auto profile = run_qos_profile(o.dds);
  dds::Domain domain(o.dds.domain,
                     domain_config(o.dds, profile, "agent-" + std::to_string(ids.front())));
  dds::Participant participant(domain, o.dds.run);
  if (o.backend == Backend::kJetbot) {
    return run_jetbot(o, ids.front(), robot_file, profile, participant);
  }
  return run_ros2(o, ids, robot_file, profile, participant);
}

}  // namespace

void register_agent_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<AgentOptions>();
  auto* cmd = app.add_subcommand("agent",
                                 "Physical robots (a JetBot, or ROS 2 diff-drive bases) executing "
                                 "their actions from `smart monitor` over DDS");
  add_dds_options(cmd, o->dds);
  cmd->add_option("--robot-id", o->robot_id, "the robot's index in the plan");
  cmd->add_option("--robot-ids", o->robot_ids,
                  "several robots in one process (--backend ros2), e.g. 0-9 or 0,2,5-7");
  add_enum_option(cmd, "--backend", o->backend, kBackendNames,
                  "jetbot (PCA9685 motor board; default) or ros2 (cmd_vel/odom of a ROS 2 base)");
  cmd->add_option("--config", o->config,
                  "robot model (name or file; default jetbot, or turtlebot3-burger with ros2)");
  cmd->add_option("--i2c", o->i2c, "I2C device (default from the robot file) or 'emulated'");
  add_enum_option(cmd, "--pose", o->pose, kPoseNames,
                  "vicon (Tracker UDP; JetBot default), odom (<ns>/odom; ros2 default) or ros "
                  "(a PoseStamped topic, --ros-topic)");
  cmd->add_option("--vicon-bind", o->vicon_bind)->capture_default_str();
  cmd->add_option("--vicon-port", o->vicon_port,
                  "UDP port of the Vicon stream (default 51001; with --i2c emulated any free "
                  "port; 0: any free port)");
  cmd->add_option("--vicon-object", o->vicon_object, "Vicon object name (default jetbot<id>)");
  cmd->add_option("--ros-topic", o->ros_topic,
                  "PoseStamped topic for --pose ros; {id} is the robot's index");
  cmd->add_option("--ros-namespace", o->ros_namespace,
                  "ROS 2 namespace of each base (--backend ros2); {id} is the robot's index")
      ->capture_default_str();
  cmd->add_option("--pose-transform", o->pose_transform,
                  "transform file from the pose source's frame to the grid (smart calibrate); "
                  "{id} is the robot's index (odometry: one file per robot); default: Vicon "
                  "millimetres, ROS metres, both already in the grid's frame");
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
