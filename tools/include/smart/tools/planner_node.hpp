// Contract: the planner's end of lifelong planning over DDS (`smart planner`; idl/smart.idl,
// "Lifelong planning over DDS"; docs/planner-protocol.md). The edge: it announces itself in its
// run (PlannerInfo, again every PLAN_ANNOUNCE_MS) and waits for the run's problem. A problem that
// names another planner is a refusal: serve() returns kRefused naming that planner, as a second
// monitor is refused. A problem naming this one makes a planner for its map (`make_planner`);
// every request addressed to it is checked (wire::check_request; a bad one is answered with an
// error reply saying why), planned and answered with the paths or the planner's error, newest
// window only (a request superseded while planning is skipped). serve() returns kRunOver when
// the run's problem is gone (the monitor ended or left), kStopped when `stop` is set. Problems
// and requests are heard only from the monitor's writers when the run has a key.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "smart/convert/plan_wire.hpp"
#include "smart/convert/validate.hpp"
#include "smart/dds/waitset.hpp"
#include "smart/dds/wire.hpp"
#include "smart/lifelong/window_planner.hpp"

namespace smart::tools {

// A planner for a run's map and fleet (BuiltinPlanner in `smart planner`; fakes in tests).
using PlannerFactory = std::function<std::unique_ptr<lifelong::WindowPlanner>(
    const grid::Grid& grid, std::size_t robots)>;

class PlannerNode {
 public:
  enum class End { kRunOver, kRefused, kStopped };
  struct Outcome {
    End end = End::kStopped;
    std::string detail;    // kRefused: the refusal, naming the run's planner
    uint64_t windows = 0;  // replies written
  };
  PlannerNode(const dds::Participant& participant, const dds::QosProfile& profile,
              const std::string& name, PlannerFactory make_planner);
  const smart_msg_PlannerInfo& info() const { return self_; }
  Outcome serve(const std::atomic<bool>& stop);

 private:
  // nullopt: go on; otherwise how serving ends.
  std::optional<Outcome> take_problems();
  void take_requests();
  void answer(const smart_msg_PlanRequest& r);
  void announce_if_due();

  const dds::Participant& participant_;
  PlannerFactory make_planner_;
  smart_msg_PlannerInfo self_{};
  dds::WriterAdmission from_monitors_, requests_from_monitors_;
  dds::WireReader<smart_msg_PlanProblem> problem_in_;
  dds::WireReader<smart_msg_PlanRequest> request_in_;
  dds::WireWriter<smart_msg_PlannerInfo> info_out_;
  dds::WireWriter<smart_msg_PlanReply> reply_out_;
  dds::WaitSet waitset_;
  std::chrono::steady_clock::time_point announced_;
  wire::Rejections rejected_;
  // The run being planned (run_id 0: none yet).
  uint64_t run_id_ = 0;
  grid::Grid grid_;
  std::size_t robots_ = 0;
  std::unique_ptr<lifelong::WindowPlanner> planner_;
  uint64_t last_window_ = 0;
  wire::PlanReplyBuffer reply_;
  Outcome outcome_;
};

}  // namespace smart::tools
