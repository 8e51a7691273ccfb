// Contract: what the viewer shows of one robot, from the run's instance (plan, actions, ADG):
// its planned path in the world frame (start, then every cell it moves to), its action count,
// and its Type-2 dependencies both ways, grouped by the other robot: `waits_for` (another
// robot's action must finish before one of this robot's, SMART §IV-B) and `waited_by`. Pure.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>

#include "smart/monitor/instance.hpp"

namespace smart::serve {

// Throws std::out_of_range when robot is not in the instance.
nlohmann::json robot_detail(const monitor::Instance& instance, uint32_t robot, double cell_m);

}  // namespace smart::serve
