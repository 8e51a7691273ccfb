#include "smart/sim/fleet.hpp"

#include <stdexcept>
#include <string>

namespace smart::sim {

std::vector<agent::Pose2D> start_poses(const grid::Grid& grid, double cell_m,
                                       const std::vector<grid::Cell>& starts, double yaw) {
  std::vector<agent::Pose2D> out;
  out.reserve(starts.size());
  for (const auto& c : starts) {
    const auto p = grid.to_world(grid::HalfCell::of(c), cell_m);
    out.push_back({p.x_m, p.y_m, yaw});
  }
  return out;
}

namespace {
// A simulated robot's backend has no device that could fail: a failed lifecycle call is a bug.
void expect_ok(const agent::LifecycleResult& r) {
  if (!r.ok()) throw std::logic_error("sim fleet: " + r.message);
}
}  // namespace

Fleet::Fleet(const grid::Grid& grid, const agent::RobotModel& model, const SimConfig& config,
             const std::vector<agent::Pose2D>& starts, double pose_timeout_s)
    : world_(grid, model, config, starts) {
  for (uint32_t i = 0; i < starts.size(); ++i) {
    backends_.push_back(
        std::make_unique<SimRobot>(world_, i, model.uncertainty, config.control_period_s));
    agents_.push_back(std::make_unique<agent::Agent>(
        agent::AgentConfig{i, model, config.control_period_s, pose_timeout_s}, *backends_[i],
        *backends_[i]));
    expect_ok(agents_.back()->activate());
  }
}

void Fleet::set_external(uint32_t robot) {
  if (robot >= agents_.size()) {
    throw std::invalid_argument("external robot " + std::to_string(robot) + " but the sim has " +
                                std::to_string(agents_.size()) + " robots");
  }
  world_.set_external(robot, true);
  expect_ok(agents_[robot]->deactivate());
}

std::pair<RobotPhysics, agent::AgentSnapshot> Fleet::release(uint32_t robot, Presence now) {
  std::pair out{world_.export_robot(robot), agents_.at(robot)->snapshot()};
  expect_ok(agents_[robot]->deactivate());
  world_.set_presence(robot, now);
  return out;
}

void Fleet::adopt(uint32_t robot, const RobotPhysics& physics, const agent::AgentSnapshot& agent) {
  world_.import_robot(robot, physics);
  expect_ok(agents_.at(robot)->activate());
  agents_[robot]->restore(agent);
}

void Fleet::step() {
  // Inactive (external) agents do nothing in step().
  for (auto& a : agents_) a->step(world_.time_s());
  world_.step();
  ++stats_.periods;
  awake_sum_ += static_cast<double>(world_.awake_robots());
  systems_sum_ += static_cast<double>(world_.active_systems());
}

void Fleet::deactivate() {
  for (auto& a : agents_) expect_ok(a->deactivate());
}

FleetStats Fleet::stats() const {
  FleetStats s = stats_;
  const double periods = static_cast<double>(std::max<uint64_t>(stats_.periods, 1));
  s.mean_awake_robots = awake_sum_ / periods;
  s.mean_active_systems = systems_sum_ / periods;
  return s;
}

}  // namespace smart::sim
