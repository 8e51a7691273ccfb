// LiveAdg's chains (live_adg.hpp, "Switching"; the one-shot rule: switchable_chain.cpp and
// SwitchOptions::chain_locations): a ready robot j whose switch with i at L was refused because
// the deadlock search found i going on ahead of it (the path from i's entry to j's leave enters
// j's stay at another location L' from i's leave there) passes i at L' too, and so on along their
// shared way, all at once. One location at a time each such switch closes a cycle; together they
// may not. The swaps are made on the edges, every new edge is checked for a cycle through it, and
// all is undone (from a log of the edges added and removed) when one closes: no action is sent in
// between. On the growing graph a later location may still have a robot h before i (i's entry
// waits for it): j then waits for h there too (h, j, i).
#include <algorithm>
#include <limits>

#include "smart/monitor/live_adg.hpp"

namespace smart::monitor {

namespace {
constexpr NodeRef kNoNode{std::numeric_limits<uint32_t>::max(),
                          std::numeric_limits<uint32_t>::max()};
}  // namespace

// The pair at the location where the path's last Type-2 edge from i to j (i's leave -> j's
// entry) lies, when it may switch as try_switch's pair may (switchable_pair); nothing otherwise.
std::optional<LiveAdg::Pair> LiveAdg::chain_link(
    const std::vector<std::pair<NodeRef, NodeRef>>& path, uint32_t i, uint32_t j) const {
  for (const auto& [i_leave, j_enter] : path) {  // the path is stored from its end
    if (i_leave.robot != i || j_enter.robot != j) continue;
    if (!has_edge(i_leave, j_enter)) return std::nullopt;
    return switchable_pair(i_leave, j_enter);
  }
  return std::nullopt;
}

// j before i at the pair's location, logged: j also waits for whoever i waited for there.
void LiveAdg::chain_swap(const Pair& p) {
  const Refs before_i = node(p.i_enter.robot, p.i_enter.seq).in;
  for (const NodeRef h : before_i) {
    if (h.robot != p.j_enter.robot && !has_edge(h, p.j_enter)) add_edge(h, p.j_enter);
  }
  swap_order(p.i_enter, p.i_leave, p.j_enter, p.j_leave);
}

// Any cycle the chain's swaps close goes through one of the edges they added: searched for a
// path back from each (still there), the last path found left in chain_path_.
LiveAdg::Reach LiveAdg::chain_cycle() {
  for (const EdgeOp& op : chain_log_) {
    if (!op.added || !has_edge(op.from, op.to)) continue;
    chain_path_.clear();
    const Reach r = reaches(op.to, op.from, kNoNode, kNoNode, chain_path_);
    if (r != Reach::kNone) return r;
  }
  return Reach::kNone;
}

// Every edge the chain added removed and every edge it removed put back, the last first, and
// the leaves' order keys exchanged back.
void LiveAdg::undo_chain() {
  logging_ = false;
  for (std::size_t n = chain_log_.size(); n-- > 0;) {
    const EdgeOp& op = chain_log_[n];
    if (op.added) {
      remove_edge(op.from, op.to);
    } else {
      add_edge(op.from, op.to);
    }
  }
  for (std::size_t n = chain_keys_.size(); n-- > 0;) {
    const auto& [a, b] = chain_keys_[n];
    std::swap(node(a.robot, a.seq).pass_key, node(b.robot, b.seq).pass_key);
  }
}

// `first` (i before the ready j at L) refused by `path`: j passes i at L and at each next
// location where the path shows i ahead, until no cycle closes (switched, recorded, true) or the
// chain cannot grow (undone, false).
bool LiveAdg::try_chain(const Pair& first, const std::vector<std::pair<NodeRef, NodeRef>>& path,
                        double time_s, std::vector<uint32_t>& changed, bool anticipated) {
  const uint32_t i = first.i_enter.robot, j = first.j_enter.robot;
  if (compares_chains()) collect_cone(first, switching_->lookahead_nodes);
  std::vector<Pair> chain{first};
  chain_log_.clear();
  chain_keys_.clear();
  logging_ = true;
  chain_swap(first);
  auto next = chain_link(path, i, j);
  for (;;) {
    if (!next || chain.size() >= switching_->chain_locations ||
        std::any_of(chain.begin(), chain.end(),
                    [&](const Pair& p) { return p.j_enter == next->j_enter; })) {
      break;
    }
    // Expected times (switchable-opt): j passes only where they expect it to save there too
    // (switchable_chain.cpp says why). The lookahead compares the whole chain once it closes no
    // cycle (chain_saves): one location at a time, its compared actions may close one.
    if (anticipating() && !compares_chains() && !(saving(*next) > 0)) break;
    chain_swap(*next);
    chain.push_back(*next);
    const Reach r = chain_cycle();
    if (r == Reach::kNone && compares_chains() &&
        !chain_saves(chain, anticipated ? margin() : 0.0)) {
      return false;  // undone
    }
    if (r == Reach::kNone) {
      logging_ = false;
      for (const Pair& p : chain) {
        switches_.push_back({time_s,
                             static_cast<uint32_t>(grid_.half_index(action(j, p.j_enter.seq).to)),
                             j, i, anticipated});
      }
      chained_ += chain.size();
      if (advance(j)) changed.push_back(j);
      return true;
    }
    if (r == Reach::kBudget) break;
    next = chain_link(chain_path_, i, j);
  }
  undo_chain();
  return false;
}

// The lookahead's comparison of a chain that closes no cycle (try_chain; the one-shot
// SwitchableTracker::chain_saves says why): over the actions walked from the first location's
// pair on the graph's edges (collected before the swaps) and on the chain's (walked now), each
// walk cut on its own. When the chain saves nothing the swaps are undone here; otherwise they
// are made again from the start (the same edges, logged as before). It must save more than
// `margin_s`: nothing for first come, first served, the lookahead's margin for anticipation.
bool LiveAdg::chain_saves(const std::vector<Pair>& chain, double margin_s) {
  ++compared_;
  ++widened_;
  const Pair& p = chain.front();
  const Pair back{p.j_enter, p.j_leave, p.i_enter, p.i_leave};  // j now before i
  collect_cone(back, switching_->lookahead_nodes, true);
  const double chained_cost = cone_cost(back, false);  // unswapped: the edges as they are now
  undo_chain();
  const double kept_cost = cone_cost(p, false);
  if (!(kept_cost - chained_cost > margin_s)) return false;
  chain_log_.clear();
  chain_keys_.clear();
  logging_ = true;
  for (const Pair& q : chain) chain_swap(q);
  return true;
}

}  // namespace smart::monitor
