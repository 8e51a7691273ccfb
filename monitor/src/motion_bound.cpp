#include "smart/monitor/motion_bound.hpp"

#include <cmath>
#include <numbers>

namespace smart::monitor {

double rest_to_rest_s(double distance, double v_max, double accel, double decel) {
  if (distance <= 0) return 0;
  const double ramps = v_max * v_max / (2 * accel) + v_max * v_max / (2 * decel);
  if (distance >= ramps) return distance / v_max + v_max / (2 * accel) + v_max / (2 * decel);
  const double peak = std::sqrt(2 * distance * accel * decel / (accel + decel));
  return peak / accel + peak / decel;
}

namespace {
// Quarter turns between two headings: 1 (90°) or 2 (180°).
int quarter_turns(grid::Heading from, grid::Heading to) {
  const int d = (static_cast<int>(to) - static_cast<int>(from) + 4) % 4;
  return d == 3 ? 1 : d;
}
}  // namespace

std::vector<double> motion_lower_bounds_s(const grid::ActionPlan& plan, double cell_m,
                                          const MotionLimits& l) {
  std::vector<double> out(plan.robots(), 0.0);
  for (uint32_t r = 0; r < plan.robots(); ++r) {
    auto heading = plan.initial_heading.empty() ? grid::Heading::kEast : plan.initial_heading[r];
    double run_m = 0;
    const auto end_run = [&] {
      out[r] += rest_to_rest_s(run_m, l.max_speed_mps, l.max_accel_mps2, l.max_decel_mps2);
      run_m = 0;
    };
    for (uint32_t s = 0; s < plan.count(r); ++s) {
      const auto& a = plan.at(r, s);
      if (a.type == grid::ActionType::kMove) {
        run_m += cell_m / 2;
        continue;
      }
      end_run();
      const double angle = quarter_turns(heading, a.heading) * std::numbers::pi / 2;
      out[r] += rest_to_rest_s(angle, l.max_turn_rate_radps, l.max_angular_accel_radps2,
                               l.max_angular_accel_radps2);
      heading = a.heading;
    }
    end_run();
  }
  return out;
}

}  // namespace smart::monitor
