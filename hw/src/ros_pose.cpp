#include "smart/hw/ros_pose.hpp"

#include <cmath>

#include "smart/agent/kinematics.hpp"

namespace smart::hw {

RosPoseSource::RosPoseSource(const dds::Participant& p, const std::string& ros_topic,
                             ViconTransform transform, double max_age_s,
                             std::function<double()> now_s)
    : transform_(transform),
      max_age_s_(max_age_s),
      now_s_(std::move(now_s)),
      topic_(p, dds::ros_topic(ros_topic)) {
  dds::TopicQos q;
  q.reliability = dds::Reliability::kBestEffort;
  q.durability = dds::Durability::kVolatile;
  q.depth = 1;
  reader_ = std::make_unique<dds::Reader<geometry_msgs_msg_dds__PoseStamped_>>(
      p, topic_, q.to_dds(), [this] { on_data(); });
}

void RosPoseSource::on_data() {
  reader_->take_each([&](const geometry_msgs_msg_dds__PoseStamped_& m) {
    const auto& o = m.pose.orientation;
    const double yaw =
        std::atan2(2.0 * (o.w * o.z + o.x * o.y), 1.0 - 2.0 * (o.y * o.y + o.z * o.z));
    const double c = std::cos(transform_.yaw_offset_rad), s = std::sin(transform_.yaw_offset_rad);
    const double X = m.pose.position.x * transform_.scale, Y = m.pose.position.y * transform_.scale;
    agent::PoseSample sample;
    sample.pose = {c * X - s * Y + transform_.x_offset_m, s * X + c * Y + transform_.y_offset_m,
                   agent::wrap_angle(yaw + transform_.yaw_offset_rad)};
    sample.stamp_s = now_s_();
    sample.valid = std::isfinite(sample.pose.x_m) && std::isfinite(sample.pose.y_m) &&
                   std::isfinite(sample.pose.yaw_rad);
    std::lock_guard<std::mutex> lock(mutex_);
    if (sample.valid) latest_ = sample;
    ++samples_;
  });
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
