#include "smart/hw/ros_pose.hpp"

#include <cmath>

namespace smart::hw {

RosPoseSource::RosPoseSource(const dds::Participant& p, const std::string& ros_topic,
                             geometry::FrameTransform transform, double max_age_s,
                             std::function<double()> now_s, Message message)
    : transform_(std::move(transform)), max_age_s_(max_age_s), now_s_(std::move(now_s)) {
  const auto qos = dds::ros_sensor_qos().to_dds();
  if (message == Message::kOdometry) {
    odom_topic_.emplace(p, dds::ros_topic(ros_topic));
    odom_reader_ =
        std::make_unique<dds::Reader<nav_msgs_msg_dds__Odometry_>>(p, *odom_topic_, qos, [this] {
          if (!ready_) return;  // a sample during construction: the next one is taken
          odom_reader_->take_each(
              [&](const nav_msgs_msg_dds__Odometry_& m) { accept(m.pose.pose); });
        });
  } else {
    pose_topic_.emplace(p, dds::ros_topic(ros_topic));
    pose_reader_ = std::make_unique<dds::Reader<geometry_msgs_msg_dds__PoseStamped_>>(
        p, *pose_topic_, qos, [this] {
          if (!ready_) return;
          pose_reader_->take_each(
              [&](const geometry_msgs_msg_dds__PoseStamped_& m) { accept(m.pose); });
        });
  }
  ready_ = true;
}

void RosPoseSource::accept(const geometry_msgs_msg_dds__Pose_& m) {
  const auto& o = m.orientation;
  const Eigen::Vector2d xy = transform_.apply({m.position.x, m.position.y});
  agent::PoseSample sample;
  sample.pose = {xy.x(), xy.y(),
                 transform_.apply_yaw(geometry::yaw_of(Eigen::Quaterniond(o.w, o.x, o.y, o.z)))};
  sample.stamp_s = now_s_();
  // A zero quaternion (an uninitialised message) has no heading.
  const double norm = std::hypot(o.w, o.x, o.y) + std::abs(o.z);
  sample.valid = std::isfinite(sample.pose.x_m) && std::isfinite(sample.pose.y_m) &&
                 std::isfinite(sample.pose.yaw_rad) && norm > 1e-6;
  std::lock_guard<std::mutex> lock(mutex_);
  if (sample.valid) latest_ = sample;
  ++samples_;
}

agent::PoseSample RosPoseSource::read() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!latest_) return {};
  auto p = *latest_;
  if (now_s_() - p.stamp_s > max_age_s_) p.valid = false;
  return p;
}

uint64_t RosPoseSource::samples() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return samples_;
}

}  // namespace smart::hw
