#include "smart/commissioning/doctor.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <map>
#include <numbers>
#include <optional>
#include <set>
#include <sstream>
#include <thread>

#include "smart/common/steady_clock.hpp"
#include "smart/convert/validate.hpp"
#include "smart/dds/waitset.hpp"
#include "smart/dds/wire.hpp"
#include "smart/hw/pca9685.hpp"

namespace smart::commissioning {

namespace {

using common::steady_s;

bool stopped(const DoctorSettings& s) { return s.stop != nullptr && s.stop->load(); }

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
  h.min_offset_s =
      std::min(h.min_offset_s, static_cast<double>(dds_time() - info.source_timestamp) * 1e-9);
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
  rows.reserve(hosts.size());
  for (const auto& [name, h] : hosts) {
    rows.push_back(
        clock_check(name, {h.robots.begin(), h.robots.end()}, h.min_offset_s, h.samples, 0.02));
  }
  return rows;
}

}  // namespace

std::vector<CheckRow> domain_checks(const DoctorSettings& s, const dds::QosProfile& profile,
                                    const dds::Participant& participant, const std::string& where) {
  dds::WireReader<smart_msg_MonitorInfo> monitors(participant, profile);
  dds::WireReader<smart_msg_ActionWindow> actions(participant, profile);
  dds::WireReader<smart_msg_RobotState> states(participant, profile);
  std::map<std::string, HeardHost> hosts;
  wire::Rejections rejected;
  std::optional<smart_msg_MonitorInfo> seen;
  std::string host;
  // Settled: nothing more to wait for (doctor.hpp, wait_s).
  const auto settled = [&] {
    const bool qos_known = actions.subscription_matched().current_count > 0 ||
                           actions.requested_incompatible_qos().total_count > 0;
    return seen && qos_known &&
           std::ranges::all_of(hosts, [](const auto& h) { return h.second.samples >= 2; });
  };
  // Woken by arrivals, not polled: a sample's receive time is when it is taken, and a 20 ms
  // poll added up to 20 ms to the clock offset + delay it measures, the WARN threshold itself
  // (the monitor's own host was warned about on a loaded machine, CI).
  dds::WaitSet arrivals(participant);
  arrivals.attach_status(monitors.handle(), DDS_DATA_AVAILABLE_STATUS, 1);
  arrivals.attach_status(states.handle(), DDS_DATA_AVAILABLE_STATUS, 2);
  const double start = steady_s();
  for (double now = start; now < start + s.listen_s || (now < start + s.wait_s && !settled());
       now = steady_s()) {
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
    arrivals.wait(std::chrono::milliseconds(20));
  }
  std::vector<CheckRow> rows = host_rows(hosts);
  if (auto row = rejected_row(rejected)) rows.push_back(*row);
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

namespace {

CheckRow board_check(const std::string& id, const hw::RobotIo& io) {
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
CheckRow drive_one_wheel(const DoctorSettings& o, const std::string& id, hw::RobotIo& io, Wheel w,
                         std::optional<double>& moved_after_s) {
  const auto before = io.pose->read().pose;
  const agent::WheelSpeeds speeds = w == Wheel::kLeft ? agent::WheelSpeeds{o.wheel_speed_mps, 0.0}
                                                      : agent::WheelSpeeds{0.0, o.wheel_speed_mps};
  const double start = steady_s();
  for (const double end = start + o.wheel_s; steady_s() < end && !stopped(o);) {
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

// The wheels turn alone, after asking; a FAIL or WARN row when they may not.
std::optional<CheckRow> wheels_blocked(const DoctorSettings& s, const std::string& id,
                                       hw::RobotIo& io) {
  if (s.confirm && !s.confirm(id)) {
    return CheckRow{id, "wheels", Level::kWarn, "not run", "answer yes, or pass --yes"};
  }
  auto ready = io.drive->configure();
  if (ready.ok()) ready = io.drive->activate();
  if (!ready.ok()) return CheckRow{id, "wheels", Level::kFail, "not run", ready.message};
  return std::nullopt;
}

void wheel_checks(const DoctorSettings& s, const std::string& id, hw::RobotIo& io,
                  std::vector<CheckRow>& rows) {
  if (auto blocked = wheels_blocked(s, id, io)) {
    rows.push_back(*blocked);
    return;
  }
  std::optional<double> left_s, right_s;
  rows.push_back(drive_one_wheel(s, id, io, Wheel::kLeft, left_s));
  rows.push_back(drive_one_wheel(s, id, io, Wheel::kRight, right_s));
  if (auto r = io.drive->deactivate(); !r.ok()) {
    rows.push_back({id, "wheels", Level::kFail, "did not stop", r.message});
  }
  rows.push_back(response_check(
      id, left_s && right_s ? std::max(*left_s, *right_s) : (left_s ? left_s : right_s)));
}

}  // namespace

std::vector<CheckRow> robot_checks(const DoctorSettings& s, const std::string& id,
                                   const std::function<hw::RobotIo()>& open) {
  std::vector<CheckRow> rows;
  hw::RobotIo io;
  try {
    io = open();
  } catch (const std::exception& e) {
    rows.push_back({id, "open", Level::kFail, e.what(),
                    "fix the device, pose source or robot file named in the message"});
    return rows;
  }
  const auto signal_stop = hw::stop_outputs_on_signal(io, s.stop);
  rows.push_back(board_check(id, io));
  rows.push_back(pose_stream_check(id, record(*io.pose, s.listen_s), s.listen_s, s.min_pose_rate_hz,
                                   s.pose_max_age_s));
  if (!s.wheels || rows.back().level == Level::kFail) return rows;
  wheel_checks(s, id, io, rows);
  return rows;
}

}  // namespace smart::commissioning
