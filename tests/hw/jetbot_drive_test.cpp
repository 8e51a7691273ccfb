// Golden I2C transactions of the JetBot motor driver: channel maps, polarity, trim, stop paths.
#include "smart/hw/jetbot_drive.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <signal.h>

#include "smart/config/yaml_checks.hpp"
#include "support/recording_i2c_bus.hpp"

namespace smart::hw {
namespace {

using ::testing::HasSubstr;

// Registers of channel ch: ON_L, ON_H, OFF_L, OFF_H.
std::array<uint8_t, 4> channel(const test::RecordingI2cBus& bus, int ch) {
  const int b = 0x06 + 4 * ch;
  return {bus.regs[b], bus.regs[b + 1], bus.regs[b + 2], bus.regs[b + 3]};
}
using Regs = std::array<uint8_t, 4>;
const Regs kPinHigh{0x00, 0x10, 0x00, 0x00}, kPinLow{0x00, 0x00, 0x00, 0x10};

struct Fixture {
  test::RecordingI2cBus bus;
  double now = 100.0;
  std::unique_ptr<JetbotDrive> drive;
  explicit Fixture(JetbotConfig c = {}) {
    drive = std::make_unique<JetbotDrive>(bus, c, [](double) {});
    drive->set_clock([this] { return now; });
    EXPECT_TRUE(drive->configure().ok());
    EXPECT_TRUE(drive->activate().ok());
    bus.ops.clear();
  }
};

TEST(JetbotDrive, ABoardThatDoesNotAnswerFailsConfigureNamingItsAddress) {
  test::RecordingI2cBus bus;
  bus.fail_writes = true;
  JetbotDrive drive(bus, {}, [](double) {});
  const auto r = drive.configure();
  EXPECT_EQ(r.code, agent::CallbackReturn::kError);
  EXPECT_THAT(r.message, HasSubstr("PCA9685 at I2C address 0x60"));
  EXPECT_THAT(r.message, HasSubstr("Remote I/O error"));
  EXPECT_THAT(r.message, HasSubstr("i2cdetect"));
  EXPECT_EQ(drive.activate().code, agent::CallbackReturn::kFailure) << "not configured";
  bus.fail_writes = false;
  drive.set_wheel_speeds({0.5, 0.5});
  EXPECT_TRUE(bus.ops.empty()) << "an unconfigured drive never writes a command";
}

TEST(JetbotDrive, ActivateBeforeConfigureIsAFailureThatCanBeRetried) {
  test::RecordingI2cBus bus;
  JetbotDrive drive(bus, {}, [](double) {});
  const auto r = drive.activate();
  EXPECT_EQ(r.code, agent::CallbackReturn::kFailure);
  EXPECT_THAT(r.message, HasSubstr("activated before configure()"));
  EXPECT_TRUE(drive.configure().ok());
  EXPECT_TRUE(drive.activate().ok());
}

TEST(JetbotDrive, AdafruitChannelMapForwardAndBackward) {
  Fixture f;
  f.drive->set_wheel_speeds({0.63, -0.315});
  // Left = M1: PWM 8 at 255·16 = 4080, IN1 (10) high, IN2 (9) low.
  EXPECT_EQ(channel(f.bus, 8), (Regs{0x00, 0x00, 0xF0, 0x0F}));
  EXPECT_EQ(channel(f.bus, 10), kPinHigh);
  EXPECT_EQ(channel(f.bus, 9), kPinLow);
  // Right = M2: half speed rounds to 128 (not truncated to 127): PWM 13 at 128·16 = 2048,
  // backward: IN1 (11) low, IN2 (12) high.
  EXPECT_EQ(channel(f.bus, 13), (Regs{0x00, 0x00, 0x00, 0x08}));
  EXPECT_EQ(channel(f.bus, 11), kPinLow);
  EXPECT_EQ(channel(f.bus, 12), kPinHigh);
  EXPECT_EQ(f.drive->left_output().speed, 255);
  EXPECT_EQ(f.drive->right_output().direction, -1);
}

TEST(JetbotDrive, PolarityAndTrimPerWheel) {
  JetbotConfig c;
  c.left.sign = -1;     // wired the other way round (upstream JetBot: "BACKWARD" drives forward)
  c.right.alpha = 0.5;  // a stronger motor on the right
  c.right.beta = 0.1;
  Fixture f(c);
  f.drive->set_wheel_speeds({0.63, 0.63});
  EXPECT_EQ(channel(f.bus, 10), kPinLow);  // left forward now means IN2 high
  EXPECT_EQ(channel(f.bus, 9), kPinHigh);
  EXPECT_EQ(f.drive->right_output().speed, 153);  // 255·(0.5·1 + 0.1)
  EXPECT_EQ(channel(f.bus, 11), kPinHigh);
}

TEST(JetbotDrive, WaveshareUsesChannelsZeroToThree) {
  JetbotConfig c;
  c.board = Board::kWaveshare;
  Fixture f(c);
  f.drive->set_wheel_speeds({0.63, -0.63});
  EXPECT_EQ(channel(f.bus, 1), (Regs{0x00, 0x00, 0xF0, 0x0F}));  // left ina
  EXPECT_EQ(channel(f.bus, 0), (Regs{0x00, 0x00, 0x00, 0x00}));  // left inb
  EXPECT_EQ(channel(f.bus, 2), (Regs{0x00, 0x00, 0x00, 0x00}));  // right ina
  EXPECT_EQ(channel(f.bus, 3), (Regs{0x00, 0x00, 0xF0, 0x0F}));  // right inb
  for (int ch : {8, 9, 10, 11, 12, 13}) EXPECT_EQ(channel(f.bus, ch), (Regs{0, 0, 0, 0})) << ch;
}

TEST(JetbotDrive, WaveshareReversedWheelSwapsItsInputs) {
  JetbotConfig c;
  c.board = Board::kWaveshare;
  c.right.sign = -1;
  Fixture f(c);
  f.drive->set_wheel_speeds({0.63, 0.63});
  EXPECT_EQ(channel(f.bus, 1), (Regs{0x00, 0x00, 0xF0, 0x0F}));  // left forward: ina
  EXPECT_EQ(channel(f.bus, 2), (Regs{0x00, 0x00, 0x00, 0x00}));  // right reversed: not ina...
  EXPECT_EQ(channel(f.bus, 3), (Regs{0x00, 0x00, 0xF0, 0x0F}));  // ...but inb
  EXPECT_TRUE(f.drive->deactivate().ok());
  for (int ch : {0, 1, 2, 3}) EXPECT_EQ(channel(f.bus, ch)[2], 0x00) << ch;
  EXPECT_EQ(f.bus.ops.back(), (test::RecordingI2cBus::Op{'w', 0x60, 0xFD, 0x10}));
}

TEST(JetbotDrive, RegressionTinyCommandsRoundToAPwmStepInsteadOfStalling) {
  // 0.002 m/s is 0.8 of a PWM step: truncation gave 0 and a rotation stalled 0.8° short.
  Fixture f;
  f.drive->set_wheel_speeds({0.002, -0.002});
  EXPECT_EQ(f.drive->left_output().speed, 1);
  EXPECT_EQ(f.drive->right_output().speed, 1);
  EXPECT_EQ(f.drive->right_output().direction, -1);
}

TEST(JetbotDrive, ZeroSpeedReleasesEvenWithTrim) {
  JetbotConfig c;
  c.left.beta = 0.2;
  Fixture f(c);
  f.drive->set_wheel_speeds({0.0, 0.0});
  EXPECT_EQ(f.drive->left_output().speed, 0);
  EXPECT_EQ(channel(f.bus, 10), kPinLow);
  EXPECT_EQ(channel(f.bus, 9), kPinLow);
}

void expect_all_off(const test::RecordingI2cBus& bus) {
  ASSERT_FALSE(bus.ops.empty());
  EXPECT_EQ(bus.ops.back(), (test::RecordingI2cBus::Op{'w', 0x60, 0xFD, 0x10}));
  EXPECT_EQ(channel(bus, 8), (Regs{0, 0, 0, 0}));
  EXPECT_EQ(channel(bus, 10), kPinLow);
  EXPECT_EQ(channel(bus, 9), kPinLow);
}

TEST(JetbotDriveStop, Deactivate) {
  Fixture f;
  f.drive->set_wheel_speeds({0.5, 0.5});
  EXPECT_TRUE(f.drive->deactivate().ok());
  expect_all_off(f.bus);
  f.bus.ops.clear();
  f.drive->set_wheel_speeds({0.5, 0.5});  // inactive: ignored
  EXPECT_TRUE(f.bus.ops.empty());
}

TEST(JetbotDriveStop, CommandWatchdog) {
  Fixture f;
  f.drive->set_wheel_speeds({0.5, 0.5});
  EXPECT_FALSE(f.drive->poll_watchdog(f.now + 0.2));
  f.bus.ops.clear();
  EXPECT_TRUE(f.drive->poll_watchdog(f.now + 0.3));
  expect_all_off(f.bus);
  EXPECT_FALSE(f.drive->poll_watchdog(f.now + 0.4));  // once
}

TEST(JetbotDriveStop, Destructor) {
  Fixture f;
  f.drive->set_wheel_speeds({0.5, 0.5});
  f.drive.reset();
  expect_all_off(f.bus);
}

TEST(JetbotDriveStop, SignalTurnsEverythingOffAndRequestsStop) {
  Fixture f;
  f.drive->set_wheel_speeds({0.5, 0.5});
  std::atomic<bool> stop{false};
  const auto before = SignalStop::signals_seen();
  {
    SignalStop guard(f.bus, 0x60, &stop);
    f.bus.ops.clear();
    ::raise(SIGTERM);
  }
  EXPECT_TRUE(stop.load());
  EXPECT_EQ(SignalStop::signals_seen(), before + 1);
  ASSERT_EQ(f.bus.ops.size(), 1u);
  EXPECT_EQ(f.bus.ops[0], (test::RecordingI2cBus::Op{'w', 0x60, 0xFD, 0x10}));
}

TEST(JetbotConfig, ShippedRobotFileAndErrors) {
  const auto c = parse_jetbot_config(
      config::read_file(std::string(SMART_SOURCE_DIR) + "/config/robots/jetbot.yaml", "robot"),
      "jetbot.yaml");
  EXPECT_EQ(c.address, 0x60);
  EXPECT_EQ(c.board, Board::kAdafruit);
  EXPECT_DOUBLE_EQ(c.command_timeout_s, 0.25);
  auto error_of = [](const std::string& y) {
    try {
      parse_jetbot_config(y, "r.yaml");
    } catch (const config::ConfigError& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  EXPECT_THAT(error_of("name: x\n"), HasSubstr("no 'hardware:' section"));
  EXPECT_THAT(error_of("hardware:\n  board: arduino\n"), HasSubstr("r.yaml:2:10"));
  EXPECT_THAT(error_of("hardware:\n  left: {sign: 0.5}\n"), HasSubstr("must be 1 or -1"));
  EXPECT_THAT(error_of("hardware:\n  address: 0x90\n"), HasSubstr("7-bit"));
}

}  // namespace
}  // namespace smart::hw
