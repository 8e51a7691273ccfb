// Contract: an I2C bus as the PCA9685 driver needs it (Linux i2c-dev semantics,
// docs/hardware.md §3): write bytes to a 7-bit address (the first byte is the
// register), read one register. LinuxI2cBus talks to /dev/i2c-N with open + ioctl(I2C_SLAVE) +
// write/read and throws I2cError carrying errno text and the device. emergency_off_fd() exposes
// the file descriptor for an async-signal-safe stop (write(2) only).
#pragma once

#include <cstdint>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

namespace smart::hw {

class I2cError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class I2cBus {
 public:
  virtual ~I2cBus() = default;
  virtual void write(uint8_t address, const std::vector<uint8_t>& bytes) = 0;
  virtual uint8_t read_register(uint8_t address, uint8_t reg) = 0;
  void write_register(uint8_t address, uint8_t reg, uint8_t value) { write(address, {reg, value}); }
  // A file descriptor on which write(2) of {reg, value} reaches `address` with no further set-up,
  // or -1 (fakes). Used from signal handlers.
  virtual int emergency_fd(uint8_t /*address*/) { return -1; }
};

class LinuxI2cBus : public I2cBus {
 public:
  // Opens /dev/i2c-<bus> (or a full path). Throws I2cError when it cannot.
  explicit LinuxI2cBus(const std::string& device);
  ~LinuxI2cBus() override;
  void write(uint8_t address, const std::vector<uint8_t>& bytes) override;
  uint8_t read_register(uint8_t address, uint8_t reg) override;
  int emergency_fd(uint8_t address) override;

 private:
  void select(uint8_t address);
  std::string device_;
  int fd_ = -1;
  int selected_ = -1;
  std::mutex mutex_;
};

}  // namespace smart::hw
