// Contract: an emulated JetBot for development and integration tests without hardware. It is
// an I2cBus whose PCA9685 register file (address 0x60) drives a simple wheel model: each
// wheel's speed follows its TB6612 inputs (duty from the PWM channel, direction from IN1/IN2 on
// the Adafruit map, or from ina/inb on the Waveshare map) scaled by max_wheel_speed and the
// wiring sign, with an acceleration limit; outputs are dead while MODE1 SLEEP is set or the
// ALL_LED_OFF full-off bit is set. A thread integrates the pose at 100 Hz and streams it as
// Vicon Tracker UDP datagrams (mm, rad) to 127.0.0.1:port, exactly what a real Tracker sends.
// Imperfections a lab meets, for calibration tests (EmulatedFlaws): a mismatched wheel (each
// wheel's ground speed scaled by its gain) and the mocap system's mounting (the datagrams are in
// a mocap frame that `mounting` maps onto the grid; by default millimetres in the grid's frame).
#pragma once

#include <array>
#include <atomic>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "smart/agent/types.hpp"
#include "smart/hw/i2c_bus.hpp"
#include "smart/hw/jetbot_drive.hpp"
#include "smart/hw/vicon.hpp"

namespace smart::hw {

struct EmulatedFlaws {
  agent::WheelFactors wheel_gain;  // ground speed per commanded speed, per wheel
  geometry::FrameTransform mounting = vicon_millimetres();  // mocap frame -> grid frame
};

class EmulatedJetbot : public I2cBus {
 public:
  EmulatedJetbot(const JetbotConfig& config, double wheel_base_m, agent::Pose2D start,
                 std::string vicon_object, uint16_t vicon_port, double accel_mps2 = 2.0,
                 EmulatedFlaws flaws = {});
  ~EmulatedJetbot() override;

  void write(uint8_t address, const std::vector<uint8_t>& bytes) override;
  uint8_t read_register(uint8_t address, uint8_t reg) override;

  agent::Pose2D pose() const;
  agent::WheelSpeeds wheel_speeds() const;
  // Wheel speed targets decoded from the current registers (no dynamics).
  agent::WheelSpeeds commanded() const;
  uint64_t writes() const;
  // Advances the wheel model by dt (the thread calls this every 10 ms).
  void advance(double dt);

 private:
  double wheel_target(bool left) const;
  bool pin_high(int channel) const;
  int duty(int channel) const;

  JetbotConfig cfg_;
  double wheel_base_m_;
  double accel_;
  EmulatedFlaws flaws_;
  geometry::FrameTransform mocap_from_grid_;
  std::string object_;
  uint16_t port_;
  mutable std::mutex mutex_;
  std::array<uint8_t, 256> regs_{};
  agent::Pose2D pose_;
  agent::WheelSpeeds wheels_;
  uint64_t writes_ = 0;
  int fd_ = -1;
  uint32_t frame_ = 0;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace smart::hw
