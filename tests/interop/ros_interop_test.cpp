// ROS 2 interop across DDS vendors: `smart run` publishes rt/smart/poses with Cyclone DDS; a
// Fast DDS program (fastdds_pose_listener.cpp, the stand-in for a ROS 2 node) discovers it on
// loopback and decodes geometry_msgs/PoseArray. Real processes, own domain.
#include <gtest/gtest.h>

#include <sstream>
#include <thread>

#include "support/monitor_fixtures.hpp"
#include "support/smart_process.hpp"

namespace smart::test {
namespace {

using namespace std::chrono_literals;

TEST(RosInterop, FastDdsNodeReadsTheFleetPosesWrittenByCyclone) {
  const auto b = benchmarks_dir();
  if (!std::filesystem::exists(b)) GTEST_SKIP() << "no benchmark data at " << b;
  const auto out = temp_file("fastdds_listener.out");
  tools::ChildProcess listener({FASTDDS_POSE_LISTENER, std::to_string(kFastDdsInterop), "4", "60"},
                               out);
  const auto run =
      run_smart({"run", "--map", (b / "maps/random-32-32-20.map").string(), "--scen",
                 (b / "scens/random-32-32-20-random-1.scen").string(), "--plan",
                 (b / "smart-examples/example_paths_xy.txt").string(), "--axis", "xy", "--agents",
                 "50", "--domain", std::to_string(kFastDdsInterop), "--no-progress"},
                120s, "interop_run");
  ASSERT_EQ(run.code, 0) << run.out;
  const auto rc = listener.wait(10s);
  ASSERT_TRUE(rc.has_value()) << "the Fast DDS listener did not finish";
  EXPECT_EQ(*rc, 0) << "the Fast DDS listener got fewer than 4 PoseArray messages";
  std::istringstream lines(slurp(out));
  std::string word, frame;
  std::size_t poses = 0, count = 0;
  double stamp = 0, last_stamp = -1, x = 0, y = 0, qz = 0, qw = 0;
  while (lines >> word >> poses >> word >> frame >> word >> stamp >> word >> x >> y >> qz >> qw) {
    ++count;
    EXPECT_EQ(poses, 50u);
    EXPECT_EQ(frame, "map");
    EXPECT_GT(stamp, last_stamp);  // sim time goes forward
    last_stamp = stamp;
    // Robot 0 is on the 32x32 map, its orientation a unit quaternion about z.
    EXPECT_GE(x, -0.5);
    EXPECT_LE(x, 31.5);
    EXPECT_GE(y, -0.5);
    EXPECT_LE(y, 31.5);
    EXPECT_NEAR(qz * qz + qw * qw, 1.0, 1e-5);
  }
  EXPECT_EQ(count, 4u);
  std::filesystem::remove(out);
}

}  // namespace
}  // namespace smart::test
