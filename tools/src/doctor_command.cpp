// `smart doctor`: bring-up checks before a run, for the robots this host drives. A table of
// OK/WARN/FAIL rows with what was measured and how to fix it (verdicts: tools/doctor.hpp):
// DDS (a monitor on the domain and run, and QoS that matches it), per robot the motor board
// (a JetBot's PCA9685 answering on I2C), the pose stream (rate, jitter, gaps) and, with
// --wheels, a wheel direction test (each wheel alone, after asking, unless --yes).
// Exit 0 when nothing FAILed, 1 otherwise.
#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>
#include <set>
#include <sstream>
#include <thread>

#include "smart/dds/wire.hpp"
#include "smart/hw/pca9685.hpp"
#include "smart/tools/cli_common.hpp"
#include "smart/tools/commands.hpp"
#include "smart/tools/doctor.hpp"
#include "smart/tools/robot_backends.hpp"

namespace smart::tools {

namespace {

struct DoctorOptions {
  DdsOptions dds;
  BackendOptions io;
  std::optional<uint32_t> robot_id;
  std::string robot_ids;
  double seconds = 2.0;
  bool wheels = false, yes = false;
  double wheel_speed_mps = 0.15, wheel_s = 0.6;
};

// Hosts heard through their robots' states: per writing participant, its robots and the
// smallest receive - source timestamp (clock offset + delay).
struct HeardHost {
  std::set<uint32_t> robots;
  double min_offset_s = 1e18;
  std::size_t samples = 0;
};

std::string short_guid(const dds_guid_t& g) {
  std::ostringstream s;
  for (int i = 0; i < 6; ++i) s << std::hex << std::setw(2) << std::setfill('0') << int{g.v[i]};
  return s.str();
}

// The host (participant) that wrote a sample, its clock offset + delay updated; null when the
// writer already left.
template <class Reader>
HeardHost* heard_from(const Reader& reader, const dds_sample_info_t& info,
                      std::map<std::string, HeardHost>& hosts) {
  const auto who = reader.participant_of(info.publication_handle);
  if (!who) return nullptr;
  auto& h = hosts[short_guid(*who)];
  h.min_offset_s = std::min(h.min_offset_s, (dds_time() - info.source_timestamp) * 1e-9);
  ++h.samples;
  return &h;
}

// Samples that fail the wire checks are not believed (anything on the wire is untrusted): they
// are counted in `rejected` and shown as one row.
void hear_states(dds::WireReader<smart_msg_RobotState>& states,
                 std::map<std::string, HeardHost>& hosts, wire::Rejections& rejected) {
  states.take_each_info([&](const smart_msg_RobotState& s, const dds_sample_info_t& info) {
    if (auto why = wire::check_state(s, 0, std::nullopt); !why.empty()) {
      rejected.count("state", why);
      return;
    }
    if (auto* h = heard_from(states, info, hosts)) h->robots.insert(s.robot_id);
  });
}

std::vector<CheckRow> host_rows(const std::map<std::string, HeardHost>& hosts) {
  std::vector<CheckRow> rows;
  for (const auto& [name, h] : hosts) {
    rows.push_back(
        clock_check(name, {h.robots.begin(), h.robots.end()}, h.min_offset_s, h.samples, 0.02));
  }
  return rows;
}

std::vector<CheckRow> dds_checks(const DoctorOptions& o, const dds::QosProfile& profile,
                                 const dds::Participant& participant) {
  dds::WireReader<smart_msg_MonitorInfo> monitors(participant, profile);
  dds::WireReader<smart_msg_ActionWindow> actions(participant, profile);
  dds::WireReader<smart_msg_RobotState> states(participant, profile);
  std::map<std::string, HeardHost> hosts;
  wire::Rejections rejected;
  std::optional<smart_msg_MonitorInfo> seen;
  std::string host;
  for (const double end = steady_s() + o.seconds; steady_s() < end;) {
    monitors.take_each_info([&](const smart_msg_MonitorInfo& m, const dds_sample_info_t& info) {
      if (auto why = wire::check_monitor_info(m); !why.empty()) {
        rejected.count("monitor", why);
        return;
      }
      seen = m;
      host = m.host;
      // Announced again every second (monitor/ownership_edge.hpp): its host's clock, too.
      heard_from(monitors, info, hosts);
    });
    hear_states(states, hosts, rejected);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  std::vector<CheckRow> rows = host_rows(hosts);
  if (auto row = rejected_row(rejected)) rows.push_back(*row);
  const std::string where = "domain " + std::to_string(o.dds.domain) + ", run " + o.dds.run;
  if (!seen) {
    rows.push_back({"", "monitor", Level::kWarn, "none seen in " + where,
                    "start `smart monitor` first, or check --domain, --run, --network and that "
                    "the firewall lets RTPS through (UDP 7400 and up)"});
    return rows;
  }
  rows.push_back({"", "monitor", Level::kOk,
                  "run " + std::to_string(seen->run_id) + " on " + host + " (pid " +
                      std::to_string(seen->pid) + "), " + where,
                  ""});
  const auto bad = actions.requested_incompatible_qos().total_count;
  const auto matched = actions.subscription_matched().current_count;
  if (bad > 0) {
    rows.push_back({"", "qos", Level::kFail, std::to_string(bad) + " incompatible writer(s)",
                    "the monitor runs another QoS profile: pass it the same --qos"});
  } else {
    rows.push_back({"", "qos", matched > 0 ? Level::kOk : Level::kWarn,
                    std::to_string(matched) + " action writer(s) matched",
                    matched > 0 ? "" : "the monitor's action writer was not matched yet"});
  }
  return rows;
}

CheckRow board_check(const std::string& id, const RobotIo& io) {
  if (io.bus == nullptr) return {id, "motor board", Level::kOk, "a ROS 2 base (cmd_vel)", ""};
  try {
    const auto mode1 = io.bus->read_register(io.hardware.address, hw::pca9685::kMode1);
    std::ostringstream m;
    m << "PCA9685 at 0x" << std::hex << int{io.hardware.address} << " answers (MODE1 0x"
      << int{mode1} << ") on " << io.hardware.i2c_device;
    return {id, "motor board", Level::kOk, m.str(), ""};
  } catch (const std::exception& e) {
    return {id, "motor board", Level::kFail, e.what(),
            "check the board's I2C address (hardware.address), its power and wiring"};
  }
}

std::vector<agent::PoseSample> record(agent::PoseSource& pose, double seconds) {
  std::vector<agent::PoseSample> out;
  double last = -1;
  for (const double end = steady_s() + seconds; steady_s() < end;) {
    const auto p = pose.read();
    if (p.valid && p.stamp_s != last) {
      out.push_back(p);
      last = p.stamp_s;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return out;
}

// Drives one wheel alone; the direction row, and the time until the pose first moved (5 mm or
// 1.5 degrees: well beyond mocap noise, 0.5 mm and 0.2 degrees, and reached within tens of ms
// of a wheel turning at the test speed).
CheckRow drive_one_wheel(const DoctorOptions& o, const std::string& id, RobotIo& io, Wheel w,
                         std::optional<double>& moved_after_s) {
  const auto before = io.pose->read().pose;
  const agent::WheelSpeeds speeds = w == Wheel::kLeft ? agent::WheelSpeeds{o.wheel_speed_mps, 0.0}
                                                      : agent::WheelSpeeds{0.0, o.wheel_speed_mps};
  const double start = steady_s();
  for (const double end = start + o.wheel_s; steady_s() < end && !g_stop_requested;) {
    io.drive->set_wheel_speeds(speeds);  // repeated: the JetBot's command watchdog stays fed
    const auto now = io.pose->read().pose;
    if (!moved_after_s &&
        (std::hypot(now.x_m - before.x_m, now.y_m - before.y_m) > 0.005 ||
         std::abs(std::remainder(now.yaw_rad - before.yaw_rad, 2 * std::numbers::pi)) >
             1.5 * std::numbers::pi / 180)) {
      moved_after_s = steady_s() - start;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  io.drive->stop();
  std::this_thread::sleep_for(std::chrono::milliseconds(500));  // come to rest, fresh pose
  return wheel_check(id, w, before, io.pose->read().pose, io.jetbot != nullptr);
}

bool confirmed(const DoctorOptions& o, const std::string& id) {
  if (o.yes) return true;
  std::cerr << "Robot " << id << ": each wheel will turn alone for " << o.wheel_s
            << " s (the robot pivots in place). Type yes to go: " << std::flush;
  std::string answer;
  std::getline(std::cin, answer);
  return answer == "yes";
}

std::vector<CheckRow> robot_checks(const DoctorOptions& o, uint32_t robot,
                                   const dds::Participant& participant) {
  const std::string id = std::to_string(robot);
  std::vector<CheckRow> rows;
  RobotIo io;
  try {
    const auto file = robot_file(o.io);
    io = open_robot(o.io, robot, agent::load_robot_model(file), file, participant);
  } catch (const std::exception& e) {
    rows.push_back({id, "open", Level::kFail, e.what(),
                    "fix the device, pose source or robot file named in the message"});
    return rows;
  }
  const auto signal_stop = stop_outputs_on_signal(io);
  rows.push_back(board_check(id, io));
  rows.push_back(
      pose_stream_check(id, record(*io.pose, o.seconds), o.seconds, 20.0, o.io.pose_max_age_s));
  if (!o.wheels || rows.back().level == Level::kFail) return rows;
  if (!confirmed(o, id)) {
    rows.push_back({id, "wheels", Level::kWarn, "not run", "answer yes, or pass --yes"});
    return rows;
  }
  auto ready = io.drive->configure();
  if (ready.ok()) ready = io.drive->activate();
  if (!ready.ok()) {
    rows.push_back({id, "wheels", Level::kFail, "not run", ready.message});
    return rows;
  }
  std::optional<double> left_s, right_s;
  rows.push_back(drive_one_wheel(o, id, io, Wheel::kLeft, left_s));
  rows.push_back(drive_one_wheel(o, id, io, Wheel::kRight, right_s));
  if (auto r = io.drive->deactivate(); !r.ok()) {
    rows.push_back({id, "wheels", Level::kFail, "did not stop", r.message});
  }
  rows.push_back(response_check(
      id, left_s && right_s ? std::max(*left_s, *right_s) : (left_s ? left_s : right_s)));
  return rows;
}

int print(const std::vector<CheckRow>& rows) {
  nlohmann::json j = {{"rows", nlohmann::json::array()}};
  int fails = 0, warns = 0;
  for (const auto& r : rows) {
    std::cout << std::left << std::setw(5) << level_name(r.level) << std::setw(10)
              << (r.robot.empty() ? "host" : "robot " + r.robot) << std::setw(14) << r.check
              << r.measured << (r.fix.empty() ? "" : "\n                             fix: " + r.fix)
              << "\n";
    j["rows"].push_back({{"robot", r.robot},
                         {"check", r.check},
                         {"level", level_name(r.level)},
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
  auto rows = dds_checks(o, profile, participant);
  for (const uint32_t id : ids) {
    for (auto& r : robot_checks(o, id, participant)) rows.push_back(std::move(r));
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
  cmd->add_flag("--wheels", o->wheels, "drive each wheel alone to check its direction");
  cmd->add_flag("--yes", o->yes, "do not ask before moving");
  cmd->callback([&exit_code, o] {
    install_stop_handlers();
    exit_code = run_doctor(*o);
  });
}

}  // namespace smart::tools
