// `smart agent`: physical robots joining a run over DDS — the same Agent class as in simulation,
// on the wall clock.
// - --backend jetbot: one JetBot (PCA9685 over i2c-dev). With `--i2c emulated` the motor board
//   is the emulated JetBot (hw/emulated_jetbot.hpp), which streams its pose to this process as
//   Vicon UDP datagrams.
// - --backend ros2: one or several ROS 2 diff-drive bases (--robot-ids 0-9), each driven through
//   cmd_vel and located by its odometry (or a mocap PoseStamped) in its namespace; one process,
//   one DDS participant, one AgentNode for all of them.
#include <spdlog/spdlog.h>

#include <chrono>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <thread>

#include "smart/agent/agent.hpp"
#include "smart/agent/agent_node.hpp"
#include "smart/agent/run_clock.hpp"
#include "smart/config/yaml_checks.hpp"
#include "smart/tools/cli_common.hpp"
#include "smart/tools/commands.hpp"
#include "smart/tools/robot_backends.hpp"
#include "smart/tools/run_key.hpp"

namespace smart::tools {

namespace {

struct AgentOptions {
  DdsOptions dds;
  BackendOptions io;
  std::optional<uint32_t> robot_id;
  std::string robot_ids;  // "0-9,12"
  double period_s = 0.1;
};

// One robot this process drives: its hardware and its agent.
struct Robot {
  RobotIo io;
  std::unique_ptr<agent::Agent> agent;
  agent::RunClock clock;  // the time its states report: since its run began
};

bool stopped_by(const std::optional<wire::Tick>& clock, const std::vector<Robot>& robots) {
  if (!clock || !clock->stop) return false;
  return std::any_of(robots.begin(), robots.end(),
                     [&](const Robot& r) { return clock->run_id == r.agent->run_id(); });
}

// The agents' read/update/write loop on the wall clock until the monitor stops their run (true)
// or a signal arrives (false).
bool control_loop(std::vector<Robot>& robots, agent::AgentNode& node, double period_s) {
  auto next = std::chrono::steady_clock::now();
  double repeated_s = steady_s();
  while (!g_stop_requested.load()) {
    node.take_windows({}, steady_s());
    if (stopped_by(node.take_monitor_clock(), robots)) return true;
    const double now = steady_s();
    for (auto& r : robots) r.agent->step(now);
    node.publish_progress(now);
    if (now - repeated_s >= 1.0) {
      node.republish_progress();
      repeated_s = now;
    }
    for (auto& r : robots) {
      const auto& a = *r.agent;
      const double t_s = r.clock.since_run_start(a.run_id(), now);
      if (a.last_pose().valid) {
        node.publish_state(a.robot_id(), a.run_id(), t_s, a.last_pose(), a.last_command());
      }
    }
    node.flush_states();
    next += std::chrono::duration_cast<std::chrono::steady_clock::duration>(
        std::chrono::duration<double>(period_s));
    std::this_thread::sleep_until(next);
  }
  return false;
}

std::vector<uint32_t> robot_ids(const AgentOptions& o) {
  if (o.robot_id.has_value() == !o.robot_ids.empty()) {
    throw std::invalid_argument(
        "give the robots as --robot-id K or --robot-ids LIST (e.g. 0-9,12)");
  }
  auto ids = o.robot_id ? std::vector<uint32_t>{*o.robot_id} : parse_id_ranges(o.robot_ids);
  if (o.io.backend == Backend::kJetbot && ids.size() != 1) {
    throw std::invalid_argument("--backend jetbot drives one robot per process: use --robot-id");
  }
  return ids;
}

// JetBots: SIGINT/SIGTERM turn the outputs off at once from the handler, and a command
// watchdog beside the control loop stops the motors if the loop stalls.
class JetbotGuards {
 public:
  explicit JetbotGuards(const std::vector<Robot>& robots) {
    for (const auto& r : robots) {
      if (r.io.jetbot == nullptr) continue;
      stops_.push_back(
          std::make_unique<hw::SignalStop>(*r.io.bus, r.io.hardware.address, &g_stop_requested));
      drives_.push_back(r.io.jetbot);
    }
    if (drives_.empty()) return;
    watchdog_ = std::thread([this] {
      while (!done_) {
        for (auto* d : drives_) d->poll_watchdog(steady_s());
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
      }
    });
  }
  ~JetbotGuards() {
    done_ = true;
    if (watchdog_.joinable()) watchdog_.join();
  }
  JetbotGuards(const JetbotGuards&) = delete;
  JetbotGuards& operator=(const JetbotGuards&) = delete;

