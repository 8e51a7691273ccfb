#include "smart/commissioning/verdicts.hpp"

#include <cmath>
#include <numbers>
#include <sstream>

namespace smart::commissioning {

std::optional<CheckRow> rejected_row(const wire::Rejections& rejected) {
  if (rejected.total() == 0) return std::nullopt;
  std::string what;
  for (const auto& [topic, reasons] : rejected.counts()) {
    for (const auto& [reason, n] : reasons) {
      what += (what.empty() ? "" : "; ") + std::to_string(n) + " " + topic + ": " + reason;
    }
  }
  return CheckRow{
      "", "wire", Level::kWarn,
      std::to_string(rejected.total()) + " sample(s) failed the wire checks (" + what + ")",
      "a program on this domain and run writes malformed samples (ignored here and by "
      "the monitor); run with --security so that only SMART's identities can write"};
}

const char* level_name(Level level) {
  switch (level) {
    case Level::kOk:
      return "OK";
    case Level::kWarn:
      return "WARN";
    case Level::kFail:
      break;
  }
  return "FAIL";
}

CheckRow pose_stream_check(const std::string& robot, const std::vector<agent::PoseSample>& samples,
                           double seconds, double min_rate_hz, double max_age_s) {
  CheckRow row{robot, "pose stream", Level::kOk, "", ""};
  if (samples.size() < 2) {
    row.level = Level::kFail;
    row.measured = std::to_string(samples.size()) + " poses in " + std::to_string(seconds) + " s";
    row.fix =
        "no pose stream: check the mocap object name and port (--vicon-object, "
        "--vicon-port), the ROS topic or namespace, and that the robot is tracked";
    return row;
  }
  double sum = 0, sum_sq = 0, max_gap = 0;
  for (std::size_t i = 1; i < samples.size(); ++i) {
    const double gap = samples[i].stamp_s - samples[i - 1].stamp_s;
    sum += gap;
    sum_sq += gap * gap;
    max_gap = std::max(max_gap, gap);
  }
  const double n = static_cast<double>(samples.size() - 1), mean = sum / n;
  const double rate = static_cast<double>(samples.size()) / seconds;
  const double jitter = std::sqrt(std::max(0.0, sum_sq / n - mean * mean));
  std::ostringstream m;
  m.precision(3);
  m << rate << " Hz, jitter " << jitter * 1000 << " ms, largest gap " << max_gap * 1000 << " ms";
  row.measured = m.str();
  if (rate < min_rate_hz) {
    row.level = Level::kWarn;
    row.fix = "the pose rate is below " + std::to_string(static_cast<int>(min_rate_hz)) +
              " Hz: check the mocap frame rate and the network";
  } else if (max_gap > max_age_s) {
    row.level = Level::kWarn;
    row.fix =
        "gaps longer than --pose-max-age-s stop the robot: check for lost tracking or "
        "packets";
  }
  return row;
}

CheckRow clock_check(const std::string& host, const std::vector<uint32_t>& robots,
                     double min_offset_s, std::size_t samples, double tolerance_s) {
  std::ostringstream m;
  m.precision(3);
  m << (robots.empty() ? "the monitor" : "robots");
  for (std::size_t i = 0; i < robots.size() && i < 8; ++i) m << (i ? "," : " ") << robots[i];
  if (robots.size() > 8) m << ",... (" << robots.size() << ")";
  m << "; clock offset + delay " << min_offset_s * 1000 << " ms over " << samples << " samples";
  CheckRow row{"", "host " + host, Level::kOk, m.str(), ""};
  if (std::abs(min_offset_s) > tolerance_s) {
    row.level = Level::kWarn;
    row.fix =
        "this host's clock and that one's differ: synchronise them (chrony or PTP; "
        "`chronyc tracking` shows the offset), or logs and pose latencies will not line up";
  }
  return row;
}

CheckRow response_check(const std::string& robot, std::optional<double> latency_s,
                        double tolerance_s) {
  CheckRow row{robot, "response", Level::kOk, "", ""};
  if (!latency_s) {
    row.level = Level::kFail;
    row.measured = "the pose never showed the commanded motion";
    row.fix = "see the wheel rows: a wheel that does not turn, or a pose stream of another robot";
    return row;
  }
  std::ostringstream m;
  m.precision(3);
  m << "pose moved " << *latency_s * 1000 << " ms after the first command (5 mm or 1.5 deg)";
  row.measured = m.str();
  if (*latency_s > tolerance_s) {
    row.level = Level::kWarn;
    row.fix =
        "the controller will overshoot: find the delay in the pose stream (mocap processing, "
        "odometry rate, network) or the motor driver (its ramp), or lower the robot file's "
        "speeds and gains";
  }
  return row;
}

CheckRow wheel_check(const std::string& robot, Wheel wheel, const agent::Pose2D& before,
                     const agent::Pose2D& after, bool board) {
  const char* name = wheel == Wheel::kLeft ? "left" : "right";
  CheckRow row{robot, std::string(name) + " wheel", Level::kOk, "", ""};
  const double turn = std::remainder(after.yaw_rad - before.yaw_rad, 2 * std::numbers::pi);
  const double ahead = std::cos(before.yaw_rad) * (after.x_m - before.x_m) +
                       std::sin(before.yaw_rad) * (after.y_m - before.y_m);
  std::ostringstream m;
  m.precision(3);
  m << "turned " << turn * 180 / std::numbers::pi << " deg, moved " << ahead * 1000 << " mm ahead";
  row.measured = m.str();
  if (std::abs(turn) < 0.05 && std::abs(ahead) < 0.005) {
    row.level = Level::kFail;
    row.fix = std::string("the ") + name + " wheel did not move: " +
              (board ? std::string("check its motor wiring and the board's channel map "
                                   "(hardware.board); a motor dead band (TT motors start only "
                                   "above about 60/255 PWM) needs hardware.") +
                           name + ".beta (examples/lab-7-jetbots/jetbot-lab.yaml)"
                     : std::string("check the base's driver and that it hears cmd_vel"));
    return row;
  }
  // Forward on one wheel: the robot pivots about the other one, turning away from it.
  const bool forward = wheel == Wheel::kLeft ? turn < 0 : turn > 0;
  if (!forward) {
    row.level = Level::kFail;
    row.fix = std::string("the ") + name + " wheel turns backwards: " +
              (board ? std::string("flip hardware.") + name + ".sign in the robot file"
                     : std::string("fix the base's driver (its wheel direction or joint axis)"));
  }
  return row;
}

}  // namespace smart::commissioning
