#include "smart/agent/robot_model.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "smart/config/yaml_checks.hpp"

namespace smart::agent {
namespace {

using ::testing::HasSubstr;

TEST(RobotModel, ShippedModelsCarryTheDocumentedLimits) {
  const auto foot = load_robot_model(std::string(SMART_SOURCE_DIR) + "/config/robots/footbot.yaml");
  EXPECT_EQ(foot.name, "footbot");
  EXPECT_DOUBLE_EQ(foot.max_speed_mps, 5.0);
  EXPECT_DOUBLE_EQ(foot.max_accel_mps2, 0.4);
  EXPECT_NEAR(foot.max_turn_rate_radps, 30.0 * M_PI / 180.0, 1e-4);
  const auto jet = load_robot_model(std::string(SMART_SOURCE_DIR) + "/config/robots/jetbot.yaml");
  EXPECT_DOUBLE_EQ(jet.wheel_base_m, 0.1025);
  EXPECT_DOUBLE_EQ(jet.max_turn_rate_radps, 1.7);
}

std::string error_of(const std::string& yaml) {
  try {
    parse_robot_model(yaml, "r.yaml");
  } catch (const config::ConfigError& e) {
    return e.what();
  }
  return "(no error)";
}

const std::string kValid =
    "name: x\nradius_m: 0.1\nmass_kg: 1\nwheel_base_m: 0.1\nwheel_radius_m: 0.02\n"
    "max_speed_mps: 1\nmax_accel_mps2: 1\nmax_decel_mps2: 1\nmax_turn_rate_radps: 1\n"
    "max_angular_accel_radps2: 1\n";

TEST(RobotModelErrors, MissingUnknownAndOutOfRange) {
  EXPECT_EQ(error_of(kValid), "(no error)");
  EXPECT_THAT(error_of("name: x\n"), HasSubstr("missing key"));
  EXPECT_THAT(error_of(kValid + "max_sped: 2\n"), HasSubstr("r.yaml:11:1: unknown key 'max_sped'"));
  EXPECT_THAT(error_of(kValid + "controller:\n  heading_kp: -1\n"),
              HasSubstr("r.yaml:12:15: 'controller.heading_kp' is -1 but must be from 0"));
  std::string neg = kValid;
  neg.replace(neg.find("max_speed_mps: 1"), 16, "max_speed_mps: -1");
  EXPECT_THAT(error_of(neg), HasSubstr("'max_speed_mps' is -1"));
  EXPECT_THROW(load_robot_model("/nonexistent/robot.yaml"), config::ConfigError);
}

TEST(RobotModel, AnUncertaintySectionIsReadAndCheckedLikeTheRest) {
  const auto m = parse_robot_model(
      kValid + "uncertainty:\n  stall_probability: 0.05\n  stall_s: 2\n  seed: 7\n", "r.yaml");
  EXPECT_DOUBLE_EQ(m.uncertainty.stall_probability, 0.05);
  EXPECT_DOUBLE_EQ(m.uncertainty.stall_s, 2.0);
  EXPECT_EQ(m.uncertainty.seed, 7u);
  EXPECT_EQ(m.uncertainty.speed_sigma, 0.0);
  EXPECT_FALSE(parse_robot_model(kValid, "r.yaml").uncertainty.any());
  EXPECT_THAT(error_of(kValid + "uncertainty:\n  stall_probability: 2\n"),
              HasSubstr("'uncertainty.stall_probability' is 2 but must be from 0"));
  EXPECT_THAT(error_of(kValid + "uncertainty:\n  stalls: 1\n"), HasSubstr("unknown key 'stalls'"));
}

}  // namespace
}  // namespace smart::agent
