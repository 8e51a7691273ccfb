#include "smart/monitor/separation_watch.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>

namespace smart::monitor {

namespace {
// Bucket coordinates are packed into one key; a map of up to kMaxGridSide cells of any sane
// size stays far inside 2^31 buckets per axis.
constexpr int64_t kAxis = int64_t{1} << 31;
int64_t pack(int64_t bx, int64_t by) { return (bx + kAxis / 2) * kAxis + (by + kAxis / 2); }
}  // namespace

SeparationWatch::SeparationWatch(std::size_t robots, double radius_m, double max_skew_s)
    : radius_m_(radius_m), reach_m_(4 * radius_m), max_skew_s_(max_skew_s), last_(robots) {}

std::pair<int64_t, int64_t> SeparationWatch::bucket_of(double x_m, double y_m) const {
  const auto axis = [this](double v) {
    return static_cast<int64_t>(std::floor(std::clamp(v / reach_m_, -1e9, 1e9)));
  };
  return {axis(x_m), axis(y_m)};
}

void SeparationWatch::move_to_bucket(uint32_t robot, int64_t bucket) {
  Last& l = last_[robot];
  if (l.valid && l.bucket == bucket) return;
  if (l.valid) {
    auto& old = buckets_[l.bucket];
    old.erase(std::find(old.begin(), old.end(), robot));
    if (old.empty()) buckets_.erase(l.bucket);
  }
  buckets_[bucket].push_back(robot);
  l.bucket = bucket;
}

void SeparationWatch::compare(uint32_t robot, uint32_t other) {
  const Last& p = last_[robot];
  const Last& q = last_[other];
  if (std::abs(p.t_s - q.t_s) > max_skew_s_) return;
  const double d = std::hypot(p.x_m - q.x_m, p.y_m - q.y_m);
  const auto pair = std::minmax(robot, other);
  const double gap = d - 2 * radius_m_;
  if (d <= reach_m_) min_gap_m_ = std::min(min_gap_m_.value_or(gap), gap);
  if (gap >= 0) {
    touching_.erase(pair);
    return;
  }
  if (!touching_.insert(pair).second) return;
  ++contacts_;
  if (!first_) first_ = PoseContact{pair.first, pair.second, p.t_s, gap};
}

void SeparationWatch::on_pose(uint32_t robot, double x_m, double y_m, double t_s) {
  if (robot >= last_.size() || !std::isfinite(x_m) || !std::isfinite(y_m) || !std::isfinite(t_s))
    return;
  const auto [bx, by] = bucket_of(x_m, y_m);
  move_to_bucket(robot, pack(bx, by));
  Last& l = last_[robot];
  l.x_m = x_m;
  l.y_m = y_m;
  l.t_s = t_s;
  l.valid = true;
  for (int64_t dx = -1; dx <= 1; ++dx) {
    for (int64_t dy = -1; dy <= 1; ++dy) {
      const auto it = buckets_.find(pack(bx + dx, by + dy));
      if (it == buckets_.end()) continue;
      for (const uint32_t other : it->second) {
        if (other != robot) compare(robot, other);
      }
    }
  }
  forget_separated(robot);
}

// A pair that touched and is now out of reach (not compared above) has separated.
void SeparationWatch::forget_separated(uint32_t robot) {
  for (auto it = touching_.begin(); it != touching_.end();) {
    const uint32_t other = it->first == robot ? it->second : it->first;
    const bool mine = it->first == robot || it->second == robot;
    const double d =
        std::hypot(last_[robot].x_m - last_[other].x_m, last_[robot].y_m - last_[other].y_m);
    it = mine && d > reach_m_ ? touching_.erase(it) : std::next(it);
  }
}

}  // namespace smart::monitor
