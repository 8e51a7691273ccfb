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

TopicQos ros_sensor_qos() {
  TopicQos q;
  q.reliability = Reliability::kBestEffort;
  q.durability = Durability::kVolatile;
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
