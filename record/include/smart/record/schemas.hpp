// Contract: the schemas an MCAP recording carries, derived from idl/ (the only wire definition)
// rather than written again:
// - ros2msg (https://mcap.dev/spec/registry#ros2msg): a ROS 2 message definition as rosbag2
//   stores it: the root message's fields, then each message it uses once, after a line of 80 '='
//   and "MSG: pkg/Type". Made from idl/ros2.idl, whose rmw names pkg::msg::dds_::Type_ map back
//   to pkg/Type and whose IDL types map to .msg types (long -> int32, double -> float64,
//   sequence<T> -> T[], T x[36] -> T[36], ...: the ROS 2 IDL mapping, design.ros2.org/articles/
//   idl_interface_definition.html, read backwards).
// - omgidl (https://mcap.dev/spec/registry#omgidl): idl/smart.idl's text as it is, the schema name
//   the type's scoped name (smart::msg::RobotState).
// Pure: text in, text out. Throws std::invalid_argument naming the type that is not defined.
#pragma once

#include <string>
#include <string_view>

namespace smart::record {

std::string_view ros2_idl_text();   // idl/ros2.idl, embedded at build time
std::string_view smart_idl_text();  // idl/smart.idl, embedded at build time

// "geometry_msgs/msg/PoseArray" -> its ros2msg definition, from ros2_idl_text().
std::string ros2msg_definition(std::string_view ros_type);
// The same from any IDL text in ros2.idl's subset (modules, @final structs, primitives, strings,
// sequences, fixed arrays; comments).
std::string ros2msg_definition(std::string_view idl_text, std::string_view ros_type);

}  // namespace smart::record
