// A stand-in for a ROS 2 diff-drive robot (TurtleBot3, a Gazebo diff drive), written with the
// second DDS vendor, Fast DDS 2.9, so that `smart agent --backend ros2` is tested against an
// implementation that shares no code with it. Per robot namespace NS it subscribes
// rt/NS/cmd_vel (geometry_msgs/msg/Twist, reliable, as nav2 and teleop publish), integrates a
// unicycle with speed and acceleration limits at 100 Hz, zeroes the command after 0.5 s without
// one (diff_drive_controller's cmd_vel_timeout default), and publishes rt/NS/odom
// (nav_msgs/msg/Odometry, best effort, frame "odom", child "base_footprint") at 50 Hz. Type
// support is written here by hand, XCDR1 as rmw_fastrtps and rmw_cyclonedds use; the layouts
// follow the ROS 2 message definitions (common_interfaces, geometry_msgs and nav_msgs).
//
// Usage: fastdds_diffdrive DOMAIN TIMEOUT_S MAX_V MAX_W MAX_ACC MAX_ALPHA ODOM NS:X,Y,YAW...
//   ODOM = world: odometry in the grid's frame (like a simulator's ground truth);
//   ODOM = start: odometry starts at (0, 0, 0) where the robot starts (like a real base);
//   ODOM = frame:S,YAW,TX,TY: poses in a frame that p_world = S R(YAW) p + (TX, TY) maps onto
//   the grid (like a mocap system mounted at an angle), for frame calibration.
//   LEFT/RIGHT wheel gains: NS:X,Y,YAW,GL,GR (default 1,1) model a mismatched wheel.
// Runs TIMEOUT_S seconds (or until SIGTERM), then prints per robot
// "robot NS x y yaw cmds N last V W" (world frame; the last command received) and exits 0; 2 on
// bad arguments.
#include <fastcdr/Cdr.h>
#include <fastcdr/FastBuffer.h>
#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>
#include <fastrtps/utils/IPLocator.h>
#include <signal.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
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

std::atomic<bool> g_stop{false};
void on_signal(int) { g_stop = true; }

struct Twist {
  std::array<double, 3> linear{}, angular{};
};

// nav_msgs/Odometry: Header, child_frame_id, PoseWithCovariance (Pose + 36), TwistWithCovariance.
struct Odometry {
  int32_t sec = 0;
  uint32_t nanosec = 0;
  std::string frame_id = "odom", child_frame_id = "base_footprint";
  std::array<double, 7> pose{};  // position xyz, orientation xyzw
  std::array<double, 36> pose_cov{};
  Twist twist;
  std::array<double, 36> twist_cov{};
};

// A hand-written TopicDataType: serialize/deserialize with Fast CDR, no keys.
template <class T>
class Type : public TopicDataType {
 public:
  explicit Type(const char* name) {
    setName(name);
    m_typeSize = 4 + 1024;
    m_isGetKeyDefined = false;
  }
  bool serialize(void* data, SerializedPayload_t* payload) override {
    FastBuffer buffer(reinterpret_cast<char*>(payload->data), payload->max_size);
    Cdr ser(buffer, Cdr::DEFAULT_ENDIAN, Cdr::DDS_CDR);
    payload->encapsulation = ser.endianness() == Cdr::BIG_ENDIANNESS ? CDR_BE : CDR_LE;
    ser.serialize_encapsulation();
    write(ser, *static_cast<T*>(data));
    payload->length = static_cast<uint32_t>(ser.getSerializedDataLength());
    return true;
  }
  bool deserialize(SerializedPayload_t* payload, void* data) override {
    FastBuffer buffer(reinterpret_cast<char*>(payload->data), payload->length);
    Cdr deser(buffer, Cdr::DEFAULT_ENDIAN, Cdr::DDS_CDR);
    try {
      deser.read_encapsulation();
      read(deser, *static_cast<T*>(data));
    } catch (const std::exception& e) {
      std::fprintf(stderr, "fastdds_diffdrive: cannot decode a %s: %s\n", getName(), e.what());
      return false;
    }
    return true;
  }
  std::function<uint32_t()> getSerializedSizeProvider(void*) override {
    return [] { return uint32_t{4 + 1024}; };
  }
  void* createData() override { return new T(); }
  void deleteData(void* data) override { delete static_cast<T*>(data); }
  bool getKey(void*, eprosima::fastrtps::rtps::InstanceHandle_t*, bool) override { return false; }

