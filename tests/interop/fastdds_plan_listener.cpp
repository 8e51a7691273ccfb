// A Fast DDS 2.9 program standing in for rviz2 (the second vendor, like fastdds_pose_listener):
// it subscribes to rt/robot_0/plan (nav_msgs/msg/Path, reliable, transient local, as rviz2's Path
// display can) and rt/smart/markers (visualization_msgs/msg/MarkerArray, reliable), decoding both
// with type support written here from the ROS 2 message definitions (common_interfaces), XCDR1.
//
// Usage: fastdds_plan_listener DOMAIN TIMEOUT_S
// Prints "path N x0 y0 xN yN frame F" for the first Path, then per MarkerArray
// "markers M moving A waiting W done D goals G arrows R deleteall K"; exits 0 once a Path and a
// MarkerArray with every robot done were seen, 1 on timeout.
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

struct Path {
  std::string frame;
  std::vector<std::array<double, 2>> xy;
};

struct Marker {
  std::string ns;
  int32_t id = 0, type = 0, action = 0;
  float r = 0, g = 0, b = 0, a = 0;
  uint32_t points = 0;
};

struct MarkerArray {
  std::vector<Marker> markers;
};

void skip_doubles(Cdr& d, int n) {
  double v;
  for (int i = 0; i < n; ++i) d >> v;
}
void read_header(Cdr& d, std::string* frame) {
  int32_t sec;
  uint32_t nsec;
  d >> sec >> nsec >> *frame;
}
void skip_bytes(Cdr& d) {  // sequence<uint8>
  uint32_t n;
  d >> n;
  uint8_t b;
  for (uint32_t i = 0; i < n; ++i) d >> b;
}

void read(Cdr& d, Path& m) {
  read_header(d, &m.frame);
  uint32_t n;
  d >> n;
  m.xy.resize(n);
  std::string frame;
  for (auto& p : m.xy) {
    read_header(d, &frame);
    d >> p[0] >> p[1];
    skip_doubles(d, 5);  // z, orientation
  }
}

void read(Cdr& d, Marker& m) {
  std::string s;
  read_header(d, &s);
  d >> m.ns >> m.id >> m.type >> m.action;
  skip_doubles(d, 7 + 3);  // pose, scale
  d >> m.r >> m.g >> m.b >> m.a;
  int32_t sec;
  uint32_t nsec;
  bool flag;
  d >> sec >> nsec >> flag;  // lifetime, frame_locked
  d >> m.points;
  skip_doubles(d, 3 * static_cast<int>(m.points));
  uint32_t colors;
  d >> colors;
  float f;
  for (uint32_t i = 0; i < 4 * colors; ++i) d >> f;
  d >> s;              // texture_resource
  read_header(d, &s);  // texture: header, format, data
  d >> s;
  skip_bytes(d);
  uint32_t uv;
  d >> uv;
  for (uint32_t i = 0; i < 2 * uv; ++i) d >> f;
  d >> s >> s >> s;  // text, mesh_resource, mesh_file.filename
  skip_bytes(d);     // mesh_file.data
  d >> flag;         // mesh_use_embedded_materials
}

void read(Cdr& d, MarkerArray& m) {
  uint32_t n;
  d >> n;
  m.markers.resize(n);
  for (auto& k : m.markers) read(d, k);
}

template <class T>
class Type : public TopicDataType {
 public:
  explicit Type(const char* name) {
    setName(name);
    m_typeSize = 4 + 64 * 1024;
    m_isGetKeyDefined = false;
  }
  bool serialize(void*, SerializedPayload_t*) override { return false; }  // a reader only
  bool deserialize(SerializedPayload_t* payload, void* data) override {
    FastBuffer buffer(reinterpret_cast<char*>(payload->data), payload->length);
    Cdr d(buffer, Cdr::DEFAULT_ENDIAN, Cdr::DDS_CDR);
    try {
      d.read_encapsulation();
      read(d, *static_cast<T*>(data));
    } catch (const std::exception& e) {
      std::fprintf(stderr, "fastdds_plan_listener: cannot decode a %s: %s\n", getName(), e.what());
      return false;
    }
    return true;
  }
  std::function<uint32_t()> getSerializedSizeProvider(void*) override {
    return [] { return uint32_t{4}; };
  }
  void* createData() override { return new T(); }
  void deleteData(void* data) override { delete static_cast<T*>(data); }
  bool getKey(void*, eprosima::fastrtps::rtps::InstanceHandle_t*, bool) override { return false; }
};

