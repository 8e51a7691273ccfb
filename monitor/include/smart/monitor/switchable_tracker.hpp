// Contract: executes a plan as ExecutionTracker does (execution_tracker.hpp), but the passing
// order at a location may switch while the run goes (issue 29): when the robot meant to pass
// first has not been sent the action that enters the location and the robot after it is ready to
// enter, and the location is free, the two swap places (first come, first served; the
// bidirectional pairs of BTPG, Su, Veerapaneni and Li, AAAI 2024, decided online on this ADG's
// rotate/move actions and footprint-dependent locations instead of precomputed on a TPG).
//
// The ADG's Type-2 edges are kept as each location's passing order (adg.hpp: PassingOrders):
// consecutive stays of different robots, leave -> next enter; swapping two adjacent stays h, i, j,
// k -> h, j, i, k replaces i.leave -> j.enter, j.leave -> k.enter with j.leave -> i.enter,
// i.leave -> k.enter. A swap is made only when it is safe:
// - no collision: i's entering action was never sent (an action that enters a location with
//   someone after it is sent only when its robot is within `commit_actions` of it, so a delayed
//   robot has not been sent it yet); the chain h -> j -> i -> k keeps one robot at a time;
// - of use now: h has left (the location is free), so j may go at once;
// - no deadlock: no path of unfinished actions leads from i.enter to j.leave without the edge
//   being reversed (searched backwards from j.leave over unfinished predecessors, at most
//   `search_budget` actions; past it, no swap);
// - no stranding: j leaves the location again (j.leave exists), i was not there from the start.
// Chains (options.chain_locations > 1): when the deadlock search refuses j because i goes on
// ahead of it (the path it found reaches j's leaving through i's stay directly before j's at
// another location), j passes i there too, and so on, up to chain_locations locations, all
// switched at once: made on the orders, then kept only when none of the new edges (h -> j,
// j -> i, i -> k at each) closes a cycle, otherwise undone before anything is sent (i's entry at
// each must be unsent, j must leave each again). switchable_chain.cpp.
// Deterministic: the robots whose situation changed are tried in id order after each progress.
// The deadlock search is bounded by a topological order of the unfinished actions, kept up as
// the orders switch (Pearce and Kelly, "A dynamic topological sort algorithm for directed
// acyclic graphs", ACM JEA 11, 2006): a path from i.enter to j.leave passes only actions
// ordered between them, so the search never walks the actions that must happen before i.enter,
// nor those sent already (they wait for finished actions alone). Both prunes are exact: a search
// that finds a path finds the same one, and most of those that ran out of budget get an answer
// (switchable_order.cpp).
//
// Anticipation (options.anticipate, `--execution switchable-opt`): the moment an entry i is to
// be sent (its robot within `commit_actions`, nothing left to wait for) is the last moment its
// place can still change. Then the next stays at the location, j and k, are looked at with the
// times their robots are expected to arrive and leave (action_durations.hpp: learned from the
// run, delays included): j passes first when that is expected to save the fleet more than
// `margin_s` of waiting (i's, j's and k's waits compared for the orders i, j, k and j, i, k),
// under the same safety conditions. SES (Feng et al., ICAPS 2024) reschedules a whole graph's
// switchable edges by expected durations; this does it for the one edge about to be committed,
// in a window of three stays, at no search cost but the deadlock check. Robots farther than
// `horizon_actions` from the location are not expected (no switch for them). First come, first
// served then also needs an expected saving (a ready robot within `horizon_actions` of a free
// location passes a late one only when that saves waiting), and never takes an entry due now
// (its robot within `commit_actions`, nothing to wait for): plain switching would have sent it.
//
// Lookahead (options.lookahead_actions > 0, `--execution switchable-lookahead`): both decisions
// above compare the orders i, j and j, i by more than the location's queue. The actions after
// i's and j's entries (Type-1 and Type-2 successors, either order) up to lookahead_actions ahead
// of each robot and lookahead_nodes in all are given expected finish times in each order (a
// longest path under expected durations, as SES evaluates a setting of switchable edges; a
// predecessor outside them at its robot's own pace), and the order with the smaller sum of the
// robots' last such times is kept (switchable_lookahead.cpp). When j would not wait for i at the
// location, nothing can be saved and the queue's answer stands (no lookahead); so it does when
// the queue expects the swap to cost the location's robots more than one mean move (the robots
// after them seldom make that up; half the comparisons, measured). A pair is first compared
// over the first lookahead_first_nodes of its cone, and over the whole cone only when the swap
// does not lose more than one mean move there (most comparisons do, and few of those would have
// gained over the whole cone, measured). An order whose compared actions form a cycle is
// expected to take for ever; the deadlock search still decides.
// Window search (options.window_pairs > 0, with the lookahead): the widened comparison also
// sets other pairs in the cone either way (at most one a location, never the compared pair's,
// the first of each not sent its entry, the second leaving again), every setting of them, and
// compares the best setting with the pair swapped against the best with it kept, as SES's
// search does over a graph's switchable edges, over a bounded window. Only the compared pair
// may switch; the window's other pairs are set when their own turn comes, through every check
// above (a setting that closes a cycle outside the cone is never made, only expected).
// Pure.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <queue>
#include <unordered_map>
#include <utility>
#include <vector>

