#include "smart/tools/dds_planner.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <random>
#include <stdexcept>
#include <utility>

#include "smart/dds/participant_directory.hpp"
#include "smart/lifelong/plan_protocol.hpp"
#include "smart/tools/cli_common.hpp"
#include "smart/tools/external_window.hpp"

namespace smart::tools {

namespace {

using Clock = std::chrono::steady_clock;
constexpr dds_attach_t kInfoTag = 1, kReplyTag = 2;
constexpr const char* kReplyTopic = smart_msg_TOPIC_PLAN_REPLY;

Clock::time_point after(double s) {
  return Clock::now() +
         std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s));
}

std::chrono::milliseconds until(Clock::time_point t, std::chrono::milliseconds at_most) {
  const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(t - Clock::now());
  return std::clamp(left, std::chrono::milliseconds(0), at_most);
}

uint64_t random_id() {
  std::random_device rd;
  return ((uint64_t{rd()} << 32) | rd()) | 1;  // never 0
}

}  // namespace

DdsPlanner::DdsPlanner(const dds::Participant& participant, const dds::QosProfile& profile,
                       const grid::Grid& grid, std::size_t robots, int window_steps,
                       DdsPlannerOptions options)
    : participant_(participant),
      grid_(grid),
      robots_(robots),
      window_steps_(window_steps),
      options_(options),
      run_id_(random_id()),
      from_planners_(dds::admit_roles(participant, {"planner"})),
      info_in_(participant, profile, from_planners_),
      problem_out_(participant, profile),
      request_out_(participant, profile),
      waitset_(participant) {
  waitset_.attach_status(info_in_.handle(), DDS_DATA_AVAILABLE_STATUS, kInfoTag);
  if (auto why = await_planner(); !why.empty()) throw std::runtime_error(why);
  replies_from_chosen_ = std::make_unique<dds::WriterAdmission>(
      [guid = *chosen_participant_, proven = dds::admit_roles(participant, {"planner"})](
          const dds_builtintopic_endpoint_t& writer) {
        if (std::memcmp(writer.participant_key.v, guid.v, sizeof(guid.v)) != 0) {
          return dds::Verdict::kRefuse;
        }
        return proven ? proven(writer) : dds::Verdict::kAdmit;
      });
  reply_in_.emplace(participant, profile, *replies_from_chosen_);
  waitset_.attach_status(reply_in_->handle(), DDS_DATA_AVAILABLE_STATUS, kReplyTag);
  wire::PlanProblemBuffer problem(run_id_, chosen_, grid, robots, window_steps);
  problem_out_.write(problem.view());
  spdlog::info("lifelong: {} plans run '{}'", wire::describe_planner(chosen_), participant.run());
}

// Announcements heard now, checked; `heard` (may be null) collects the live ones; the chosen
// planner's leaving is noted in gone_.
void DdsPlanner::take_announcements(std::vector<smart_msg_PlannerInfo>* heard) {
  for (const auto& [writer, n] : from_planners_.take_refused()) {
    if (rejected_.count(smart_msg_TOPIC_PLANNER, dds::kNotRunMember, {}, n)) {
      spdlog::warn("lifelong: {} planner announcement(s) from {} ignored: {}", n,
                   dds::describe_sender(info_in_.participant_of(writer)), dds::kNotRunMember);
    }
  }
  for (;;) {
    auto samples = info_in_.take();
    if (samples.empty()) break;
    for (auto s : samples) {
      const auto& m = s.data();  // key fields are set in invalid samples too
      if (!s.alive()) {
        if (chosen_participant_ && m.planner_id == chosen_.planner_id && gone_.empty()) {
          gone_ = wire::describe_planner(chosen_) + " left the run; no more windows from it";
        }
        continue;
      }
      if (!s.valid() || heard == nullptr) continue;
      const auto from = s.info().publication_handle;
      auto why = wire::check_planner_info(m);
      const auto parts = info_in_.partitions_of(from);
      if (why.empty() && parts &&
          *parts != std::vector<std::string>{participant_.run_partition()}) {
        why = "written to partitions other than exactly this run's (a wildcard reaches every run)";
      }
      if (why.empty()) {
        if (std::none_of(heard->begin(), heard->end(),
                         [&](const auto& h) { return h.planner_id == m.planner_id; })) {
          heard->push_back(m);
          writer_of_[m.planner_id] = from;
        }
      } else if (rejected_.count(smart_msg_TOPIC_PLANNER, why)) {
        spdlog::warn("lifelong: a planner announcement from {} ignored: {}",
                     dds::describe_sender(info_in_.participant_of(from)), why);
      }
    }
  }
}

