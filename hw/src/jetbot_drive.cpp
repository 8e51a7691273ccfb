#include "smart/hw/jetbot_drive.hpp"

#include <signal.h>  // NOLINT(modernize-deprecated-headers): sigaction is POSIX, not <csignal>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#include "smart/common/steady_clock.hpp"
#include "smart/config/yaml_checks.hpp"

namespace smart::hw {

namespace {

struct Channels {
  int pwm, in1, in2;  // Adafruit: speed on pwm, direction on in1/in2; Waveshare: ina=in1, inb=in2
};
// Adafruit_DCMotor pin map (docs/hardware.md §1).
constexpr Channels kAdafruitLeft{8, 10, 9}, kAdafruitRight{13, 11, 12};
// Waveshare: (ina, inb) = (1, 0) for motor 1 and (2, 3) for motor 2.
constexpr Channels kWaveshareLeft{-1, 1, 0}, kWaveshareRight{-1, 2, 3};

}  // namespace

JetbotConfig parse_jetbot_config(const std::string& text, const std::string& source) {
  const auto root = config::load(text, source);
  JetbotConfig c;
  const auto hw = root.IsMap() ? root["hardware"] : YAML::Node();
  if (!hw) {
    throw config::ConfigError(source +
                              ": no 'hardware:' section; add one with board, i2c_device, "
                              "address, pwm_frequency_hz, max_wheel_speed_mps, left, right");
  }
  config::require_map(source, hw, "hardware");
  config::reject_unknown(source, hw, "hardware",
                         {"board", "i2c_device", "address", "pwm_frequency_hz",
                          "max_wheel_speed_mps", "command_timeout_s", "left", "right"});
  if (hw["board"]) {
    c.board =
        config::choice<Board>(source, hw["board"], "hardware.board",
                              {{"adafruit", Board::kAdafruit}, {"waveshare", Board::kWaveshare}});
  }
  if (hw["i2c_device"]) {
    c.i2c_device = config::scalar<std::string>(source, hw["i2c_device"], "hardware.i2c_device",
                                               "a device path such as /dev/i2c-1");
  }
  if (hw["address"]) {
    const auto a = config::scalar<int>(source, hw["address"], "hardware.address",
                                       "a 7-bit I2C address such as 0x60");
    if (a < 0x03 || a > 0x77) {
      config::fail(source, hw["address"], "'hardware.address' must be a 7-bit address 0x03..0x77");
    }
    c.address = static_cast<uint8_t>(a);
  }
  if (hw["pwm_frequency_hz"]) {
    // Above ~1526 Hz the prescale bottoms out at 3 (Adafruit's default 1600 gives 1526 Hz).
    c.pwm_frequency_hz =
        config::number(source, hw["pwm_frequency_hz"], "hardware.pwm_frequency_hz", 24, 1600);
  }
  if (hw["max_wheel_speed_mps"]) {
    c.max_wheel_speed_mps =
        config::number(source, hw["max_wheel_speed_mps"], "hardware.max_wheel_speed_mps", 0.01, 10);
  }
  if (hw["command_timeout_s"]) {
    c.command_timeout_s =
        config::number(source, hw["command_timeout_s"], "hardware.command_timeout_s", 0.01, 10);
  }
  for (const auto& [key, wheel] : {std::pair{"left", &c.left}, std::pair{"right", &c.right}}) {
    const auto w = hw[key];
    if (!w) continue;
    const std::string path = std::string("hardware.") + key;
    config::require_map(source, w, path);
    config::reject_unknown(source, w, path, {"sign", "alpha", "beta"});
    if (w["sign"]) {
      wheel->sign = config::number(source, w["sign"], path + ".sign", -1, 1);
      if (wheel->sign != 1 && wheel->sign != -1) {
        config::fail(source, w["sign"], "'" + path + ".sign' must be 1 or -1");
      }
    }
    if (w["alpha"]) wheel->alpha = config::number(source, w["alpha"], path + ".alpha", 0, 2);
    if (w["beta"]) wheel->beta = config::number(source, w["beta"], path + ".beta", -0.5, 0.5);
  }
  return c;
}

JetbotDrive::JetbotDrive(I2cBus& bus, JetbotConfig config, Sleeper sleeper)
    : pwm_(bus, config.address, std::move(sleeper)),
      cfg_(std::move(config)),
      now_s_(common::steady_s) {}

JetbotDrive::~JetbotDrive() {
  try {
    if (configured_) outputs_off();
  } catch (...) {
    // Nothing more can be done from a destructor; the watchdog on the board side is wiring.
  }
}

agent::LifecycleResult JetbotDrive::configure() {
  std::lock_guard<std::mutex> lock(mutex_);
  try {
    pwm_.init(cfg_.pwm_frequency_hz);
    configured_ = true;
    outputs_off();
  } catch (const std::exception& e) {
    return agent::LifecycleResult::error(board() + " did not configure: " + e.what() +
                                         "; check its wiring and address (`i2cdetect -y 1`)");
  }
  return agent::LifecycleResult::success();
}

agent::LifecycleResult JetbotDrive::activate() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!configured_) {
    return agent::LifecycleResult::failure(board() + " activated before configure(); configure it");
  }
  active_ = true;
  last_command_s_ = now_s_();
  timed_out_ = false;
  return agent::LifecycleResult::success();
}