 private:
  static void write(Cdr& s, const Twist& m) {
    for (double v : m.linear) s << v;
    for (double v : m.angular) s << v;
  }
  static void read(Cdr& s, Twist& m) {
    for (double& v : m.linear) s >> v;
    for (double& v : m.angular) s >> v;
  }
  static void write(Cdr& s, const Odometry& m) {
    s << m.sec << m.nanosec << m.frame_id << m.child_frame_id;
    for (double v : m.pose) s << v;
    for (double v : m.pose_cov) s << v;
    write(s, m.twist);
    for (double v : m.twist_cov) s << v;
  }
  static void read(Cdr& s, Odometry& m) {
    s >> m.sec >> m.nanosec >> m.frame_id >> m.child_frame_id;
    for (double& v : m.pose) s >> v;
    for (double& v : m.pose_cov) s >> v;
    read(s, m.twist);
    for (double& v : m.twist_cov) s >> v;
  }
};

struct Limits {
  double v = 0.22, w = 2.84, acc = 0.5, alpha = 3.0;
};

struct Robot {
  std::string ns;
  double x = 0, y = 0, yaw = 0;     // world frame
  double x0 = 0, y0 = 0, yaw0 = 0;  // start pose (the odom origin with ODOM = start)
  double gain_left = 1, gain_right = 1;
  double v = 0, w = 0;  // current twist
  Twist cmd;
  double cmd_at_s = -1e9;
  long cmds = 0;
  DataReader* reader = nullptr;
  DataWriter* writer = nullptr;
};

double approach(double current, double target, double max_step) {
  return current + std::clamp(target - current, -max_step, max_step);
}

// One integration step: commanded twist limited, wheel gains applied, unicycle integrated.
void step(Robot& r, const Limits& lim, double now_s, double dt, double wheel_base) {
  const bool fresh = now_s - r.cmd_at_s < 0.5;
  const double v_cmd = fresh ? std::clamp(r.cmd.linear[0], -lim.v, lim.v) : 0.0;
  const double w_cmd = fresh ? std::clamp(r.cmd.angular[2], -lim.w, lim.w) : 0.0;
  r.v = approach(r.v, v_cmd, lim.acc * dt);
  r.w = approach(r.w, w_cmd, lim.alpha * dt);
  // A mismatched wheel: each wheel's ground speed scaled by its gain.
  const double left = (r.v - r.w * wheel_base / 2) * r.gain_left;
  const double right = (r.v + r.w * wheel_base / 2) * r.gain_right;
  const double v = (left + right) / 2, w = (right - left) / wheel_base;
  r.x += v * std::cos(r.yaw + w * dt / 2) * dt;
  r.y += v * std::sin(r.yaw + w * dt / 2) * dt;
  r.yaw = std::remainder(r.yaw + w * dt, 2 * M_PI);
}

// The odometry frame: where the published poses are expressed.
struct OdomFrame {
  bool at_start = false;                      // relative to each robot's start pose
  double scale = 1, yaw = 0, tx = 0, ty = 0;  // else: p_world = scale R(yaw) p + t
};

bool parse_odom_frame(const std::string& s, OdomFrame* f) {
  if (s == "world") return true;
  if (s == "start") return f->at_start = true;
  return std::sscanf(s.c_str(), "frame:%lf,%lf,%lf,%lf", &f->scale, &f->yaw, &f->tx, &f->ty) == 4 &&
         f->scale > 0;
}

Odometry odometry(const Robot& r, const OdomFrame& f, double now_s) {
  Odometry m;
  m.sec = static_cast<int32_t>(now_s);
  m.nanosec = static_cast<uint32_t>((now_s - m.sec) * 1e9);
  // p = R(-yaw0) (p_world - p0) / scale, with the origin and heading of the frame.
  const double ox = f.at_start ? r.x0 : f.tx, oy = f.at_start ? r.y0 : f.ty;
  const double oyaw = f.at_start ? r.yaw0 : f.yaw, scale = f.at_start ? 1.0 : f.scale;
  const double dx = r.x - ox, dy = r.y - oy, c = std::cos(oyaw), s = std::sin(oyaw);
  const double x = (c * dx + s * dy) / scale, y = (-s * dx + c * dy) / scale;
  const double yaw = std::remainder(r.yaw - oyaw, 2 * M_PI);
  m.pose = {x, y, 0, 0, 0, std::sin(yaw / 2), std::cos(yaw / 2)};
  m.twist.linear[0] = r.v;
  m.twist.angular[2] = r.w;
  return m;
}

bool parse_robot(const char* arg, Robot* r) {
  const std::string s(arg);
  const auto colon = s.find(':');
  if (colon == std::string::npos) return false;
  r->ns = s.substr(0, colon);
  double g[2] = {1, 1};
  const int n = std::sscanf(s.c_str() + colon + 1, "%lf,%lf,%lf,%lf,%lf", &r->x, &r->y, &r->yaw,
                            &g[0], &g[1]);
  if (n != 3 && n != 5) return false;
  r->gain_left = g[0];
  r->gain_right = g[1];
  r->x0 = r->x, r->y0 = r->y, r->yaw0 = r->yaw;
  return true;
}

