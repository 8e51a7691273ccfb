#include "smart/sim/shard.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <memory>

#include "support/sim_fixtures.hpp"

namespace smart::sim {
namespace {

const grid::Grid kLong(24, 4, std::vector<uint8_t>(96, 0), "long");

// Cell-by-cell moves along row `row` (world y = 3 - row) from column `from` to column `to`.
std::vector<agent::AgentAction> drive_row(int row, int from, int to) {
  std::vector<agent::AgentAction> out;
  const double y = 3.0 - row, heading = to > from ? 0.0 : M_PI;
  uint32_t seq = 0;
  if (to < from)
    out.push_back({seq++, agent::ActionKind::kRotate, 1.0 * from, y, 1.0 * from, y, heading});
  for (int c = from; c != to; c += to > from ? 1 : -1) {
    const int n = c + (to > from ? 1 : -1);
    out.push_back({seq++, agent::ActionKind::kMove, 1.0 * c, y, 1.0 * n, y, heading});
  }
  return out;
}

std::vector<agent::Pose2D> starts(const std::vector<grid::Cell>& cells) {
  return start_poses(kLong, 1.0, cells, 0.0);
}

// N shards in one process, exchanging their outboxes after every period as the sim hosts do
// over DDS.
struct ShardedFleet {
  ShardMap map;
  std::vector<std::unique_ptr<Fleet>> fleets;
  std::vector<std::unique_ptr<FleetShard>> shards;
  std::vector<ShardOutbox> boxes;
  std::size_t handovers = 0;

