#include "smart/agent/robot_model.hpp"

#include <functional>
#include <map>

#include "smart/config/yaml_checks.hpp"

namespace smart::agent {

namespace {

using config::ConfigError;

struct Field {
  double min, max;
  std::function<double&(RobotModel&)> ref;
  bool required;
};

}  // namespace

namespace {
// The `uncertainty:` section: every key optional, each within its range.
void read_uncertainty(const std::string& source, const YAML::Node& u, Uncertainty& out) {
  config::require_map(source, u, "uncertainty");
  config::reject_unknown(
      source, u, "uncertainty",
      {"stall_probability", "stall_s", "speed_sigma", "slip_sigma", "seed", "delay_probability",
       "delay_rate_hz", "delay_min_s", "delay_max_s", "delay_mean_ratio", "delay_std_ratio"});
  const auto read = [&](const char* key, double lo, double hi, double& v) {
    if (u[key]) v = config::number(source, u[key], std::string("uncertainty.") + key, lo, hi);
  };
  read("stall_probability", 0.0, 1.0, out.stall_probability);
  read("stall_s", 0.0, 3600.0, out.stall_s);
  read("speed_sigma", 0.0, 1.0, out.speed_sigma);
  read("slip_sigma", 0.0, 0.5, out.slip_sigma);
  read("delay_probability", 0.0, 1.0, out.delay_probability);
  read("delay_rate_hz", 0.0, 10.0, out.delay_rate_hz);
  read("delay_min_s", 0.0, 3600.0, out.delay_min_s);
  read("delay_max_s", 0.0, 3600.0, out.delay_max_s);
  read("delay_mean_ratio", 0.0, 1.0, out.delay_mean_ratio);
  read("delay_std_ratio", 0.0, 10.0, out.delay_std_ratio);
  if (out.delay_max_s < out.delay_min_s) {
    throw ConfigError(source + ": uncertainty.delay_max_s " + std::to_string(out.delay_max_s) +
                      " is below delay_min_s " + std::to_string(out.delay_min_s) +
                      "; a delay lasts from min to max seconds");
  }
  double seed = 0;
  read("seed", 0.0, 9007199254740991.0, seed);
  out.seed = static_cast<uint64_t>(seed);
}
}  // namespace

RobotModel parse_robot_model(const std::string& text, const std::string& source) {
  const auto root = config::load(text, source);
  if (!root.IsMap()) throw ConfigError(source + ": a robot model must be a YAML mapping");
  // clang-format off
  const std::map<std::string, Field> fields = {
      {"radius_m", {0.01, 2.0, [](RobotModel& m) -> double& { return m.radius_m; }, true}},
      {"mass_kg", {0.05, 1000.0, [](RobotModel& m) -> double& { return m.mass_kg; }, true}},
      {"wheel_base_m", {0.01, 5.0, [](RobotModel& m) -> double& { return m.wheel_base_m; }, true}},
      {"wheel_radius_m", {0.001, 1.0, [](RobotModel& m) -> double& { return m.wheel_radius_m; }, true}},
      {"max_speed_mps", {0.01, 20.0, [](RobotModel& m) -> double& { return m.max_speed_mps; }, true}},
      {"max_accel_mps2", {0.01, 50.0, [](RobotModel& m) -> double& { return m.max_accel_mps2; }, true}},
      {"max_decel_mps2", {0.01, 50.0, [](RobotModel& m) -> double& { return m.max_decel_mps2; }, true}},
      {"max_turn_rate_radps", {0.01, 50.0, [](RobotModel& m) -> double& { return m.max_turn_rate_radps; }, true}},
      {"max_angular_accel_radps2", {0.01, 500.0, [](RobotModel& m) -> double& { return m.max_angular_accel_radps2; }, true}},
  };
  const std::map<std::string, Field> gains = {
      {"heading_kp", {0.0, 100.0, [](RobotModel& m) -> double& { return m.gains.heading_kp; }, false}},
      {"heading_kd", {0.0, 100.0, [](RobotModel& m) -> double& { return m.gains.heading_kd; }, false}},
      {"cross_track_kp", {0.0, 100.0, [](RobotModel& m) -> double& { return m.gains.cross_track_kp; }, false}},
      {"distance_kp", {0.1, 100.0, [](RobotModel& m) -> double& { return m.gains.distance_kp; }, false}},
      {"position_tolerance_m", {0.0001, 0.5, [](RobotModel& m) -> double& { return m.gains.position_tolerance_m; }, false}},
      {"heading_tolerance_rad", {0.0001, 0.5, [](RobotModel& m) -> double& { return m.gains.heading_tolerance_rad; }, false}},
      {"min_wheel_speed_mps", {0.0, 1.0, [](RobotModel& m) -> double& { return m.gains.min_wheel_speed_mps; }, false}},
  };
  // clang-format on
  std::vector<std::string> known{"name",     "description", "controller",
                                 "hardware", "uncertainty", "trim"};
  for (const auto& [k, _] : fields) known.push_back(k);
  config::reject_unknown(source, root, "(top level)", known);

  RobotModel m;
  if (!root["name"]) throw ConfigError(source + ": missing key 'name'; add e.g. 'name: footbot'");
  m.name = config::scalar<std::string>(source, root["name"], "name", "a robot model name");
  for (const auto& [key, f] : fields) {
    if (!root[key]) {
      throw ConfigError(source + ": missing key '" + key + "' (a number from " +
                        std::to_string(f.min) + " to " + std::to_string(f.max) + ")");
    }
    f.ref(m) = config::number(source, root[key], key, f.min, f.max);
  }
  if (const auto c = root["controller"]) {
    config::require_map(source, c, "controller");
    std::vector<std::string> gain_keys;
    gain_keys.reserve(gains.size());
    for (const auto& [k, _] : gains) gain_keys.push_back(k);
    config::reject_unknown(source, c, "controller", gain_keys);
    for (const auto& [key, f] : gains) {
      if (c[key]) f.ref(m) = config::number(source, c[key], "controller." + key, f.min, f.max);
    }
  }
  if (const auto u = root["uncertainty"]) read_uncertainty(source, u, m.uncertainty);
  if (const auto t = root["trim"]) {
    config::require_map(source, t, "trim");
    config::reject_unknown(source, t, "trim", {"left", "right"});
    if (t["left"]) m.trim.left = config::number(source, t["left"], "trim.left", 0.5, 1.0);
    if (t["right"]) m.trim.right = config::number(source, t["right"], "trim.right", 0.5, 1.0);
  }
  return m;
}

RobotModel load_robot_model(const std::string& path) {
  return parse_robot_model(config::read_file(path, "robot model"), path);
}

}  // namespace smart::agent
