// Contract: the DDS edge of the Foxglove bridge: a read-only participant (no writer; under DDS
// Security the keystore's `viewer` identity) that reads a run's ROS 2 view (idl/smart.idl "The
// ROS 2 view", "The plan as rviz2 sees it") under its namespace: <ns>/map and <ns>/smart/markers
// (reliable, transient local: a bridge started late still gets them), <ns>/tf and
// <ns>/smart/poses (best effort), and hands each sample on as CDR (record/cdr.hpp, the bytes the
// wire carries) with its header stamp (sim time) in nanoseconds. A sample that is too large to be
// a fleet's (more than kMaxRobots poses or transforms, more than 4 markers per robot) is dropped
// and counted, never forwarded. Once the first PoseArray tells the fleet's size N, it also reads
// each robot's <ns>/robot_<i>/plan (reliable, transient local; for fleets up to
// kMaxPlanTopics robots) and announces their channels through `on_channels`; the chosen robots'
// <ns>/robot_<i>/pose are read from the start. A thread pumps samples until destruction.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "smart/bridge/foxglove_protocol.hpp"
#include "smart/dds/domain.hpp"

namespace smart::bridge {

inline constexpr uint32_t kMaxRobots = 100000;
inline constexpr uint32_t kMaxPlanTopics = 2000;
inline constexpr uint32_t kFirstRobotChannel = 16;

struct RosWatchOptions {
  int domain = 0;
  dds::DomainConfig config;
  std::string ros_namespace;          // "" or "/run_a" (dds::check_ros_namespace)
  std::vector<uint32_t> pose_robots;  // robots whose /robot_<i>/pose is read
};

// The channels of a run's ROS 2 view, ids 1.. in this order, with ros2msg schemas from idl/,
// then the chosen robots' poses from kFirstRobotChannel (the robots' plans follow them once the
// fleet is known).
enum ChannelId : uint32_t { kMapChannel = 1, kTfChannel, kPosesChannel, kMarkersChannel };
std::vector<Channel> ros_view_channels(const std::string& ros_namespace,
                                       const std::vector<uint32_t>& pose_robots);
// Channels whose last message a new subscriber gets at once (transient local on DDS).
bool latched(uint32_t channel);

class RosWatch {
 public:
  using Sink = std::function<void(uint32_t channel, uint64_t stamp_ns, std::string cdr)>;
  using ChannelsSink = std::function<void(std::vector<Channel> channels, bool latched)>;
  // Throws dds::Error when the participant or a reader cannot be made, std::invalid_argument for
  // a bad namespace.
  RosWatch(const RosWatchOptions& options, Sink sink, ChannelsSink on_channels);
  ~RosWatch();
  uint64_t dropped() const { return dropped_.load(); }

 private:
  struct Pump;
  void loop();
  void add_robot_topics(uint32_t robots);
  void take_robot_topics();
  RosWatchOptions options_;
  std::unique_ptr<Pump> pump_;
  Sink sink_;
  ChannelsSink on_channels_;
  std::atomic<uint64_t> dropped_{0};
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace smart::bridge
