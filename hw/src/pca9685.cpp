#include "smart/hw/pca9685.hpp"

#include <algorithm>
#include <cmath>

namespace smart::hw {

uint8_t pca9685::prescale_for(double f) {
  const double p = std::floor(25e6 / 4096.0 / f - 1.0 + 0.5);
  return static_cast<uint8_t>(std::clamp(p, 3.0, 255.0));
}

Pca9685::Pca9685(I2cBus& bus, uint8_t address, Sleeper sleeper)
    : bus_(bus), address_(address), sleep_(std::move(sleeper)) {}

void Pca9685::init(double f) {
  using namespace pca9685;
  // Adafruit_PWM_Servo_Driver constructor, then setPWMFreq (docs/hardware.md §2, steps 1-5).
  bus_.write_register(address_, kAllLedOnL, 0);
  bus_.write_register(address_, kAllLedOnH, 0);
  bus_.write_register(address_, kAllLedOffL, 0);
  bus_.write_register(address_, kAllLedOffH, 0);
  bus_.write_register(address_, kMode2, kOutDrv);
  bus_.write_register(address_, kMode1, kAllCall);
  sleep_(0.005);
  const uint8_t mode1 = bus_.read_register(address_, kMode1);
  bus_.write_register(address_, kMode1, mode1 & static_cast<uint8_t>(~kSleep));  // wake
  sleep_(0.005);
  const uint8_t old = bus_.read_register(address_, kMode1);
  bus_.write_register(address_, kMode1, static_cast<uint8_t>((old & 0x7F) | kSleep));
  bus_.write_register(address_, kPreScale, prescale_for(f));  // only while asleep
  bus_.write_register(address_, kMode1, old);
  sleep_(0.005);  // >= 500 µs after waking before RESTART (data sheet 7.3.1.1)
  bus_.write_register(address_, kMode1, static_cast<uint8_t>(old | kRestart));
}

void Pca9685::set_pwm(int channel, uint16_t on, uint16_t off) {
  const auto base = static_cast<uint8_t>(pca9685::kLed0OnL + 4 * channel);
  bus_.write_register(address_, base, static_cast<uint8_t>(on & 0xFF));
  bus_.write_register(address_, base + 1, static_cast<uint8_t>(on >> 8));
  bus_.write_register(address_, base + 2, static_cast<uint8_t>(off & 0xFF));
  bus_.write_register(address_, base + 3, static_cast<uint8_t>(off >> 8));
}

void Pca9685::all_off() { bus_.write_register(address_, pca9685::kAllLedOffH, pca9685::kFullBit); }

}  // namespace smart::hw
