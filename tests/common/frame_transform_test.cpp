#include "smart/geometry/frame_transform.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <numbers>

#include "smart/config/yaml_checks.hpp"

namespace smart::geometry {
namespace {

using ::testing::HasSubstr;
constexpr double kPi = std::numbers::pi;

TEST(FrameTransform, MapsMillimetresRotatedAndShiftedIntoTheWorld) {
  FrameTransform t{0.001, kPi / 2, {1.0, 2.0}};
  const Eigen::Vector2d p = t.apply({1000.0, 0.0});  // 1 m along the source x = world +y
  EXPECT_NEAR(p.x(), 1.0, 1e-12);
  EXPECT_NEAR(p.y(), 3.0, 1e-12);
  EXPECT_NEAR(t.apply_yaw(kPi), -kPi / 2, 1e-12);
  const Eigen::Vector2d back = t.inverse().apply(p);
  EXPECT_NEAR(back.x(), 1000.0, 1e-9);
  EXPECT_NEAR(back.y(), 0.0, 1e-9);
}

TEST(FrameTransform, YawOfAQuaternionIgnoresRollAndPitch) {
  EXPECT_NEAR(yaw_of(quaternion_of_yaw(0.7)), 0.7, 1e-12);
  const Eigen::Quaterniond tilted = quaternion_of_yaw(-2.0) * Eigen::Quaterniond(Eigen::AngleAxisd(
                                                                  0.2, Eigen::Vector3d::UnitX()));
  EXPECT_NEAR(yaw_of(tilted), -2.0, 1e-12);  // a roll keeps the body x axis where it points
  EXPECT_NEAR(wrap_rad(3 * kPi), kPi, 1e-12);
}

TEST(FitSimilarity, RecoversAKnownMountingFromNoisyPoints) {
  const FrameTransform truth{0.001, 0.3, {-0.5, 1.25}};
  const std::vector<Eigen::Vector2d> world{{0.15, 0.15}, {1.65, 0.15}, {1.65, 0.75}, {0.45, 1.05}};
  std::vector<Eigen::Vector2d> mocap;
  const double noise_mm[][2] = {{0.8, -0.4}, {-0.6, 0.2}, {0.1, 0.9}, {-0.3, -0.7}};
  for (std::size_t i = 0; i < world.size(); ++i) {
    mocap.push_back(truth.inverse().apply(world[i]) +
                    Eigen::Vector2d(noise_mm[i][0], noise_mm[i][1]));
  }
  const auto fit = fit_similarity(mocap, world);
  EXPECT_NEAR(fit.transform.scale, 0.001, 1e-6);
  EXPECT_NEAR(fit.transform.yaw_rad, 0.3, 2e-3);
  EXPECT_NEAR(fit.transform.translation_m.x(), -0.5, 2e-3);
  EXPECT_NEAR(fit.transform.translation_m.y(), 1.25, 2e-3);
  ASSERT_EQ(fit.residuals_m.size(), 4u);
  EXPECT_GT(fit.max_m, 1e-5);  // the noise shows
  EXPECT_LT(fit.max_m, 2e-3);
  EXPECT_LE(fit.rms_m, fit.max_m);
}

TEST(FitSimilarity, RefusesTooFewOrCollinearPoints) {
  const std::vector<Eigen::Vector2d> two{{0, 0}, {1, 0}};
  EXPECT_THROW(fit_similarity(two, two), std::invalid_argument);
  const std::vector<Eigen::Vector2d> row{{0, 0}, {1, 0}, {2, 0}};
  try {
    fit_similarity(row, row);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("one line"));
  }
}

TEST(TransformFile, RoundTripsWithItsFitAndNamesBadFields) {
  const FrameTransform t{0.001, -0.25, {0.3, -1.5}};
  const std::vector<Eigen::Vector2d> a{{0, 0}, {1000, 0}, {0, 1000}};
  std::vector<Eigen::Vector2d> b;
  for (const auto& p : a) b.push_back(t.apply(p));
  const auto fit = fit_similarity(a, b);
  const auto text = frame_transform_yaml(fit.transform, &fit, &a, &b);
  const auto back = parse_frame_transform(text, "t.yaml");
  EXPECT_NEAR(back.scale, 0.001, 1e-12);
  EXPECT_NEAR(back.yaw_rad, -0.25, 1e-9);
  EXPECT_NEAR(back.translation_m.y(), -1.5, 1e-9);
  try {
    parse_frame_transform("scale: 1\nyaw_rad: 0\ntranslation_m: [1]\n", "t.yaml");
    FAIL();
  } catch (const config::ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("t.yaml:3"));
    EXPECT_THAT(e.what(), HasSubstr("[x, y]"));
  }
  EXPECT_THROW(parse_frame_transform("scale: 0\nyaw_rad: 0\ntranslation_m: [0, 0]\n", "t"),
               config::ConfigError);
  EXPECT_THROW(parse_frame_transform("yaw_rad: 0\ntranslation_m: [0, 0]\n", "t"),
               config::ConfigError);
  EXPECT_THROW(load_frame_transform("/nonexistent/t.yaml"), config::ConfigError);
}

}  // namespace
}  // namespace smart::geometry