#include "smart/monitor/action_builder.hpp"
#include "smart/monitor/action_durations.hpp"
#include "smart/monitor/adg.hpp"
#include "smart/monitor/execution.hpp"
#include "smart/monitor/robot_set.hpp"
#include "smart/monitor/switching.hpp"

namespace smart::monitor {

class SwitchableTracker final : public Execution {
 public:
  // `orders`: the plan's (passing_orders), or a stopped run's with its switches replayed
  // (apply_switches). Paused (a resume's rebuild): progress only advances robots, nothing
  // switches and every entry due is sent in its place, as the stopped monitor had sent it;
  // until unpause().
  SwitchableTracker(const ActionPlan& actions, PassingOrders orders, SwitchOptions options = {},
                    bool paused = false);
  void unpause();

  ProgressUpdate on_progress(uint32_t robot, int64_t finished_seq, double time_s) override;
  ActionWindowRange window(uint32_t robot, uint32_t cap) const override;
  uint32_t finished(uint32_t robot) const override { return finished_[robot]; }
  uint32_t enqueued(uint32_t robot) const override { return enqueued_[robot]; }
  uint32_t known(uint32_t robot) const override { return actions_.count(robot); }
  const grid::Action& action(uint32_t robot, uint32_t seq) const override {
    return actions_.at(robot, seq);
  }
  std::size_t robots() const override { return finished_.size(); }
  std::size_t finished_total() const override { return finished_total_; }
  std::size_t total() const override { return actions_.actions.size(); }
  bool robot_done(uint32_t robot) const override {
    return finished_[robot] == actions_.count(robot);
  }
  bool complete() const override { return finished_total_ == actions_.actions.size(); }
  bool deadlocked() const override;
  std::optional<WaitCause> wait_cause(uint32_t robot) const override;

  const std::vector<PassingSwitch>* switches() const override { return &switches_; }
  // Switches made by anticipation (a part of switches()).
  std::size_t anticipated() const { return anticipated_; }
  // Switches made as parts of chains (SwitchOptions::chain_locations; a part of switches()).
  std::size_t chained() const { return chained_; }
  // Pairs compared over their cone (switchable-lookahead; tests, the bench).
  std::size_t lookahead_comparisons() const { return compared_; }
  // Of those, the ones compared over the whole cone, not the first lookahead_first_nodes alone.
  std::size_t lookahead_widened() const { return widened_; }
  // Of those, the ones searched over a window of other pairs (SwitchOptions::window_pairs), and
  // the settings of the window's pairs they compared in all.
  std::size_t lookahead_windowed() const { return windowed_; }
  std::size_t window_settings() const { return window_settings_; }
  const ActionDurations& durations() const { return durations_; }
  // The robots in location `location`'s current passing order (tests, the viewer).
  std::vector<uint32_t> order_at(uint32_t location) const;
  // The search's topological order holds on every edge between unfinished actions (tests: the
  // order is checked after switches), and it was never given up (a cycle found while ordering;
  // the search then runs unbounded by it, as before).
  bool order_holds() const;
  bool ordered() const { return ordered_; }
  // Each action's copy of its first stays' neighbours agrees with the passing orders (tests: it
  // is checked after switches, as the orders are).
  bool neighbours_hold() const;
  // Actions the deadlock search visited in all (tests, the bench).
  std::size_t search_visits() const { return search_visits_; }
  // Unfinished Type-2 predecessors of an action (node id), as the current orders give them.
  uint32_t pending(uint32_t node) const { return pending_[node]; }
  // Its Type-2 predecessors (node ids, finished or not) in the current orders, appended to out.
  void predecessors(uint32_t node, std::vector<uint32_t>& out) const;

