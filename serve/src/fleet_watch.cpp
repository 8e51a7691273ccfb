#include "smart/serve/fleet_watch.hpp"

#include <spdlog/spdlog.h>

#include <chrono>

#include "smart/convert/validate.hpp"
#include "smart/dds/participant.hpp"
#include "smart/dds/reader.hpp"
#include "smart/dds/topics.hpp"
#include "smart/dds/waitset.hpp"
#include "smart/dds/wire.hpp"

namespace smart::serve {

namespace {
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}
}  // namespace

// Readers only: nothing here writes to the domain.
struct FleetWatch::Pump {
  dds::Domain domain;
  dds::Participant participant;
  dds::WireReader<smart_msg_RobotState> states;
  dds::WireReader<smart_msg_Progress> progress;
  dds::WireReader<smart_msg_MonitorInfo> monitors;
  dds::WaitSet waitset;
  wire::Rejections rejected;
  Clock::time_point start = Clock::now();

  // The run partition's wildcard "*" (DDS 1.4 §2.2.3.13, PARTITION: fnmatch patterns) sees
  // every run on the domain.
  explicit Pump(const WatchOptions& o)
      : domain(o.domain, o.config),
        participant(domain, o.run.empty() ? "*" : o.run),
        states(participant, o.qos),
        progress(participant, o.qos),
        monitors(participant, o.qos),
        waitset(participant) {
    waitset.attach_status(states.handle(), DDS_DATA_AVAILABLE_STATUS, 1);
    waitset.attach_status(progress.handle(), DDS_DATA_AVAILABLE_STATUS, 2);
    waitset.attach_status(monitors.handle(), DDS_DATA_AVAILABLE_STATUS, 3);
  }

  void reject(const char* topic, const std::string& why) {
    if (rejected.count(topic, why)) spdlog::warn("watch: dropped a {} sample: {}", topic, why);
  }

  void take_into(WatchBoard& board, std::mutex& m) {
    const double now = seconds_since(start);
    std::lock_guard lock(m);
    states.take_each([&](const smart_msg_RobotState& s) {
      if (auto why = wire::check_state(s, WatchBoard::kMaxRobots, std::nullopt); !why.empty()) {
        return reject("state", why);
      }
      board.on_state({s.robot_id, s.run_id, s.sim_time_s, s.pose.x_m, s.pose.y_m, s.pose.yaw_rad,
                      s.linear_mps, s.angular_radps, s.queue_length},
                     now);
    });
    progress.take_each([&](const smart_msg_Progress& p) {
      if (auto why = wire::check_progress(p, WatchBoard::kMaxRobots); !why.empty()) {
        return reject("progress", why);
      }
      board.on_progress({p.robot_id, p.run_id, p.finished_seq, p.executing_seq}, now);
    });
    monitors.take_each([&](const smart_msg_MonitorInfo& mi) {
      if (auto why = wire::check_monitor_info(mi); !why.empty()) return reject("monitor", why);
      const std::string host(mi.host, strnlen(mi.host, sizeof(mi.host)));
      const std::string run(mi.run, strnlen(mi.run, sizeof(mi.run)));
      board.on_monitor({mi.run_id, host, mi.pid, run}, now);
    });
  }
};

FleetWatch::FleetWatch(const WatchOptions& options)
    : pump_(std::make_unique<Pump>(options)), thread_([this] { loop(); }) {}

FleetWatch::~FleetWatch() {
  stop_ = true;
  thread_.join();
}

void FleetWatch::loop() {
  while (!stop_.load()) {
    pump_->waitset.wait(std::chrono::milliseconds(100));
    pump_->take_into(board_, m_);
  }
}

nlohmann::json FleetWatch::snapshot(uint64_t run_id) const {
  const double now = seconds_since(pump_->start);
  std::lock_guard lock(m_);
  auto j = board_.snapshot(now, run_id);
  j["rejected_samples"] = pump_->rejected.total();
  return j;
}

}  // namespace smart::serve
