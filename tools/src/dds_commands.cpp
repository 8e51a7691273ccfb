// `smart dds-echo`, `smart dds-ping`, `smart dds-send`: DDS round trips over the real topics,
// for checking a network and measuring QoS profiles without a fleet. dds-echo is a minimal
// responder: it answers every action window with the progress (and a robot state) of having
// finished it, and every sim clock tick with the same tick. dds-ping drives it and measures
// round trips. dds-send publishes a numbered burst (delivery under the lossy profile).
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <random>
#include <thread>

#include "smart/common/child_process.hpp"
#include "smart/dds/action_window.hpp"
#include "smart/dds/participant.hpp"
#include "smart/dds/reader.hpp"
#include "smart/dds/topics.hpp"
#include "smart/dds/waitset.hpp"
#include "smart/dds/wire.hpp"
#include "smart/dds/writer.hpp"
#include "smart/tools/cli_common.hpp"
#include "smart/tools/commands.hpp"

namespace smart::tools {

namespace {

using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;

// dds-echo answers ticks the way a monitor does; dds-ping sends them as a sim host does.
constexpr uint32_t kSimSource = dds::kSimClockSource;
constexpr uint32_t kEchoSource = dds::kMonitorClockSource;

int run_echo(const DdsOptions& o, double duration_s) {
  const auto profile = dds::find_qos_profile(o.qos);
  dds::Domain domain(o.domain, domain_config(o, profile, "viewer"));
  dds::Participant participant(domain, o.run);
  dds::WireReader<smart_msg_ActionWindow> actions(participant, profile);
  dds::WireReader<smart_msg_Clock> clocks(participant, profile);
  dds::WireWriter<smart_msg_Progress> progress(participant, profile);
  dds::WireWriter<smart_msg_RobotState> states(participant, profile);
  dds::WireWriter<smart_msg_Clock> clock_out(participant, profile);
  dds::WaitSet waitset(participant);
  waitset.attach_status(actions.handle(), DDS_DATA_AVAILABLE_STATUS, 1);
  waitset.attach_status(clocks.handle(), DDS_DATA_AVAILABLE_STATUS, 2);
  spdlog::info("dds-echo: domain {}, QoS profile '{}', waiting for action windows", o.domain,
               profile.name);

  const auto start = Clock::now();
  std::size_t windows = 0, ticks = 0;
  while (!g_stop_requested.load()) {
    if (duration_s > 0 &&
        std::chrono::duration<double>(Clock::now() - start).count() >= duration_s) {
      break;
    }
    waitset.wait(milliseconds(100));
    actions.take_each([&](const smart_msg_ActionWindow& w) {
      ++windows;
      smart_msg_Progress p{};
      p.robot_id = w.robot_id;
      p.run_id = w.run_id;
      p.finished_seq = dds::kNoSeq;
      p.executing_seq = dds::kNoSeq;
      smart_msg_RobotState s{};
      s.robot_id = w.robot_id;
      s.run_id = w.run_id;
      if (w.actions._length > 0) {
        const auto& last = w.actions._buffer[w.actions._length - 1];
        p.finished_seq = static_cast<int32_t>(last.seq);
        s.pose.x_m = last.to.x_m;
        s.pose.y_m = last.to.y_m;
        s.pose.yaw_rad = last.heading_rad;
      }
      progress.write_batched(p);
      states.write_batched(s);
    });
    // The answers to every window taken go out together, as a sim host sends a period's states.
    progress.flush();
    states.flush();
    clocks.take_each([&](const smart_msg_Clock& c) {
      if (c.source_id != kSimSource) return;  // our own answers come back too
      ++ticks;
      smart_msg_Clock answer = c;
      answer.source_id = kEchoSource;
      clock_out.write(answer);
    });
  }
  spdlog::info("dds-echo: answered {} action windows and {} clock ticks", windows, ticks);
  return 0;
}

double percentile(std::vector<double> xs, double q) {
  if (xs.empty()) return 0.0;
  std::sort(xs.begin(), xs.end());
  const auto i = static_cast<std::size_t>(std::llround(q * static_cast<double>(xs.size() - 1)));
  return xs[std::min(i, xs.size() - 1)];
}

struct PingOptions {
  uint32_t robots = 100;
  uint32_t rounds = 20;
  uint32_t steps = 3;
  double timeout_s = 10.0;
  bool spawn_echo = false;
};

// The monitor-like side of dds-ping: windows and ticks out, progress and answers back.
struct Pinger {
  const PingOptions& po;
  dds::WireWriter<smart_msg_ActionWindow> actions;
  dds::WireWriter<smart_msg_Clock> clock_out;
  dds::WireReader<smart_msg_Progress> progress;
  dds::WireReader<smart_msg_RobotState> states;
  dds::WireReader<smart_msg_Clock> clocks;
  dds::WaitSet waitset;
  const uint64_t run_id = std::random_device{}() | (uint64_t{1} << 40);
  std::size_t progress_samples = 0, state_samples = 0, clock_replies = 0;