std::string DdsPlanner::await_planner() {
  spdlog::info(
      "lifelong: waiting up to {} s for a planner; start one with: smart planner --domain {} "
      "--run {}",
      options_.wait_s, participant_.domain_id(), participant_.run());
  const auto deadline = after(options_.wait_s);
  std::optional<Clock::time_point> settled, latest;
  std::vector<smart_msg_PlannerInfo> heard;
  // Settled: settle_s after the first announcement, once every matched announcer was heard (two
  // planners started together are discovered at about the same time, and the earlier started
  // must win however late it is heard), and at the latest 5 x settle_s after the first.
  const auto all_heard = [&] { return info_in_.matched_writers().size() <= writer_of_.size(); };
  while (!settled || ((Clock::now() < *settled || !all_heard()) && Clock::now() < *latest)) {
    if (options_.stop != nullptr && options_.stop->load()) return "stopped waiting for a planner";
    if (!settled && Clock::now() >= deadline) {
      return "--planner external: no planner announced itself on run '" + participant_.run() +
             "', domain " + std::to_string(participant_.domain_id()) + " within " +
             exact(options_.wait_s) + " s; start one with `smart planner --domain " +
             std::to_string(participant_.domain_id()) + " --run " + participant_.run() +
             "` (same --qos, --run-key and --security as the run; docs/planner-protocol.md)";
    }
    take_announcements(&heard);
    if (!heard.empty() && !settled) {
      settled = after(options_.settle_s);
      latest = after(5 * options_.settle_s);
    }
    (void)waitset_.wait(until(settled ? *settled : deadline, std::chrono::milliseconds(100)));
  }
  chosen_ = heard[wire::choose_planner(heard)];
  chosen_participant_ = info_in_.participant_of(writer_of_[chosen_.planner_id]);
  if (!chosen_participant_) {
    return "--planner external: " + wire::describe_planner(chosen_) +
           " left before the run began; start it again";
  }
  for (const auto& other : heard) {
    if (other.planner_id == chosen_.planner_id) continue;
    spdlog::warn("lifelong: a second {} is refused: {} plans run '{}'",
                 wire::describe_planner(other), wire::describe_planner(chosen_),
                 participant_.run());
  }
  return {};
}

void DdsPlanner::refuse_sample(const std::string& why, dds_instance_handle_t writer) {
  const auto who = dds::describe_sender(reply_in_->participant_of(writer));
  if (rejected_.count(kReplyTopic, why, who)) {
    spdlog::warn("lifelong: a plan reply from {} ignored: {}", who, why);
  }
}

std::optional<std::string> DdsPlanner::take_replies(const planning::WindowRequest& request,
                                                    lifelong::PlannedWindow& out) {
  for (const auto& [writer, n] : replies_from_chosen_->take_refused()) {
    const auto why = "not from the run's chosen " + wire::describe_planner(chosen_) +
                     (participant_.run_key() ? " proven with the run's key" : "");
    const auto who = dds::describe_sender(reply_in_->participant_of(writer));
    if (rejected_.count(kReplyTopic, why, who, n)) {
      spdlog::warn("lifelong: {} plan reply(ies) from {} ignored: {}", n, who, why);
    }
  }
  for (;;) {
    auto samples = reply_in_->take();
    if (samples.empty()) break;
    for (auto s : samples) {
      if (!s.valid()) continue;
      const auto& r = s.data();
      const auto writer = s.info().publication_handle;
      if (r.planner_id != chosen_.planner_id) {
        refuse_sample("planner id " + std::to_string(r.planner_id) + " is not the run's chosen " +
                          wire::describe_planner(chosen_),
                      writer);
        continue;
      }
      if (r.run_id != run_id_ || r.window < window_) continue;  // another run's, or late
      if (r.window > window_) {
        refuse_sample("a reply to window " + std::to_string(r.window) + ", not yet asked", writer);
        continue;
      }
      if (auto why = wire::check_reply(r, robots_, static_cast<uint32_t>(request.steps));
          !why.empty()) {
        return "malformed: " + why;
      }
      if (r.error[0] != '\0') return std::string("the planner's error: ") + r.error;
      auto paths = wire::paths_of(r);
      if (auto why = lifelong::check_window(grid_, request, paths); !why.empty()) return why;
      out.paths = std::move(paths);
      return std::string();
    }
  }
  return std::nullopt;
}

std::string DdsPlanner::exchange(const planning::WindowRequest& request,
                                 lifelong::PlannedWindow& out) {
  const auto deadline = after(options_.timeout_s);
  request_buffer_.set(run_id_, chosen_.planner_id, window_, options_.budget_s, request);
  request_out_.write(request_buffer_.view());
  for (;;) {
    if (auto verdict = take_replies(request, out)) return *verdict;
    take_announcements(nullptr);
    if (!gone_.empty()) return gone_;
    if (Clock::now() >= deadline) {
      return "late: no reply within " + exact(options_.timeout_s) +
             " s (--planner-timeout-s); robots stop at the cut";
    }
    (void)waitset_.wait(until(deadline, std::chrono::milliseconds(200)));
  }
}

void DdsPlanner::submit(planning::WindowRequest request) {
  ++window_;
  answer_ =
      external_window("--planner external", window_, std::string("external: ") + chosen_.name,
                      gone_, [&](lifelong::PlannedWindow& out) { return exchange(request, out); });
}

std::optional<lifelong::PlannedWindow> DdsPlanner::poll() {
  return std::exchange(answer_, std::nullopt);
}

}  // namespace smart::tools
