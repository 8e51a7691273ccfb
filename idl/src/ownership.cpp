#include "smart/wire/ownership.hpp"

#include <algorithm>

namespace smart::wire {

namespace {
// Mirrors idl/smart.idl (this library does not include the generated header).
constexpr int64_t kStrengthMin = int64_t{1} << 30;
constexpr int64_t kStrengthResume = 2147483647;
}  // namespace

int32_t monitor_strength(uint64_t unix_time_ms, bool resume) {
  if (resume) return static_cast<int32_t>(kStrengthResume);
  const int64_t span = kStrengthResume - kStrengthMin;  // 2^30 - 1 steps below resume
  const auto step = static_cast<int64_t>((unix_time_ms / 10) % static_cast<uint64_t>(span));
  return static_cast<int32_t>(kStrengthResume - 1 - step);
}

bool outranks(const MonitorClaim& a, const MonitorClaim& b) {
  if (a.resume != b.resume) return !a.resume;
  if (a.strength != b.strength) return a.strength > b.strength;
  return a.monitor_id < b.monitor_id;
}

std::optional<MonitorClaim> owner_over(const MonitorClaim& self,
                                       const std::vector<MonitorClaim>& others) {
  std::optional<MonitorClaim> best;
  for (const auto& o : others) {
    if (o.monitor_id == self.monitor_id || !outranks(o, self)) continue;
    if (!best || outranks(o, *best)) best = o;
  }
  return best;
}

std::string describe(const MonitorClaim& c) {
  return "monitor on host " + (c.host.empty() ? std::string("?") : c.host) + " (pid " +
         std::to_string(c.pid) + ", run id " + std::to_string(c.run_id) + ")";
}

void ClaimBook::heard(const MonitorClaim& claim, double now_s) {
  auto it = heard_.find(claim.monitor_id);
  if (it == heard_.end() && heard_.size() >= kMaxClaims) {
    auto quiet = heard_.begin();
    for (auto h = heard_.begin(); h != heard_.end(); ++h) {
      if (h->second.last_s < quiet->second.last_s) quiet = h;
    }
    heard_.erase(quiet);
  }
  auto& h = heard_[claim.monitor_id];
  h.claim = claim;
  h.times = std::min(h.times + 1, 2);
  h.last_s = now_s;
}

std::vector<MonitorClaim> ClaimBook::live(double now_s) const {
  std::vector<MonitorClaim> out;
  for (const auto& [id, h] : heard_) {
    if (h.times >= 2 && now_s - h.last_s <= kClaimLiveS) out.push_back(h.claim);
  }
  return out;
}

bool ClaimBook::pending(double now_s) const {
  for (const auto& [id, h] : heard_) {
    if (h.times < 2 && now_s - h.last_s <= kClaimLiveS) return true;
  }
  return false;
}

}  // namespace smart::wire
