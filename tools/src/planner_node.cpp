#include "smart/tools/planner_node.hpp"

#include <spdlog/spdlog.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <random>
#include <thread>
#include <utility>

#include "smart/dds/participant_directory.hpp"

namespace smart::tools {

namespace {

using Clock = std::chrono::steady_clock;
constexpr auto kAnnounce = std::chrono::milliseconds(smart_msg_PLAN_ANNOUNCE_MS);

smart_msg_PlannerInfo self_info(const std::string& name) {
  smart_msg_PlannerInfo m{};
  std::random_device rd;
  m.planner_id = ((uint64_t{rd()} << 32) | rd()) | 1;  // never 0
  std::snprintf(m.name, sizeof(m.name), "%s", name.c_str());
  if (gethostname(m.host, sizeof(m.host) - 1) != 0) std::snprintf(m.host, sizeof(m.host), "?");
  m.pid = static_cast<int32_t>(getpid());
  m.started_ms = static_cast<uint64_t>(std::chrono::duration_cast<std::chrono::milliseconds>(
                                           std::chrono::system_clock::now().time_since_epoch())
                                           .count());
  return m;
}

}  // namespace

PlannerNode::PlannerNode(const dds::Participant& participant, const dds::QosProfile& profile,
                         const std::string& name, PlannerFactory make_planner)
    : participant_(participant),
      make_planner_(std::move(make_planner)),
      self_(self_info(name)),
      from_monitors_(dds::admit_roles(participant, {"monitor"})),
      requests_from_monitors_(dds::admit_roles(participant, {"monitor"})),
      problem_in_(participant, profile, from_monitors_),
      request_in_(participant, profile, requests_from_monitors_),
      info_out_(participant, profile),
      reply_out_(participant, profile),
      waitset_(participant) {
  waitset_.attach_status(problem_in_.handle(), DDS_DATA_AVAILABLE_STATUS, 1);
  waitset_.attach_status(request_in_.handle(), DDS_DATA_AVAILABLE_STATUS, 2);
  info_out_.write(self_);
  announced_ = Clock::now();
}

void PlannerNode::announce_if_due() {
  // Written again each PLAN_ANNOUNCE_MS: the same announcement (keep-last), its sign of life.
  if (Clock::now() - announced_ < kAnnounce) return;
  info_out_.write(self_);
  announced_ = Clock::now();
}

PlannerNode::Outcome PlannerNode::serve(const std::atomic<bool>& stop) {
  spdlog::info("planner '{}' (id {:016x}) waits for run '{}' on domain {}", self_.name,
               self_.planner_id, participant_.run(), participant_.domain_id());
  while (!stop.load()) {
    announce_if_due();
    if (auto end = take_problems()) return *end;
    if (run_id_ != 0) {
      take_requests();
    } else {
      (void)request_in_.read();  // kept for when the problem is in (marked read meanwhile)
    }
    const auto left = kAnnounce - (Clock::now() - announced_);
    (void)waitset_.wait(std::clamp(std::chrono::duration_cast<std::chrono::milliseconds>(left),
                                   std::chrono::milliseconds(1), kAnnounce));
  }
  outcome_.end = End::kStopped;
  return outcome_;
}

std::optional<PlannerNode::Outcome> PlannerNode::take_problems() {
  for (const auto& [writer, n] : from_monitors_.take_refused()) {
    if (rejected_.count(smart_msg_TOPIC_PLAN_PROBLEM, dds::kNotRunMember, {}, n)) {
      spdlog::warn("planner: {} problem(s) from {} ignored: {}", n,
                   dds::describe_sender(problem_in_.participant_of(writer)), dds::kNotRunMember);
    }
  }
  for (;;) {
    auto samples = problem_in_.take();
    if (samples.empty()) break;
    for (auto s : samples) {
      const auto& p = s.data();  // key fields are set in invalid samples too
      if (!s.alive() && run_id_ != 0 && p.run_id == run_id_) {
        outcome_.end = End::kRunOver;
        return outcome_;
      }
      if (!s.valid()) continue;
      if (auto why = wire::check_problem(p); !why.empty()) {
        const auto who =
            dds::describe_sender(problem_in_.participant_of(s.info().publication_handle));
        if (rejected_.count(smart_msg_TOPIC_PLAN_PROBLEM, why, who)) {
          spdlog::warn("planner: a problem from {} ignored: {}", who, why);
        }
        continue;
      }
      if (p.planner.planner_id != self_.planner_id) {
        outcome_.end = End::kRefused;
        outcome_.detail = "refused: run '" + participant_.run() + "' on domain " +
                          std::to_string(participant_.domain_id()) + " is planned by " +
                          wire::describe_planner(p.planner) +
                          "; stop that planner, or start this one with another --run";
        return outcome_;
      }
      if (!s.alive()) {  // this planner's run came and went before it was read
        outcome_.end = End::kRunOver;
        return outcome_;
      }
      if (p.run_id == run_id_) continue;
      run_id_ = p.run_id;
      grid_ = wire::grid_of(p);
      robots_ = p.robots;
      last_window_ = 0;
      planner_ = make_planner_(grid_, robots_);
      spdlog::info("planner: planning run '{}': {} robots on a {}x{} map, {} steps a window",
                   participant_.run(), p.robots, p.width, p.height, p.window_steps);
    }
  }
  return std::nullopt;
}

void PlannerNode::take_requests() {
  std::optional<uint64_t> newest;
  auto samples = request_in_.take();
  // Keyed by run, keep-last 1: at most one request of this run is here; take the newest.
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const auto s = samples[i];
    const auto& r = s.data();
    if (!s.valid() || r.run_id != run_id_ || r.planner_id != self_.planner_id) continue;
    if (r.window <= last_window_ || (newest && r.window <= samples[*newest].data().window)) {
      continue;
    }
    newest = i;
  }
  if (newest) answer(samples[*newest].data());
}

void PlannerNode::answer(const smart_msg_PlanRequest& r) {
  last_window_ = r.window;
  if (auto why = wire::check_request(r, grid_, robots_); !why.empty()) {
    reply_.set_error(self_.planner_id, run_id_, r.window, "request refused by the planner: " + why);
  } else {
    lifelong::PlannedWindow planned;
    try {
      planner_->submit(wire::request_of(r));
      auto answer = planner_->poll();
      for (; !answer; answer = planner_->poll()) {  // a planner that answers later
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
      }
      planned = std::move(*answer);
    } catch (const std::exception& e) {
      planned.error = e.what();
    }
    if (planned.error.empty()) {
      reply_.set_paths(self_.planner_id, run_id_, r.window, planned.paths);
    } else {
      reply_.set_error(self_.planner_id, run_id_, r.window, planned.error);
    }
  }
  reply_out_.write(reply_.view());
  ++outcome_.windows;
}

}  // namespace smart::tools