 private:
  struct Neighbour {
    uint32_t stay = kNoAction;
    bool edge = false;  // a different robot: a Type-2 edge
  };
  Neighbour before(uint32_t stay) const;
  Neighbour after(uint32_t stay) const;
  bool finished_by(uint32_t robot, uint32_t node) const;
  bool sent_by(uint32_t robot, uint32_t node) const;
  bool committed(uint32_t robot, uint32_t node) const;
  bool needs_commit(uint32_t node) const;
  bool advance(uint32_t robot);
  bool candidate(uint32_t robot) const;
  // How far from its entry a robot may switch: commit_actions, or horizon_actions when
  // anticipating.
  uint32_t reach() const {
    return options_.anticipate ? std::max(options_.commit_actions, options_.horizon_actions)
                               : options_.commit_actions;
  }
  void consider(uint32_t stay);  // its robot may switch now: tried (dirty_) if a candidate
  void release(uint32_t node, std::vector<uint32_t>& changed);
  bool try_switch(uint32_t robot, double time_s, std::vector<uint32_t>& changed);
  void try_switches(double time_s, std::vector<uint32_t>& changed);
  enum class Reach : uint8_t { kNone, kPath, kBudget };
  // floor: the lowest place in the topological order an action on a path may have (kNoAction:
  // `from`'s; a chain's tried swaps lower it to their new edges' entries, which are not ordered
  // yet: chain_floor()).
  Reach reaches(uint32_t from, uint32_t to, uint32_t skip_from, uint32_t skip_to,
                std::vector<std::pair<uint32_t, uint32_t>>& path, uint32_t floor = kNoAction);
  void next_stamp();
  // The topological order (switchable_order.cpp).
  void init_order();
  void order_swapped(const std::vector<uint32_t>& stays);
  bool order_edge(uint32_t from, uint32_t to);
  bool order_walk(uint32_t start, uint32_t bound, bool forward, uint32_t stop,
                  std::vector<uint32_t>& out);
  bool unordered(uint32_t from, uint32_t to) const;
  // The Type-2 edges into `node` (f(the leave before it)) and out of it (f(the entry after it)),
  // as the current orders give them.
  template <class F>
  void each_edge_in(uint32_t node, F&& f) const {
    for (uint32_t i = enter_begin_[node]; i < enter_begin_[node + 1]; ++i) {
      const auto b = before(enter_stays_[i]);
      if (b.edge && stay_[b.stay].leave != kNoAction) f(stay_[b.stay].leave);
    }
  }
  template <class F>
  void each_edge_out(uint32_t node, F&& f) const {
    for (uint32_t i = leave_begin_[node]; i < leave_begin_[node + 1]; ++i) {
      const auto next = after(leave_stays_[i]);
      if (next.edge && stay_[next.stay].enter != kNoAction) f(stay_[next.stay].enter);
    }
  }
  bool has_edge(uint32_t from, uint32_t to) const;
  bool still_refused(uint32_t robot, uint32_t node, uint32_t theirs) const;
  bool path_holds(uint32_t robot) const;
  void refuse(uint32_t robot, bool by_path);
  void forget_refusal(uint32_t robot);
  void unsettle(uint32_t stay);
  void unsettle_watchers(uint32_t node);
  void swap_with_next(uint32_t stay, std::vector<uint32_t>& changed);
  void relink(uint32_t stay);
  void settle(uint32_t j);
  // Chains (switchable_chain.cpp).
  bool try_chain(uint32_t i, const std::vector<std::pair<uint32_t, uint32_t>>& path, double time_s,
                 std::vector<uint32_t>& changed, bool anticipated = false);
  uint32_t chain_link(const std::vector<std::pair<uint32_t, uint32_t>>& path, uint32_t first,
                      uint32_t second) const;
  Reach chain_cycle(const std::vector<uint32_t>& chain);
  uint32_t chain_floor(const std::vector<uint32_t>& chain) const;
  template <class F>
  void each_chain_edge(const std::vector<uint32_t>& chain, F&& f) const;
  void undo_chain(const std::vector<uint32_t>& chain);
  void redo_chain(const std::vector<uint32_t>& chain);
  // switchable-lookahead with chains: a chain's orders compared with the plan's over one cone.
  bool compares_chains() const {
    return options_.lookahead_actions > 0 && options_.chain_locations > 1;
  }
  bool chain_saves(const std::vector<uint32_t>& chain, double margin_s);
  uint32_t blocking_stay(uint32_t robot, uint32_t node) const;
  // Anticipation.
  void observe(uint32_t robot, uint32_t from, uint32_t upto, double time_s);
  double finish_estimate(uint32_t robot, uint32_t seq) const;
  grid::ActionType kind(uint32_t node) const;
  bool turn_at(uint32_t robot, uint32_t seq) const;  // seq is a turn (false past the last)
  double arrival(uint32_t stay) const;
  PassQueue queue_of(uint32_t i, uint32_t j) const;
  static double expected_saving(const PassQueue& q);
  bool anticipate(uint32_t robot, double time_s, std::vector<uint32_t>& changed);
  void decide(uint32_t robot, std::vector<uint32_t>& changed);
  // Lookahead (switchable_lookahead.cpp).
  struct Swap {
    uint32_t i = kNoAction, j = kNoAction;  // adjacent stays, i before j in the current order
    bool swapped = false;                   // read as h, j, i, k
  };
  uint32_t next_in(uint32_t stay, const Swap& s) const;
  uint32_t prev_in(uint32_t stay, const Swap& s) const;
  void collect_cone(const Swap& s, std::size_t nodes, bool extend = false);
  template <bool kExtend>
  void walk_cone(const Swap& s, std::size_t nodes);
  void init_look();
  double expect(uint32_t node, const Swap& s);
  double cone_cost(const Swap& s);
  double saving(uint32_t i, uint32_t j);
  double margin() const {
    return options_.lookahead_actions > 0 ? options_.lookahead_margin_s : options_.margin_s;
  }
  double cone_saving(uint32_t i, uint32_t j, std::size_t nodes, bool window = false);
  void collect_window(const Swap& s);
  double window_saving(const Swap& s);
  double lookahead_saving(uint32_t i, uint32_t j);

