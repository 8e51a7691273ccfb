#include "smart/hw/emulated_jetbot.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "smart/hw/vicon.hpp"

namespace smart::hw {

EmulatedJetbot::EmulatedJetbot(const JetbotConfig& config, double wheel_base_m, agent::Pose2D start,
                               std::string object, uint16_t port, double accel,
                               const EmulatedFlaws& flaws, Stepping stepping)
    : cfg_(config),
      wheel_base_m_(wheel_base_m),
      accel_(accel),
      flaws_(flaws),
      mocap_from_grid_(flaws.mounting.inverse()),
      object_(std::move(object)),
      port_(port),
      pose_(start),
      noise_(flaws.seed) {
  regs_[pca9685::kMode1] = pca9685::kSleep | pca9685::kAllCall;  // power-on default: asleep
  if (port_ != 0) fd_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  if (stepping == Stepping::kManual) return;
  thread_ = std::thread([this] {
    auto next = std::chrono::steady_clock::now();
    while (!stop_) {
      next += std::chrono::milliseconds(10);
      std::this_thread::sleep_until(next);
      advance(0.01);
    }
  });
}

EmulatedJetbot::~EmulatedJetbot() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
  if (fd_ >= 0) ::close(fd_);
}

void EmulatedJetbot::write(uint8_t address, const std::vector<uint8_t>& bytes) {
  if (address != cfg_.address || bytes.empty()) {
    throw I2cError("emulated JetBot: no device at this address (the PCA9685 is at 0x" +
                   std::to_string(cfg_.address) + ")");
  }
  std::lock_guard<std::mutex> lock(mutex_);
  uint8_t reg = bytes[0];
  for (std::size_t i = 1; i < bytes.size(); ++i) {
    if (reg >= pca9685::kAllLedOnL && reg <= pca9685::kAllLedOffH) {
      // ALL_LED registers load the same register of every channel at once (data sheet 7.3.4).
      for (int ch = 0; ch < 16; ++ch)
        regs_[pca9685::kLed0OnL + 4 * ch + (reg - pca9685::kAllLedOnL)] = bytes[i];
    } else {
      // A write of MODE1 with RESTART set clears the bit again (data sheet 7.3.1.1).
      regs_[reg] = reg == pca9685::kMode1 ? (bytes[i] & 0x7F) : bytes[i];
    }
    ++reg;
  }
  ++writes_;
}

uint8_t EmulatedJetbot::read_register(uint8_t address, uint8_t reg) {
  if (address != cfg_.address) throw I2cError("emulated JetBot: no device at this address");
  std::lock_guard<std::mutex> lock(mutex_);
  return regs_[reg];
}

bool EmulatedJetbot::pin_high(int ch) const {
  const auto base = pca9685::kLed0OnL + 4 * ch;
  return (regs_[base + 1] & pca9685::kFullBit) && !(regs_[base + 3] & pca9685::kFullBit);
}

int EmulatedJetbot::duty(int ch) const {
  const auto base = pca9685::kLed0OnL + 4 * ch;
  if (regs_[base + 3] & pca9685::kFullBit) return 0;
  if (regs_[base + 1] & pca9685::kFullBit) return 4096;
  return (regs_[base + 2] | ((regs_[base + 3] & 0x0F) << 8)) -
         (regs_[base] | ((regs_[base + 1] & 0x0F) << 8));
}

double EmulatedJetbot::wheel_target(bool left) const {
  if (regs_[pca9685::kMode1] & pca9685::kSleep) return 0.0;  // oscillator off
  const WheelConfig& w = left ? cfg_.left : cfg_.right;
  int d = 0, dir = 0;
  if (cfg_.board == Board::kAdafruit) {
    const int pwm = left ? 8 : 13, in1 = left ? 10 : 11, in2 = left ? 9 : 12;
    d = std::max(0, duty(pwm));
    const bool a = pin_high(in1), b = pin_high(in2);
    dir = a && !b ? 1 : (b && !a ? -1 : 0);
  } else {
    const int ina = left ? 1 : 2, inb = left ? 0 : 3;
    const int da = std::max(0, duty(ina)), db = std::max(0, duty(inb));
    d = std::max(da, db);
    dir = da > 0 && db == 0 ? 1 : (db > 0 && da == 0 ? -1 : 0);
  }
  // The wiring's sign undoes the driver's polarity setting: forward means forward.
  const double fraction = d / 4080.0, db = flaws_.dead_band;
  const double effective = fraction <= db ? 0.0 : (fraction - db) / (1.0 - db);
  return w.sign * dir * effective * cfg_.max_wheel_speed_mps;
}

