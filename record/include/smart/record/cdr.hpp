// Contract: a sample of an idlc-generated type as the CDR bytes a ROS 2 bag and Foxglove expect:
// the 4-byte encapsulation header (CDR_LE: 00 01 00 00) and the sample in XCDR1 little endian,
// written by Cyclone DDS's own serializer from the type's descriptor (dds/ddsi/ddsi_cdrstream.h),
// so the recorded bytes are the ones the live topic carries (all of idl/ is @final, XCDR1).
// CdrWriter does the same into one buffer it keeps (a recording serializes millions of samples:
// no allocation each).
// read_cdr is the way back for untrusted bytes: the encapsulation header is checked (CDR_LE or
// CDR_BE), the payload is validated by Cyclone's normalizer against the descriptor's ops (every
// length and enum within the bytes) before Cyclone's deserializer reads it.
// Pure: no participant, no DDS entity.
#pragma once

#include <dds/dds.h>

#include <memory>
#include <string>
#include <string_view>

#include "smart/dds/topic.hpp"

namespace smart::record {

std::string cdr_bytes(const void* sample, const dds_topic_descriptor_t& descriptor);

template <class T>
std::string cdr_bytes(const T& sample) {
  return cdr_bytes(&sample, *dds::TopicTraits<T>::descriptor());
}

class CdrWriter {
 public:
  CdrWriter();
  ~CdrWriter();
  CdrWriter(const CdrWriter&) = delete;
  CdrWriter& operator=(const CdrWriter&) = delete;
  // The sample's CDR bytes as cdr_bytes makes them; valid until the next write.
  std::string_view write(const void* sample, const dds_topic_descriptor_t& descriptor);
  template <class T>
  std::string_view write(const T& sample) {
    return write(&sample, *dds::TopicTraits<T>::descriptor());
  }

 private:
  struct Stream;
  std::unique_ptr<Stream> stream_;
  std::string out_;
};

// Fills `sample` (zero-initialized or read before) from `bytes`; throws std::invalid_argument
// saying what is wrong (short, not CDR, not this type). Free a sample's contents with
// dds_sample_free(sample, &descriptor, DDS_FREE_CONTENTS) when the type has strings or sequences.
void read_cdr(std::string_view bytes, const dds_topic_descriptor_t& descriptor, void* sample);
template <class T>
void read_cdr(std::string_view bytes, T& sample) {
  read_cdr(bytes, *dds::TopicTraits<T>::descriptor(), &sample);
}

// A ROS 2 message type's name ("geometry_msgs/msg/PoseArray") from its idlc descriptor's rmw
// name ("geometry_msgs::msg::dds_::PoseArray_"): the name schemas and channels carry, never
// written a second time.
std::string ros_type_name(const dds_topic_descriptor_t& descriptor);
template <class T>
std::string ros_type_name() {
  return ros_type_name(*dds::TopicTraits<T>::descriptor());
}

}  // namespace smart::record
