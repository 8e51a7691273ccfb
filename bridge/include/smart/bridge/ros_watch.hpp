// Contract: the DDS edge of the Foxglove bridge: a read-only participant (no writer; under DDS
// Security the keystore's `viewer` identity) that reads a run's ROS 2 view (idl/smart.idl "The
// ROS 2 view", "The plan as rviz2 sees it") under its namespace: <ns>/map and <ns>/smart/markers
// (reliable, transient local: a bridge started late still gets them), <ns>/tf and
// <ns>/smart/poses (best effort), and hands each sample on as CDR (record/cdr.hpp, the bytes the
// wire carries) with its header stamp (sim time) in nanoseconds. A sample that is too large to be
// a fleet's (more than kMaxRobots poses or transforms, more than 4 markers per robot) is dropped
// and counted, never forwarded. A thread pumps samples until destruction.
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

struct RosWatchOptions {
  int domain = 0;
  dds::DomainConfig config;
  std::string ros_namespace;  // "" or "/run_a" (dds::check_ros_namespace)
};

// The channels of a run's ROS 2 view, ids 1.. in this order, with ros2msg schemas from idl/.
enum ChannelId : uint32_t { kMapChannel = 1, kTfChannel, kPosesChannel, kMarkersChannel };
std::vector<Channel> ros_view_channels(const std::string& ros_namespace);
// Channels whose last message a new subscriber gets at once (transient local on DDS).
bool latched(uint32_t channel);

class RosWatch {
 public:
  using Sink = std::function<void(uint32_t channel, uint64_t stamp_ns, std::string cdr)>;
  // Throws dds::Error when the participant or a reader cannot be made, std::invalid_argument for
  // a bad namespace.
  RosWatch(const RosWatchOptions& options, Sink sink);
  ~RosWatch();
  uint64_t dropped() const { return dropped_.load(); }

 private:
  struct Pump;
  void loop();
  std::unique_ptr<Pump> pump_;
  Sink sink_;
  std::atomic<uint64_t> dropped_{0};
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace smart::bridge
