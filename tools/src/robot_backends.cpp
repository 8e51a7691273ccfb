#include "smart/tools/robot_backends.hpp"

#include <chrono>
#include <thread>

#include "smart/config/yaml_checks.hpp"
#include "smart/dds/topics.hpp"
#include "smart/tools/cli_common.hpp"

namespace smart::tools {

namespace {

const EnumNames<Backend> kBackendNames{{"jetbot", Backend::kJetbot}, {"ros2", Backend::kRos2}};
const EnumNames<PoseKind> kPoseNames{
    {"vicon", PoseKind::kVicon}, {"ros", PoseKind::kRos}, {"odom", PoseKind::kOdom}};

// Robot `id`'s transform file (odometry starts where each robot stood: one file per robot).
geometry::FrameTransform pose_transform(const BackendOptions& o, PoseKind kind, uint32_t id) {
  if (!o.pose_transform.empty()) {
    return geometry::load_frame_transform(with_id(o.pose_transform, id));
  }
  return kind == PoseKind::kVicon ? hw::vicon_millimetres() : geometry::FrameTransform{};
}

void open_ros_pose(const BackendOptions& o, uint32_t id, PoseKind kind,
                   const dds::Participant& participant, RobotIo& io) {
  const auto ns = dds::ros_namespace(
      o.ros_namespace.empty() ? std::string(dds::kRosNamespacePattern) : o.ros_namespace, id);
  io.pose_name = kind == PoseKind::kOdom ? dds::ros_odom_topic(ns) : with_id(o.ros_topic, id);
  auto pose = std::make_unique<hw::RosPoseSource>(
      participant, io.pose_name, pose_transform(o, kind, id), o.pose_max_age_s, steady_s,
      kind == PoseKind::kOdom ? hw::RosPoseSource::Message::kOdometry
                              : hw::RosPoseSource::Message::kPoseStamped);
  io.ros_pose = pose.get();
  io.pose = std::move(pose);
}

hw::EmulatedFlaws emulated_flaws(const BackendOptions& o) {
  hw::EmulatedFlaws f =
      o.emulate_realistic ? hw::realistic_flaws(o.emulate_seed) : hw::EmulatedFlaws{};
  if (o.emulate_wheel_gains.size() == 2)
    f.wheel_gain = {o.emulate_wheel_gains[0], o.emulate_wheel_gains[1]};
  if (!o.emulate_mounting.empty()) f.mounting = geometry::load_frame_transform(o.emulate_mounting);
  if (o.emulate_motor_lag_s) f.lag_s = *o.emulate_motor_lag_s;
  return f;
}

void open_jetbot(const BackendOptions& o, uint32_t id, const agent::RobotModel& model,
                 const std::string& file, const dds::Participant& participant, RobotIo& io) {
  io.hardware = hw::parse_jetbot_config(config::read_file(file, "robot"), file);
  if (!o.i2c.empty()) io.hardware.i2c_device = o.i2c;
  const bool emulated = io.hardware.i2c_device == "emulated";
  const PoseKind kind = o.pose == PoseKind::kDefault ? PoseKind::kVicon : o.pose;
  const std::string object =
      o.vicon_object.empty() ? "jetbot" + std::to_string(id) : o.vicon_object;
  if (kind == PoseKind::kVicon) {
    // An emulated JetBot streams to this process's own receiver: any free port, so several
    // emulated agents on one host never fight over the Vicon port.
    const uint16_t port = o.vicon_port.value_or(emulated ? 0 : 51001);
    io.vicon = std::make_unique<hw::ViconReceiver>(o.vicon_bind, port, pose_transform(o, kind, id),
                                                   std::vector<std::string>{object}, steady_s);
    io.pose = std::make_unique<hw::ViconPoseSource>(*io.vicon, object, o.pose_max_age_s, steady_s);
    io.pose_name = "Vicon UDP " + object;
  } else if (kind == PoseKind::kRos && !o.ros_topic.empty()) {
    open_ros_pose(o, id, kind, participant, io);
  } else {
    throw std::invalid_argument(
        "a JetBot's pose comes from --pose vicon, or --pose ros with --ros-topic, e.g. "
        "/vrpn_mocap/jetbot1/pose");
  }
  if (!emulated) {
    io.bus = std::make_unique<hw::LinuxI2cBus>(io.hardware.i2c_device);
  } else if (o.emulate_pose.size() != 3 || !io.vicon) {
    throw std::invalid_argument("--i2c emulated needs --emulate-pose X,Y,YAW and --pose vicon");
  } else {
    io.bus = std::make_unique<hw::EmulatedJetbot>(
        io.hardware, model.wheel_base_m,
        agent::Pose2D{o.emulate_pose[0], o.emulate_pose[1], o.emulate_pose[2]}, object,
        io.vicon->port(), std::max(model.max_accel_mps2, model.max_decel_mps2) * 1.5,
        emulated_flaws(o));
  }
  auto drive = std::make_unique<hw::JetbotDrive>(*io.bus, io.hardware, [](double s) {
    std::this_thread::sleep_for(std::chrono::duration<double>(s));
  });
  io.jetbot = drive.get();
  io.drive = std::move(drive);
}

}  // namespace

std::string with_id(std::string pattern, const std::string& id) {
  const auto at = pattern.find("{id}");
  if (at != std::string::npos) pattern.replace(at, 4, id);
  return pattern;
}

std::string robot_file(const BackendOptions& o) {
  const std::string name =
      !o.config.empty() ? o.config : (o.backend == Backend::kRos2 ? "turtlebot3-burger" : "jetbot");
  return find_config_file("robots", name);
}

RobotIo open_robot(const BackendOptions& o, uint32_t id, const agent::RobotModel& model,
                   const std::string& file, const dds::Participant& participant) {
  RobotIo io;
  if (o.backend == Backend::kJetbot) {
    open_jetbot(o, id, model, file, participant, io);
    return io;
  }
  const PoseKind kind = o.pose == PoseKind::kDefault ? PoseKind::kOdom : o.pose;
  if (kind == PoseKind::kVicon || (kind == PoseKind::kRos && o.ros_topic.empty())) {
    throw std::invalid_argument(
        "a ROS 2 robot's pose comes from --pose odom (<ns>/odom) or --pose ros with --ros-topic "
        "(\"{id}\" is the robot's index, e.g. /vrpn_mocap/robot_{id}/pose)");
  }
  open_ros_pose(o, id, kind, participant, io);
  const auto ns = dds::ros_namespace(
      o.ros_namespace.empty() ? std::string(dds::kRosNamespacePattern) : o.ros_namespace, id);
  auto drive = std::make_unique<hw::RosTwistDrive>(participant, ns, model.wheel_base_m, model.trim);
  io.twist = drive.get();
  io.drive = std::move(drive);
  return io;
}

std::unique_ptr<hw::SignalStop> stop_outputs_on_signal(const RobotIo& io) {
  if (io.jetbot == nullptr) return nullptr;
  return std::make_unique<hw::SignalStop>(*io.bus, io.hardware.address, &g_stop_requested);
}

void add_backend_options(CLI::App* cmd, BackendOptions& o) {
  add_enum_option(cmd, "--backend", o.backend, kBackendNames,
                  "jetbot (PCA9685 motor board; default) or ros2 (cmd_vel/odom of a ROS 2 base)");
  cmd->add_option("--config", o.config,
                  "robot model (name or file; default jetbot, or turtlebot3-burger with ros2)");
  cmd->add_option("--i2c", o.i2c, "I2C device (default from the robot file) or 'emulated'");
  add_enum_option(cmd, "--pose", o.pose, kPoseNames,
                  "vicon (Tracker UDP; JetBot default), odom (<ns>/odom; ros2 default) or ros "
                  "(a PoseStamped topic, --ros-topic)");
  cmd->add_option("--vicon-bind", o.vicon_bind)->capture_default_str();
  cmd->add_option("--vicon-port", o.vicon_port,
                  "UDP port of the Vicon stream (default 51001; with --i2c emulated any free "
                  "port; 0: any free port)");
  cmd->add_option("--vicon-object", o.vicon_object, "Vicon object name (default jetbot<id>)");
  cmd->add_option("--ros-topic", o.ros_topic,
                  "PoseStamped topic for --pose ros; {id} is the robot's index");
  cmd->add_option("--ros-namespace", o.ros_namespace,
                  "ROS 2 namespace of each base (--backend ros2; default /robot_{id}); {id} is "
                  "the robot's index");
  cmd->add_option("--pose-transform", o.pose_transform,
                  "transform file from the pose source's frame to the grid (smart calibrate "
                  "frame); {id} is the robot's index (odometry: one file per robot); default: "
                  "Vicon millimetres, ROS metres, both already in the grid's frame");
  cmd->add_option("--pose-max-age-s", o.pose_max_age_s, "older poses stop the robot")
      ->check(finite_in(0.001, 60.0))
      ->capture_default_str();
  cmd->add_option("--emulate-pose", o.emulate_pose, "start pose X Y YAW of an emulated JetBot")
      ->delimiter(',')
      ->expected(3);
  cmd->add_option("--emulate-wheel-gains", o.emulate_wheel_gains,
                  "an emulated JetBot's wheel ground speed per command, LEFT,RIGHT (a mismatched "
                  "wheel; negative: wired backwards; default 1,1)")
      ->delimiter(',')
      ->expected(2)
      ->check(finite_in(-2.0, 2.0));
  cmd->add_flag("--emulate-realistic", o.emulate_realistic,
                "an emulated JetBot with a real one's flaws: motor dead band and lag, Vicon "
                "latency and noise (hw/emulated_jetbot.hpp cites the values)");
  cmd->add_option("--emulate-motor-lag-s", o.emulate_motor_lag_s,
                  "an emulated JetBot's motor time constant (first-order response; "
                  "--emulate-realistic: 0.1)")
      ->check(finite_in(0.0, 5.0));
  cmd->add_option("--emulate-seed", o.emulate_seed, "seed of the emulated Vicon's noise")
      ->capture_default_str();
  cmd->add_option("--emulate-mounting", o.emulate_mounting,
                  "transform file: how the emulated Vicon's frame (mm) lies on the grid "
                  "(default: millimetres in the grid's frame)");
}

}  // namespace smart::tools
