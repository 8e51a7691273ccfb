#include "smart/sim/pacer.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace smart::sim {

Pacer::Pacer(double real_time_factor, double period_s) {
  if (!(real_time_factor >= 0) || !(period_s > 0)) {
    throw std::invalid_argument(
        "pacing needs a real-time factor >= 0 (0: unpaced) and a period "
        "> 0 s; got " +
        std::to_string(real_time_factor) + " and " + std::to_string(period_s));
  }
  if (real_time_factor > 0) interval_wall_s_ = period_s / real_time_factor;
}

double Pacer::wait_s(double wall_s) const {
  if (!paced() || !next_wall_s_) return 0;
  return std::max(0.0, *next_wall_s_ - wall_s);
}

void Pacer::started(double wall_s) {
  if (!paced()) return;
  const bool on_schedule =
      next_wall_s_ && wall_s - *next_wall_s_ <= std::max(kCatchUpS, interval_wall_s_);
  next_wall_s_ = (on_schedule ? *next_wall_s_ : wall_s) + interval_wall_s_;
}

}  // namespace smart::sim
