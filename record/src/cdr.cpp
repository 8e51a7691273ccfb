#include "smart/record/cdr.hpp"

#include <dds/ddsi/ddsi_cdrstream.h>
#include <dds/ddsi/q_protocol.h>

#include <algorithm>
#include <string_view>

namespace smart::record {

std::string cdr_bytes(const void* sample, const dds_topic_descriptor_t& descriptor) {
  dds_ostreamLE_t os;
  dds_ostreamLE_init(&os, 0, CDR_ENC_VERSION_1);
  dds_stream_writeLE(&os, static_cast<const char*>(sample), descriptor.m_ops);
  // RTPS encapsulation header, big-endian identifier CDR_LE then two option bytes (DDSI-RTPS
  // 2.5, 10.2).
  std::string out("\x00\x01\x00\x00", 4);
  out.append(reinterpret_cast<const char*>(os.x.m_buffer), os.x.m_index);
  dds_ostreamLE_fini(&os);
  return out;
}

std::string ros_type_name(const dds_topic_descriptor_t& descriptor) {
  // pkg::msg::dds_::Type_ -> pkg/msg/Type
  const std::string_view rmw = descriptor.m_typename;
  std::string name;
  for (std::size_t at = 0; at <= rmw.size();) {
    const auto end = std::min(rmw.find("::", at), rmw.size());
    const auto part = rmw.substr(at, end - at);
    if (part != "dds_") name.append(name.empty() ? "" : "/").append(part);
    at = end + 2;
  }
  if (!name.empty() && name.back() == '_') name.pop_back();
  return name;
}

}  // namespace smart::record
