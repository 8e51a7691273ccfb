#include "smart/hw/emulated_jetbot.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "smart/hw/vicon.hpp"

namespace smart::hw {
namespace {

TEST(EmulatedJetbot, TheRealDriverMovesItAndItStopsWhenOutputsGoOff) {
  JetbotConfig c;
  c.left.sign = -1;  // the emulator's wiring matches the configuration
  EmulatedJetbot bot(c, 0.1025, {0, 0, 0}, "", 0);
  EXPECT_EQ(bot.commanded().left_mps, 0.0);  // asleep until init
  JetbotDrive drive(bot, c, [](double) {});
  drive.configure();
  drive.activate();
  drive.set_wheel_speeds({0.3, 0.3});
  EXPECT_NEAR(bot.commanded().left_mps, 0.3, 0.01);
  EXPECT_NEAR(bot.commanded().right_mps, 0.3, 0.01);
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  EXPECT_GT(bot.pose().x_m, 0.05);
  drive.set_wheel_speeds({-0.2, 0.2});
  EXPECT_NEAR(bot.commanded().left_mps, -0.2, 0.01);
  drive.deactivate();
  EXPECT_EQ(bot.commanded().left_mps, 0.0);
  EXPECT_EQ(bot.commanded().right_mps, 0.0);
}

TEST(EmulatedJetbot, StreamsItsPoseAsViconDatagrams) {
  auto now = [] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
  };
  ViconReceiver rx("127.0.0.1", 0, vicon_millimetres(), {"jb"}, now);
  JetbotConfig c;
  EmulatedJetbot bot(c, 0.1025, {1.0, 2.0, 0.5}, "jb", rx.port());
  std::optional<agent::PoseSample> p;
  for (int i = 0; i < 200 && !p; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    p = rx.latest("jb");
  }
  ASSERT_TRUE(p);
  EXPECT_NEAR(p->pose.x_m, 1.0, 1e-9);
  EXPECT_NEAR(p->pose.y_m, 2.0, 1e-9);
  EXPECT_NEAR(p->pose.yaw_rad, 0.5, 1e-9);
}

}  // namespace
}  // namespace smart::hw
