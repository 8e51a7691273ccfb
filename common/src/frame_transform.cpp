#include "smart/geometry/frame_transform.hpp"

#include <Eigen/SVD>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "smart/config/yaml_checks.hpp"

namespace smart::geometry {

double wrap_rad(double a) {
  a = std::remainder(a, 2.0 * std::numbers::pi);
  return a <= -std::numbers::pi ? a + 2.0 * std::numbers::pi : a;
}

double FrameTransform::apply_yaw(double yaw_source_rad) const {
  return wrap_rad(yaw_source_rad + yaw_rad);
}

FrameTransform FrameTransform::inverse() const {
  FrameTransform inv;
  inv.scale = 1.0 / scale;
  inv.yaw_rad = wrap_rad(-yaw_rad);
  inv.translation_m = -inv.scale * (Eigen::Rotation2Dd(inv.yaw_rad) * translation_m);
  return inv;
}

double yaw_of(const Eigen::Quaterniond& q) {
  // The body x axis in the world; its heading on the xy plane (defined unless it points up).
  const Eigen::Vector3d x = q.normalized() * Eigen::Vector3d::UnitX();
  return std::atan2(x.y(), x.x());
}

Eigen::Quaterniond quaternion_of_yaw(double yaw_rad) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()));
}

namespace {

Eigen::Matrix2Xd columns(const std::vector<Eigen::Vector2d>& points, const char* which) {
  Eigen::Matrix2Xd m(2, static_cast<Eigen::Index>(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite()) {
      throw std::invalid_argument(std::string(which) + " point " + std::to_string(i + 1) +
                                  " is not a finite number");
    }
    m.col(static_cast<Eigen::Index>(i)) = points[i];
  }
  return m;
}

// Points spread along one line only leave the rotation undetermined.
void require_spread(const Eigen::Matrix2Xd& source) {
  const Eigen::Matrix2Xd centred = source.colwise() - source.rowwise().mean();
  const Eigen::Vector2d sv =
      Eigen::JacobiSVD<Eigen::Matrix2d>(centred * centred.transpose()).singularValues();
  if (!(sv(0) > 0) || sv(1) < 1e-9 * sv(0)) {
    throw std::invalid_argument(
        "the source points lie on one line (or on one point): place the robots or the wand on "
        "at least three cells that are not in a row");
  }
}

}  // namespace

SimilarityFit fit_similarity(const std::vector<Eigen::Vector2d>& source,
                             const std::vector<Eigen::Vector2d>& world_m) {
  if (source.size() != world_m.size()) {
    throw std::invalid_argument("fit_similarity: " + std::to_string(source.size()) +
                                " source points but " + std::to_string(world_m.size()) +
                                " world points");
  }
  if (source.size() < 3) {
    throw std::invalid_argument("a frame fit needs at least 3 point pairs, got " +
                                std::to_string(source.size()));
  }
  const Eigen::Matrix2Xd src = columns(source, "source"), dst = columns(world_m, "world");
  require_spread(src);
  // Dynamic sizes: with fixed 2xN matrices GCC 12 reports a false -Wstringop-overread inside
  // Eigen 3.4's umeyama (the vectorised store of the 2-row translation into a 3x3 block).
  const Eigen::MatrixXd m = Eigen::umeyama(Eigen::MatrixXd(src), Eigen::MatrixXd(dst), true);
  SimilarityFit fit;
  const Eigen::Matrix2d sr = m.topLeftCorner(2, 2);
  fit.transform.scale = std::sqrt(sr.determinant());
  fit.transform.yaw_rad = std::atan2(sr(1, 0), sr(0, 0));
  fit.transform.translation_m = m.topRightCorner(2, 1);
  double sum_sq = 0;
  for (std::size_t i = 0; i < source.size(); ++i) {
    const double r = (fit.transform.apply(source[i]) - world_m[i]).norm();
    fit.residuals_m.push_back(r);
    sum_sq += r * r;
    fit.max_m = std::max(fit.max_m, r);
  }
  fit.rms_m = std::sqrt(sum_sq / static_cast<double>(source.size()));
  return fit;
}

FrameTransform parse_frame_transform(const std::string& yaml_text, const std::string& source) {
  const YAML::Node root = config::load(yaml_text, source);
  config::require_map(source, root, "the transform file");
  config::reject_unknown(source, root, "the transform file",
                         {"scale", "yaw_rad", "translation_m", "fit"});
  FrameTransform t;
  for (const char* key : {"scale", "yaw_rad", "translation_m"}) {
    if (!root[key]) {
      config::fail(source, root,
                   std::string("missing '") + key +
                       "'; a transform file has scale, yaw_rad and translation_m [x, y] "
                       "(write one with `smart calibrate`)");
    }
  }
  t.scale = config::number(source, root["scale"], "scale", 1e-9, 1e9);
  t.yaw_rad = config::number(source, root["yaw_rad"], "yaw_rad", -10.0, 10.0);
  const YAML::Node tr = root["translation_m"];
  if (!tr.IsSequence() || tr.size() != 2) {
    config::fail(source, tr, "'translation_m' must be [x, y] in metres");
  }
  t.translation_m = {config::number(source, tr[0], "translation_m[0]", -1e6, 1e6),
                     config::number(source, tr[1], "translation_m[1]", -1e6, 1e6)};
  return t;
}

FrameTransform load_frame_transform(const std::string& path) {
  std::ifstream in(path);
  if (!in) {
    throw config::ConfigError(path +
                              ": cannot read the transform file; write it with "
                              "`smart calibrate` or check the path");
  }
  std::stringstream text;
  text << in.rdbuf();
  return parse_frame_transform(text.str(), path);
}

std::string frame_transform_yaml(const FrameTransform& t, const SimilarityFit* fit,
                                 const std::vector<Eigen::Vector2d>* source,
                                 const std::vector<Eigen::Vector2d>* world_m) {
  std::ostringstream out;
  out << std::setprecision(12);
  out << "# Pose source frame -> grid world frame: p_world = scale * R(yaw_rad) * p_source + "
         "translation_m\n";
  out << "scale: " << t.scale << "\nyaw_rad: " << t.yaw_rad << "\ntranslation_m: ["
      << t.translation_m.x() << ", " << t.translation_m.y() << "]\n";
  if (fit == nullptr) return out.str();
  out << "fit:\n  rms_m: " << fit->rms_m << "\n  max_m: " << fit->max_m << "\n  points:\n";
  for (std::size_t i = 0; i < fit->residuals_m.size(); ++i) {
    out << "    - {";
    if (source != nullptr && world_m != nullptr) {
      out << "source: [" << (*source)[i].x() << ", " << (*source)[i].y() << "], world_m: ["
          << (*world_m)[i].x() << ", " << (*world_m)[i].y() << "], ";
    }
    out << "residual_m: " << fit->residuals_m[i] << "}\n";
  }
  return out.str();
}

}  // namespace smart::geometry
