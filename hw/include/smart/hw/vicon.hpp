// Contract: Vicon Tracker's UDP object stream (docs/hardware.md §5): little-endian
// datagrams of uint32 frame number, uint8 item count, then per item uint8 id (0 = object),
// uint16 data size (72), char name[24], float64 x, y, z (mm) and Euler XYZ rotations (rad).
// parse_vicon_datagram() is pure and never throws: malformed input (short, wrong item size,
// NaN/inf values) is reported as an error string. ViconReceiver owns a UDP socket and a
// background thread (receiving never blocks the control loop); it keeps the latest pose of each
// configured object, transformed into the grid's world frame, and counts what it drops.
// ViconPoseSource is one robot's PoseSource: invalid when no pose is newer than max_age_s.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "smart/agent/interfaces.hpp"
#include "smart/geometry/frame_transform.hpp"

namespace smart::hw {

struct ViconObject {
  std::string name;
  double position_mm[3];
  double rotation_rad[3];
};

struct ViconFrame {
  uint32_t frame = 0;
  std::vector<ViconObject> objects;
  uint32_t skipped_items = 0;  // items that are not objects (id != 0)
};

std::optional<ViconFrame> parse_vicon_datagram(const uint8_t* data, std::size_t size,
                                               std::string* error);
// Builds a datagram (padded to 256/512/1024 bytes like Tracker does), for emulators and tests.
std::vector<uint8_t> make_vicon_datagram(uint32_t frame, const std::vector<ViconObject>& objects);

// Vicon frame (mm, rad) -> world frame (m, rad): a transform file (`smart calibrate`), or by
// default the millimetre scale alone.
inline geometry::FrameTransform vicon_millimetres() {
  return {0.001, 0.0, Eigen::Vector2d::Zero()};
}

struct ViconStats {
  uint64_t datagrams = 0;
  uint64_t malformed = 0;
  uint64_t unknown_names = 0;
  uint64_t poses = 0;
};

// Whether DDS may send to UDP `port`: the RTPS ports 7400 + 250 d + {0, 1, 10 + 2 i, 11 + 2 i}
// for domain d and participant index i (DDSI-RTPS 2.5 §9.6.1.1); with our 120 participant
// indices (dds::DomainConfig) they fill each domain's block but for offsets 2-9. Cyclone sends
// discovery to every index's port of each configured peer, so a Vicon socket there hears RTPS
// packets as malformed frames.
bool rtps_may_use_port(uint16_t port);

class ViconReceiver {
 public:
  // Listens on `bind_address`:`port` (UDP); port 0 picks the first free port below the DDS
  // ports (7399, 7398, ...): an ephemeral port can be another domain's discovery port. Throws
  // std::runtime_error when it cannot bind.
  ViconReceiver(const std::string& bind_address, uint16_t port, geometry::FrameTransform transform,
                const std::vector<std::string>& objects, std::function<double()> now_s);
  ~ViconReceiver();
  uint16_t port() const { return port_; }
  // Latest pose of the object (world frame), stamped with the receive time.
  std::optional<agent::PoseSample> latest(const std::string& object) const;
  ViconStats stats() const;
  // Feeds one datagram as if received (the thread uses it too).
  void handle(const uint8_t* data, std::size_t size);

 private:
  void loop();
  int fd_ = -1;
  uint16_t port_ = 0;
  geometry::FrameTransform transform_;
  std::map<std::string, std::optional<agent::PoseSample>> latest_;
  std::function<double()> now_s_;
  mutable std::mutex mutex_;
  ViconStats stats_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

class ViconPoseSource : public agent::PoseSource {
 public:
  ViconPoseSource(const ViconReceiver& receiver, std::string object, double max_age_s,
                  std::function<double()> now_s);
  agent::PoseSample read() override;

 private:
  const ViconReceiver& receiver_;
  std::string object_;
  double max_age_s_;
  std::function<double()> now_s_;
};

}  // namespace smart::hw
