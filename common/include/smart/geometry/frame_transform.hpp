// Contract: pose geometry on Eigen, pure (no I/O but the transform file's text).
// - FrameTransform: the similarity that maps a pose source's frame (a mocap system, a robot's
//   odometry frame) into the grid's world frame (MovingAI x = column, y = rows counted upwards,
//   metres; docs/architecture.md): p_world = scale * R(yaw) * p_source + translation. Headings
//   turn by yaw; scale converts the source's unit (Vicon: mm, so 0.001).
// - yaw_of(): heading of a body whose orientation is a unit quaternion (ROS poses, odometry):
//   the angle of the body's x axis projected on the world's xy plane, robust to roll and pitch.
// - fit_similarity(): the least-squares similarity from point pairs, Umeyama's method
//   (S. Umeyama, "Least-squares estimation of transformation parameters between two point
//   patterns", IEEE PAMI 13(4), 1991; Eigen::umeyama), with each pair's residual.
// - The transform file (YAML, written by `smart calibrate`, read by `smart agent
//   --pose-transform`): keys scale, yaw_rad, translation_m [x, y]; a `fit:` section with
//   residuals may follow and is kept for the reader. Errors are config::ConfigError naming
//   file:line:column and the accepted range.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace smart::geometry {

struct FrameTransform {
  double scale = 1.0;
  double yaw_rad = 0.0;
  Eigen::Vector2d translation_m = Eigen::Vector2d::Zero();

  Eigen::Vector2d apply(const Eigen::Vector2d& p_source) const {
    return scale * (Eigen::Rotation2Dd(yaw_rad) * p_source) + translation_m;
  }
  // A heading in the source frame, in the world frame, wrapped to (-pi, pi].
  double apply_yaw(double yaw_source_rad) const;
  // The transform whose apply() undoes this one's.
  FrameTransform inverse() const;
  bool operator==(const FrameTransform&) const = default;
};

// (-pi, pi]
double wrap_rad(double a);
double yaw_of(const Eigen::Quaterniond& q);
// The unit quaternion of a heading about +z (for ROS messages).
Eigen::Quaterniond quaternion_of_yaw(double yaw_rad);

struct SimilarityFit {
  FrameTransform transform;
  std::vector<double> residuals_m;  // |apply(source[i]) - world[i]| per pair, metres
  double rms_m = 0;
  double max_m = 0;
};
// Throws std::invalid_argument for fewer than 3 pairs, unequal sizes, non-finite points or
// collinear source points (no unique rotation).
SimilarityFit fit_similarity(const std::vector<Eigen::Vector2d>& source,
                             const std::vector<Eigen::Vector2d>& world_m);

FrameTransform parse_frame_transform(const std::string& yaml_text, const std::string& source);
FrameTransform load_frame_transform(const std::string& path);
// The file's text; with `fit`, its residuals and the point pairs are written below the transform.
std::string frame_transform_yaml(const FrameTransform& t, const SimilarityFit* fit = nullptr,
                                 const std::vector<Eigen::Vector2d>* source = nullptr,
                                 const std::vector<Eigen::Vector2d>* world_m = nullptr);

}  // namespace smart::geometry
