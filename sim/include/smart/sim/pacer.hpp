// Contract: paces a lock-step run to at most `real_time_factor` times real time, so that a run
// can be watched live (`smart run --real-time-factor`, the web app's upload form). Pure: it is
// told the wall time and answers how long to wait; it never reads a clock or sleeps. Pacing
// changes only when periods start on the wall clock, never what a period computes, so a paced
// lock-step run gives the same results as an unpaced one.
// Schedule: one period of `period_s` sim seconds every period_s / factor wall seconds, on a fixed
// schedule, so wake-up latency and the monitor's round trip do not add up: periods that start
// late are caught up on. A period that starts more than kCatchUpS (or one interval) late, where
// the sim is slower than the factor, restarts the schedule from then, so a slow stretch is not
// followed by a long burst. Like Gazebo's target real-time factor (SDFormat <physics>
// <real_time_factor>, http://sdformat.org/spec?elem=physics), a target, not a promise.
#pragma once

#include <optional>

namespace smart::sim {

class Pacer {
 public:
  // Wall seconds a paced run may fall behind and still catch up: a quarter second of faster
  // playback is not noticed by someone watching, and at high factors (intervals of 1 ms) the
  // round trips of single periods are longer than one interval.
  static constexpr double kCatchUpS = 0.25;

  // real_time_factor 0: unpaced (wait_s is always 0). Throws std::invalid_argument for a
  // negative or NaN factor or a period that is not > 0.
  Pacer(double real_time_factor, double period_s);

  bool paced() const { return interval_wall_s_ > 0; }
  // Wall seconds to wait at wall time `wall_s` before the next period may start (0: now).
  double wait_s(double wall_s) const;
  // The next period started at wall time `wall_s`.
  void started(double wall_s);

 private:
  double interval_wall_s_ = 0;         // wall seconds per period; 0: unpaced
  std::optional<double> next_wall_s_;  // when the next period is due; none before the first
};

}  // namespace smart::sim
