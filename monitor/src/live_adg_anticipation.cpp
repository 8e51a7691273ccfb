// LiveAdg's switchable-opt (live_adg.hpp, "switchable-opt"): the expected times of
// SwitchableTracker's anticipation (switchable_tracker.hpp) on the growing graph, where a stay is
// read off the actions as in live_adg_switching.cpp (a move enters the location, its robot's next
// move leaves it).
#include <algorithm>
#include <cmath>
#include <limits>

#include "smart/monitor/live_adg.hpp"

namespace smart::monitor {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}  // namespace

// A report of one finished action is a duration sample: from its start (the previous finish, or
// its sending when later) to now. Several at once are no sample (their split is unknown).
void LiveAdg::observe(uint32_t r, uint32_t upto, double time_s) {
  auto& rb = robots_[r];
  if (upto == rb.finished + 1) {
    const Node& n = node(r, rb.finished);
    durations_.observe(n.action.type, time_s - std::max(rb.finished_s, n.sent_s));
  }
  rb.finished_s = time_s;
}

// When robot r is expected to finish its action `seq` (unfinished).
double LiveAdg::finish_estimate(uint32_t r, uint32_t seq) const {
  const auto& rb = robots_[r];
  if (seq < rb.finished) return now_s_;
  types_.clear();
  for (uint32_t s = rb.finished; s <= seq; ++s) types_.push_back(action(r, s).type);
  const double started =
      rb.enqueued > rb.finished ? std::max(rb.finished_s, node(r, rb.finished).sent_s) : -1.0;
  return durations_.finish_s(now_s_, started, types_);
}

// When a robot is expected at the location its move `enter` enters: when it finishes the action
// before; infinite for a robot more than horizon_actions away (not expected anywhere yet).
double LiveAdg::arrival(NodeRef enter) const {
  const uint32_t finished = robots_[enter.robot].finished;
  if (enter.seq <= finished) return now_s_;
  if (enter.seq - finished > switching_->horizon_actions) return kInf;
  return finish_estimate(enter.robot, enter.seq - 1);
}

// Expected waiting saved by passing j before i (i's entry waits for nobody: the location is
// free now); the robot after j waits for the last of the two. Infinite when i is not expected
// (j goes), minus infinite when j is not.
LiveAdg::PairQueue LiveAdg::queue_of(const Pair& p) const {
  const double ai = arrival(p.i_enter), aj = arrival(p.j_enter);
  if (!std::isfinite(aj)) return {ai, aj, kInf, -kInf};
  if (!std::isfinite(ai)) return {ai, aj, kInf, kInf};
  double ak = kInf;
  for (const NodeRef k : node(p.j_leave.robot, p.j_leave.seq).out) {
    if (k.robot != p.i_enter.robot) {
      ak = arrival(k);
      break;
    }
  }
  const double fi = finish_estimate(p.i_leave.robot, p.i_leave.seq);
  const double dj = finish_estimate(p.j_leave.robot, p.j_leave.seq) - aj;
  return {ai, aj, fi, queue_saving({now_s_, {ai, fi - ai}, {aj, dj}, ak})};
}

// Robot i's next entry is due: the robot j that follows its stay passes first when expected to
// save more than margin_s and it is safe (try_switch's conditions, read from i's side). True
// when switched (i then waits for j's leave; decided again when it is due again).
bool LiveAdg::anticipate(uint32_t i, double time_s, std::vector<uint32_t>& changed) {
  const uint32_t seq = robots_[i].enqueued;
  if (seq >= end(i) || node(i, seq).pending != 0 || !shared(i, seq)) return false;
  const NodeRef i_enter{i, seq}, i_leave{i, *next_move(i, seq)};
  const auto location = static_cast<uint32_t>(grid_.half_index(action(i, seq).to));
  if (stays_before(i, seq, location)) return false;
  const Refs followers = node(i, i_leave.seq).out;
  for (const NodeRef j_enter : followers) {
    const Node& theirs = node(j_enter.robot, j_enter.seq);
    if (theirs.pending != 1 || theirs.in.size() != 1 || theirs.action.type != ActionType::kMove ||
        grid_.half_index(theirs.action.to) != location) {
      continue;
    }
    const uint32_t j = j_enter.robot;
    const auto leave = next_move(j, j_enter.seq);
    if (!leave || comes_back(j, *leave, location)) continue;
    const NodeRef j_leave{j, *leave};
    const Pair pair{i_enter, i_leave, j_enter, j_leave};
    const double gain = saving(pair);
    // A chain only where the location's queue expects it to save more than the margin
    // (SwitchableTracker::anticipate says why).
    const bool whole_chain =
        compares_chains() && std::isinf(gain) && gain < 0 && queue_of(pair).saving > margin();
    if (gain <= margin() && !whole_chain) continue;
    std::vector<std::pair<NodeRef, NodeRef>> path;
    const Reach r = reaches(i_enter, j_leave, i_leave, j_enter, path);
    if (r == Reach::kPath && whole_chain && try_chain(pair, path, time_s, changed, true)) {
      return true;
    }
    if (r != Reach::kNone || whole_chain) continue;
    switches_.push_back({time_s, location, j, i, true});
    swap_order(i_enter, i_leave, j_enter, j_leave);
    if (advance(j)) changed.push_back(j);
    return true;
  }
  return false;
}

// The due entry keeps its place: it is sent, with what follows it.
void LiveAdg::decide(uint32_t r, std::vector<uint32_t>& changed) {
  auto& rb = robots_[r];
  if (rb.enqueued >= end(r) || node(r, rb.enqueued).pending != 0) return;  // it waits again
  node(r, rb.enqueued).sent_s = now_s_;
  ++rb.enqueued;
  advance(r);
  changed.push_back(r);
}

// Every due entry decided (anticipation first, then sent) before the graph is left to wait for
// the next report; each decision may make another entry due (the loop ends: each one sends an
// action or switches one of finitely many unsent stays, bounded as try_switches is).
void LiveAdg::settle_due(double time_s, std::vector<uint32_t>& changed) {
  std::size_t budget = 4 * robots_.size() + 16;
  while (!ahead_.empty()) {
    const bool may_switch = budget > 0;
    if (may_switch) --budget;
    decide_due(pop_first(ahead_), may_switch, time_s, changed);
  }
}

// Robot r's due entry: passed by the robot after it (anticipation, when allowed; true), or sent.
bool LiveAdg::decide_due(uint32_t r, bool may_switch, double time_s,
                         std::vector<uint32_t>& changed) {
  if (may_switch && anticipate(r, time_s, changed)) return true;
  decide(r, changed);
  return false;
}

}  // namespace smart::monitor
