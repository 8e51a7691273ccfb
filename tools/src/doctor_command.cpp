// `smart doctor`: bring-up checks before a run, for the robots this host drives, measured by
// commissioning/doctor.hpp. A table of OK/WARN/FAIL rows with what was measured and how to fix it:
// DDS (a monitor on the domain and run, and QoS that matches it), per robot the motor board
// (a JetBot's PCA9685 answering on I2C), the pose stream (rate, jitter, gaps) and, with
// --wheels, a wheel direction test (each wheel alone, after asking, unless --yes).
// Exit 0 when nothing FAILed, 1 otherwise.
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>

#include "smart/commissioning/doctor.hpp"
#include "smart/tools/cli_common.hpp"
#include "smart/tools/commands.hpp"
#include "smart/tools/robot_backends.hpp"

namespace smart::tools {

namespace {

using commissioning::CheckRow;
using commissioning::Level;

struct DoctorOptions {
  DdsOptions dds;
  BackendOptions io;
  std::optional<uint32_t> robot_id;
  std::string robot_ids;
  double seconds = 2.0;
  double wait_s = 0;
  bool wheels = false, yes = false;
  double wheel_speed_mps = 0.15, wheel_s = 0.6;
};

bool confirmed(const std::string& id, double wheel_s) {
  std::cerr << "Robot " << id << ": each wheel will turn alone for " << wheel_s
            << " s (the robot pivots in place). Type yes to go: " << std::flush;
  std::string answer;
  std::getline(std::cin, answer);
  return answer == "yes";
}

commissioning::DoctorSettings settings(const DoctorOptions& o) {
  commissioning::DoctorSettings s;
  s.listen_s = o.seconds;
  s.wait_s = o.wait_s;
  s.pose_max_age_s = o.io.pose_max_age_s;
  s.wheels = o.wheels;
  s.wheel_speed_mps = o.wheel_speed_mps;
  s.wheel_s = o.wheel_s;
  if (!o.yes)
    s.confirm = [wheel_s = o.wheel_s](const std::string& id) { return confirmed(id, wheel_s); };
  s.stop = &g_stop_requested;
  return s;
}

int print(const std::vector<CheckRow>& rows) {
  nlohmann::json j = {{"rows", nlohmann::json::array()}};
  int fails = 0, warns = 0;
  for (const auto& r : rows) {
    std::cout << std::left << std::setw(5) << commissioning::level_name(r.level) << std::setw(10)
              << (r.robot.empty() ? "host" : "robot " + r.robot) << std::setw(14) << r.check
              << r.measured << (r.fix.empty() ? "" : "\n                             fix: " + r.fix)
              << "\n";
    j["rows"].push_back({{"robot", r.robot},
                         {"check", r.check},
                         {"level", commissioning::level_name(r.level)},
                         {"measured", r.measured},
                         {"fix", r.fix}});
    fails += r.level == Level::kFail;
    warns += r.level == Level::kWarn;
  }
  j["fail"] = fails;
  j["warn"] = warns;
  std::cout << j.dump() << std::endl;
  return fails > 0 ? kExitRunFailed : kExitSuccess;
}

int run_doctor(const DoctorOptions& o) {
  if (o.robot_id.has_value() && !o.robot_ids.empty()) {
    throw std::invalid_argument("give --robot-id or --robot-ids, not both");
  }
  std::vector<uint32_t> ids;
  if (o.robot_id) ids.push_back(*o.robot_id);
  if (!o.robot_ids.empty()) ids = parse_id_ranges(o.robot_ids);
  const auto profile = run_qos_profile(o.dds);
  dds::Domain domain(o.dds.domain, domain_config(o.dds, profile, "viewer"));
  dds::Participant participant(domain, o.dds.run);
  const auto s = settings(o);
  auto rows = commissioning::domain_checks(
      s, profile, participant, "domain " + std::to_string(o.dds.domain) + ", run " + o.dds.run);
  for (const uint32_t id : ids) {
    const auto open = [&] {
      const auto file = hw::robot_file(o.io);
      return hw::open_robot(o.io, id, agent::load_robot_model(file), file, participant);
    };
    for (auto& r : commissioning::robot_checks(s, std::to_string(id), open)) {
      rows.push_back(std::move(r));
    }
  }
  return print(rows);
}

}  // namespace

void register_doctor_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<DoctorOptions>();
  auto* cmd = app.add_subcommand(
      "doctor",
      "Bring-up checks before a run: DDS and the monitor, motor boards, pose streams, "
      "wheel directions (OK/WARN/FAIL and how to fix)");
  add_dds_options(cmd, o->dds);
  cmd->add_option("--robot-id", o->robot_id, "check this robot's hardware");
  cmd->add_option("--robot-ids", o->robot_ids, "check several robots (e.g. 0-9)");
  add_backend_options(cmd, o->io);
  cmd->add_option("--seconds", o->seconds, "how long to listen (monitor, pose streams)")
      ->check(finite_in(0.2, 60.0))
      ->capture_default_str();
  cmd->add_option("--wait-s", o->wait_s,
                  "listen on, up to this long, until a monitor was seen, its action writer "
                  "matched and every host was heard twice (0: just --seconds)")
      ->check(finite_in(0.0, 600.0))
      ->capture_default_str();
  cmd->add_flag("--wheels", o->wheels, "drive each wheel alone to check its direction");
  cmd->add_flag("--yes", o->yes, "do not ask before moving");
  cmd->callback([&exit_code, o] {
    install_stop_handlers();
    exit_code = run_doctor(*o);
  });
}

}  // namespace smart::tools
