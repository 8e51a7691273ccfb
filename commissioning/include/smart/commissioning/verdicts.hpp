// Contract: the verdicts of `smart doctor` (pure; doctor.hpp measures): each check becomes a row
// with a level (OK, WARN, FAIL), what was measured and, unless OK, how to fix it.
// - pose_stream_check(): a pose stream recorded for `seconds`: its rate, jitter (standard
//   deviation of the gaps) and largest gap; FAIL without poses, WARN below min_rate_hz or with a
//   gap longer than max_age_s (the agent would stop the robot then).
// - wheel_check(): one wheel driven forward alone from `before` to `after`: a left wheel alone
//   turns the robot clockwise (right), a right wheel counter-clockwise, and both move it forward;
//   FAIL names the sign to flip in the robot file, or a wheel that did not move.
// - response_check(): the time from the first wheel command to the pose stream showing motion
//   (motor start-up + pose latency, what the controller lives with); WARN above tolerance_s,
//   FAIL when the pose never moved.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "smart/agent/types.hpp"
#include "smart/convert/validate.hpp"

namespace smart::commissioning {

enum class Level { kOk, kWarn, kFail };

struct CheckRow {
  std::string robot;  // "3", or "" for host-wide checks
  std::string check;
  Level level = Level::kOk;
  std::string measured;
  std::string fix;  // empty when OK
};

CheckRow pose_stream_check(const std::string& robot, const std::vector<agent::PoseSample>& samples,
                           double seconds, double min_rate_hz, double max_age_s);

enum class Wheel { kLeft, kRight };
// board: the robot's wheels are driven by this project (a JetBot: the fix is in its robot file),
// not by a ROS 2 base's own driver.
CheckRow wheel_check(const std::string& robot, Wheel wheel, const agent::Pose2D& before,
                     const agent::Pose2D& after, bool board = true);

CheckRow response_check(const std::string& robot, std::optional<double> latency_s,
                        double tolerance_s = 0.25);

// A host heard on the domain through its robots' states (robots empty: the monitor's
// announcements): the smallest (receive time - the
// sample's source timestamp) over `samples` is its clock's offset from this host's plus the
// one-way delay, an upper bound on the offset when positive. Above tolerance_s: WARN.
CheckRow clock_check(const std::string& host, const std::vector<uint32_t>& robots,
                     double min_offset_s, std::size_t samples, double tolerance_s);

// Samples heard on the domain that failed the wire checks (wire::Rejections): one WARN row
// naming how many, on which topic and why; none when every sample passed.
std::optional<CheckRow> rejected_row(const wire::Rejections& rejected);

const char* level_name(Level level);

}  // namespace smart::commissioning
