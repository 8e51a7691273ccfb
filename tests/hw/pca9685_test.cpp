#include "smart/hw/pca9685.hpp"

#include <gtest/gtest.h>

#include "support/recording_i2c_bus.hpp"

namespace smart::hw {
namespace {

using Op = test::RecordingI2cBus::Op;

TEST(Pca9685, PrescaleFollowsTheDataSheetFormula) {
  EXPECT_EQ(pca9685::prescale_for(1600), 3);  // floor(25e6/4096/1600 - 1 + 0.5)
  EXPECT_EQ(pca9685::prescale_for(50), 121);
  EXPECT_EQ(pca9685::prescale_for(5000), 3);  // hardware minimum
}

TEST(Pca9685, GoldenInitSequence) {
  test::RecordingI2cBus bus;
  bus.regs[pca9685::kMode1] = 0x11;  // power-on: SLEEP | ALLCALL
  std::vector<double> sleeps;
  Pca9685 chip(bus, 0x60, [&](double s) { sleeps.push_back(s); });
  chip.init(1600);
  const std::vector<Op> expected = {
      {'w', 0x60, 0xFA, 0x00}, {'w', 0x60, 0xFB, 0x00}, {'w', 0x60, 0xFC, 0x00},
      {'w', 0x60, 0xFD, 0x00}, {'w', 0x60, 0x01, 0x04},  // MODE2 <- OUTDRV
      {'w', 0x60, 0x00, 0x01},                           // MODE1 <- ALLCALL
      {'r', 0x60, 0x00, 0x01}, {'w', 0x60, 0x00, 0x01},  // wake (SLEEP cleared)
      {'r', 0x60, 0x00, 0x01}, {'w', 0x60, 0x00, 0x11},  // sleep to set the prescale
      {'w', 0x60, 0xFE, 0x03},                           // PRE_SCALE for 1600 Hz
      {'w', 0x60, 0x00, 0x01},                           // restore MODE1
      {'w', 0x60, 0x00, 0x81},                           // RESTART
  };
  EXPECT_EQ(bus.ops, expected);
  EXPECT_EQ(sleeps, (std::vector<double>{0.005, 0.005, 0.005}));
}

TEST(Pca9685, SetPwmWritesFourRegistersAndFullBits) {
  test::RecordingI2cBus bus;
  Pca9685 chip(bus, 0x60, [](double) {});
  chip.set_pwm(8, 0, 4080);
  EXPECT_EQ(bus.ops, (std::vector<Op>{{'w', 0x60, 0x26, 0x00},
                                      {'w', 0x60, 0x27, 0x00},
                                      {'w', 0x60, 0x28, 0xF0},
                                      {'w', 0x60, 0x29, 0x0F}}));
  bus.ops.clear();
  chip.set_pin(10, true);  // ON_H full bit
  EXPECT_EQ(bus.regs[0x06 + 40 + 1], 0x10);
  EXPECT_EQ(bus.regs[0x06 + 40 + 3], 0x00);
  chip.all_off();
  EXPECT_EQ(bus.ops.back(), (Op{'w', 0x60, 0xFD, 0x10}));
}

}  // namespace
}  // namespace smart::hw
