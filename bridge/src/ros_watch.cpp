#include "smart/bridge/ros_watch.hpp"

#include <spdlog/spdlog.h>

#include <cmath>
#include <optional>

#include "smart/dds/participant.hpp"
#include "smart/dds/reader.hpp"
#include "smart/dds/topics.hpp"
#include "smart/dds/waitset.hpp"
#include "smart/record/cdr.hpp"
#include "smart/record/schemas.hpp"

namespace smart::bridge {

namespace {

struct ViewTopic {
  ChannelId id;
  std::string type;
  std::string_view name;
};
std::vector<ViewTopic> view_topics() {
  using record::ros_type_name;
  return {{kMapChannel, ros_type_name<nav_msgs_msg_dds__OccupancyGrid_>(), dds::kRosMapTopic},
          {kTfChannel, ros_type_name<tf2_msgs_msg_dds__TFMessage_>(), dds::kRosTfTopic},
          {kPosesChannel, ros_type_name<geometry_msgs_msg_dds__PoseArray_>(), dds::kRosPosesTopic},
          {kMarkersChannel, ros_type_name<visualization_msgs_msg_dds__MarkerArray_>(),
           dds::kRosMarkersTopic}};
}

uint64_t ns_of(const builtin_interfaces_msg_dds__Time_& t) {
  return t.sec < 0 ? 0 : static_cast<uint64_t>(t.sec) * 1000000000ULL + t.nanosec;
}

std::string topic_name(const std::string& ns, std::string_view name) {
  return dds::ros_topic(dds::ros_view_topic(ns, std::string(name)));
}

}  // namespace

std::vector<Channel> ros_view_channels(const std::string& ros_namespace,
                                       const std::vector<uint32_t>& pose_robots) {
  dds::check_ros_namespace(ros_namespace);
  std::vector<Channel> out;
  for (const auto& t : view_topics()) {
    out.push_back({t.id, dds::ros_view_topic(ros_namespace, std::string(t.name)), t.type,
                   record::ros2msg_definition(t.type)});
  }
  uint32_t id = kFirstRobotChannel;
  const auto pose_type = record::ros_type_name<geometry_msgs_msg_dds__PoseStamped_>();
  for (const uint32_t r : pose_robots) {
    out.push_back({id++, dds::ros_view_topic(ros_namespace, dds::ros_robot_pose_topic(r)),
                   pose_type, record::ros2msg_definition(pose_type)});
  }
  return out;
}

bool latched(uint32_t channel) { return channel == kMapChannel || channel == kMarkersChannel; }

// Readers only: nothing here writes to the domain.
struct RosWatch::Pump {
  dds::Domain domain;
  dds::Participant participant;
  dds::Topic<nav_msgs_msg_dds__OccupancyGrid_> map_topic;
  dds::Topic<tf2_msgs_msg_dds__TFMessage_> tf_topic;
  dds::Topic<geometry_msgs_msg_dds__PoseArray_> poses_topic;
  dds::Topic<visualization_msgs_msg_dds__MarkerArray_> markers_topic;
  dds::Reader<nav_msgs_msg_dds__OccupancyGrid_> map;
  dds::Reader<tf2_msgs_msg_dds__TFMessage_> tf;
  dds::Reader<geometry_msgs_msg_dds__PoseArray_> poses;
  dds::Reader<visualization_msgs_msg_dds__MarkerArray_> markers;
  dds::WaitSet waitset;
  // Per robot, once the fleet's size is known: plans, then the chosen robots' poses.
  std::vector<dds::Topic<nav_msgs_msg_dds__Path_>> plan_topics;
  std::vector<dds::Reader<nav_msgs_msg_dds__Path_>> plans;
  std::vector<dds::Topic<geometry_msgs_msg_dds__PoseStamped_>> pose_topics;
  std::vector<dds::Reader<geometry_msgs_msg_dds__PoseStamped_>> poses_of;
  bool robot_topics = false;

