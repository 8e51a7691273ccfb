#include "smart/record/cdr.hpp"

#include <dds/ddsi/ddsi_cdrstream.h>
#include <dds/ddsi/q_protocol.h>

#include <algorithm>
#include <bit>
#include <cstring>
#include <stdexcept>
#include <string_view>
#include <vector>

namespace smart::record {

// RTPS encapsulation header, big-endian identifier CDR_LE then two option bytes (DDSI-RTPS 2.5,
// 10.2).
constexpr std::string_view kCdrLe("\x00\x01\x00\x00", 4);

struct CdrWriter::Stream {
  dds_ostreamLE_t os{};
  Stream() { dds_ostreamLE_init(&os, 0, CDR_ENC_VERSION_1); }
  ~Stream() { dds_ostreamLE_fini(&os); }
};

CdrWriter::CdrWriter() : stream_(std::make_unique<Stream>()) {}
CdrWriter::~CdrWriter() = default;

std::string_view CdrWriter::write(const void* sample, const dds_topic_descriptor_t& descriptor) {
  auto& os = stream_->os;
  os.x.m_index = 0;  // the buffer is kept; alignment counts from the payload's start
  dds_stream_writeLE(&os, static_cast<const char*>(sample), descriptor.m_ops);
  out_.assign(kCdrLe);
  out_.append(reinterpret_cast<const char*>(os.x.m_buffer), os.x.m_index);
  return out_;
}

std::string cdr_bytes(const void* sample, const dds_topic_descriptor_t& descriptor) {
  CdrWriter w;
  return std::string(w.write(sample, descriptor));
}

void read_cdr(std::string_view bytes, const dds_topic_descriptor_t& descriptor, void* sample) {
  const std::string type = descriptor.m_typename;
  if (bytes.size() < 4 || bytes.size() - 4 > UINT32_MAX) {
    throw std::invalid_argument(type + ": " + std::to_string(bytes.size()) +
                                " bytes are not a CDR message (a 4-byte header and its payload)");
  }
  // Encapsulation identifiers (DDSI-RTPS 2.5, 10.2): 00 00 CDR_BE, 00 01 CDR_LE.
  if (bytes[0] != 0 || (bytes[1] != 0 && bytes[1] != 1)) {
    throw std::invalid_argument(type + ": not plain CDR (encapsulation " +
                                std::to_string(static_cast<uint8_t>(bytes[0])) + " " +
                                std::to_string(static_cast<uint8_t>(bytes[1])) + ")");
  }
  const bool little = bytes[1] == 1;
  const auto size = static_cast<uint32_t>(bytes.size() - 4);
  std::vector<uint64_t> aligned(size / 8 + 1);  // the normalizer swaps in place, aligned
  auto* data = reinterpret_cast<char*>(aligned.data());
  std::memcpy(data, bytes.data() + 4, size);
  uint32_t used = 0;
  const bool swap = little != (std::endian::native == std::endian::little);
  if (!dds_stream_normalize_data(data, &used, size, swap, CDR_ENC_VERSION_1, descriptor.m_ops)) {
    throw std::invalid_argument(type +
                                ": the CDR payload does not hold this type (cut short, a "
                                "length past its end, or written for another version of the IDL)");
  }
  dds_istream_t is;
  dds_istream_init(&is, size, data, CDR_ENC_VERSION_1);
  dds_stream_read(&is, static_cast<char*>(sample), descriptor.m_ops);
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
