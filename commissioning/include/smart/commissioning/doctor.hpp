// Contract: `smart doctor`'s checks, measured on the real domain and the real robots; each
// becomes verdict rows (verdicts.hpp: OK, WARN or FAIL, what was measured, how to fix it).
// - domain_checks(): listens `listen_s` on a participant: the monitor of the run (MonitorInfo),
//   whether its action writer matched this host's QoS, every host heard through its robots'
//   states with its clock offset, and samples that failed the wire checks (never believed).
//   With `wait_s` > `listen_s` it listens on, up to `wait_s`, until what it heard is settled: a
//   monitor seen, its action writer matched (or refused as incompatible), and every host heard
//   at least twice (one sample gives a clock offset with its delay unknown). Started beside a
//   monitor that is still starting, it reports once the monitor is there, not after a guess.
// - robot_checks(): one robot this host drives: `open` builds its hardware (hw/robot_io.hpp; a
//   failure is a FAIL row naming it), then the motor board (a JetBot's PCA9685 answering on
//   I2C), the pose stream (rate, jitter, gaps) and, with `wheels` and `confirm` saying yes, each
//   wheel driven alone (direction, response time). The wheels stop at the end, on `stop` (its
//   SIGINT flag, which also turns a JetBot's outputs off from the signal handler) and on failure.
// Blocking: these sleep while they measure (an edge, not a core).
#pragma once

#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include "smart/commissioning/verdicts.hpp"
#include "smart/dds/participant.hpp"
#include "smart/dds/qos_profile.hpp"
#include "smart/hw/robot_io.hpp"

namespace smart::commissioning {

struct DoctorSettings {
  double listen_s = 2.0;  // the monitor and every pose stream
  double wait_s = 0;      // listen on, up to this long, until the domain is settled (above)
  double min_pose_rate_hz = 20.0;
  double pose_max_age_s = 0.1;  // a longer gap would stop the robot (the agent's limit)
  bool wheels = false;
  double wheel_speed_mps = 0.15, wheel_s = 0.6;
  // Asked before a robot's wheels turn (a person stands by); empty: go.
  std::function<bool(const std::string& robot)> confirm;
  std::atomic<bool>* stop = nullptr;
};

// where: "domain 3, run x", named in the rows.
std::vector<CheckRow> domain_checks(const DoctorSettings& s, const dds::QosProfile& profile,
                                    const dds::Participant& participant, const std::string& where);

std::vector<CheckRow> robot_checks(const DoctorSettings& s, const std::string& robot,
                                   const std::function<hw::RobotIo()>& open);

}  // namespace smart::commissioning