  explicit Pump(const RosWatchOptions& o)
      : domain(o.domain, o.config),
        participant(domain),
        map_topic(participant, topic_name(o.ros_namespace, dds::kRosMapTopic)),
        tf_topic(participant, topic_name(o.ros_namespace, dds::kRosTfTopic)),
        poses_topic(participant, topic_name(o.ros_namespace, dds::kRosPosesTopic)),
        markers_topic(participant, topic_name(o.ros_namespace, dds::kRosMarkersTopic)),
        map(participant, map_topic, dds::ros_latched_qos().to_dds()),
        tf(participant, tf_topic, dds::ros_sensor_qos().to_dds()),
        poses(participant, poses_topic, dds::ros_sensor_qos().to_dds()),
        markers(participant, markers_topic, dds::ros_latched_qos().to_dds()),
        waitset(participant) {
    waitset.attach_status(map.handle(), DDS_DATA_AVAILABLE_STATUS, kMapChannel);
    waitset.attach_status(tf.handle(), DDS_DATA_AVAILABLE_STATUS, kTfChannel);
    waitset.attach_status(poses.handle(), DDS_DATA_AVAILABLE_STATUS, kPosesChannel);
    waitset.attach_status(markers.handle(), DDS_DATA_AVAILABLE_STATUS, kMarkersChannel);
    for (const uint32_t r : o.pose_robots) {
      pose_topics.emplace_back(participant,
                               topic_name(o.ros_namespace, dds::ros_robot_pose_topic(r)));
      poses_of.emplace_back(participant, pose_topics.back(), dds::ros_sensor_qos().to_dds());
    }
  }
};

RosWatch::RosWatch(const RosWatchOptions& options, Sink sink, ChannelsSink on_channels)
    : options_(options),
      pump_((dds::check_ros_namespace(options.ros_namespace), std::make_unique<Pump>(options))),
      sink_(std::move(sink)),
      on_channels_(std::move(on_channels)),
      thread_([this] { loop(); }) {}

RosWatch::~RosWatch() {
  stop_ = true;
  thread_.join();
}

void RosWatch::loop() {
  auto drop = [this](const char* what) {
    if (dropped_++ == 0) spdlog::warn("bridge: dropped a {} sample too large for a fleet", what);
  };
  while (!stop_.load()) {
    pump_->waitset.wait(std::chrono::milliseconds(100));
    pump_->map.take_each([&](const nav_msgs_msg_dds__OccupancyGrid_& m) {
      sink_(kMapChannel, ns_of(m.header.stamp), record::cdr_bytes(m));
    });
    pump_->tf.take_each([&](const tf2_msgs_msg_dds__TFMessage_& m) {
      if (m.transforms._length > kMaxRobots) return drop("tf");
      const uint64_t t = m.transforms._length ? ns_of(m.transforms._buffer[0].header.stamp) : 0;
      sink_(kTfChannel, t, record::cdr_bytes(m));
    });
    std::optional<uint32_t> fleet;
    pump_->poses.take_each([&](const geometry_msgs_msg_dds__PoseArray_& m) {
      if (m.poses._length > kMaxRobots) return drop("PoseArray");
      fleet = m.poses._length;
      sink_(kPosesChannel, ns_of(m.header.stamp), record::cdr_bytes(m));
    });
    if (fleet && !pump_->robot_topics) add_robot_topics(*fleet);
    take_robot_topics();
    pump_->markers.take_each([&](const visualization_msgs_msg_dds__MarkerArray_& m) {
      if (m.markers._length > 4 * kMaxRobots) return drop("MarkerArray");
      const uint64_t t = m.markers._length ? ns_of(m.markers._buffer[0].header.stamp) : 0;
      sink_(kMarkersChannel, t, record::cdr_bytes(m));
    });
  }
}

void RosWatch::add_robot_topics(uint32_t robots) {
  auto& p = *pump_;
  p.robot_topics = true;
  const auto& ns = options_.ros_namespace;
  std::vector<Channel> plans;
  auto id = static_cast<uint32_t>(kFirstRobotChannel + options_.pose_robots.size());
  if (robots <= kMaxPlanTopics) {
    const auto type = record::ros_type_name<nav_msgs_msg_dds__Path_>();
    const auto schema = record::ros2msg_definition(type);
    for (uint32_t r = 0; r < robots; ++r) {
      p.plan_topics.emplace_back(p.participant, topic_name(ns, dds::ros_robot_plan_topic(r)));
      p.plans.emplace_back(p.participant, p.plan_topics.back(), dds::ros_latched_qos().to_dds());
      plans.push_back({id++, dds::ros_view_topic(ns, dds::ros_robot_plan_topic(r)), type, schema});
    }
  } else {
    spdlog::info("bridge: {} robots: their plan topics are not served (at most {})", robots,
                 kMaxPlanTopics);
  }
  if (!plans.empty()) on_channels_(std::move(plans), true);
}

// Plans and chosen poses are polled with the waitset's period (their readers are not attached:
// a fleet's thousand plan readers would make every wait scan them).
void RosWatch::take_robot_topics() {
  auto& p = *pump_;
  uint32_t id = kFirstRobotChannel;
  for (auto& reader : p.poses_of) {
    const uint32_t channel = id++;
    reader.take_each([&](const geometry_msgs_msg_dds__PoseStamped_& m) {
      sink_(channel, ns_of(m.header.stamp), record::cdr_bytes(m));
    });
  }
  for (auto& reader : p.plans) {
    const uint32_t channel = id++;
    reader.take_each([&](const nav_msgs_msg_dds__Path_& m) {
      if (m.poses._length > 1000000) return;
      sink_(channel, ns_of(m.header.stamp), record::cdr_bytes(m));
    });
  }
}

}  // namespace smart::bridge
