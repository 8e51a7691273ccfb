// A fake I2C bus that records every transaction and answers reads from a register file.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "smart/hw/i2c_bus.hpp"

namespace smart::test {

class RecordingI2cBus : public hw::I2cBus {
 public:
  struct Op {
    char kind;  // 'w' write, 'r' read
    uint8_t address, reg, value;
    bool operator==(const Op&) const = default;
  };
  void write(uint8_t address, const std::vector<uint8_t>& bytes) override {
    if (fail_writes) throw hw::I2cError("I2C write to 0x60 on /dev/i2c-1 failed: Remote I/O error");
    for (std::size_t i = 1; i < bytes.size(); ++i) {
      ops.push_back({'w', address, static_cast<uint8_t>(bytes[0] + i - 1), bytes[i]});
      regs[static_cast<uint8_t>(bytes[0] + i - 1)] = bytes[i];
    }
  }
  uint8_t read_register(uint8_t address, uint8_t reg) override {
    ops.push_back({'r', address, reg, regs[reg]});
    return regs[reg];
  }
  std::vector<Op> writes_to(uint8_t reg) const {
    std::vector<Op> out;
    for (const auto& o : ops)
      if (o.kind == 'w' && o.reg == reg) out.push_back(o);
    return out;
  }
  bool fail_writes = false;  // a board that does not answer
  std::vector<Op> ops;
  std::array<uint8_t, 256> regs{};
};

}  // namespace smart::test