agent::LifecycleResult JetbotDrive::deactivate() {
  std::lock_guard<std::mutex> lock(mutex_);
  active_ = false;
  try {
    if (configured_) outputs_off();
  } catch (const std::exception& e) {
    return agent::LifecycleResult::error(board() + " did not stop its outputs: " + e.what() +
                                         "; cut the motor power");
  }
  return agent::LifecycleResult::success();
}

std::string JetbotDrive::board() const {
  char addr[8];
  std::snprintf(addr, sizeof addr, "0x%02x", static_cast<unsigned>(cfg_.address));
  return std::string("JetBot motor driver (PCA9685 at I2C address ") + addr + ")";
}

void JetbotDrive::stop() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (configured_) outputs_off();
}

void JetbotDrive::set_wheel_speeds(agent::WheelSpeeds s) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!configured_ || !active_) return;  // only an active drive moves
  last_command_s_ = now_s_();
  timed_out_ = false;
  drive_wheel(true, s.left_mps);
  drive_wheel(false, s.right_mps);
}

bool JetbotDrive::poll_watchdog(double now_s) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!configured_ || timed_out_ || now_s - last_command_s_ <= cfg_.command_timeout_s) {
    return false;
  }
  timed_out_ = true;
  outputs_off();
  return true;
}

void JetbotDrive::drive_wheel(bool left, double v) {
  const WheelConfig& w = left ? cfg_.left : cfg_.right;
  const Channels ch = cfg_.board == Board::kAdafruit ? (left ? kAdafruitLeft : kAdafruitRight)
                                                     : (left ? kWaveshareLeft : kWaveshareRight);
  const double value = std::clamp(v / cfg_.max_wheel_speed_mps, -1.0, 1.0);
  int mapped = 0;
  if (value != 0.0) {
    // JetBot motor.py: mapped = int(255·(alpha·value + beta)), trim per wheel; beta pushes
    // through the motor's dead band in the direction of motion.
    // Rounded, not truncated: a command below half a PWM step would otherwise never move a
    // wheel, and a heading controller would stall short of its target.
    mapped =
        static_cast<int>(std::lround(255.0 * (w.alpha * value + (value > 0 ? w.beta : -w.beta))));
    mapped = static_cast<int>(w.sign) * mapped;
  }
  const int speed = std::clamp(std::abs(mapped), 0, 255);
  const int dir = speed == 0 ? 0 : (mapped > 0 ? 1 : -1);
  (left ? left_out_ : right_out_) = {speed, dir};
  const auto duty = static_cast<uint16_t>(speed * 16);
  if (cfg_.board == Board::kAdafruit) {
    // run(FORWARD): IN2 low, IN1 high; run(BACKWARD): IN1 low, IN2 high; RELEASE: both low.
    pwm_.set_pwm(ch.pwm, 0, duty);
    pwm_.set_pin(ch.in1, dir > 0);
    pwm_.set_pin(ch.in2, dir < 0);
  } else {
    pwm_.set_pwm(ch.in1, 0, dir > 0 ? duty : 0);
    pwm_.set_pwm(ch.in2, 0, dir < 0 ? duty : 0);
  }
}

void JetbotDrive::outputs_off() {
  // Release both motors explicitly, then the chip-wide full-off bit.
  for (const bool left : {true, false}) {
    const Channels ch = cfg_.board == Board::kAdafruit ? (left ? kAdafruitLeft : kAdafruitRight)
                                                       : (left ? kWaveshareLeft : kWaveshareRight);
    if (cfg_.board == Board::kAdafruit) {
      pwm_.set_pwm(ch.pwm, 0, 0);
      pwm_.set_pin(ch.in1, false);
      pwm_.set_pin(ch.in2, false);
    } else {
      pwm_.set_pwm(ch.in1, 0, 0);
      pwm_.set_pwm(ch.in2, 0, 0);
    }
  }
  left_out_ = right_out_ = {};
  pwm_.all_off();
}

// --- SignalStop ---

namespace {
std::atomic<int> g_fd{-1};
I2cBus* g_bus = nullptr;
uint8_t g_address = 0;
std::atomic<bool>* g_flag = nullptr;
std::atomic<uint64_t> g_signals{0};

void on_signal(int) {
  const uint8_t off[2] = {pca9685::kAllLedOffH, pca9685::kFullBit};
  const int fd = g_fd.load();
  if (fd >= 0) {
    [[maybe_unused]] const auto n = ::write(fd, off, 2);  // async-signal-safe
  } else if (g_bus != nullptr) {
    g_bus->write_register(g_address, off[0], off[1]);  // in-process fakes and emulators only
  }
  ++g_signals;
  if (g_flag != nullptr) g_flag->store(true);
}
}  // namespace

struct SignalStop::Saved {
  struct sigaction old_int {
  }, old_term{};
};

SignalStop::SignalStop(I2cBus& bus, uint8_t address, std::atomic<bool>* stop_flag)
    : saved_(std::make_unique<Saved>()) {
  g_bus = &bus;
  g_address = address;
  g_flag = stop_flag;
  g_fd = bus.emergency_fd(address);
  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, &saved_->old_int);
  sigaction(SIGTERM, &sa, &saved_->old_term);
}

SignalStop::~SignalStop() {
  sigaction(SIGINT, &saved_->old_int, nullptr);
  sigaction(SIGTERM, &saved_->old_term, nullptr);
  g_bus = nullptr;
  g_flag = nullptr;
  g_fd = -1;
}

uint64_t SignalStop::signals_seen() { return g_signals.load(); }

}  // namespace smart::hw
