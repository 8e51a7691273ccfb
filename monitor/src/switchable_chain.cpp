// SwitchableTracker's chains (switching.hpp, SwitchOptions::chain_locations): a ready robot j
// whose switch with i was refused because the deadlock search found i going on ahead of it
// (the path from i's entry enters j's leaving through i's stay directly before j's at the next
// location) passes i at that location too, and so on along their shared way, all at once. One
// location at a time each such switch closes a cycle; together they may not. Measured on plain
// ADG's runs, such waits are 18-55 % of all waiting on random-64-64-10 (docs/execution.md,
// "What switching can reach"). The swaps are made on the order and the pending counts only,
// checked, and undone when any new edge closes a cycle: no action is sent in between.
#include <algorithm>

#include "smart/monitor/switchable_tracker.hpp"

namespace smart::monitor {

// The stay of `first` right before a stay of `second` whose entry the path's last Type-2 edge
// from first to second enters (that edge is first's leave -> second's entry there), if first's
// entry there may still be switched; kNoAction otherwise.
uint32_t SwitchableTracker::chain_link(const std::vector<std::pair<uint32_t, uint32_t>>& path,
                                       uint32_t first, uint32_t second) const {
  for (std::size_t n = path.size(); n-- > 0;) {  // the last edge first
    const auto& e = path[n];
    if (actions_.actions[e.first].robot != first || actions_.actions[e.second].robot != second) {
      continue;
    }
    for (uint32_t k = leave_begin_[e.first]; k < leave_begin_[e.first + 1]; ++k) {
      const uint32_t i = leave_stays_[k];
      const auto j = after(i);
      if (!j.edge || stay_[j.stay].enter != e.second) continue;
      const Stay& a = stay_[i];
      const Stay& b = stay_[j.stay];
      if (a.enter == kNoAction || committed(first, a.enter) || b.leave == kNoAction) {
        return kNoAction;
      }
      return i;
    }
    return kNoAction;
  }
  return kNoAction;
}

// The new edges u -> v of the chain's swaps (h -> j, j -> i, i -> k at each: each stay i now
// after the j it was before), as f(u's leave, v's entry), in the order chain_cycle searches them.
template <class F>
void SwitchableTracker::each_chain_edge(const std::vector<uint32_t>& chain, F&& f) const {
  for (const uint32_t i : chain) {
    const uint32_t j = before(i).stay, h = before(j).stay, k = after(i).stay;
    for (const auto& [u, v] : {std::pair{j, i}, std::pair{h, j}, std::pair{i, k}}) {
      if (u == kNoAction || v == kNoAction || stay_[u].robot == stay_[v].robot) continue;
      const uint32_t leave = stay_[u].leave, enter = stay_[v].enter;
      if (leave == kNoAction || enter == kNoAction || finished_by(stay_[u].robot, leave)) continue;
      if (!f(leave, enter)) return;
    }
  }
}

// Any cycle the swaps of `chain` close goes through one of their new edges u -> v, so through a
// path from v to u: searched for each, the last path found left in chain_path_.
SwitchableTracker::Reach SwitchableTracker::chain_cycle(const std::vector<uint32_t>& chain) {
  const uint32_t floor = chain_floor(chain);
  Reach r = Reach::kNone;
  each_chain_edge(chain, [&](uint32_t leave, uint32_t enter) {
    chain_path_.clear();
    r = reaches(enter, leave, kNoAction, kNoAction, chain_path_, floor);
    return r == Reach::kNone;
  });
  return r;
}

// The lowest place in the topological order an action on a path between unfinished actions may
// have while the chain's swaps are made: the order holds on every edge but the chain's new ones,
// so a path goes up the order from its start, and from the entry each new edge leads to. The
// searches skip what is below (exact: no path from an entry can reach it, so they find the same
// paths; only searches that ran out of budget may now finish; docs/execution.md, "A chain's
// cycle checks bounded by the order").
uint32_t SwitchableTracker::chain_floor(const std::vector<uint32_t>& chain) const {
  uint32_t floor = kNoAction;
  each_chain_edge(chain, [&](uint32_t, uint32_t enter) {
    floor = std::min(floor, mark_[enter].ord);
    return true;
  });
  return floor == kNoAction ? 0 : floor;
}

// `i` (before j, the ready robot's stay) refused by `path`: j passes i at i's location and at
// each next location where the path shows i ahead, until no cycle closes (switched, recorded,
// true) or the chain cannot grow (undone, false).
bool SwitchableTracker::try_chain(uint32_t i,
                                  const std::vector<std::pair<uint32_t, uint32_t>>& path,
                                  double time_s, std::vector<uint32_t>& changed, bool anticipated) {
  const uint32_t passed = stay_[i].robot, ready = stay_[after(i).stay].robot;
  std::vector<uint32_t> chain{i};
  // The stay each one passes, taken before it is relinked: with two stays of the robot passed
  // at one location, the one before a stay afterwards may be its own.
  std::vector<uint32_t> passes{after(i).stay};
  relink(i);
  uint32_t next = chain_link(path, passed, ready);
  for (;;) {
    if (next == kNoAction || chain.size() >= options_.chain_locations ||
        std::find(chain.begin(), chain.end(), next) != chain.end()) {
      break;
    }
    // Expected times (switchable-opt, -lookahead): j passes only where they expect it to save
    // there too. Without this check the robot passed found a saving in passing back at those
    // locations: 24-62 thousand switches a run at 200-750 robots (docs/execution.md, "Chains").
    // The lookahead compares the whole chain once it closes no cycle (chain_saves): one
    // location at a time its compared actions may close one and cost for ever.
    if (options_.anticipate && !compares_chains() && !(saving(next, after(next).stay) > 0)) {
      break;
    }
    passes.push_back(after(next).stay);
    relink(next);
    chain.push_back(next);
    const Reach r = chain_cycle(chain);
    if (r == Reach::kNone && compares_chains() &&
        !chain_saves(chain, anticipated ? margin() : 0.0)) {
      return false;  // undone
    }
    if (r == Reach::kNone) {
      order_swapped(chain);
      for (std::size_t n = 0; n < chain.size(); ++n) {
        const uint32_t s = chain[n];
        switches_.push_back({time_s, location_[s], ready, passed, anticipated,
                             stay_[passes[n]].enter, stay_[s].enter});
        settle(before(s).stay);
      }
      if (anticipated) anticipated_ += chain.size();
      chained_ += chain.size();
      if (advance(ready)) changed.push_back(ready);
      return true;
    }
    if (r == Reach::kBudget) break;
    next = chain_link(chain_path_, passed, ready);
  }
  undo_chain(chain);
  return false;
}

// The chain's swaps undone (the last first) and made again (in the order they were made).
void SwitchableTracker::undo_chain(const std::vector<uint32_t>& chain) {
  for (std::size_t n = chain.size(); n-- > 0;) relink(before(chain[n]).stay);
}

void SwitchableTracker::redo_chain(const std::vector<uint32_t>& chain) {
  for (const uint32_t s : chain) relink(s);
}

// The lookahead's comparison of a chain that closes no cycle (try_chain): over the actions
// walked from the first location's pair in the orders before the swaps and in the chain's, each
// walk cut on its own, so that the robot passed, comparing the chain back, gets the same actions
// and the opposite answer (one walk, in the orders before the swaps alone, swapped pairs back
// and forth: 19-57 thousand switches a run at 750 robots). The chain saves when the fleet's
// expected finish of those actions is sooner; otherwise the swaps are undone here. It must save
// more than `margin_s`: nothing for first come, first served, the lookahead's margin for
// anticipation, as for one location.
// The first walk is made here, with the swaps undone for it, not before the chain is built:
// most chains close a cycle or stop before they are compared, and the walk made for each of
// them was 59 % of the cone's walks in the replay bench (docs/execution.md, "A chain's cone
// walked when it is compared").
bool SwitchableTracker::chain_saves(const std::vector<uint32_t>& chain, double margin_s) {
  ++compared_;
  ++widened_;
  const uint32_t i = chain.front();
  undo_chain(chain);
  collect_cone({i, after(i).stay, false}, options_.lookahead_nodes);
  redo_chain(chain);
  collect_cone({before(i).stay, i, false}, options_.lookahead_nodes, true);
  const double chained_cost = cone_cost(Swap{});  // unswapped: the orders as they are now
  undo_chain(chain);
  const double kept_cost = cone_cost(Swap{});
  if (!(kept_cost - chained_cost > margin_s)) return false;
  redo_chain(chain);
  return true;
}

}  // namespace smart::monitor
