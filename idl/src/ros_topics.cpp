#include <cctype>
#include <cmath>
#include <stdexcept>

#include "smart/dds/topics.hpp"

namespace smart::dds {

std::string ros_namespace(const std::string& pattern, uint32_t robot) {
  const auto at = pattern.find("{id}");
  std::string ns = at == std::string::npos
                       ? pattern
                       : pattern.substr(0, at) + std::to_string(robot) + pattern.substr(at + 4);
  if (ns.empty() || ns.front() != '/') ns.insert(ns.begin(), '/');
  while (ns.size() > 1 && ns.back() == '/') ns.pop_back();
  return ns == "/" ? "" : ns;
}

void check_ros_namespace(const std::string& ros_namespace) {
  if (ros_namespace.empty()) return;
  auto bad = [&](const std::string& why) {
    throw std::invalid_argument("ROS namespace '" + ros_namespace + "': " + why +
                                " (e.g. /run_a or /lab/run_1)");
  };
  if (ros_namespace.front() != '/') bad("must start with '/'");
  if (ros_namespace.back() == '/') bad("must not end with '/'");
  bool start = true;
  for (std::size_t i = 1; i < ros_namespace.size(); ++i) {
    const char c = ros_namespace[i];
    if (c == '/') {
      if (start) bad("has an empty name between two '/'");
      start = true;
      continue;
    }
    const bool ok = std::isalnum(static_cast<unsigned char>(c)) || c == '_';
    if (!ok) bad(std::string("has '") + c + "': names hold letters, digits and '_' only");
    if (start && std::isdigit(static_cast<unsigned char>(c)))
      bad("has a name starting with a digit");
    start = false;
  }
}

builtin_interfaces_msg_dds__Time_ ros_stamp(double t_s) {
  const double sec = std::floor(t_s);
  auto nanosec = static_cast<uint32_t>(std::llround((t_s - sec) * 1e9));
  auto whole = static_cast<int32_t>(sec);
  if (nanosec >= 1000000000u) {  // rounding up to the next second
    nanosec -= 1000000000u;
    ++whole;
  }
  return {whole, nanosec};
}

geometry_msgs_msg_dds__Quaternion_ yaw_quaternion(double yaw_rad) {
  return {0.0, 0.0, std::sin(yaw_rad / 2), std::cos(yaw_rad / 2)};
}

TopicQos ros_sensor_qos() {
  TopicQos q;
  q.reliability = Reliability::kBestEffort;
  q.durability = Durability::kVolatile;
  q.depth = 1;
  return q;
}

TopicQos ros_latched_qos() {
  TopicQos q;
  q.reliability = Reliability::kReliable;
  q.durability = Durability::kTransientLocal;
  q.depth = 1;
  return q;
}

TopicQos ros_command_qos() {
  TopicQos q;
  q.reliability = Reliability::kReliable;
  q.durability = Durability::kVolatile;
  q.depth = 10;
  return q;
}

}  // namespace smart::dds