  const ActionPlan& actions_;
  // Each location's stay ids in plan order (begin); its stays are moved to stay_.
  PassingOrders orders_;
  std::vector<uint32_t> location_;  // stay id -> location
  // stay id -> the stays before and after it at its location (kNoAction: none): the current
  // order as a list, one lookup for a neighbour (an array of positions took four).
  struct Link {
    uint32_t prev = kNoAction, next = kNoAction;
  };
  // node -> the robot and entry of the stay after the first stay it leaves, and the robot and
  // leaving of the stay before the first stay it enters (kNoAction: none; kept up by link_prev()
  // and link_next() as the orders change); a node's other stays (a footprint's second location)
  // are read from link_ and stay_ (near_of()). Read by the cone's walk, expect() and
  // blocking_stay(). Kept per stay, they were the walk's largest cache miss (stay ids are grouped
  // by location, so a robot's consecutive actions' stays lie far apart); per node, a robot's next
  // actions share a cache line (docs/execution.md, "A robot's next actions read together"). Kept
  // out of Link, whose 8 bytes the tries and releases read (in it, they made those slower).
  // Also whether the stay after the node's first entered stay is another robot's that leaves
  // again (needs_commit(): read as a robot's next action is sent, from the line the tries read).
  // (A bit of next_robot's word: 16 bytes, four nodes a cache line; a bool of its own made the
  // record 20 bytes and the tries' misses grew by what needs_commit's fell.)
  struct Near {
    uint32_t next_robot : 31 = 0, shared_next : 1 = 0;
    uint32_t next_enter = kNoAction;
    uint32_t prev_robot = 0, prev_leave = kNoAction;
  };
  Near near_of(uint32_t stay) const;
  bool shares_next(uint32_t stay) const;
  void link_prev(uint32_t stay, uint32_t prev);
  void link_next(uint32_t stay, uint32_t next);
  std::vector<Link> link_;
  std::vector<Near> near_;                           // node -> its first stays' neighbours
  std::vector<Stay> stay_;                           // stay id -> the stay
  std::vector<uint32_t> enter_begin_, enter_stays_;  // node -> stays it enters (CSR)
  std::vector<uint32_t> leave_begin_, leave_stays_;  // node -> stays it leaves (CSR)
  SwitchOptions options_;
  bool paused_ = false;
  std::vector<uint32_t> pending_;
  std::vector<uint32_t> finished_, enqueued_;
  std::size_t finished_total_ = 0;
  RobotSet dirty_;  // robots to try, smallest id first (deterministic): their situation changed
  // A ready robot whose switch the comparison declined (no saving expected) is tried again once
  // as much time has passed as the switch was expected to lose, at least kRetryS, doubled at each
  // decline of the same entry: the answer rests on the expected times of the robots it compares,
  // which move as they progress or fall behind, and nothing else would try the robot again while
  // it waits (retry_declined). Earliest first, then by robot: deterministic.
  struct Retry {
    double at_s = 0;
    uint32_t robot = 0, node = 0;
    bool operator>(const Retry& o) const {
      return at_s != o.at_s ? at_s > o.at_s : (robot != o.robot ? robot > o.robot : node > o.node);
    }
  };
  std::priority_queue<Retry, std::vector<Retry>, std::greater<>> retries_;
  static constexpr double kRetryS = 2.0;
  // Per robot (anticipating executions): the entry last declined, and how often in a row.
  std::vector<uint32_t> declined_node_;
  std::vector<uint8_t> declines_;
  void decline(uint32_t robot, uint32_t node, double gain);
  void retry_declined(double time_s);
  // Per node, the deadlock search's stamp and the node's robot side by side: the search reads
  // both for every action it meets, where reading the plan's action (48 bytes) cost a cache miss
  // of its own. On LaCAM's 1000-robot plan under delays the search took 6.3 % of the monitor's
  // CPU under switchable, 5.9 % so (one run each; docs/execution.md, "Cost").
  // And its place in the topological order (ord): the search reads it for each action too.
  struct Mark {
    uint32_t seen = 0, robot = 0, ord = 0;
  };
  std::vector<Mark> mark_;
  uint32_t stamp_ = 0;
  std::size_t search_visits_ = 0;
  bool ordered_ = true;  // mark_'s ord is a topological order (false: given up, never again)
  std::vector<std::pair<uint32_t, uint32_t>> unordered_;  // new edges not ordered yet
  std::vector<uint32_t> forward_, backward_, pool_;       // one edge's reordering (scratch)
  std::vector<PassingSwitch> switches_;
  // Per robot, its last refused switch: the entry, the stay it would pass, and why.
  struct Refusal {
    uint32_t node = kNoAction, theirs = kNoAction;
    uint32_t epoch = 0;                               // switches made when searched
    uint32_t id = 0;                                  // refusals made before it
    std::vector<std::pair<uint32_t, uint32_t>> path;  // the Type-2 edges of a path found
    bool by_path = false;
  };
  std::vector<std::pair<uint32_t, uint32_t>> chain_path_;  // a chain's cycle search
  std::vector<uint32_t> parent_;                           // search tree
  std::vector<uint32_t> stack_;  // search frontier (kept: no allocation per search)
  std::vector<Refusal> refused_;
  uint32_t refusals_ = 0;
  RobotSet with_refusal_;  // robots whose refused_ names an entry
  // Robots whose refusal a switch may have lifted (past the budget, the stay it would pass
  // changed, an edge of its path switched away): tried again after each switch; the others
  // would be refused again. A refusal ends when its entry is sent. Before, every robot with a
  // refusal, however old, was tried after every switch: about 420 a switch at 1000 robots, most
  // of switchable-opt's decision time (docs/execution.md, "Cost").
  RobotSet unsettled_;
  struct Watcher {
    uint32_t robot, refusal;  // Refusal::id: a later refusal of the robot makes it stale
  };
  // A leave -> the refusals whose path has a Type-2 edge from it.
  std::unordered_map<uint32_t, std::vector<Watcher>> watchers_;
  // Anticipation: expected durations, and when each robot's current action started.
  ActionDurations durations_;
  double now_s_ = 0;
  std::vector<double> started_s_;  // robot -> when its first unfinished action started (or now)
  // robot -> its action now (seq finished_) is a turn: wait_cause() read it from the plan's
  // 48-byte action, a cache miss a blocker (docs/performance.md, "Wait causes read from records,
  // and robots without a goal ranked without a table").
  std::vector<uint8_t> turning_;
  std::vector<uint64_t> turn_bits_;  // node -> it is a turn, a bit each
  // location -> changes of its order so far (link_prev and link_next count them).
  std::vector<uint32_t> epoch_;
  // A waiting robot's next action's stays and the stays before them, kept while their
  // locations' orders do not change: the run supervisor asks a waiting robot every 0.5 s, and
  // each ask read five stay- and node-indexed arrays, a cache miss each (docs/performance.md,
  // "Wait causes read from records, and robots without a goal ranked without a table").
  // Mutable: a cache of what the orders say.
  struct WaitLook {
    static constexpr uint32_t kKept = 4;  // a node entering more stays is read each time
    struct Before {
      uint32_t location = 0, epoch = 0;
      bool edge = false;  // the stay before is another robot's
      Stay stay;          // that stay (a copy: stays never change)
    };
    uint32_t node = kNoAction, count = 0;
    std::array<Before, kKept> before{};
    bool valid(uint32_t at, const std::vector<uint32_t>& epoch) const;
    void fill(const SwitchableTracker& t, uint32_t at);
  };
  mutable std::vector<WaitLook> wait_look_;
  std::vector<uint8_t> decided_;  // node -> its place was decided when it was to be sent
  RobotSet ahead_;                // robots whose next entry awaits that decision
  std::size_t anticipated_ = 0;
  std::vector<uint32_t> moves_before_;  // node -> moves before it in the plan (prefix sums)
  // Lookahead: the actions a pair's order affects (cone_); per action, the comparison whose cone
  // it is in and the order whose expected finish `time_s` is computed (NaN while computed: a
  // cycle), with the action's robot, place and kind, in one place: one cache line per action
  // looked at (reading the plan's actions too cost a miss each in the monitor's runs).
  // Also the first stays the action enters and leaves and how many of each (255: count them in
  // enter_begin_, leave_begin_; the rest: enter_stays_, leave_stays_), read by the cone's walk
  // and expect() where the action's record is already in cache. Its place in its robot's queue
  // is node - actions_.offset[robot] (a table of a few kB).
  struct alignas(32) Look {
    uint32_t cone = 0, order = 0;
    double time_s = 0;
    uint32_t robot = 0;
    uint32_t enter = kNoAction, leave = kNoAction;
    grid::ActionType type = grid::ActionType::kMove;
    uint8_t enters = 0, leaves = 0;
  };
  static uint32_t stays_of(uint8_t count, const std::vector<uint32_t>& begin, uint32_t node) {
    return count < 255 ? count : begin[node + 1] - begin[node];
  }
  static_assert(sizeof(Look) == 32);
  void next_mark(uint32_t& id, uint32_t Look::*mark);  // a new cone or order id
  std::vector<uint32_t> cone_, cone_robot_;            // the compared actions and their robots
  std::vector<uint32_t> walk_, walk_robot_;            // a second walk's (chain_saves; scratch)
  std::vector<Look> look_;
  uint32_t cone_id_ = 0, order_id_ = 0;
  std::size_t compared_ = 0, widened_ = 0;
  // The window's pairs: each the stay its first robot holds, passed by the stay after it.
  std::vector<uint32_t> window_;
  std::size_t windowed_ = 0, window_settings_ = 0;
  std::size_t chained_ = 0;
};

}  // namespace smart::monitor
