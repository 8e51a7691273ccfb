// Contract: the Action Dependency Graph of a lifelong run, grown window by window while it is
// executed (SMART §IV-B and Hönig et al. 2019 for the graph; the commit cut of Lifelong SMART,
// smart-mapf/lifelong-smart, for where a new window may begin). Pure: no clock, no I/O.
//
// Execution, as ExecutionTracker (execution_tracker.hpp): an action is enqueued once its robot's
// previous action is enqueued and every Type-2 predecessor finished; progress is cumulative per
// robot (finishing seq k finishes every seq <= k); progress out of range, stale or for an
// action never enqueued is refused and changes nothing. Seqs grow for the life of the run; the
// graph keeps only unfinished actions (finished ones are dropped as they finish, so memory stays
// flat however long the run), and every robot's position after its last finished action.
//
// Growth:
// - commit_cut(keep, lookahead): per robot, every action already sent to it (`keep[r]`, which the
//   robot may be executing), at least `lookahead` unfinished actions beyond what it finished, then
//   closed: an action kept keeps every unfinished Type-2 predecessor (and so its robot's actions
//   before it), and a cut never ends on an edge midpoint (the next half-move is kept), so every
//   robot stops on a cell and no kept action waits for one that is dropped. Closure is a worklist
//   fixpoint over in-edges, O(kept actions + their edges).
// - truncate(cut): drops every action beyond the cut (never sent, so no robot knows them).
// - append(paths, plan_time_s): each robot's timed cells from its cut cell (paths[r][0]), turned
//   into rotate/half-move actions continuing its seqs and heading; Type-2 edges, per location,
//   between consecutive occupants in plan order: the last kept occupant (the kept unfinished
//   action leaving it latest) before the window's occupants sorted by arrival (the robot standing
//   there first). Old actions never wait for new ones, so a cycle could only lie inside the
//   window; Kahn's algorithm over the new actions checks it, and a window that is cyclic, or has a
//   robot enter a location where another stays for good, is refused whole (nothing appended).
// Locations are half cells (Footprint::kHalfCells); robots of the cells footprint are refused.
//
// Switching (enable_switching, issue 29; the rule of switchable_tracker.hpp on the growing
// graph): robot j's next unsent move into location L waits only for robot i leaving L; i's move
// into L was never sent (a move beginning a stay someone follows is sent only within
// `commit_actions` of its robot), i is not at L and has no earlier stay there, whoever was before
// i has left, j leaves L again and never comes back within the graph, and no path of unfinished
// actions leads from i's entry to j's leave (bounded search) -> the order becomes j, i: j.leave ->
// i.enter replaces i.leave -> j.enter, and whoever followed j now follows i. The stays' order keys
// (the leaves' pass keys, by which a later window finds the last occupant) are exchanged, so the
// next append links behind the order as it is now. Robots to try are those whose situation
// changed, in id order: deterministic. Chains (SwitchOptions::chain_locations > 1,
// live_adg_chain.cpp): when the search refuses j because i goes on ahead of it, j passes i at
// each next location the search shows i ahead too (up to chain_locations at once, waiting there
// for whoever i waited for), kept only when none of the new edges closes a cycle.
//
// switchable-opt (SwitchOptions::anticipate; switchable_tracker.hpp, "Anticipation", the same
// rule on the growing graph): action durations are learned from the progress reports
// (action_durations.hpp) and
// - first come, first served reaches robots up to `horizon_actions` from their entry, and
//   switches only when the pair's order j, i is expected to save waiting (queue_saving: i, j and
//   the robot after j); it never takes an entry that is due (its robot within `commit_actions`,
//   nothing to wait for);
// - a due entry i is decided before it is sent: the robot j next at its location passes first
//   when that is expected to save more than `margin_s`, under the same safety conditions.
// Every due entry is decided before on_progress (or append) returns: none waits for a decision
// between reports.
//
// switchable-lookahead (SwitchOptions::lookahead_actions > 0; switchable_tracker.hpp,
// "Lookahead"; live_adg_lookahead.cpp): both decisions compare the pair's two orders by the
// expected finish times of the unfinished actions reachable from i's and j's entries (their
// robots' next actions and the entries waiting for their leaves, either order) up to
// lookahead_actions ahead of each robot and lookahead_nodes in all, first over
// lookahead_first_nodes of them; an anticipated switch must save lookahead_margin_s. The same
// skips: the location's queue answers when j would not wait for i, or when it expects the swap to
// lose more than one mean move. An order whose compared actions form a cycle costs for ever.
// With SwitchOptions::window_pairs, the widened comparison also sets up to that many other pairs
// of the cone either way (switchable_tracker.hpp, "Window search"): each setting's edges are
// exchanged and the nodes they touched restored from a copy before anything is sent.
#pragma once

