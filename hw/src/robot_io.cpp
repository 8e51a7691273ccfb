#include "smart/hw/robot_io.hpp"

#include <chrono>
#include <thread>

#include "smart/common/steady_clock.hpp"
#include "smart/config/yaml_checks.hpp"
#include "smart/dds/qos_profile.hpp"
#include "smart/dds/topics.hpp"

namespace smart::hw {

namespace {

using common::steady_s;

// Robot `id`'s transform file (odometry starts where each robot stood: one file per robot).
geometry::FrameTransform pose_transform(const RobotIoOptions& o, PoseKind kind, uint32_t id) {
  if (!o.pose_transform.empty()) {
    return geometry::load_frame_transform(with_id(o.pose_transform, id));
  }
  return kind == PoseKind::kVicon ? vicon_millimetres() : geometry::FrameTransform{};
}

void open_ros_pose(const RobotIoOptions& o, uint32_t id, PoseKind kind,
                   const dds::Participant& participant, RobotIo& io) {
  const auto ns = dds::ros_namespace(
      o.ros_namespace.empty() ? std::string(dds::kRosNamespacePattern) : o.ros_namespace, id);
  io.pose_name = kind == PoseKind::kOdom ? dds::ros_odom_topic(ns) : with_id(o.ros_topic, id);
  auto pose = std::make_unique<RosPoseSource>(
      participant, io.pose_name, pose_transform(o, kind, id), o.pose_max_age_s, steady_s,
      kind == PoseKind::kOdom ? RosPoseSource::Message::kOdometry
                              : RosPoseSource::Message::kPoseStamped);
  io.ros_pose = pose.get();
  io.pose = std::move(pose);
}

EmulatedFlaws emulated_flaws(const RobotIoOptions& o) {
  EmulatedFlaws f = o.emulate_realistic ? realistic_flaws(o.emulate_seed) : EmulatedFlaws{};
  if (o.emulate_wheel_gains.size() == 2)
    f.wheel_gain = {o.emulate_wheel_gains[0], o.emulate_wheel_gains[1]};
  if (!o.emulate_mounting.empty()) f.mounting = geometry::load_frame_transform(o.emulate_mounting);
  if (o.emulate_motor_lag_s) f.lag_s = *o.emulate_motor_lag_s;
  return f;
}

void open_jetbot(const RobotIoOptions& o, uint32_t id, const agent::RobotModel& model,
                 const std::string& file, const dds::Participant& participant, RobotIo& io) {
  io.hardware = parse_jetbot_config(config::read_file(file, "robot"), file);
  if (!o.i2c.empty()) io.hardware.i2c_device = o.i2c;
  const bool emulated = io.hardware.i2c_device == "emulated";
  const PoseKind kind = o.pose == PoseKind::kDefault ? PoseKind::kVicon : o.pose;
  const std::string object =
      o.vicon_object.empty() ? "jetbot" + std::to_string(id) : o.vicon_object;
  if (kind == PoseKind::kVicon) {
    // An emulated JetBot streams to this process's own receiver: any free port, so several
    // emulated agents on one host never fight over the Vicon port.
    const uint16_t port = o.vicon_port.value_or(emulated ? 0 : 51001);
    io.vicon = std::make_unique<ViconReceiver>(o.vicon_bind, port, pose_transform(o, kind, id),
                                               std::vector<std::string>{object}, steady_s);
    io.pose = std::make_unique<ViconPoseSource>(*io.vicon, object, o.pose_max_age_s, steady_s);
    io.pose_name = "Vicon UDP " + object;
  } else if (kind == PoseKind::kRos && !o.ros_topic.empty()) {
    open_ros_pose(o, id, kind, participant, io);
  } else {
    throw std::invalid_argument(
        "a JetBot's pose comes from --pose vicon, or --pose ros with --ros-topic, e.g. "
        "/vrpn_mocap/jetbot1/pose");
  }
  if (!emulated) {
    io.bus = std::make_unique<LinuxI2cBus>(io.hardware.i2c_device);
  } else if (o.emulate_pose.size() != 3 || !io.vicon) {
    throw std::invalid_argument("--i2c emulated needs --emulate-pose X,Y,YAW and --pose vicon");
  } else {
    io.bus = std::make_unique<EmulatedJetbot>(
        io.hardware, model.wheel_base_m,
        agent::Pose2D{o.emulate_pose[0], o.emulate_pose[1], o.emulate_pose[2]}, object,
        io.vicon->port(), std::max(model.max_accel_mps2, model.max_decel_mps2) * 1.5,
        emulated_flaws(o));
  }
  auto drive = std::make_unique<JetbotDrive>(*io.bus, io.hardware, [](double s) {
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

std::string robot_file(const RobotIoOptions& o) {
  const std::string name =
      !o.config.empty() ? o.config : (o.backend == Backend::kRos2 ? "turtlebot3-burger" : "jetbot");
  return dds::find_config_file("robots", name);
}

RobotIo open_robot(const RobotIoOptions& o, uint32_t id, const agent::RobotModel& model,
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
  auto drive = std::make_unique<RosTwistDrive>(participant, ns, model.wheel_base_m, model.trim);
  io.twist = drive.get();
  io.drive = std::move(drive);
  return io;
}

std::unique_ptr<SignalStop> stop_outputs_on_signal(const RobotIo& io,
                                                   std::atomic<bool>* stop_flag) {
  if (io.jetbot == nullptr) return nullptr;
  return std::make_unique<SignalStop>(*io.bus, io.hardware.address, stop_flag);
}

}  // namespace smart::hw
