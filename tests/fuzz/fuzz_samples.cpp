// Fuzz target: every DDS sample handler, with samples made of raw fuzz bytes (as a rogue on the
// wire could send them): the edge checks (wire/validate.hpp), then, for what passes, what the
// receivers do with it: a window becomes agent actions in an ActionQueue; progress, states,
// ticks and sim status become RunSupervisor events; answers drive the host's handshake; a sim
// shard's exchange is checked; lifelong planning samples (convert/plan_wire.hpp) are checked, and
// what passes becomes a request for a planner or a window checked for execution.
#include <vector>

#include "fuzz_input.hpp"
#include "smart/agent/action_queue.hpp"
#include "smart/convert/convert.hpp"
#include "smart/convert/plan_wire.hpp"
#include "smart/convert/validate.hpp"
#include "smart/lifelong/plan_protocol.hpp"
#include "smart/monitor/adg.hpp"
#include "smart/monitor/run_supervisor.hpp"
#include "support/monitor_fixtures.hpp"

namespace {

using namespace smart;

struct NullWriter : monitor::RunWriter {
  void publish_window(uint32_t, uint64_t, monitor::ExecutionTracker::Window) override {}
  void answer_tick(const wire::Tick&) override {}
};

const monitor::Instance& corridor() {
  static const monitor::Instance in = [] {
    monitor::Instance i;
    i.grid = test::grid_of({"....", ".@.."});
    i.plan = test::plan_of({{{1, 0}, {2, 0}, {3, 0}}, {{0, 0}, {0, 0}, {1, 0}}});
    i.scen = test::scen_of(i.plan, i.grid);
    i.actions = monitor::build_actions(i.plan, monitor::Heading::kEast);
    std::vector<grid::Problem> problems;
    i.adg = monitor::build_adg(i.actions, i.grid, "fuzz", problems);
    return i;
  }();
  return in;
}

constexpr std::size_t kRobots = 2;

// Cyclone's deserializer (dds_stream_normalize) lets no boolean other than 0/1 and no enum value
// past the last enumerator through, so raw samples are made to keep that; the rest is arbitrary.
smart_msg_ActionStep step(fuzz::Bytes& in) {
  auto s = in.take<smart_msg_ActionStep>();
  s.type = static_cast<smart_msg_ActionType>(in.take<uint8_t>() % 2);
  return s;
}
smart_msg_Clock clock(fuzz::Bytes& in) {
  auto c = in.take<smart_msg_Clock>();
  c.stop = (in.take<uint8_t>() & 1) != 0;
  return c;
}

void window(fuzz::Bytes& in, agent::ActionQueue& queue, const wire::Bounds& bounds) {
  smart_msg_ActionWindow w = in.take<smart_msg_ActionWindow>();
  std::vector<smart_msg_ActionStep> steps(in.take<uint8_t>() % 8);
  for (auto& s : steps) s = step(in);
  w.actions._buffer = steps.data();
  w.actions._length = w.actions._maximum = static_cast<uint32_t>(steps.size());
  w.actions._release = false;
  if (!wire::check_window(w, kRobots, bounds).empty()) return;
  (void)queue.apply(w.run_id, wire::actions_from_wire(w));
}

// A sim shard's exchange (sim/shard.hpp) with fuzz-sized nested sequences: the check must read
// only what the sequences hold, whatever their contents (the sim host's use of what passes is
// tested in tests/sim/shard_wire_test.cpp and the sharded runs).
template <class T>
std::vector<T> items(fuzz::Bytes& in) {
  std::vector<T> v(in.take<uint8_t>() % 4);
  for (auto& x : v) x = in.take<T>();
  return v;
}
template <class T, class Seq>
void borrow(Seq& seq, std::vector<T>& v) {
  seq._length = seq._maximum = static_cast<uint32_t>(v.size());
  seq._buffer = v.empty() ? nullptr : v.data();
  seq._release = false;
}

void exchange(fuzz::Bytes& in, const wire::Bounds& bounds) {
  auto e = in.take<smart_msg_ShardExchange>();
  auto handovers = items<smart_msg_RobotHandover>(in);
  std::vector<std::vector<smart_msg_PairContact>> pairs;
  std::vector<std::vector<smart_msg_QueuedAction>> pending;
  for (std::size_t i = 0; i < handovers.size(); ++i) {
    pairs.push_back(items<smart_msg_PairContact>(in));
    pending.push_back(items<smart_msg_QueuedAction>(in));
    for (auto& a : pending.back())
      a.type = static_cast<smart_msg_ActionType>(in.take<uint8_t>() % 2);
  }
  for (std::size_t i = 0; i < handovers.size(); ++i) {
    borrow(handovers[i].pairs, pairs[i]);
    borrow(handovers[i].pending, pending[i]);
  }
  auto ghosts = items<smart_msg_GhostRobot>(in);
  auto progress = items<smart_msg_Progress>(in);
  auto states = items<smart_msg_RobotState>(in);
  borrow(e.handovers, handovers);
  borrow(e.ghosts, ghosts);
  borrow(e.progress, progress);
  borrow(e.states, states);
  (void)wire::check_exchange(e, kRobots, bounds);
}

// Cyclone's deserializer ends every bounded string within its bound.
template <std::size_t N>
void terminate(char (&text)[N]) {
  text[N - 1] = '\0';
}

void plan_problem(fuzz::Bytes& in) {
  auto p = in.take<smart_msg_PlanProblem>();
  terminate(p.planner.name);
  terminate(p.planner.host);
  p.width %= 9;
  p.height %= 9;
  auto blocked = items<uint8_t>(in);
  if (in.take<uint8_t>() % 2) blocked.assign(std::size_t{p.width} * p.height, in.take<uint8_t>());
  borrow(p.blocked, blocked);
  if (!wire::check_problem(p).empty()) return;
  const auto g = wire::grid_of(p);
  (void)g.free_cells();
}

// A request for the corridor's two robots, then a reply to it: what passes the wire checks is
// converted and the window checked as the monitor checks it.
void plan_exchange(fuzz::Bytes& in, const grid::Grid& grid) {
  auto r = in.take<smart_msg_PlanRequest>();
  auto starts = items<smart_msg_GridCell>(in), errands = items<smart_msg_GridCell>(in);
  auto headings = items<uint8_t>(in);
  auto counts = items<uint32_t>(in);
  borrow(r.starts, starts);
  borrow(r.errands, errands);
  borrow(r.headings, headings);
  borrow(r.errand_counts, counts);
  if (!wire::check_request(r, grid, kRobots).empty()) return;
  const auto request = wire::request_of(r);
  auto reply = in.take<smart_msg_PlanReply>();
  terminate(reply.error);
  reply.steps %= 4;
  auto cells = items<smart_msg_GridCell>(in);
  if (in.take<uint8_t>() % 2) cells.resize(kRobots * (std::size_t{reply.steps} + 1));
  borrow(reply.cells, cells);
  if (!wire::check_reply(reply, kRobots, r.steps).empty()) return;
  (void)lifelong::check_window(grid, request, wire::paths_of(reply));
}

void one_sample(fuzz::Bytes& in, monitor::RunSupervisor& sup, agent::ActionQueue& queue,
                wire::HostHandshake& host, const wire::Bounds& bounds, double now_s) {
  switch (in.take<uint8_t>() % 9) {
    case 7:
      return plan_problem(in);
    case 8:
      return plan_exchange(in, corridor().grid);
    case 0:
      return window(in, queue, bounds);
    case 1: {
      const auto p = in.take<smart_msg_Progress>();
      if (wire::check_progress(p, kRobots).empty())
        sup.on_progress({p.robot_id, p.run_id, p.finished_seq}, now_s);
      return;
    }
    case 2: {
      const auto s = in.take<smart_msg_RobotState>();
      if (wire::check_state(s, kRobots, bounds).empty())
        sup.on_state({s.robot_id, s.run_id, s.pose.x_m, s.pose.y_m}, now_s);
      return;
    }
    case 3: {
      const auto c = clock(in);
      if (wire::check_clock(c).empty()) sup.on_clock(wire::from_wire(c), now_s);
      return;
    }
    case 4: {
      const auto s = in.take<smart_msg_SimStatus>();
      if (wire::check_status(s, kRobots).empty()) {
        sup.on_sim_status({s.run_id, s.robot_contacts, s.wall_contacts, s.min_gap_m, s.peak_rss_mb,
                           s.first_contact_a, s.first_contact_b, s.sim_time_s});
      }
      return;
    }
    case 5:
      return exchange(in, bounds);
    default: {
      const auto c = clock(in);
      if (wire::check_clock(c).empty()) host.on_answer(wire::from_wire(c));
      (void)host.may_step(c.run_id, in.take<uint32_t>());
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto& in = corridor();
  NullWriter writer;
  monitor::SupervisorConfig config;
  config.run_id = 7;
  monitor::RunSupervisor sup(in, config, writer);
  agent::ActionQueue queue;
  wire::HostHandshake host(5.0, 0.5);
  const auto bounds = wire::bounds_of(in.grid, 1.0);
  sup.start(0);
  fuzz::Bytes bytes(data, size);
  for (double now_s = 0; !bytes.empty(); now_s += 0.01) {
    one_sample(bytes, sup, queue, host, bounds, now_s);
    sup.poll(now_s);
  }
  sup.finish(1e6);
  sup.conclude();
  return 0;
}
