// Where a plain ADG run's waiting went (wait_causes.hpp).
#include "smart/monitor/wait_causes.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace smart::monitor {

namespace {

// Per action, when its last Type-2 predecessor finished and the entry of that predecessor's
// stay (the blocker's action that entered the location; kNoAction: it started there).
struct Release {
  std::vector<double> at_s;
  std::vector<uint32_t> blocker_enter;
  std::vector<uint32_t> blocker_leave, waiter_leave;  // the edge's leave, and the waiter's
};

Release releases(const PassingOrders& orders, const std::vector<double>& finish_s) {
  Release r{std::vector<double>(finish_s.size(), 0.0),
            std::vector<uint32_t>(finish_s.size(), kNoAction),
            std::vector<uint32_t>(finish_s.size(), kNoAction),
            std::vector<uint32_t>(finish_s.size(), kNoAction)};
  std::vector<bool> blocked(finish_s.size(), false);
  // The Type-2 edges as adg_of_orders() makes them: consecutive stays of different robots.
  for (std::size_t loc = 0; loc + 1 < orders.begin.size(); ++loc) {
    for (uint32_t k = orders.begin[loc] + 1; k < orders.begin[loc + 1]; ++k) {
      const Stay& p = orders.stays[k - 1];
      const Stay& q = orders.stays[k];
      if (p.robot == q.robot || p.leave == kNoAction || q.enter == kNoAction) continue;
      const double t = finish_s[p.leave];  // NaN: never left; the entry is never counted
      if (!blocked[q.enter] || t > r.at_s[q.enter]) {
        r.at_s[q.enter] = t;
        r.blocker_enter[q.enter] = p.enter;
        r.blocker_leave[q.enter] = p.leave;
        r.waiter_leave[q.enter] = q.leave;
        blocked[q.enter] = true;
      }
    }
  }
  return r;
}

// When `node` began: its robot's previous action and its predecessors finished.
double start_s(const ActionPlan& actions, const Release& r, const std::vector<double>& finish_s,
               uint32_t node) {
  const double previous = actions.actions[node].seq == 0 ? 0.0 : finish_s[node - 1];
  return std::max(previous, r.at_s[node]);
}

// How long, within [from, until], the robot of `node` waited for others before `node` began:
// its actions' waits (each from its previous action's end to its release), latest first.
double waited_before(const ActionPlan& actions, const Release& r,
                     const std::vector<double>& finish_s, uint32_t node, double from,
                     double until) {
  double waited = 0;
  for (uint32_t n = node + 1; n-- > node - actions.actions[node].seq;) {
    const double begin = actions.actions[n].seq == 0 ? 0.0 : finish_s[n - 1];
    const double end = std::max(begin, r.at_s[n]);
    if (end <= from) break;  // earlier actions' waits are earlier still
    waited += std::max(0.0, std::min(end, until) - std::max(begin, from));
  }
  return waited;
}

// switchable_tracker.hpp's deadlock search, on the plan's edges at `at_s`: passing the blocker
// (entry `target`, leave `skip_from`) lets the waiter (entry `skip_to`) in first only if no path
// of actions unfinished then leads from `target` to the waiter's leave `to` but the edge
// reversed. Searched backwards from `to`, at most kBudget actions (past it, refused too).
class CycleSearch {
 public:
  CycleSearch(const ActionPlan& actions, const PassingOrders& orders,
              const std::vector<double>& finish_s)
      : actions_(actions),
        adg_(adg_of_orders(orders, actions, Footprint::kHalfCells)),
        finish_s_(finish_s),
        seen_(finish_s.size(), 0) {}

  bool closes(uint32_t target, uint32_t skip_from, uint32_t skip_to, uint32_t to, double at_s) {
    if (to == kNoAction) return true;  // the waiter would park there: never passes (no switch)
    ++stamp_;
    stack_.assign(1, to);
    std::size_t visited = 0;
    while (!stack_.empty()) {
      const uint32_t n = stack_.back();
      stack_.pop_back();
      if (n == target) return true;
      if (++visited > kBudget) return true;
      if (actions_.actions[n].seq > 0) push(n - 1, at_s);
      for (uint32_t e = adg_.in_begin[n]; e < adg_.in_begin[n + 1]; ++e) {
        if (adg_.in[e] != skip_from || n != skip_to) push(adg_.in[e], at_s);
      }
    }
    return false;
  }

 private:
  static constexpr std::size_t kBudget = 4096;  // SwitchOptions::search_budget's default
  void push(uint32_t n, double at_s) {
    if (seen_[n] == stamp_ || finish_s_[n] <= at_s) return;  // seen, or finished by then
    seen_[n] = stamp_;
    stack_.push_back(n);
  }
  const ActionPlan& actions_;
  Adg adg_;
  const std::vector<double>& finish_s_;
  std::vector<uint32_t> seen_, stack_;
  uint32_t stamp_ = 0;
};

}  // namespace

WaitCauses wait_causes(const ActionPlan& actions, const PassingOrders& orders,
                       const std::vector<double>& finish_s, uint32_t commit_actions) {
  if (finish_s.size() != actions.actions.size()) {
    throw std::invalid_argument("wait_causes: " + std::to_string(finish_s.size()) +
                                " finish times for " + std::to_string(actions.actions.size()) +
                                " actions; give one per action (NaN: never finished)");
  }
  const Release r = releases(orders, finish_s);
  CycleSearch search(actions, orders, finish_s);
  WaitCauses w;
  for (uint32_t node = 0; node < finish_s.size(); ++node) {
    const double from = actions.actions[node].seq == 0 ? 0.0 : finish_s[node - 1];
    const double until = r.at_s[node];
    if (std::isnan(finish_s[node]) || std::isnan(from) || !(until > from)) continue;
    ++w.waits;
    w.total_s += until - from;
    const uint32_t e = r.blocker_enter[node];
    // The blocker's entry began at `began` and ended at `entered`: before, it was on its way.
    const double began =
        e == kNoAction ? from : std::clamp(start_s(actions, r, finish_s, e), from, until);
    const double entered = e == kNoAction ? from : std::clamp(finish_s[e], began, until);
    w.on_its_way_s += began - from;
    if (began > from) {
      w.on_its_way_waiting_s += waited_before(actions, r, finish_s, e, from, began);
      // Its entry unsent under switchable execution until the blocker came within
      // commit_actions of it: it finished the action commit_actions + 1 before.
      const uint32_t seq = actions.actions[e].seq;
      if (seq > commit_actions) {
        const double free_s = std::clamp(finish_s[e - commit_actions - 1], from, began) - from;
        w.uncommitted_s += free_s;
        if (free_s > 0 &&
            search.closes(e, r.blocker_leave[node], node, r.waiter_leave[node], from)) {
          w.uncommitted_cycle_s += free_s;
        }
      }
    }
    w.entering_s += entered - began;
    w.at_location_s += until - entered;
  }
  return w;
}

}  // namespace smart::monitor