#include <boost/container/small_vector.hpp>
#include <cstdint>
#include <functional>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "smart/monitor/action_builder.hpp"
#include "smart/monitor/action_durations.hpp"
#include "smart/monitor/execution.hpp"
#include "smart/monitor/execution_tracker.hpp"
#include "smart/monitor/ring.hpp"
#include "smart/monitor/switching.hpp"
#include "smart/monitor/vocabulary.hpp"

namespace smart::monitor {

struct NodeRef {
  uint32_t robot = 0;
  uint32_t seq = 0;
  bool operator==(const NodeRef&) const = default;
};

struct CommitCut {
  std::vector<uint32_t> end;  // per robot: one past the last kept seq
  std::vector<Cell> cell;     // where each robot stands after its kept actions
  std::vector<Heading> heading;
  std::size_t kept_unfinished = 0;  // actions kept and not finished (all robots)
};

struct AppendStats {
  std::size_t actions = 0;
  std::size_t type2 = 0;
};

class LiveAdg final : public Execution {
 public:
  using Update = ExecutionTracker::Update;
  using Window = ExecutionTracker::Window;

  LiveAdg(const Grid& grid, const std::vector<Cell>& start, Heading initial_heading);

  // --- execution ---
  // `finished` sees each action this progress finishes, in order, before it is dropped;
  // `time_s` stamps the switches it allows.
  Update on_progress(uint32_t robot, int64_t finished_seq, double time_s,
                     const std::function<void(const Action&)>& finished);
  Update on_progress(uint32_t robot, int64_t finished_seq, double time_s) override {
    return on_progress(robot, finished_seq, time_s, std::function<void(const Action&)>{});
  }
  Window window(uint32_t robot, uint32_t cap) const override;
  std::size_t robots() const override { return robots_.size(); }
  uint32_t finished(uint32_t r) const override { return robots_[r].finished; }
  uint32_t enqueued(uint32_t r) const override { return robots_[r].enqueued; }
  uint32_t end(uint32_t r) const { return robots_[r].base + uint32_t(robots_[r].nodes.size()); }
  uint32_t known(uint32_t r) const override { return end(r); }
  // An unfinished action: seq in [finished(r), end(r)).
  const Action& action(uint32_t r, uint32_t seq) const override { return node(r, seq).action; }
  bool robot_done(uint32_t) const override { return false; }
  std::size_t total() const override { return appended_total_; }
  bool complete() const override { return false; }  // a growing graph has no end of its own
  std::size_t finished_total() const override { return finished_total_; }
  std::size_t appended_total() const { return appended_total_; }
  std::size_t unfinished_total() const { return appended_total_ - finished_total_; }
  std::size_t type2_total() const { return type2_total_; }
  // No robot has an enqueued unfinished action, yet some remain.
  bool deadlocked() const override;
  // Where the robot stands after its last finished action: a cell or an edge midpoint.
  HalfCell after_finished(uint32_t r) const { return robots_[r].done; }
  Heading heading_after_finished(uint32_t r) const { return robots_[r].done_heading; }
  // Every robot's unfinished Type-2 predecessors of (r, seq) (tests and viewers: who it waits for).
  std::vector<NodeRef> waits_for(uint32_t r, uint32_t seq) const;
  // Why robot r waits (execution.hpp WaitCause), if it does (enqueued == finished): nullopt when
  // it has an action to execute. O(its blockers' actions up to their leaves).
  std::optional<WaitCause> wait_cause(uint32_t r) const override;

