// Contract: the monitor's end of lifelong planning over DDS (`smart run|monitor --lifelong
// --planner external`; idl/smart.idl, "Lifelong planning over DDS"; docs/planner-protocol.md).
// The edge: construction waits (at most wait_s of wall time) for planners to announce themselves
// in the run (after the first, until every matched announcer was heard: settle_s to 5 x
// settle_s), chooses one (wire::choose_planner), logs the others as refused and writes the run's
// problem naming the chosen one, which makes every other planner of the run refuse to plan and
// exit. Per window it writes a request and takes the chosen planner's reply to it within
// `timeout_s` of wall time. A reply is heard only from the chosen planner's participant (and,
// with a run key, only from writers proven in the planner role; under DDS Security only the
// planner identity may write one); it passes wire::check_reply and lifelong::check_window. A
// window is refused, with the reason as PlannedWindow::error and in the log, when the reply
// collides, jumps, leaves the map, starts elsewhere than the cut, is malformed, is the planner's
// error or is late; once the chosen planner has left the run, every later window is refused at
// once. Replies to earlier windows (late ones) are skipped; replies from any other participant
// are filtered out before they reach the reader (dds/admission.hpp) and counted. submit() blocks
// for at most timeout_s: lock-step runs call it inline, real-time runs on a ThreadedPlanner.
// Memory: Cyclone keeps the latest reply per planner (keep-last 1); this edge one request.
#pragma once

#include <dds/dds.h>

#include <atomic>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "smart/convert/plan_wire.hpp"
#include "smart/convert/validate.hpp"
#include "smart/dds/waitset.hpp"
#include "smart/dds/wire.hpp"
#include "smart/grid/grid.hpp"
#include "smart/lifelong/window_planner.hpp"

namespace smart::tools {

struct DdsPlannerOptions {
  double wait_s = 60;      // wall seconds to wait for a planner's announcement
  double settle_s = 0.5;   // after the first, for planners started with it to be heard
  double timeout_s = 2.0;  // wall seconds per window, request and reply
  double budget_s = 0;     // told to the planner: sim seconds it is charged per call
  const std::atomic<bool>* stop = nullptr;  // set (Ctrl-C): stop waiting for a planner
};

class DdsPlanner final : public lifelong::WindowPlanner {
 public:
  // Throws std::runtime_error naming the run, the domain and the command that starts a planner
  // when none announced itself in time (or `stop` was set).
  DdsPlanner(const dds::Participant& participant, const dds::QosProfile& profile,
             const grid::Grid& grid, std::size_t robots, int window_steps,
             DdsPlannerOptions options);
  void submit(planning::WindowRequest request) override;
  std::optional<lifelong::PlannedWindow> poll() override;
  const smart_msg_PlannerInfo& chosen() const { return chosen_; }
  const wire::Rejections& rejections() const { return rejected_; }

 private:
  std::string await_planner();
  void take_announcements(std::vector<smart_msg_PlannerInfo>* heard);
  std::string exchange(const planning::WindowRequest& request, lifelong::PlannedWindow& out);
  // The reply to this window among the samples now in the reader: nothing yet, or the verdict.
  std::optional<std::string> take_replies(const planning::WindowRequest& request,
                                          lifelong::PlannedWindow& out);
  void refuse_sample(const std::string& why, dds_instance_handle_t writer);

  const dds::Participant& participant_;
  const grid::Grid& grid_;
  std::size_t robots_;
  int window_steps_;
  DdsPlannerOptions options_;
  uint64_t run_id_;
  dds::WriterAdmission from_planners_;
  dds::WireReader<smart_msg_PlannerInfo> info_in_;
  // Made once the planner is chosen: its admission hears that planner's participant only, so a
  // stranger's reply can neither displace the planner's in the reader's history nor be taken.
  std::unique_ptr<dds::WriterAdmission> replies_from_chosen_;
  std::optional<dds::WireReader<smart_msg_PlanReply>> reply_in_;
  dds::WireWriter<smart_msg_PlanProblem> problem_out_;
  dds::WireWriter<smart_msg_PlanRequest> request_out_;
  dds::WaitSet waitset_;
  smart_msg_PlannerInfo chosen_{};
  std::optional<dds_guid_t> chosen_participant_;
  std::map<uint64_t, dds_instance_handle_t> writer_of_;  // announced planner -> its writer
  wire::PlanRequestBuffer request_buffer_;
  wire::Rejections rejected_;
  uint64_t window_ = 0;
  std::string gone_;  // why the planner answers no more (empty: it may)
  std::optional<lifelong::PlannedWindow> answer_;
};

}  // namespace smart::tools
