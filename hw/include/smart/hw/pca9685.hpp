// Contract: the PCA9685 16-channel PWM controller (NXP data sheet; register map and the
// Adafruit init sequence in docs/hardware.md §2). init() runs: all outputs off,
// MODE2 totem pole, MODE1 ALLCALL, wake, set the prescale for the PWM frequency (only while
// asleep), restart. set_pwm() writes a channel's four ON/OFF registers; full_on/full_off use
// bit 4 of ON_H / OFF_H. all_off() writes the full-off bit to ALL_LED_OFF_H, which loads it into
// every channel's OFF_H at once (orderly shutdown, one I2C write).
// Sleeps between steps go through a Sleeper so golden tests run instantly.
#pragma once

#include <cstdint>
#include <functional>

#include "smart/hw/i2c_bus.hpp"

namespace smart::hw {

namespace pca9685 {
inline constexpr uint8_t kMode1 = 0x00;
inline constexpr uint8_t kMode2 = 0x01;
inline constexpr uint8_t kLed0OnL = 0x06;  // + 4·channel: ON_L, ON_H, OFF_L, OFF_H
inline constexpr uint8_t kAllLedOnL = 0xFA;
inline constexpr uint8_t kAllLedOnH = 0xFB;
inline constexpr uint8_t kAllLedOffL = 0xFC;
inline constexpr uint8_t kAllLedOffH = 0xFD;
inline constexpr uint8_t kPreScale = 0xFE;
inline constexpr uint8_t kRestart = 0x80;
inline constexpr uint8_t kSleep = 0x10;
inline constexpr uint8_t kAllCall = 0x01;
inline constexpr uint8_t kOutDrv = 0x04;
inline constexpr uint8_t kFullBit = 0x10;  // bit 4 of ON_H / OFF_H
inline constexpr uint16_t kFull = 4096;
// PRE_SCALE = round(25 MHz / (4096 · f)) − 1, at least 3 (data sheet 7.3.5).
uint8_t prescale_for(double frequency_hz);
}  // namespace pca9685

using Sleeper = std::function<void(double seconds)>;

class Pca9685 {
 public:
  Pca9685(I2cBus& bus, uint8_t address, Sleeper sleeper);
  void init(double pwm_frequency_hz);
  // on/off in 0..4096 (4096 = the full on/off bit).
  void set_pwm(int channel, uint16_t on, uint16_t off);
  void set_pin(int channel, bool high) {
    high ? set_pwm(channel, pca9685::kFull, 0) : set_pwm(channel, 0, pca9685::kFull);
  }
  void all_off();
  uint8_t address() const { return address_; }
  I2cBus& bus() { return bus_; }

 private:
  I2cBus& bus_;
  uint8_t address_;
  Sleeper sleep_;
};

}  // namespace smart::hw