// "markers ..." line; true when every robot marker is grey (done).
bool print_markers(const MarkerArray& m) {
  int moving = 0, waiting = 0, done = 0, goals = 0, arrows = 0, deleteall = 0;
  for (const auto& k : m.markers) {
    if (k.action == 3) {
      ++deleteall;
    } else if (k.ns == "robots") {
      (k.g > 0.7f && k.r < 0.5f ? moving : (k.r > 0.9f ? waiting : done))++;
    } else if (k.ns == "goals") {
      ++goals;
    } else if (k.ns == "waits" && k.type == 0 && k.points == 2) {
      ++arrows;
    }
  }
  std::printf("markers %zu moving %d waiting %d done %d goals %d arrows %d deleteall %d\n",
              m.markers.size(), moving, waiting, done, goals, arrows, deleteall);
  std::fflush(stdout);
  return moving == 0 && waiting == 0 && done > 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: fastdds_plan_listener DOMAIN TIMEOUT_S\n");
    return 2;
  }
  DomainParticipant* p =
      smart::interop::make_loopback_participant(std::atoi(argv[1]), "fastdds_plan_listener");
  if (p == nullptr) return 2;
  TypeSupport path_type(new Type<Path>("nav_msgs::msg::dds_::Path_"));
  TypeSupport marker_type(new Type<MarkerArray>("visualization_msgs::msg::dds_::MarkerArray_"));
  path_type.register_type(p);
  marker_type.register_type(p);
  Subscriber* sub = p->create_subscriber(SUBSCRIBER_QOS_DEFAULT);
  DataReaderQos q = DATAREADER_QOS_DEFAULT;
  q.reliability().kind = RELIABLE_RELIABILITY_QOS;
  q.durability().kind = TRANSIENT_LOCAL_DURABILITY_QOS;
  q.history().kind = KEEP_LAST_HISTORY_QOS;
  q.history().depth = 100;
  q.endpoint().history_memory_policy =
      eprosima::fastrtps::rtps::PREALLOCATED_WITH_REALLOC_MEMORY_MODE;
  DataReader* paths = sub->create_datareader(
      p->create_topic("rt/robot_0/plan", path_type.get_type_name(), TOPIC_QOS_DEFAULT), q);
  DataReader* markers = sub->create_datareader(
      p->create_topic("rt/smart/markers", marker_type.get_type_name(), TOPIC_QOS_DEFAULT), q);
  bool got_path = false, all_done = false;
  const auto deadline =
      std::chrono::steady_clock::now() + std::chrono::duration<double>(std::atof(argv[2]));
  while (!(got_path && all_done) && std::chrono::steady_clock::now() < deadline) {
    Path path;
    MarkerArray array;
    SampleInfo info;
    bool any = false;
    if (paths->take_next_sample(&path, &info) == ReturnCode_t::RETCODE_OK && info.valid_data &&
        !got_path && !path.xy.empty()) {
      got_path = any = true;
      std::printf("path %zu %.3f %.3f %.3f %.3f frame %s\n", path.xy.size(), path.xy.front()[0],
                  path.xy.front()[1], path.xy.back()[0], path.xy.back()[1], path.frame.c_str());
    }
    if (markers->take_next_sample(&array, &info) == ReturnCode_t::RETCODE_OK && info.valid_data) {
      any = true;
      all_done = print_markers(array) || all_done;
    }
    if (!any) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  p->delete_contained_entities();
  DomainParticipantFactory::get_instance()->delete_participant(p);
  return got_path && all_done ? 0 : 1;
}