 private:
  std::vector<std::unique_ptr<hw::SignalStop>> stops_;
  std::vector<hw::JetbotDrive*> drives_;
  std::atomic<bool> done_{false};
  std::thread watchdog_;
};

nlohmann::json robot_report(const Robot& r) {
  nlohmann::json out = {{"robot_id", r.agent->robot_id()},
                        {"finished_seq", r.agent->finished_seq()},
                        {"watchdog_stops", r.agent->watchdog_stops()}};
  if (r.io.vicon) {
    const auto s = r.io.vicon->stats();
    out["vicon"] = {
        {"datagrams", s.datagrams}, {"malformed", s.malformed}, {"unknown_names", s.unknown_names}};
  }
  if (r.io.twist != nullptr) out["cmd_vel_writes"] = r.io.twist->commands();
  if (r.io.ros_pose != nullptr) out["pose_samples"] = r.io.ros_pose->samples();
  return out;
}

// Brings every robot's wheels to zero; the first failure, if any, is logged for each and returned.
agent::LifecycleResult deactivate_all(std::vector<Robot>& robots) {
  agent::LifecycleResult first;
  for (auto& r : robots) {
    auto d = r.agent->deactivate();
    if (d.ok()) continue;
    spdlog::error("{}", d.message);
    if (first.ok()) first = std::move(d);
  }
  return first;
}

// Hosts the robots on one AgentNode, runs them until the monitor stops their run (true) or a
// signal arrives (false), and brings their wheels to zero. A robot that does not configure,
// activate or stop ends the command (the others stopped first): exit 3 with its message.
bool execute(const dds::QosProfile& profile, const dds::Participant& participant,
             std::vector<Robot>& robots, double period_s) {
  std::vector<uint32_t> ids;  // it speaks for these robots only (their partitions)
  ids.reserve(robots.size());
  for (const auto& r : robots) ids.push_back(r.agent->robot_id());
  agent::AgentNode node(participant, profile, 0, std::nullopt, ids);
  node.set_link(profile.link);
  for (auto& r : robots) {
    node.host(*r.agent);
    if (auto a = r.agent->activate(); !a.ok()) {  // configures first
      (void)deactivate_all(robots);
      throw std::runtime_error(a.message);
    }
  }
  const bool stopped_by_monitor = control_loop(robots, node, period_s);
  if (auto d = deactivate_all(robots); !d.ok()) throw std::runtime_error(d.message);
  return stopped_by_monitor;
}

int run_agent(const AgentOptions& o) {
  const auto ids = robot_ids(o);
  const auto file = robot_file(o.io);
  const auto model = agent::load_robot_model(file);
  const auto profile = run_qos_profile(o.dds);
  if (const auto warning = link_model_warning(false, o.dds, profile)) {
    spdlog::warn("agent: {}", *warning);  // an agent always runs in real time
  }
  if (!o.dds.security.empty() && ids.size() > 1) {
    // Its identity's permissions grant one robot's partition (security/keystore.hpp).
    throw std::invalid_argument(
        "--security with " + std::to_string(ids.size()) +
        " robots: an agent identity speaks for its own robot only; start one `smart agent` per "
        "robot, each with its agent-<id> identity");
  }
  dds::Domain domain(o.dds.domain,
                     domain_config(o.dds, profile, "agent-" + std::to_string(ids.front())));
  dds::Participant participant(domain, o.dds.run);
  prove_member(participant, o.dds, "agent");
  std::vector<Robot> robots;
  for (const uint32_t id : ids) {
    Robot r{open_robot(o.io, id, model, file, participant), nullptr, {}};
    r.agent = std::make_unique<agent::Agent>(agent::AgentConfig{id, model, o.period_s, 0.5},
                                             *r.io.drive, *r.io.pose);
    spdlog::info("agent {}: {}, pose from {}, domain {}", id, model.name, r.io.pose_name,
                 o.dds.domain);
    robots.push_back(std::move(r));
  }
  bool stopped_by_monitor = false;
  {
    JetbotGuards guards(robots);
    stopped_by_monitor = execute(profile, participant, robots, o.period_s);
  }
  // One robot (a JetBot): its report; several: one line with all of them.
  nlohmann::json report;
  if (robots.size() == 1 && o.io.backend == Backend::kJetbot) {
    report = robot_report(robots.front());
  } else {
    report["robots"] = nlohmann::json::array();
    for (const auto& r : robots) report["robots"].push_back(robot_report(r));
  }
  report["stopped_by_monitor"] = stopped_by_monitor;
  std::cout << report.dump() << std::endl;
  return kExitSuccess;
}

}  // namespace

void register_agent_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<AgentOptions>();
  auto* cmd = app.add_subcommand("agent",
                                 "Physical robots (a JetBot, or ROS 2 diff-drive bases) executing "
                                 "their actions from `smart monitor` over DDS");
  add_dds_options(cmd, o->dds);
  cmd->add_option("--robot-id", o->robot_id, "the robot's index in the plan");
  cmd->add_option("--robot-ids", o->robot_ids,
                  "several robots in one process (--backend ros2), e.g. 0-9 or 0,2,5-7");
  add_backend_options(cmd, o->io);
  cmd->add_option("--period-s", o->period_s, "control period")
      ->check(finite_in(0.005, 10.0))
      ->capture_default_str();
  group_options(cmd);
  cmd->callback([&exit_code, o] { exit_code = run_agent(*o); });
}

}  // namespace smart::tools