  // --- growth ---
  CommitCut commit_cut(const std::vector<uint32_t>& keep, uint32_t lookahead) const;
  void truncate(const CommitCut& cut);
  // Problems name the robots and locations of a refused window (nothing appended then).
  std::vector<Problem> append(const std::vector<std::vector<Cell>>& paths, double plan_time_s,
                              AppendStats* stats = nullptr);
  // The plan time of the last appended window's first step (its steps are one plan time unit
  // apart; a window starts where the previous one ended or at its append time, the later).
  double window_start() const { return window_start_; }

  // --- switching (before the first append) ---
  void enable_switching(SwitchOptions options) { switching_ = options; }
  const std::vector<PassingSwitch>* switches() const override {
    return switching_ ? &switches_ : nullptr;
  }
  // Pairs compared over their cone, and of those the ones compared over the whole cone
  // (switchable-lookahead; tests, the bench).
  std::size_t lookahead_comparisons() const { return compared_; }
  std::size_t lookahead_widened() const { return widened_; }
  // Of those, the ones searched over a window of other pairs (SwitchOptions::window_pairs), and
  // the settings of the window's pairs they compared in all.
  std::size_t lookahead_windowed() const { return windowed_; }
  std::size_t window_settings() const { return window_settings_; }
  // Switches made as parts of chains (SwitchOptions::chain_locations; a part of switches()).
  std::size_t chained() const { return chained_; }

 private:
  // Most actions have at most two Type-2 edges each way: kept inline (no allocation per node,
  // boost::container::small_vector), which halves an append's time at 10 000 robots.
  using Refs = boost::container::small_vector<NodeRef, 2>;
  // NOLINTNEXTLINE(bugprone-exception-escape): clang-tidy 14 flags the implicit special members
  struct Node {
    Action action;
    double pass_key = 0;   // a move: orders its leave among the location's last occupants
    uint32_t stamp = 0;    // the deadlock search's visit mark
    NodeRef parent{};      // and the action it came from
    uint32_t pending = 0;  // unfinished Type-2 predecessors
    double sent_s = 0;     // switchable-opt: when it was sent
    uint32_t cone = 0;     // switchable-lookahead: the comparison whose cone holds it,
    uint32_t order = 0;    // the order whose expected finish look_s is,
    double look_s = 0;     // and that finish
    Refs in;               // unfinished Type-2 predecessors
    Refs out;              // Type-2 successors
  };
  struct Robot {
    uint32_t base = 0;  // seq of nodes.front()
    // The unfinished actions: finishing pops the front, a window pushes at the back, and slots
    // (with their edge lists' storage) are reused, so memory settles at the longest queue.
    Ring<Node> nodes;
    uint32_t finished = 0;
    uint32_t enqueued = 0;
    HalfCell done;  // after its last finished action (its start before any)
    Heading done_heading = Heading::kEast;
    Cell tail_cell;  // after its last appended action
    Heading tail_heading = Heading::kEast;
    double finished_s = 0;  // switchable-opt: when its last action finished
  };
  // A window's actions, robot by robot: robot r's are all[first[r] .. first[r + 1]).
  struct NewActions {
    std::vector<Action> all;
    std::vector<uint32_t> first;
  };
  struct Occupancy;

