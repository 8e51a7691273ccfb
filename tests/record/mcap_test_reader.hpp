// Test support: a minimal MCAP record walker (https://mcap.dev/spec), independent of the writer,
// to check what the writer wrote: records in order with their offsets, little-endian fields.
#pragma once

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace smart::record::test {

inline constexpr std::string_view kMagic("\x89MCAP0\r\n", 8);

struct Rec {
  uint8_t op;
  uint64_t offset;   // of the opcode in the bytes walked
  std::string body;  // the record's content
};

template <class T>
T get(std::string_view b, std::size_t at) {
  if (at + sizeof(T) > b.size()) throw std::out_of_range("field past the end");
  uint64_t v = 0;
  for (std::size_t i = 0; i < sizeof(T); ++i) {
    v |= static_cast<uint64_t>(static_cast<uint8_t>(b[at + i])) << (8 * i);
  }
  return static_cast<T>(v);
}

// Records of `bytes` from `from` until `to` (both offsets into bytes).
inline std::vector<Rec> walk(std::string_view bytes, std::size_t from, std::size_t to) {
  std::vector<Rec> out;
  for (std::size_t at = from; at < to;) {
    const auto op = static_cast<uint8_t>(bytes[at]);
    const auto len = get<uint64_t>(bytes, at + 1);
    out.push_back({op, at, std::string(bytes.substr(at + 9, len))});
    at += 9 + len;
  }
  return out;
}

}  // namespace smart::record::test
