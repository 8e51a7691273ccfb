// Contract: opening one physical robot's drive and pose source from options, shared by `smart
// agent` (driving robots in a run), `smart doctor` and `smart calibrate` (checks and trials
// before a run), so all accept the same flags (tools/robot_backends.hpp binds them) and build
// the same objects.
// - jetbot: a PCA9685 board on i2c-dev (or the emulated JetBot, --i2c emulated, with optional
//   flaws: a mismatched wheel, a mocap mounting), poses from Vicon UDP or a ROS 2 PoseStamped;
// - ros2: a ROS 2 diff-drive base in namespace --ros-namespace ({id}), cmd_vel out, poses from
//   its odometry or a ROS 2 PoseStamped.
// Poses go through --pose-transform ({id}: one file per robot) into the grid frame.
// Errors are std::invalid_argument or config::ConfigError saying which option to fix.
#pragma once

#include <atomic>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "smart/agent/interfaces.hpp"
#include "smart/agent/robot_model.hpp"
#include "smart/dds/participant.hpp"
#include "smart/hw/emulated_jetbot.hpp"
#include "smart/hw/i2c_bus.hpp"
#include "smart/hw/jetbot_drive.hpp"
#include "smart/hw/ros_pose.hpp"
#include "smart/hw/ros_twist_drive.hpp"
#include "smart/hw/vicon.hpp"

namespace smart::hw {

enum class Backend { kJetbot, kRos2 };
enum class PoseKind { kDefault, kVicon, kRos, kOdom };

struct RobotIoOptions {
  Backend backend = Backend::kJetbot;
  std::string config;  // default: jetbot, or turtlebot3-burger for ros2
  std::string i2c;     // default: the robot file's hardware.i2c_device
  PoseKind pose = PoseKind::kDefault;
  std::string vicon_bind = "0.0.0.0";
  std::optional<uint16_t> vicon_port;  // default: 51001, or any free port with --i2c emulated
  std::string vicon_object;            // default: jetbot<id>
  std::string ros_topic;               // --pose ros: PoseStamped topic; {id} is the robot's index
  std::string ros_namespace;           // default dds::kRosNamespacePattern
  double pose_max_age_s = 0.1;
  std::string pose_transform;        // mocap/odometry frame -> grid frame (smart calibrate frame)
  std::vector<double> emulate_pose;  // x, y, yaw for --i2c emulated
  std::vector<double> emulate_wheel_gains;    // left, right: a mismatched wheel
  std::string emulate_mounting;               // transform file: the emulated mocap's mounting
  bool emulate_realistic = false;             // hw::realistic_flaws(): dead band, lag, Vicon
  std::optional<double> emulate_motor_lag_s;  // overrides the flaws' motor time constant
  uint64_t emulate_seed = 0;                  // its Vicon noise
};

// The robot model file: --config, or the backend's default model.
std::string robot_file(const RobotIoOptions& o);

// "{id}" in a topic, namespace or file pattern is the robot's index (or a point's ID).
std::string with_id(std::string pattern, const std::string& id);
inline std::string with_id(const std::string& pattern, uint32_t robot) {
  return with_id(pattern, std::to_string(robot));
}

// One robot's hardware. Members are destroyed in reverse order: the pose source and drive
// before the receiver and the bus they use.
struct RobotIo {
  std::unique_ptr<ViconReceiver> vicon;
  std::unique_ptr<I2cBus> bus;
  std::unique_ptr<agent::DriveBackend> drive;
  std::unique_ptr<agent::PoseSource> pose;
  JetbotDrive* jetbot = nullptr;      // drive, when a JetBot (command watchdog)
  RosTwistDrive* twist = nullptr;     // drive, when a ROS 2 base
  RosPoseSource* ros_pose = nullptr;  // pose, when from ROS 2
  JetbotConfig hardware;              // a JetBot's hardware section
  std::string pose_name;              // where poses come from, for logs
};

RobotIo open_robot(const RobotIoOptions& o, uint32_t id, const agent::RobotModel& model,
                   const std::string& robot_file, const dds::Participant& participant);

// For a JetBot, SIGINT/SIGTERM turn its outputs off at once from the handler (SignalStop) and
// set *stop_flag; nullptr for other robots (their loops watch the flag, and their drive's
// destructor stops them).
std::unique_ptr<SignalStop> stop_outputs_on_signal(const RobotIo& io, std::atomic<bool>* stop_flag);

}  // namespace smart::hw
