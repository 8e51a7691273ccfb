#include "smart/wire/ownership.hpp"

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

}  // namespace smart::wire
