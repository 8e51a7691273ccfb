// Contract: reads an MCAP file (https://mcap.dev/spec, version 0) from its start, record by record,
// as untrusted input (`smart serve --open FILE.mcap`, import.hpp). Every length is checked against
// the bytes left in its record or chunk before anything is allocated; a chunk may not declare more
// than limits.max_chunk_bytes uncompressed (zstd or uncompressed; other compressions are refused
// by name), a record read whole (attachments, messages outside chunks) no more than
// limits.max_record_bytes; the data section's, each chunk's, each attachment's and the summary's
// CRC-32 are checked when the writer gave them (0: not given). The file must open with the magic
// and a Header and end with a Footer and the magic: a file cut anywhere is an error naming the
// byte where it ends. Schemas and channels must be defined before their use and never redefined
// differently. Index and summary records are read and checked for their bounds but not used.
// Errors are McapError (std::invalid_argument) naming the source, the byte offset, the record and
// what to do; nothing else escapes for any input (tests/fuzz/fuzz_mcap.cpp).
// Memory: one record or one decompressed chunk at a time. Pure: bytes come from a ByteSource.
#pragma once

#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <string_view>

namespace smart::record {

class McapError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

class ByteSource {
 public:
  virtual ~ByteSource() = default;
  // Up to n bytes into out; fewer only at the end. Throws std::runtime_error on a read failure.
  virtual std::size_t read(char* out, std::size_t n) = 0;
};

class StringSource : public ByteSource {
 public:
  explicit StringSource(std::string_view bytes) : bytes_(bytes) {}
  std::size_t read(char* out, std::size_t n) override;

 private:
  std::string_view bytes_;
  std::size_t at_ = 0;
};

struct McapLimits {
  uint64_t max_chunk_bytes = uint64_t{256} << 20;
  uint64_t max_record_bytes = uint64_t{1} << 30;
};

struct McapSchemaInfo {
  uint16_t id = 0;
  std::string name, encoding, data;
};
struct McapChannelInfo {
  uint16_t id = 0, schema_id = 0;  // schema 0: none
  std::string topic, message_encoding;
  std::map<std::string, std::string> metadata;
};
struct McapMessageView {
  const McapChannelInfo& channel;
  uint32_t sequence = 0;
  uint64_t log_time_ns = 0, publish_time_ns = 0;
  std::string_view data;  // valid during the call only
};
struct McapAttachmentView {
  uint64_t log_time_ns = 0, create_time_ns = 0;
  std::string_view name, media_type, data;  // valid during the call only
};

// What the reader found, in file order. Exceptions thrown by a visitor pass through unchanged.
class McapVisitor {
 public:
  virtual ~McapVisitor() = default;
  virtual void header(std::string_view /*profile*/, std::string_view /*library*/) {}
  virtual void schema(const McapSchemaInfo& /*schema*/) {}
  virtual void channel(const McapChannelInfo& /*channel*/) {}
  virtual void message(const McapMessageView& /*message*/) {}
  virtual void attachment(const McapAttachmentView& /*attachment*/) {}
};

// Reads the whole source; `source_name` starts every error message (a file name).
void read_mcap(ByteSource& source, McapVisitor& visitor, const std::string& source_name,
               const McapLimits& limits = {});

}  // namespace smart::record