  ShardedFleet(uint32_t n, const std::vector<agent::Pose2D>& start)
      : map(kLong, SimConfig{}, test::sim_test_model(), n, start) {
    for (uint32_t s = 0; s < n; ++s) {
      fleets.push_back(std::make_unique<Fleet>(kLong, test::sim_test_model(), SimConfig{}, start));
      shards.push_back(std::make_unique<FleetShard>(*fleets[s], map, s));
      boxes.push_back(shards[s]->initial_outbox());
    }
    exchange();
  }
  void exchange() {
    for (std::size_t s = 0; s < shards.size(); ++s) {
      std::vector<const ShardOutbox*> others;
      for (std::size_t o = 0; o < boxes.size(); ++o) {
        if (o != s) others.push_back(&boxes[o]);
      }
      handovers += shards[s]->before_step(others).size();
    }
  }
  void window(uint32_t robot, const std::vector<agent::AgentAction>& w) {
    for (auto& f : fleets) f->agent(robot).on_window(1, w);  // every shard hears every window
  }
  void step() {
    for (std::size_t s = 0; s < shards.size(); ++s) {
      fleets[s]->step();
      boxes[s] = shards[s]->after_step([](uint32_t) { return FleetShard::Reported{-1, -1}; });
    }
    exchange();
  }
  Fleet& of(uint32_t robot) {
    for (std::size_t s = 0; s < shards.size(); ++s) {
      if (shards[s]->simulates(robot)) return *fleets[s];
    }
    throw std::logic_error("robot simulated nowhere");
  }
  uint64_t robot_contacts() const {
    uint64_t n = 0;
    for (const auto& f : fleets) n += f->world().contacts().robot_robot_events;
    return n;
  }
};

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST(ShardMap, CutsAtCellEdgesBalanceTheStartsAlongTheLongerAxis) {
  const ShardMap map(kLong, SimConfig{}, test::sim_test_model(), 2,
                     starts({{0, 0}, {1, 0}, {19, 0}, {20, 0}}));
  EXPECT_TRUE(map.along_x());
  EXPECT_DOUBLE_EQ(map.cut_m(1), 10.5);  // between the 2nd and 3rd start, at a cell edge
  EXPECT_EQ(map.region_of(10.4, 0), 0u);
  EXPECT_EQ(map.region_of(10.6, 0), 1u);
  // Hysteresis: kept until more than half a cell past the cut.
  EXPECT_EQ(map.keeper(0, 10.9, 0), 0u);
  EXPECT_EQ(map.keeper(0, 11.1, 0), 1u);
  EXPECT_EQ(map.keeper(1, 10.1, 0), 1u);
  EXPECT_TRUE(map.near(1, 10.5 - map.margin_m() + 0.01, 0));
  EXPECT_FALSE(map.near(1, 10.5 - map.margin_m() - 0.01, 0));
}

TEST(ShardMap, RefusesMoreShardsThanCellsAcross) {
  EXPECT_THROW(ShardMap(kLong, SimConfig{}, test::sim_test_model(), 25, starts({{0, 0}})),
               std::invalid_argument);
  EXPECT_THROW(ShardMap(kLong, SimConfig{}, test::sim_test_model(), 0, starts({{0, 0}})),
               std::invalid_argument);
}

// Robots crossing borders both ways, one turning first: every pose, every period, bit for bit
// the unsharded fleet's, with 2 and 3 shards.
TEST(FleetShard, RobotsCrossingBordersFollowTheUnshardedTrajectoriesBitForBit) {
  const auto start = starts({{0, 0}, {23, 2}, {5, 1}, {12, 3}});
  for (const uint32_t n : {2u, 3u}) {
    Fleet whole(kLong, test::sim_test_model(), SimConfig{}, start);
    ShardedFleet sharded(n, start);
    const std::vector<std::vector<agent::AgentAction>> plan{
        drive_row(0, 0, 20), drive_row(2, 23, 2), drive_row(1, 5, 14), {}};
    for (uint32_t r = 0; r < plan.size(); ++r) {
      whole.agent(r).on_window(1, plan[r]);
      sharded.window(r, plan[r]);
    }
    for (int k = 0; k < 400; ++k) {
      whole.step();
      sharded.step();
      for (uint32_t r = 0; r < start.size(); ++r) {
        const auto a = whole.world().motion(r), b = sharded.of(r).world().motion(r);
        ASSERT_TRUE(same_bits(a.x_m, b.x_m) && same_bits(a.y_m, b.y_m) &&
                    same_bits(a.yaw_rad, b.yaw_rad) && same_bits(a.vx_mps, b.vx_mps))
            << n << " shards, robot " << r << " at period " << k << ": " << a.x_m << " vs "
            << b.x_m;
        ASSERT_EQ(whole.agent(r).finished_seq(), sharded.of(r).agent(r).finished_seq());
      }
    }
    EXPECT_EQ(whole.agent(0).finished_seq(), 19);  // the plans were executed to the end
    EXPECT_EQ(whole.agent(1).finished_seq(), 21);
    // Cuts at 8.5 (2 shards), at 2.5 and 8.5 (3): robots 0 and 2 cross every border on their
    // way, robot 1 stops 0.5 m short of leaving the middle strip (hysteresis).
    EXPECT_EQ(sharded.handovers, n == 2 ? 3u : 4u);
    EXPECT_EQ(sharded.robot_contacts(), 0u);
  }
}

// Two robots driving head-on meet on the border, each still simulated by its own shard and
// seen by the other as a ghost: the contact is simulated (it is counted once over both shards,
// as in the unsharded fleet) and the robots bounce apart. The ghost moves on at its last
// velocity through the period, so it sinks in deeper than the braking robot it stands for: the
// closest approach is within 2 cm of the unsharded one, the rebound not the same.
TEST(FleetShard, AContactAcrossTheBorderIsSimulatedAndCountedOnce) {
  auto start = starts({{6, 2}, {17, 2}, {0, 3}, {23, 3}});
  start[1].yaw_rad = M_PI;
  auto west = drive_row(2, 17, 7);
  west.erase(west.begin());  // already facing west
  for (uint32_t s = 0; s < west.size(); ++s) west[s].seq = s;
  ShardedFleet sharded(2, start);
  ASSERT_DOUBLE_EQ(sharded.map.cut_m(1), 11.5);
  Fleet whole(kLong, test::sim_test_model(), SimConfig{}, start);
  for (Fleet* f : {&whole}) {
    f->agent(0).on_window(1, drive_row(2, 6, 16));
    f->agent(1).on_window(1, west);
  }
  sharded.window(0, drive_row(2, 6, 16));
  sharded.window(1, west);
  bool met_across = false;
  for (int k = 0; k < 300; ++k) {
    whole.step();
    sharded.step();
    const bool touching = whole.world().contacts().robot_robot_now > 0;
    met_across |= touching && !sharded.shards[0]->simulates(1) && !sharded.shards[1]->simulates(0);
  }
  ASSERT_TRUE(met_across) << "the robots did not touch while in different shards";
  EXPECT_EQ(whole.world().contacts().robot_robot_events, 1u);
  EXPECT_EQ(sharded.robot_contacts(), 1u);
  double gap = 1e9;
  for (const auto& f : sharded.fleets) gap = std::min(gap, f->world().contacts().min_gap_m);
  EXPECT_NEAR(gap, whole.world().contacts().min_gap_m, 0.02);
  EXPECT_LT(gap, 0.0);
  const double x0 = sharded.of(0).world().motion(0).x_m, x1 = sharded.of(1).world().motion(1).x_m;
  EXPECT_GT(x1 - x0, 2 * test::sim_test_model().radius_m) << "still overlapping, or passed through";
}

}  // namespace
}  // namespace smart::sim
