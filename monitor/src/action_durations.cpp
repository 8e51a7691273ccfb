#include "smart/monitor/action_durations.hpp"

#include <algorithm>
#include <cmath>

namespace smart::monitor {

namespace {
constexpr uint32_t kMemory = 256;  // the running mean's longest memory, in samples
}  // namespace

void ActionDurations::observe(grid::ActionType type, double duration_s) {
  if (!std::isfinite(duration_s) || duration_s < 0) return;  // a report out of order: no sample
  const std::size_t k = index(type);
  samples_[k] = std::min(samples_[k] + 1, kMemory);
  mean_s_[k] += (duration_s - mean_s_[k]) / samples_[k];
}

double ActionDurations::finish_s(double now_s, double started_s,
                                 std::span<const grid::ActionType> to_go) const {
  if (to_go.empty()) return now_s;
  double t = started_s < 0 ? now_s + mean_s(to_go[0]) : started_s + mean_s(to_go[0]);
  if (t < now_s) t = now_s + mean_s(to_go[0]);  // late: one more mean from now
  for (std::size_t i = 1; i < to_go.size(); ++i) t += mean_s(to_go[i]);
  return t;
}

double queue_saving(const PassQueue& q) {
  const auto waits = [&q](const ExpectedStay& first, const ExpectedStay& second) {
    const double e1 = std::max(first.arrive_s, q.free_s);
    const double e2 = std::max(second.arrive_s, e1 + first.stay_s);
    const double next =
        std::isfinite(q.next_arrive_s) ? std::max(0.0, e2 + second.stay_s - q.next_arrive_s) : 0.0;
    return (e1 - first.arrive_s) + (e2 - second.arrive_s) + next;
  };
  return waits(q.i, q.j) - waits(q.j, q.i);
}

}  // namespace smart::monitor