agent::WheelSpeeds EmulatedJetbot::commanded() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return {wheel_target(true), wheel_target(false)};
}

EmulatedFlaws realistic_flaws(uint64_t seed) {
  EmulatedFlaws f;
  f.dead_band = 60.0 / 255.0;
  f.lag_s = 0.1;
  f.vicon_rate_hz = 100.0;
  f.vicon_latency_s = 0.010;
  f.vicon_noise_m = 0.0005;
  f.vicon_noise_rad = 0.2 * M_PI / 180.0;
  f.seed = seed;
  return f;
}

// Wheels follow their targets (first-order lag, then the acceleration limit); the pose follows
// the wheels (each scaled by its gain).
void EmulatedJetbot::step_wheels(double dt) {
  const double tl = wheel_target(true), tr = wheel_target(false);
  const double k = flaws_.lag_s > 0 ? 1.0 - std::exp(-dt / flaws_.lag_s) : 1.0;
  const double dv = accel_ * dt;
  wheels_.left_mps += std::clamp(k * (tl - wheels_.left_mps), -dv, dv);
  wheels_.right_mps += std::clamp(k * (tr - wheels_.right_mps), -dv, dv);
  const double left = wheels_.left_mps * flaws_.wheel_gain.left;
  const double right = wheels_.right_mps * flaws_.wheel_gain.right;
  const double v = (left + right) / 2, w = (right - left) / wheel_base_m_;
  pose_.x_m += v * std::cos(pose_.yaw_rad) * dt;
  pose_.y_m += v * std::sin(pose_.yaw_rad) * dt;
  pose_.yaw_rad = std::remainder(pose_.yaw_rad + w * dt, 2 * M_PI);
}

// The pose as Vicon reports it: in the mocap frame, with measurement noise.
std::vector<uint8_t> EmulatedJetbot::vicon_frame() {
  // A unit normal scaled: a distribution's standard deviation must be positive, and a noiseless
  // Vicon has none (libstdc++'s assertions abort on it).
  std::normal_distribution<double> unit(0.0, 1.0);
  const double nx = flaws_.vicon_noise_m > 0 ? flaws_.vicon_noise_m * unit(noise_) : 0.0;
  const double ny = flaws_.vicon_noise_m > 0 ? flaws_.vicon_noise_m * unit(noise_) : 0.0;
  const double nyaw = flaws_.vicon_noise_rad > 0 ? flaws_.vicon_noise_rad * unit(noise_) : 0.0;
  const Eigen::Vector2d p = mocap_from_grid_.apply({pose_.x_m + nx, pose_.y_m + ny});
  ViconObject o{
      object_, {p.x(), p.y(), 0}, {0, 0, mocap_from_grid_.apply_yaw(pose_.yaw_rad + nyaw)}};
  return make_vicon_datagram(++frame_, {o});
}

void EmulatedJetbot::advance(double dt) {
  std::vector<std::vector<uint8_t>> due;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    step_wheels(dt);
    time_s_ += dt;
    if (fd_ >= 0 && time_s_ + 1e-9 >= next_frame_s_) {
      next_frame_s_ += 1.0 / flaws_.vicon_rate_hz;
      in_flight_.emplace_back(time_s_ + flaws_.vicon_latency_s, vicon_frame());
    }
    while (!in_flight_.empty() && in_flight_.front().first <= time_s_ + 1e-9) {
      due.push_back(std::move(in_flight_.front().second));
      in_flight_.pop_front();
    }
  }
  for (const auto& d : due) send(d);
}

void EmulatedJetbot::send(const std::vector<uint8_t>& datagram) {
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(port_);
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ::sendto(fd_, datagram.data(), datagram.size(), 0, reinterpret_cast<sockaddr*>(&a), sizeof a);
}

agent::Pose2D EmulatedJetbot::pose() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return pose_;
}

agent::WheelSpeeds EmulatedJetbot::wheel_speeds() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return wheels_;
}

uint64_t EmulatedJetbot::writes() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return writes_;
}

}  // namespace smart::hw
