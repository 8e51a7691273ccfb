#include "smart/tools/pipe_planner.hpp"

#include <spdlog/spdlog.h>

#include <chrono>
#include <stdexcept>
#include <utility>

#include "smart/lifelong/plan_protocol.hpp"
#include "smart/tools/cli_common.hpp"
#include "smart/tools/external_window.hpp"

namespace smart::tools {

namespace {

using Clock = std::chrono::steady_clock;
using Io = common::PipedProcess::Io;

// Wall seconds a planner has to read the map and say it is ready.
constexpr double kStartTimeoutS = 30;

Clock::time_point after(double s) {
  return Clock::now() +
         std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s));
}

std::size_t reply_bound(const PipePlannerOptions& o, std::size_t robots, int steps) {
  if (o.max_reply_bytes > 0) return o.max_reply_bytes;
  return robots * (static_cast<std::size_t>(steps) + 1) * 32 + 65536;
}

std::string seconds(double s) { return exact(s) + " s"; }

}  // namespace

PipePlanner::PipePlanner(const grid::Grid& grid, std::size_t robots, int window_steps,
                         PipePlannerOptions options)
    : grid_(grid), robots_(robots), options_(std::move(options)), process_(options_.command) {
  options_.max_reply_bytes = reply_bound(options_, robots, window_steps);
  const auto deadline = after(kStartTimeoutS);
  std::string line;
  auto io = process_.write_line(lifelong::encode_start(grid, robots, window_steps), deadline);
  if (io == Io::kOk) io = process_.read_line(line, options_.max_reply_bytes, deadline);
  std::string why;
  if (io == Io::kOk) {
    const auto ready = lifelong::decode_ready(line);
    if (ready.ok) {
      name_ = ready.name;
      return;
    }
    why = ready.reason;
  } else if (io == Io::kTimeout) {
    why = "did not answer its start line within " + seconds(kStartTimeoutS);
  } else if (io == Io::kTooLong) {
    why = "answered its start line with a line longer than the bound";
  } else {
    const auto code = process_.exit_code(std::chrono::milliseconds(500));
    why = "exited before it was ready" +
          (code ? " (exit code " + std::to_string(*code) + ")" : std::string()) +
          "; run the command by hand to see why";
  }
  throw std::runtime_error("--planner-cmd '" + options_.command + "' " + why +
                           " (docs/planner-protocol.md)");
}

std::string PipePlanner::closed() {
  const auto code = process_.exit_code(std::chrono::milliseconds(500));
  gone_ = "the planner closed its output" +
          (code ? " and exited with code " + std::to_string(*code) : std::string()) +
          "; no more windows from it";
  return gone_;
}

// The reply to this window, or why there is none.
std::string PipePlanner::exchange(const planning::WindowRequest& request,
                                  lifelong::PlannedWindow& out) {
  const auto deadline = after(options_.timeout_s);
  const auto line = lifelong::encode_request(window_, request.time_s, options_.budget_s, request);
  switch (process_.write_line(line, deadline)) {
    case Io::kOk:
      break;
    case Io::kTimeout:
      gone_ = "the planner stopped reading its input (a request was not taken within " +
              seconds(options_.timeout_s) + ")";
      return gone_;
    default:
      return closed();
  }
  std::string reply;
  for (;;) {
    switch (process_.read_line(reply, options_.max_reply_bytes, deadline)) {
      case Io::kOk:
        break;
      case Io::kTimeout:
        return "late: no reply within " + seconds(options_.timeout_s) +
               " (--planner-timeout-s); robots stop at the cut";
      case Io::kTooLong:
        return "a reply longer than " + std::to_string(options_.max_reply_bytes) +
               " bytes was dropped";
      case Io::kClosed:
        return closed();
    }
    auto r = lifelong::decode_reply(reply, window_, robots_);
    if (r.kind == lifelong::PlanReply::Kind::kStale) continue;  // an earlier window's, late
    if (r.kind != lifelong::PlanReply::Kind::kWindow) return r.reason;
    if (auto why = lifelong::check_window(grid_, request, r.paths); !why.empty()) return why;
    out.paths = std::move(r.paths);
    return {};
  }
}

void PipePlanner::submit(planning::WindowRequest request) {
  ++window_;
  answer_ = external_window("--planner-cmd", window_,
                            "external" + (name_.empty() ? std::string() : ": " + name_), gone_,
                            [&](lifelong::PlannedWindow& out) { return exchange(request, out); });
}

std::optional<lifelong::PlannedWindow> PipePlanner::poll() {
  return std::exchange(answer_, std::nullopt);
}

}  // namespace smart::tools
