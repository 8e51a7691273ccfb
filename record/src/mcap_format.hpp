// The MCAP format's constants shared by the writer and the reader (https://mcap.dev/spec,
// "Records"): the magic, the opcodes, a record's opening (opcode, u64 length) and the CRC-32 the
// format uses (zlib's). Internal to record/.
#pragma once

#include <zlib.h>

#include <cstdint>
#include <string_view>

namespace smart::record::mcap {

inline constexpr std::string_view kMagic("\x89MCAP0\r\n", 8);
inline constexpr std::size_t kRecordHeader = 9;  // opcode, u64 length

enum Op : uint8_t {
  kHeader = 0x01,
  kFooter = 0x02,
  kSchema = 0x03,
  kChannel = 0x04,
  kMessage = 0x05,
  kChunk = 0x06,
  kMessageIndex = 0x07,
  kChunkIndex = 0x08,
  kAttachment = 0x09,
  kAttachmentIndex = 0x0A,
  kStatistics = 0x0B,
  kSummaryOffset = 0x0E,
  kDataEnd = 0x0F,
};

inline uint32_t crc(uint32_t running, std::string_view bytes) {
  return static_cast<uint32_t>(
      crc32_z(running, reinterpret_cast<const Bytef*>(bytes.data()), bytes.size()));
}

}  // namespace smart::record::mcap
