#include "smart/hw/i2c_bus.hpp"

#include <fcntl.h>
#include <linux/i2c-dev.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace smart::hw {

namespace {
std::string hex(unsigned v) {
  char b[8];
  std::snprintf(b, sizeof b, "0x%02x", v);
  return b;
}
}  // namespace

LinuxI2cBus::LinuxI2cBus(const std::string& device) : device_(device) {
  fd_ = ::open(device.c_str(), O_RDWR | O_CLOEXEC);
  if (fd_ < 0) {
    throw I2cError("cannot open I2C bus " + device + ": " + std::strerror(errno) +
                   "; check the bus number (JetBot: /dev/i2c-1), that i2c-dev is loaded and "
                   "that this user may access it (group i2c)");
  }
}

LinuxI2cBus::~LinuxI2cBus() {
  if (fd_ >= 0) ::close(fd_);
}

void LinuxI2cBus::select(uint8_t address) {
  if (selected_ == address) return;
  if (::ioctl(fd_, I2C_SLAVE, static_cast<long>(address)) < 0) {
    throw I2cError("ioctl(I2C_SLAVE, " + hex(address) + ") on " + device_ + " failed: " +
                   std::strerror(errno) + "; is another driver bound to this address?");
  }
  selected_ = address;
}

void LinuxI2cBus::write(uint8_t address, const std::vector<uint8_t>& bytes) {
  std::lock_guard<std::mutex> lock(mutex_);
  select(address);
  const auto n = ::write(fd_, bytes.data(), bytes.size());
  if (n != static_cast<ssize_t>(bytes.size())) {
    throw I2cError("I2C write of " + std::to_string(bytes.size()) + " bytes to " + hex(address) +
                   " (register " + hex(bytes.empty() ? 0 : bytes[0]) + ") on " + device_ +
                   " failed: " + (n < 0 ? std::strerror(errno) : "short write") +
                   "; check wiring and the board's address");
  }
}

uint8_t LinuxI2cBus::read_register(uint8_t address, uint8_t reg) {
  std::lock_guard<std::mutex> lock(mutex_);
  select(address);
  uint8_t value = 0;
  if (::write(fd_, &reg, 1) != 1 || ::read(fd_, &value, 1) != 1) {
    throw I2cError("I2C read of register " + hex(reg) + " from " + hex(address) + " on " + device_ +
                   " failed: " + std::strerror(errno));
  }
  return value;
}

int LinuxI2cBus::emergency_fd(uint8_t address) {
  std::lock_guard<std::mutex> lock(mutex_);
  select(address);
  return fd_;
}

}  // namespace smart::hw
