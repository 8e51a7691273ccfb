#include "smart/hw/emulated_jetbot.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <thread>

#include "smart/hw/vicon.hpp"

namespace smart::hw {
namespace {

// `seconds` of the model in its thread's 10 ms steps.
void advance(EmulatedJetbot& bot, double seconds) {
  for (int i = 0; i < static_cast<int>(std::lround(seconds / 0.01)); ++i) bot.advance(0.01);
}

TEST(EmulatedJetbot, TheRealDriverMovesItAndItStopsWhenOutputsGoOff) {
  JetbotConfig c;
  c.left.sign = -1;  // the emulator's wiring matches the configuration
  // Stepped here, 10 ms at a time: the model's time is told, not slept (a loaded machine
  // stretches a sleep).
  EmulatedJetbot bot(c, 0.1025, {0, 0, 0}, "", 0, 2.0, {}, Stepping::kManual);
  EXPECT_EQ(bot.commanded().left_mps, 0.0);  // asleep until init
  JetbotDrive drive(bot, c, [](double) {});
  EXPECT_TRUE(drive.configure().ok());
  EXPECT_TRUE(drive.activate().ok());
  drive.set_wheel_speeds({0.3, 0.3});
  EXPECT_NEAR(bot.commanded().left_mps, 0.3, 0.01);
  EXPECT_NEAR(bot.commanded().right_mps, 0.3, 0.01);
  advance(bot, 0.5);
  EXPECT_GT(bot.pose().x_m, 0.05);
  drive.set_wheel_speeds({-0.2, 0.2});
  EXPECT_NEAR(bot.commanded().left_mps, -0.2, 0.01);
  EXPECT_TRUE(drive.deactivate().ok());
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
  // Until the first pose arrives; the deadline only catches a hang (a loaded machine is slow).
  for (const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(30);
       !p && std::chrono::steady_clock::now() < end;) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    p = rx.latest("jb");
  }
  ASSERT_TRUE(p);
  EXPECT_NEAR(p->pose.x_m, 1.0, 1e-9);
  EXPECT_NEAR(p->pose.y_m, 2.0, 1e-9);
  EXPECT_NEAR(p->pose.yaw_rad, 0.5, 1e-9);
}

// A lab JetBot's flaws (realistic_flaws): below the dead band the wheel does not turn, and the
// JetBot's own compensation (beta = the dead band, alpha = 1 - beta: jetbot-lab.yaml) restores
// a linear response; the motor lags; Vicon poses are noisy.
TEST(EmulatedJetbot, RealisticFlawsDeadBandLagAndNoise) {
  JetbotConfig plain;
  EmulatedFlaws flaws = realistic_flaws(7);
  EmulatedJetbot bot(plain, 0.1025, {0, 0, 0}, "", 0, 100.0, flaws, Stepping::kManual);
  JetbotDrive drive(bot, plain, [](double) {});
  EXPECT_TRUE(drive.configure().ok());
  EXPECT_TRUE(drive.activate().ok());
  drive.set_wheel_speeds({0.1, 0.1});  // 16 % duty: inside the dead band
  EXPECT_EQ(bot.commanded().left_mps, 0.0);
  JetbotConfig compensated;
  compensated.left.alpha = compensated.right.alpha = 1.0 - 60.0 / 255.0;
  compensated.left.beta = compensated.right.beta = 60.0 / 255.0;
  EmulatedJetbot lab(compensated, 0.1025, {0, 0, 0}, "", 0, 100.0, flaws, Stepping::kManual);
  JetbotDrive lab_drive(lab, compensated, [](double) {});
  EXPECT_TRUE(lab_drive.configure().ok());
  EXPECT_TRUE(lab_drive.activate().ok());
  lab_drive.set_wheel_speeds({0.1, 0.3});
  EXPECT_NEAR(lab.commanded().left_mps, 0.1, 0.005);
  EXPECT_NEAR(lab.commanded().right_mps, 0.3, 0.005);
  advance(lab, 0.03);
  // A 0.1 s time constant: still rising (without it, one 10 ms step would reach 0.3 m/s).
  EXPECT_LT(lab.wheel_speeds().right_mps, 0.95 * 0.3);
  advance(lab, 0.6);
  EXPECT_NEAR(lab.wheel_speeds().right_mps, 0.3, 0.01);
}

TEST(EmulatedJetbot, RealisticViconIsNoisyAroundTheTruePose) {
  auto now = [] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
  };
  ViconReceiver rx("127.0.0.1", 0, vicon_millimetres(), {"jb"}, now);
  EmulatedJetbot bot(JetbotConfig{}, 0.1025, {1.0, 2.0, 0.5}, "jb", rx.port(), 2.0,
                     realistic_flaws(3));
  std::vector<double> xs;
  double last = -1;
  for (const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(30);
       xs.size() < 60 && std::chrono::steady_clock::now() < end;) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    const auto p = rx.latest("jb");
    if (p && p->stamp_s != last) {
      xs.push_back(p->pose.x_m);
      last = p->stamp_s;
    }
  }
  ASSERT_GE(xs.size(), 30u);
  double mean = 0, sq = 0;
  for (const double x : xs) mean += x / xs.size();
  for (const double x : xs) sq += (x - mean) * (x - mean) / xs.size();
  EXPECT_NEAR(mean, 1.0, 0.0005);
  EXPECT_GT(std::sqrt(sq), 0.0002);  // 0.5 mm noise, measured
  EXPECT_LT(std::sqrt(sq), 0.001);
}

}  // namespace
}  // namespace smart::hw