  Node& node(uint32_t r, uint32_t seq) { return robots_[r].nodes[seq - robots_[r].base]; }
  const Node& node(uint32_t r, uint32_t seq) const {
    return robots_[r].nodes[seq - robots_[r].base];
  }
  bool advance(uint32_t r);
  void finish(uint32_t r, uint32_t seq, Update& u);
  std::vector<Problem> build_window(const std::vector<std::vector<Cell>>& paths, double t0,
                                    NewActions& acts, double& t_end) const;
  std::vector<Occupancy> occupancies(const NewActions& acts) const;
  std::vector<Problem> link(const std::vector<Occupancy>& occ,
                            std::vector<std::pair<NodeRef, NodeRef>>& edges) const;
  std::vector<Problem> check_window_acyclic(
      const NewActions& acts, const std::vector<std::pair<NodeRef, NodeRef>>& edges) const;
  void insert(const NewActions& acts, const std::vector<std::pair<NodeRef, NodeRef>>& edges);

  static void erase_ref(Refs& v, NodeRef x);
  WaitCause blocker_state(NodeRef leave) const;
  static uint32_t pop_first(std::set<uint32_t>& robots);
  // Switching (live_adg_switching.cpp).
  bool held(uint32_t r, uint32_t seq) const;
  bool shared(uint32_t r, uint32_t seq) const;
  bool anticipating() const { return switching_ && switching_->anticipate; }
  bool due(NodeRef enter) const;
  uint32_t reach() const;
  std::optional<uint32_t> next_move(uint32_t r, uint32_t after_seq) const;
  bool stays_before(uint32_t r, uint32_t seq, uint32_t location) const;
  bool comes_back(uint32_t r, uint32_t after_seq, uint32_t location) const;
  void dirty_after_release(NodeRef target);
  void try_switches(double time_s, std::vector<uint32_t>& changed);
  bool try_switch(uint32_t j, double time_s, std::vector<uint32_t>& changed);
  enum class Reach : uint8_t { kNone, kPath, kBudget };
  Reach reaches(NodeRef from, NodeRef to, NodeRef skip_from, NodeRef skip_to,
                std::vector<std::pair<NodeRef, NodeRef>>& path);
  bool has_edge(NodeRef from, NodeRef to) const;
  bool still_refused(uint32_t j, NodeRef mine, NodeRef theirs) const;
  void add_edge(NodeRef from, NodeRef to);
  void remove_edge(NodeRef from, NodeRef to);
  void swap_order(NodeRef i_enter, NodeRef i_leave, NodeRef j_enter, NodeRef j_leave);
  // switchable-opt (live_adg_anticipation.cpp).
  void observe(uint32_t r, uint32_t upto, double time_s);
  double finish_estimate(uint32_t r, uint32_t seq) const;
  double arrival(NodeRef enter) const;
  // A pair of stays at one location, i before j now (i's entry waits for nobody).
  struct Pair {
    NodeRef i_enter, i_leave, j_enter, j_leave;
  };
  // Its queue at the location: when i and j are expected there, when i is expected to leave, and
  // the waiting j passing first is expected to save (queue_saving).
  struct PairQueue {
    double i_arrive_s = 0, j_arrive_s = 0, i_leave_s = 0, saving = 0;
  };
  PairQueue queue_of(const Pair& p) const;
  bool anticipate(uint32_t i, double time_s, std::vector<uint32_t>& changed);
  void decide(uint32_t r, std::vector<uint32_t>& changed);
  bool decide_due(uint32_t r, bool may_switch, double time_s, std::vector<uint32_t>& changed);
  void settle_due(double time_s, std::vector<uint32_t>& changed);
  std::optional<Pair> switchable_pair(NodeRef i_leave, NodeRef j_enter) const;
  // Chains (live_adg_chain.cpp).
  std::optional<Pair> chain_link(const std::vector<std::pair<NodeRef, NodeRef>>& path, uint32_t i,
                                 uint32_t j) const;
  void chain_swap(const Pair& p);
  Reach chain_cycle();
  // switchable-lookahead with chains: a chain's edges compared with the graph's over one cone.
  bool compares_chains() const {
    return switching_ && switching_->lookahead_actions > 0 && switching_->chain_locations > 1;
  }
  bool chain_saves(const std::vector<Pair>& chain, double margin_s);
  void undo_chain();
  bool try_chain(const Pair& first, const std::vector<std::pair<NodeRef, NodeRef>>& path,
                 double time_s, std::vector<uint32_t>& changed, bool anticipated = false);
  // switchable-lookahead (live_adg_lookahead.cpp).
  double margin() const;
  void clear_marks(uint32_t Node::*mark);  // every unfinished action's
  double saving(const Pair& p);
  double lookahead_saving(const Pair& p);
  double cone_saving(const Pair& p, std::size_t nodes, bool window = false);
  void collect_window(const Pair& p);
  double window_saving(const Pair& p);
  void exchange_edges(const Pair& p);
  void collect_cone(const Pair& p, std::size_t nodes, bool extend = false);
  void successors(const Pair& p, NodeRef u, bool swapped, std::vector<NodeRef>& out) const;
  double expect(NodeRef n, const Pair& p, bool swapped);
  double cone_cost(const Pair& p, bool swapped);

