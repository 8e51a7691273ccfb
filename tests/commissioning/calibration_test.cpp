// Calibration: points placed on a map (pure), and the straight-line trim trial on an in-process
// emulated JetBot whose right wheel is weak.
#include "smart/commissioning/calibration.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>

#include "smart/grid/map_reader.hpp"
#include "smart/hw/emulated_jetbot.hpp"
#include "support/dds_test_support.hpp"
#include "support/emulated_robot_io.hpp"

namespace smart::commissioning {
namespace {

using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

const grid::Grid& map4x3() {
  static const auto g =
      grid::parse_map("type octile\nheight 3\nwidth 4\nmap\n....\n....\n....\n", "tiny.map");
  return g;
}

TEST(PlacePoints, PutsEachIdOnItsCellCentre) {
  const auto p = place_points({"3:0,2", "jb:3,0"}, map4x3(), 0.5, "tiny.map");
  ASSERT_EQ(p.size(), 2u);
  EXPECT_EQ(p[0].id, "3");
  EXPECT_EQ(p[0].col, 0);
  EXPECT_EQ(p[0].row, 2);
  const auto w = map4x3().to_world({0, 4}, 0.5);
  EXPECT_DOUBLE_EQ(p[0].world_m.x(), w.x_m);
  EXPECT_DOUBLE_EQ(p[0].world_m.y(), w.y_m);
  EXPECT_EQ(p[1].id, "jb");
}

TEST(PlacePoints, BadTextsCellsOutsideTheMapAndRepeatedIdsAreNamed) {
  for (const char* bad : {"3", ":1,1", "3:1", "3:1;1", "3:1,1x"}) {
    EXPECT_THAT([&] { place_points({bad}, map4x3(), 1, "tiny.map"); },
                ThrowsMessage<std::invalid_argument>(HasSubstr("write ID:COL,ROW")))
        << bad;
  }
  EXPECT_THAT([] { place_points({"3:4,0"}, map4x3(), 1, "tiny.map"); },
              ThrowsMessage<std::invalid_argument>(HasSubstr("outside the 4x3 map tiny.map")));
  EXPECT_THAT(
      [] {
        place_points({"3:0,0", "3:1,1"}, map4x3(), 1, "tiny.map");
      },
      ThrowsMessage<std::invalid_argument>(HasSubstr("3 is already placed")));
}

// An emulated JetBot at (0.5, 0.5) with the given wheel gains, on its own Vicon port.
class Trim : public ::testing::Test {
 protected:
  hw::RobotIo open(std::vector<double> wheel_gains = {}) {
    return test::open_emulated_jetbot(participant_, std::move(wheel_gains), &model_);
  }
  dds::Domain domain_{test::kCommissioningTrim, test::loopback()};
  dds::Participant participant_{domain_, "trim"};
  agent::RobotModel model_;
};

TEST_F(Trim, AWeakRightWheelPullsRightAndItsAlphaIsProposedLower) {
  auto io = open({1.0, 0.9});
  const auto& model = model_;
  const TrimTrial trial{.speed_mps = 0.15, .seconds = 2.0};
  const auto samples = drive_straight(trial, 0, io);
  ASSERT_GT(samples.size(), 20u);
  const auto measured =
      agent::measure_wheel_trial(samples, trial.speed_mps, model.wheel_base_m, trial.settle_s);
  EXPECT_LT(measured.turn_rate_radps, -0.05);  // pulls to the right
  const auto p = propose_trim(0, measured, model, io);
  EXPECT_NEAR(p.report["proposed"]["hardware.left.alpha"].get<double>(),
              io.hardware.left.alpha * 0.9, 0.02);
  EXPECT_DOUBLE_EQ(p.report["proposed"]["hardware.right.alpha"].get<double>(),
                   io.hardware.right.alpha);
  EXPECT_THAT(p.yaml, HasSubstr("hardware:\n  left: {alpha: "));
}

TEST_F(Trim, AStopFlagEndsTheTrialWithTheWheelsOff) {
  auto io = open();
  const auto& board = dynamic_cast<const hw::EmulatedJetbot&>(*io.bus);
  std::atomic<bool> stop{false};
  // The stop comes once the wheels turn, as a Ctrl-C during the trial.
  std::thread signal([&] {
    while (board.commanded().left_mps <= 0)
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    stop = true;
  });
  EXPECT_THAT([&] { drive_straight({.seconds = 30.0, .stop = &stop}, 0, io); },
              ThrowsMessage<std::runtime_error>(HasSubstr("stopped by signal")));
  signal.join();
  EXPECT_EQ(board.commanded().left_mps, 0.0);
  EXPECT_EQ(board.commanded().right_mps, 0.0);
}

}  // namespace
}  // namespace smart::commissioning