  Pinger(const dds::Participant& p, const dds::QosProfile& q, const PingOptions& o)
      : po(o),
        actions(p, q),
        clock_out(p, q),
        progress(p, q),
        states(p, q),
        clocks(p, q),
        waitset(p) {
    waitset.attach_status(progress.handle(), DDS_DATA_AVAILABLE_STATUS, 1);
    waitset.attach_status(clocks.handle(), DDS_DATA_AVAILABLE_STATUS, 2);
  }

  void send_round(uint32_t r) {
    for (uint32_t robot = 0; robot < po.robots; ++robot) {
      dds::ActionWindowBuffer w(robot, run_id, po.rounds * po.steps);
      for (uint32_t k = 0; k < po.steps; ++k) {
        smart_msg_ActionStep s{};
        s.seq = r * po.steps + k;
        s.type = k == 0 ? smart_msg_ACTION_ROTATE : smart_msg_ACTION_MOVE;
        s.to.x_m = robot;
        s.to.y_m = r + 0.5 * k;
        w.steps().push_back(s);
      }
      actions.write(w.view());
    }
    clock_out.write(smart_msg_Clock{kSimSource, run_id, r, 0.1 * r, 0, false});
  }

  // Waits until every robot finished round r and the tick was answered; false on timeout.
  bool await_round(uint32_t r, Clock::time_point t0) {
    const auto last_seq = static_cast<int32_t>((r + 1) * po.steps - 1);
    std::vector<bool> done(po.robots, false);
    uint32_t remaining = po.robots;
    bool answered = false;
    while (remaining > 0 || !answered) {
      if (Clock::now() - t0 > std::chrono::duration<double>(po.timeout_s)) {
        std::cerr << "dds-ping: round " << r << " timed out after " << po.timeout_s << " s with "
                  << remaining << " of " << po.robots << " robots unanswered"
                  << (answered ? "" : " and no clock answer") << "\n";
        return false;
      }
      waitset.wait(milliseconds(50));
      progress.take_each([&](const smart_msg_Progress& p) {
        ++progress_samples;
        if (p.run_id != run_id || p.robot_id >= po.robots) return;
        if (p.finished_seq >= last_seq && !done[p.robot_id]) {
          done[p.robot_id] = true;
          --remaining;
        }
      });
      clocks.take_each([&](const smart_msg_Clock& c) {
        if (c.source_id != kEchoSource || c.run_id != run_id || c.tick != r) return;
        answered = true;
        ++clock_replies;
      });
      states.take_each([&](const smart_msg_RobotState&) { ++state_samples; });
    }
    return true;
  }
};

int run_ping(const DdsOptions& o, const PingOptions& po) {
  std::optional<common::ChildProcess> echo;
  if (po.spawn_echo) {
    std::vector<std::string> argv{common::self_executable().string(), "dds-echo"};
    const auto dds = dds_argv(o);
    argv.insert(argv.end(), dds.begin(), dds.end());
    echo.emplace(argv);
  }
  const auto profile = dds::find_qos_profile(o.qos);
  dds::Domain domain(o.domain, domain_config(o, profile, "viewer"));
  dds::Participant participant(domain, o.run);
  Pinger ping(participant, profile, po);
  const auto timeout = milliseconds(static_cast<long>(po.timeout_s * 1000));
  if (!ping.actions.wait_for_readers(1, timeout) || !ping.progress.wait_for_writers(1, timeout)) {
    std::cerr << "dds-ping: no agent matched on domain " << o.domain << " within " << po.timeout_s
              << " s; start `smart dds-echo --domain " << o.domain
              << "` (same --qos and --network) or pass --spawn-echo\n";
    return kExitSystem;
  }
  std::vector<double> rtt_ms;
  for (uint32_t r = 0; r < po.rounds && !g_stop_requested.load(); ++r) {
    const auto t0 = Clock::now();
    ping.send_round(r);
    if (!ping.await_round(r, t0)) return kExitRunFailed;
    rtt_ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
  }
  ping.states.take_each([&](const smart_msg_RobotState&) { ++ping.state_samples; });
  std::cout << nlohmann::json{{"robots", po.robots},
                              {"rounds", rtt_ms.size()},
                              {"qos", profile.name},
                              {"round_trip_ms",
                               {{"median", percentile(rtt_ms, 0.5)},
                                {"p99", percentile(rtt_ms, 0.99)},
                                {"max", percentile(rtt_ms, 1.0)}}},
                              {"progress_samples", ping.progress_samples},
                              {"state_samples", ping.state_samples},
                              {"clock_replies", ping.clock_replies}}
                   .dump()
            << std::endl;
  return rtt_ms.size() == po.rounds ? kExitSuccess : kExitRunFailed;
}

struct SendOptions {
  uint32_t count = 500;
  std::string reliability = "reliable";
  int interval_ms = 1;
  double timeout_s = 20.0;
};

int run_send(const DdsOptions& o, const SendOptions& so) {
  const auto profile = dds::find_qos_profile(o.qos);
  dds::Domain domain(o.domain, domain_config(o, profile, "viewer"));
  dds::Participant participant(domain, o.run);
  // Progress QoS made keep-all: every sample counts, so losses show.
  dds::Topic<smart_msg_Progress> topic(participant, std::string(dds::kProgressTopic));
  auto qos = profile.progress;
  qos.reliability =
      so.reliability == "reliable" ? dds::Reliability::kReliable : dds::Reliability::kBestEffort;
  qos.history = dds::HistoryKind::kKeepAll;
  qos.max_blocking = milliseconds(static_cast<long>(so.timeout_s * 1000));
  dds::Writer<smart_msg_Progress> writer(participant, topic,
                                         qos.to_dds().partition(participant.run_partition()));
  const auto timeout = milliseconds(static_cast<long>(so.timeout_s * 1000));
  if (!writer.wait_for_readers(1, timeout)) {
    std::cerr << "dds-send: no reader matched on domain " << o.domain << " within " << so.timeout_s
              << " s\n";
    return kExitSystem;
  }
  // Matching is seen by the writer first; give the reader side time to match as well, or best
  // effort samples sent in between would count as losses.
  std::this_thread::sleep_for(milliseconds(300));
  const uint64_t run_id = 7;
  for (uint32_t i = 0; i < so.count && !g_stop_requested.load(); ++i) {
    smart_msg_Progress p{};
    p.robot_id = i;
    p.run_id = run_id;
    p.finished_seq = static_cast<int32_t>(i);
    p.executing_seq = dds::kNoSeq;
    writer.write(p);
    if (so.interval_ms > 0) std::this_thread::sleep_for(milliseconds(so.interval_ms));
  }
  const bool acked =
      qos.reliability == dds::Reliability::kReliable ? writer.wait_for_acks(timeout) : true;
  std::this_thread::sleep_for(milliseconds(200));
  std::cout << nlohmann::json{{"sent", so.count}, {"acked", acked}}.dump() << std::endl;
  return acked ? kExitSuccess : kExitRunFailed;
}

}  // namespace

void register_dds_commands(CLI::App& app, int& exit_code) {
  auto echo_opts = std::make_shared<DdsOptions>();
  auto echo_duration = std::make_shared<double>(0.0);
  auto* echo = app.add_subcommand(
      "dds-echo",
      "Answer action windows with finished progress and clock ticks with the same tick "
      "(an agent stand-in for DDS round trips)");
  add_dds_options(echo, *echo_opts);
  echo->add_option("--duration-s", *echo_duration, "stop after this many seconds (0: on signal)");
  echo->callback([&exit_code, echo_opts, echo_duration] {
    install_stop_handlers();
    exit_code = run_echo(*echo_opts, *echo_duration);
  });

  auto ping_dds = std::make_shared<DdsOptions>();
  auto ping_opts = std::make_shared<PingOptions>();
  auto* ping = app.add_subcommand(
      "dds-ping",
      "Send action windows to N robots and clock ticks, wait for every answer, and "
      "print round-trip times as JSON");
  add_dds_options(ping, *ping_dds);
  ping->add_option("--robots", ping_opts->robots, "robots (keyed instances)")
      ->check(CLI::Range(1u, 100000u))
      ->capture_default_str();
  ping->add_option("--rounds", ping_opts->rounds, "round trips")->capture_default_str();
  ping->add_option("--steps", ping_opts->steps, "actions per window")
      ->check(CLI::Range(1u, 1000u))
      ->capture_default_str();
  ping->add_option("--timeout-s", ping_opts->timeout_s, "per-round timeout")->capture_default_str();
  ping->add_flag("--spawn-echo", ping_opts->spawn_echo, "start a `smart dds-echo` child process");
  ping->callback([&exit_code, ping_dds, ping_opts] {
    install_stop_handlers();
    exit_code = run_ping(*ping_dds, *ping_opts);
  });

  auto send_dds = std::make_shared<DdsOptions>();
  auto send_opts = std::make_shared<SendOptions>();
  auto* send = app.add_subcommand(
      "dds-send", "Publish COUNT progress samples (robot_id 0..COUNT-1) once a reader matched");
  add_dds_options(send, *send_dds);
  send->add_option("--count", send_opts->count, "progress samples to publish")
      ->capture_default_str();
  send->add_option("--reliability", send_opts->reliability, "reliability of the writer")
      ->check(CLI::IsMember({"reliable", "best_effort"}))
      ->capture_default_str();
  send->add_option("--interval-ms", send_opts->interval_ms, "pause between samples")
      ->capture_default_str();
  send->add_option("--timeout-s", send_opts->timeout_s, "give up when no reader matched by then")
      ->capture_default_str();
  send->callback([&exit_code, send_dds, send_opts] {
    install_stop_handlers();
    exit_code = run_send(*send_dds, *send_opts);
  });
}

}  // namespace smart::tools
