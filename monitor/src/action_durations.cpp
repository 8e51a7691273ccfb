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
  Later later;
  for (std::size_t i = 1; i < to_go.size(); ++i) {
    ++(to_go[i] == grid::ActionType::kMove ? later.moves : later.rotations);
  }
  return finish_s(now_s, started_s, to_go[0], later);
}

double ActionDurations::finish_s(double now_s, double started_s, grid::ActionType current,
                                 Later later) const {
  double t = started_s < 0 ? now_s + mean_s(current) : started_s + mean_s(current);
  if (t < now_s) t = now_s + mean_s(current);  // late: one more mean from now
  return t + later.moves * mean_s(grid::ActionType::kMove) +
         later.rotations * mean_s(grid::ActionType::kRotate);
}

}  // namespace smart::monitor