  const Grid& grid_;
  std::vector<Robot> robots_;
  std::size_t finished_total_ = 0;
  std::size_t appended_total_ = 0;
  std::size_t type2_total_ = 0;
  double last_plan_time_s_ = 0;
  double window_start_ = 0;
  std::optional<SwitchOptions> switching_;
  std::vector<PassingSwitch> switches_;
  std::set<uint32_t> dirty_;  // robots to try: their situation changed since they were tried
  // Per robot, its last refused switch (the move and the leave it waits for): still refused
  // while the Type-2 edges of the path that showed the cycle are there and nothing was truncated
  // (live_adg_switching.cpp still_refused), or, past the search budget, while the graph's orders
  // are unchanged (`epoch_`: switches and truncations).
  struct Refusal {
    NodeRef mine{}, theirs{};
    uint64_t epoch = 0, truncations = 0;
    bool valid = false;
    bool by_path = false;
    std::vector<std::pair<NodeRef, NodeRef>> path;
  };
  std::vector<Refusal> refused_;
  uint64_t epoch_ = 0;
  uint64_t truncations_ = 0;
  uint32_t stamp_ = 0;
  // switchable-opt: learned durations, the latest time told, robots whose next entry is due and
  // awaits its decision.
  ActionDurations durations_;
  double now_s_ = 0;
  std::set<uint32_t> ahead_;
  mutable std::vector<ActionType> types_;  // scratch
  // switchable-lookahead: the compared actions, comparison and order ids (Node::cone, order).
  std::vector<NodeRef> cone_;
  std::vector<NodeRef> walk_;  // one walk of the cone (scratch)
  std::vector<NodeRef> next_;  // scratch
  uint32_t cone_id_ = 0;
  uint32_t order_id_ = 0;
  std::size_t compared_ = 0;
  std::size_t widened_ = 0;
  // The window search: its pairs, the edges of the nodes a setting changes (restored exactly
  // after each), and its counts.
  std::vector<Pair> window_;
  // NOLINTNEXTLINE(bugprone-exception-escape): clang-tidy 14 flags the implicit special members
  struct SavedEdges {
    NodeRef ref{};
    Refs in, out;
    uint32_t pending = 0;
  };
  std::vector<SavedEdges> saved_;
  std::size_t windowed_ = 0, window_settings_ = 0;
  // Chains: while logging_, every edge added or removed and every pass-key exchange is logged,
  // so a chain that closes a cycle is undone exactly; the last cycle search's path.
  struct EdgeOp {
    bool added = false;
    NodeRef from{}, to{};
  };
  bool logging_ = false;
  std::vector<EdgeOp> chain_log_;
  std::vector<std::pair<NodeRef, NodeRef>> chain_keys_;
  std::vector<std::pair<NodeRef, NodeRef>> chain_path_;
  std::size_t chained_ = 0;
};

}  // namespace smart::monitor
