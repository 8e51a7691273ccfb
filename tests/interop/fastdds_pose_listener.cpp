// A Fast DDS 2.9 program standing in for a ROS 2 node (docs/architecture.md, "ROS 2 view"): it
// subscribes to rt/smart/poses as geometry_msgs/msg/PoseArray, with the type support written
// here by hand (no code generator: the ROS 2 message layout is small and fixed, XCDR1 as
// rmw_cyclonedds and rmw_fastrtps both use). A second DDS vendor reading what SMART-DDS writes
// with Cyclone proves the topic and type names, the encoding and discovery are interoperable.
//
// Usage: fastdds_pose_listener DOMAIN MESSAGES TIMEOUT_S
// Prints one line per PoseArray received: "poses <n> frame <id> stamp <sec>.<nanosec>
// first <x> <y> <qz> <qw>"; exits 0 after MESSAGES messages, 1 on timeout.
// Discovery is loopback-only and unicast, like SMART-DDS's default: UDPv4 on 127.0.0.1 with
// the initial peers at the RTPS well-known ports of participant indices 0..9.
#include <fastcdr/Cdr.h>
#include <fastcdr/FastBuffer.h>
#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>
#include <fastrtps/utils/IPLocator.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/TopicDataType.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "fastdds_support.hpp"

namespace {

using namespace eprosima::fastdds::dds;
using eprosima::fastcdr::Cdr;
using eprosima::fastcdr::FastBuffer;
using eprosima::fastrtps::rtps::SerializedPayload_t;

// geometry_msgs/PoseArray: Header (Time sec/nanosec, frame_id) + Pose[] (position xyz,
// orientation xyzw).
struct PoseArray {
  int32_t sec = 0;
  uint32_t nanosec = 0;
  std::string frame_id;
  std::vector<std::array<double, 7>> poses;
};

class PoseArrayType : public TopicDataType {
 public:
  PoseArrayType() {
    setName("geometry_msgs::msg::dds_::PoseArray_");  // the rmw name of the ROS 2 type
    m_typeSize = 4 + 64 * 1024;  // grows as needed (reader history reallocates)
    m_isGetKeyDefined = false;
  }
  bool serialize(void* data, SerializedPayload_t* payload) override {
    const auto& m = *static_cast<PoseArray*>(data);
    FastBuffer buffer(reinterpret_cast<char*>(payload->data), payload->max_size);
    Cdr ser(buffer, Cdr::DEFAULT_ENDIAN, Cdr::DDS_CDR);
    payload->encapsulation = ser.endianness() == Cdr::BIG_ENDIANNESS ? CDR_BE : CDR_LE;
    ser.serialize_encapsulation();
    ser << m.sec << m.nanosec << m.frame_id << static_cast<uint32_t>(m.poses.size());
    for (const auto& p : m.poses) {
      for (const double v : p) ser << v;
    }
    payload->length = static_cast<uint32_t>(ser.getSerializedDataLength());
    return true;
  }
  bool deserialize(SerializedPayload_t* payload, void* data) override {
    auto& m = *static_cast<PoseArray*>(data);
    FastBuffer buffer(reinterpret_cast<char*>(payload->data), payload->length);
    Cdr deser(buffer, Cdr::DEFAULT_ENDIAN, Cdr::DDS_CDR);
    try {
      deser.read_encapsulation();
      uint32_t n = 0;
      deser >> m.sec >> m.nanosec >> m.frame_id >> n;
      m.poses.resize(n);
      for (auto& p : m.poses) {
        for (double& v : p) deser >> v;
      }
    } catch (const std::exception& e) {
      std::fprintf(stderr, "fastdds_pose_listener: cannot decode a PoseArray: %s\n", e.what());
      return false;
    }
    return true;
  }
  std::function<uint32_t()> getSerializedSizeProvider(void* data) override {
    return [data] {
      const auto& m = *static_cast<PoseArray*>(data);
      return static_cast<uint32_t>(4 + 8 + 4 + m.frame_id.size() + 1 + 8 + 4 + m.poses.size() * 56 +
                                   8);
    };
  }
  void* createData() override { return new PoseArray(); }
  void deleteData(void* data) override { delete static_cast<PoseArray*>(data); }
  bool getKey(void*, eprosima::fastrtps::rtps::InstanceHandle_t*, bool) override { return false; }
};

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: fastdds_pose_listener DOMAIN MESSAGES TIMEOUT_S\n");
    return 2;
  }
  const int domain = std::atoi(argv[1]);
  const int wanted = std::atoi(argv[2]);
  const double timeout_s = std::atof(argv[3]);

  auto* factory = DomainParticipantFactory::get_instance();
  DomainParticipant* participant =
      smart::interop::make_loopback_participant(domain, "fastdds_pose_listener");
  if (participant == nullptr) {
    std::fprintf(stderr, "fastdds_pose_listener: cannot create a participant\n");
    return 2;
  }
  TypeSupport type(new PoseArrayType());
  type.register_type(participant);
  Topic* topic =
      participant->create_topic("rt/smart/poses", type.get_type_name(), TOPIC_QOS_DEFAULT);
  Subscriber* subscriber = participant->create_subscriber(SUBSCRIBER_QOS_DEFAULT);
  DataReaderQos rqos = DATAREADER_QOS_DEFAULT;
  rqos.reliability().kind = BEST_EFFORT_RELIABILITY_QOS;
  rqos.history().kind = KEEP_LAST_HISTORY_QOS;
  rqos.history().depth = 1;
  rqos.endpoint().history_memory_policy =
      eprosima::fastrtps::rtps::PREALLOCATED_WITH_REALLOC_MEMORY_MODE;
  DataReader* reader = subscriber->create_datareader(topic, rqos);

  int got = 0;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  PoseArray m;
  SampleInfo info;
  while (got < wanted && std::chrono::steady_clock::now() < deadline) {
    if (reader->take_next_sample(&m, &info) == ReturnCode_t::RETCODE_OK && info.valid_data) {
      ++got;
      const auto first = m.poses.empty() ? std::array<double, 7>{} : m.poses.front();
      std::printf("poses %zu frame %s stamp %d.%09u first %.6f %.6f %.6f %.6f\n", m.poses.size(),
                  m.frame_id.c_str(), m.sec, m.nanosec, first[0], first[1], first[5], first[6]);
      std::fflush(stdout);
    } else {
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  }
  participant->delete_contained_entities();
  factory->delete_participant(participant);
  if (got < wanted) {
    std::fprintf(stderr, "fastdds_pose_listener: %d of %d PoseArray messages in %.1f s\n", got,
                 wanted, timeout_s);
    return 1;
  }
  return 0;
}
