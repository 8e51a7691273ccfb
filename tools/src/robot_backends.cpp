#include "smart/tools/robot_backends.hpp"

#include "smart/tools/cli_common.hpp"

namespace smart::tools {

namespace {

const EnumNames<Backend> kBackendNames{{"jetbot", Backend::kJetbot}, {"ros2", Backend::kRos2}};
const EnumNames<PoseKind> kPoseNames{
    {"vicon", PoseKind::kVicon}, {"ros", PoseKind::kRos}, {"odom", PoseKind::kOdom}};

}  // namespace

void add_backend_options(CLI::App* cmd, BackendOptions& o) {
  add_enum_option(cmd, "--backend", o.backend, kBackendNames,
                  "jetbot (PCA9685 motor board; default) or ros2 (cmd_vel/odom of a ROS 2 base)");
  cmd->add_option("--config", o.config,
                  "robot model (name or file; default jetbot, or turtlebot3-burger with ros2)");
  cmd->add_option("--i2c", o.i2c, "I2C device (default from the robot file) or 'emulated'");
  add_enum_option(cmd, "--pose", o.pose, kPoseNames,
                  "vicon (Tracker UDP; JetBot default), odom (<ns>/odom; ros2 default) or ros "
                  "(a PoseStamped topic, --ros-topic)");
  cmd->add_option("--vicon-bind", o.vicon_bind, "local IPv4 address the Vicon socket listens on")
      ->capture_default_str();
  cmd->add_option("--vicon-port", o.vicon_port,
                  "UDP port of the Vicon stream (default 51001; with --i2c emulated or 0: the "
                  "first free port below 7400, where DDS never sends)");
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
