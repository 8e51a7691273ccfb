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
#include <deque>
#include <mutex>
#include <random>
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
  // Motor: duty below dead_band (fraction of full) does not turn the wheel; above it the speed
  // grows linearly to full (a DC motor's static friction); lag_s: first-order response.
  double dead_band = 0.0;
  double lag_s = 0.0;
  // Vicon: frames at vicon_rate_hz (at most 100, the emulator's step), each delayed by
  // vicon_latency_s, with Gaussian noise (seeded) on position and heading.
  double vicon_rate_hz = 100.0;
  double vicon_latency_s = 0.0;
  double vicon_noise_m = 0.0;
  double vicon_noise_rad = 0.0;
  uint64_t seed = 0;
};

// The flaws of a real lab JetBot, for experiments (examples/lab-7-jetbots): dead band 60/255
// of full duty, what Duckietown's driver for the same class of TT gear motors on a Jetson motor
// HAT uses as minimum PWM (duckietown/dt-duckiebot-interface, wheels_driver,
// dagu_wheels_driver.py, *_MOTOR_MIN_PWM = 60); a 0.1 s motor time constant (order of magnitude of
// small brushed gear motors; an assumption); Vicon at 100 Hz with 10 ms latency and 0.5 mm /
// 0.2 deg noise (sub-millimetre static precision: Merriaux et al., "A Study of Vicon System
// Positioning Performance", Sensors 17(7):1591, 2017; latency: Vicon Tracker's stated < 10 ms).
EmulatedFlaws realistic_flaws(uint64_t seed);

// Who advances the model: its own thread every 10 ms of wall time (a robot beside real
// processes), or the caller through advance() (tests of the model itself: a loaded machine
// stretches any wall-clock wait, a told time does not).
enum class Stepping : uint8_t { kThread, kManual };

class EmulatedJetbot : public I2cBus {
 public:
  EmulatedJetbot(const JetbotConfig& config, double wheel_base_m, agent::Pose2D start,
                 std::string vicon_object, uint16_t vicon_port, double accel_mps2 = 2.0,
                 const EmulatedFlaws& flaws = {}, Stepping stepping = Stepping::kThread);
  ~EmulatedJetbot() override;

  void write(uint8_t address, const std::vector<uint8_t>& bytes) override;
  uint8_t read_register(uint8_t address, uint8_t reg) override;

  agent::Pose2D pose() const;
  agent::WheelSpeeds wheel_speeds() const;
  // Wheel speed targets decoded from the current registers (no dynamics).
  agent::WheelSpeeds commanded() const;
  uint64_t writes() const;
  // Advances the wheel model by dt (with Stepping::kThread, the thread calls this every 10 ms).
  void advance(double dt);

 private:
  double wheel_target(bool left) const;
  void step_wheels(double dt);
  std::vector<uint8_t> vicon_frame();
  void send(const std::vector<uint8_t>& datagram);
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
  double time_s_ = 0, next_frame_s_ = 0;
  std::mt19937_64 noise_;
  std::deque<std::pair<double, std::vector<uint8_t>>> in_flight_;  // due time, datagram
  int fd_ = -1;
  uint32_t frame_ = 0;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace smart::hw
