// Contract: the JetBot motor driver — a PCA9685 driving two TB6612 H-bridge channels —
// implementing the agent's DriveBackend (docs/hardware.md §1-2).
// - Boards: Adafruit Motor HAT (left = M1: PWM 8, IN2 9, IN1 10; right = M2: PWM 13, IN2 12,
//   IN1 11; forward = IN1 high, IN2 low; speed s in 0..255 -> setPWM(pwm, 0, 16·s)) and the
//   Waveshare board (motor inputs on channels 0-3: left (ina, inb) = (1, 0), right (2, 3);
//   forward -> ina = 16·s, inb = 0).
// - Wheel speed (m/s) -> value = v / max_wheel_speed in [-1, 1] -> JetBot's
//   mapped = 255·(alpha·value + beta) per wheel (trim), times the wheel's sign (polarity,
//   verified with a wheel-lift test). Zero speed is released (coast), never trimmed.
// - Outputs go off on deactivate(), in the destructor, when poll_watchdog(now) finds no
//   command for command_timeout_s, and from a SIGINT/SIGTERM handler (SignalStop).
#pragma once

#include <atomic>
#include <memory>
#include <mutex>
#include <string>

#include "smart/agent/interfaces.hpp"
#include "smart/hw/pca9685.hpp"

namespace smart::hw {

enum class Board { kAdafruit, kWaveshare };

struct WheelConfig {
  double sign = 1.0;   // +1 or -1: wiring polarity
  double alpha = 1.0;  // JetBot trim: mapped = 255·(alpha·value + beta)
  double beta = 0.0;
};

struct JetbotConfig {
  Board board = Board::kAdafruit;
  std::string i2c_device = "/dev/i2c-1";
  uint8_t address = 0x60;
  double pwm_frequency_hz = 1600;
  double max_wheel_speed_mps = 0.63;  // TT motor at 200 rpm on 60 mm wheels
  double command_timeout_s = 0.25;    // jetbot_ros diff_drive.yaml cmd_vel_timeout
  WheelConfig left, right;
};

// Reads the `hardware:` section of a robot YAML (strict; ConfigError with file:line).
JetbotConfig parse_jetbot_config(const std::string& yaml_text, const std::string& source);

class JetbotDrive : public agent::DriveBackend {
 public:
  JetbotDrive(I2cBus& bus, JetbotConfig config, Sleeper sleeper);
  ~JetbotDrive() override;

  // PCA9685 init, outputs off; kError naming the board's address when the bus fails.
  agent::LifecycleResult configure() override;
  agent::LifecycleResult activate() override;    // kFailure before configure()
  agent::LifecycleResult deactivate() override;  // outputs off
  void set_wheel_speeds(agent::WheelSpeeds speeds) override;
  void stop() override;
  // Stops the motors when the last command is older than command_timeout_s; true if it did.
  bool poll_watchdog(double now_s);
  void set_clock(std::function<double()> now_s) { now_s_ = std::move(now_s); }

  // Duty (0..255) and direction the last command produced, per wheel (for tests and logs).
  struct WheelOutput {
    int speed = 0;
    int direction = 0;  // +1 forward, -1 backward, 0 released
  };
  WheelOutput left_output() const { return left_out_; }
  WheelOutput right_output() const { return right_out_; }

 private:
  std::string board() const;  // "JetBot motor driver (PCA9685 at I2C address 0x60)"
  void drive_wheel(bool left, double speed_mps);
  void outputs_off();

  Pca9685 pwm_;
  JetbotConfig cfg_;
  std::mutex mutex_;
  bool configured_ = false;
  bool active_ = false;
  double last_command_s_ = 0;
  bool timed_out_ = false;
  std::function<double()> now_s_;
  WheelOutput left_out_, right_out_;
};

// Installs SIGINT/SIGTERM handlers that turn every PCA9685 output off at once (one write(2) of
// ALL_LED_OFF_H full-off, async-signal-safe) and then set `stop_flag`. Restores the previous
// handlers on destruction. One instance at a time.
class SignalStop {
 public:
  SignalStop(I2cBus& bus, uint8_t address, std::atomic<bool>* stop_flag);
  ~SignalStop();
  static uint64_t signals_seen();

 private:
  struct Saved;
  std::unique_ptr<Saved> saved_;
};

}  // namespace smart::hw