void open_endpoints(DomainParticipant* p, Subscriber* sub, Publisher* pub, Robot& r) {
  Topic* cmd = p->create_topic("rt" + r.ns + "/cmd_vel", "geometry_msgs::msg::dds_::Twist_",
                               TOPIC_QOS_DEFAULT);
  Topic* odom =
      p->create_topic("rt" + r.ns + "/odom", "nav_msgs::msg::dds_::Odometry_", TOPIC_QOS_DEFAULT);
  DataReaderQos rq = DATAREADER_QOS_DEFAULT;
  rq.reliability().kind = RELIABLE_RELIABILITY_QOS;
  rq.history().kind = KEEP_LAST_HISTORY_QOS;
  rq.history().depth = 10;
  r.reader = sub->create_datareader(cmd, rq);
  DataWriterQos wq = DATAWRITER_QOS_DEFAULT;
  wq.reliability().kind = BEST_EFFORT_RELIABILITY_QOS;
  wq.history().kind = KEEP_LAST_HISTORY_QOS;
  wq.history().depth = 1;
  r.writer = pub->create_datawriter(odom, wq);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 9) {
    std::fprintf(stderr,
                 "usage: fastdds_diffdrive DOMAIN TIMEOUT_S MAX_V MAX_W MAX_ACC MAX_ALPHA "
                 "world|start|frame:S,YAW,TX,TY NS:X,Y,YAW[,GL,GR]...\n");
    return 2;
  }
  const int domain = std::atoi(argv[1]);
  const double timeout_s = std::atof(argv[2]);
  const Limits lim{std::atof(argv[3]), std::atof(argv[4]), std::atof(argv[5]), std::atof(argv[6])};
  OdomFrame frame;
  if (!parse_odom_frame(argv[7], &frame)) {
    std::fprintf(stderr, "fastdds_diffdrive: bad ODOM '%s' (world, start, frame:S,YAW,TX,TY)\n",
                 argv[7]);
    return 2;
  }
  std::vector<Robot> robots(static_cast<std::size_t>(argc - 8));
  for (int i = 8; i < argc; ++i) {
    if (!parse_robot(argv[i], &robots[static_cast<std::size_t>(i - 8)])) {
      std::fprintf(stderr, "fastdds_diffdrive: bad robot '%s' (NS:X,Y,YAW[,GL,GR])\n", argv[i]);
      return 2;
    }
  }
  signal(SIGTERM, on_signal);
  signal(SIGINT, on_signal);
  DomainParticipant* participant =
      smart::interop::make_loopback_participant(domain, "fastdds_diffdrive");
  if (participant == nullptr) return 2;
  TypeSupport twist(new Type<Twist>("geometry_msgs::msg::dds_::Twist_"));
  TypeSupport odom(new Type<Odometry>("nav_msgs::msg::dds_::Odometry_"));
  twist.register_type(participant);
  odom.register_type(participant);
  Subscriber* sub = participant->create_subscriber(SUBSCRIBER_QOS_DEFAULT);
  Publisher* pub = participant->create_publisher(PUBLISHER_QOS_DEFAULT);
  for (auto& r : robots) open_endpoints(participant, sub, pub, r);

  constexpr double kDt = 0.01, kWheelBase = 0.16;
  const auto start = std::chrono::steady_clock::now();
  auto next = start;
  for (long tick = 0; !g_stop; ++tick) {
    const double now_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (now_s > timeout_s) break;
    for (auto& r : robots) {
      Twist m;
      SampleInfo info;
      while (r.reader->take_next_sample(&m, &info) == ReturnCode_t::RETCODE_OK) {
        if (!info.valid_data) continue;
        r.cmd = m;
        r.cmd_at_s = now_s;
        ++r.cmds;
      }
      step(r, lim, now_s, kDt, kWheelBase);
      if (tick % 2 == 0) {
        Odometry o = odometry(r, frame, now_s);
        r.writer->write(&o);
      }
    }
    next += std::chrono::milliseconds(10);
    std::this_thread::sleep_until(next);
  }
  for (const auto& r : robots) {
    std::printf("robot %s %.4f %.4f %.4f cmds %ld last %.4f %.4f\n", r.ns.c_str(), r.x, r.y, r.yaw,
                r.cmds, r.cmd.linear[0], r.cmd.angular[2]);
  }
  std::fflush(stdout);
  participant->delete_contained_entities();
  DomainParticipantFactory::get_instance()->delete_participant(participant);
  return 0;
}
