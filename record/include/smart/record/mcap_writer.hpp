// Contract: an MCAP file written from the specification (https://mcap.dev/spec, version 0; no C++
// library is packaged in Debian): magic, Header (profile, library), the data section as chunks
// (Schema, Channel and Message records, each chunk zstd-compressed by default, followed by its
// Message Index records; Attachment records between chunks), Data End with the data section's
// CRC-32, then the summary section (Schema, Channel, Statistics, Chunk Index, Attachment Index
// records), Summary Offset records for each group, the
// Footer (with the summary's CRC-32) and the closing magic. Readers can open such a file from its
// end at once (the summary and chunk index) or stream it from its start.
// Pure: bytes go to a ByteSink; memory is bounded by two chunks (chunk_bytes: the one filling and
// the one being compressed) plus one index entry per chunk and one counter per channel, whatever
// the number of messages. With background_chunks a full chunk is compressed and checksummed on a
// second thread (std::async) while the next one fills; the bytes written are the same either way
// and are written by the calling thread, in order.
// Records must be added in this order: a channel's schema before the channel, a channel before
// its messages; write() after finish() throws std::logic_error, as does an unknown channel id.
// Ids are 16 bits in MCAP: more than kMaxIds schemas or channels throw std::length_error.
#pragma once

#include <cstdint>
#include <future>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace smart::record {

class ByteSink {
 public:
  virtual ~ByteSink() = default;
  virtual void write(std::string_view bytes) = 0;
};

// Collects the bytes in memory (tests, small exports).
class StringSink : public ByteSink {
 public:
  void write(std::string_view bytes) override { bytes_.append(bytes); }
  const std::string& bytes() const { return bytes_; }

 private:
  std::string bytes_;
};

struct McapOptions {
  std::string profile = "ros2";  // https://mcap.dev/spec/registry#profiles
  std::string library = "smart-dds";
  std::size_t chunk_bytes = std::size_t{1} << 20;  // uncompressed records per chunk
  bool compress = true;                            // zstd; false: chunks stored as they are
  int zstd_level = 3;                              // zstd's default
  bool background_chunks = true;                   // compress on a second thread
};

struct McapChannel {
  uint16_t schema_id = 0;  // 0: no schema
  std::string topic;
  std::string message_encoding;  // "cdr" for ros2msg and omgidl schemas
  std::map<std::string, std::string> metadata = {};
};

class McapWriter {
 public:
  static constexpr std::size_t kMaxIds = 65535;
  McapWriter(ByteSink& sink, McapOptions options);  // writes the magic and the Header
  ~McapWriter();  // waits for a chunk still being compressed (its bytes are dropped)
  McapWriter(const McapWriter&) = delete;
  McapWriter& operator=(const McapWriter&) = delete;
  // Ids count from 1 in the order of the calls.
  uint16_t add_schema(std::string_view name, std::string_view encoding, std::string_view data);
  uint16_t add_channel(const McapChannel& channel);
  void write(uint16_t channel_id, uint64_t log_time_ns, uint64_t publish_time_ns,
             std::string_view data);
  // An Attachment record (a file carried with the recording, with its CRC-32), written at once
  // after the open chunk; listed in the summary's Attachment Index.
  void attach(std::string_view name, std::string_view media_type, std::string_view data,
              uint64_t log_time_ns = 0);
  // Writes what is left and the summary; nothing may be written after it.
  void finish();
  uint64_t messages() const { return message_count_; }
  // CPU time the background chunk threads used so far (what they add to the process's).
  double background_cpu_s() const { return background_cpu_s_; }
  struct ChannelCount {
    std::string topic, schema_name;
    uint64_t messages = 0;
  };
  // Each channel with its schema's name and messages so far, in channel order (`mcap info`).
  std::vector<ChannelCount> channel_counts() const;

 private:
  struct SchemaRecord {
    std::string name, encoding, data;
  };
  struct ChunkIndex {
    uint64_t start_ns, end_ns, offset, length;
    std::map<uint16_t, uint64_t> index_offsets;
    uint64_t index_length, compressed_size, uncompressed_size;
  };
  // A full chunk's records and message index, and what building it made of them.
  struct OpenChunk {
    std::string records;
    uint64_t start_ns = 0, end_ns = 0;
    std::map<uint16_t, std::vector<std::pair<uint64_t, uint64_t>>> index;  // (log time, offset)
  };
  struct BuiltChunk {
    std::string bytes;  // the Chunk record, then its Message Index records
    uint32_t crc = 0;   // of bytes
    uint64_t chunk_length = 0, compressed_size = 0, uncompressed_size = 0;
    uint64_t start_ns = 0, end_ns = 0;
    std::vector<std::pair<uint16_t, uint64_t>> index_lengths;  // per channel, in order
    double thread_cpu_s = 0;  // the building thread's CPU time when done (background only)
  };
  static BuiltChunk build_chunk(const OpenChunk& chunk, bool compress, int level, bool own_thread);
  void put(std::string_view bytes);  // to the sink, counted in the data CRC and offset
  void put_built(const BuiltChunk& built);
  void flush_chunk();  // seals the open chunk (built in the background, or at once)
  void drain_built();  // writes the chunk being built, if any
  std::string schema_record(uint16_t id) const;
  std::string channel_record(uint16_t id) const;
  std::string statistics_record() const;
  std::string chunk_index_record(const ChunkIndex& c) const;
  struct AttachmentIndex {
    uint64_t offset, length, log_time_ns, data_size;
    std::string name, media_type;
  };
  static std::string attachment_index_record(const AttachmentIndex& a);
  void write_summary();

  ByteSink& sink_;
  McapOptions options_;
  uint64_t offset_ = 0;
  uint32_t data_crc_ = 0;
  bool finished_ = false;
  std::vector<SchemaRecord> schemas_;
  std::vector<McapChannel> channels_;
  std::vector<uint64_t> channel_counts_;
  std::vector<ChunkIndex> chunk_indexes_;
  std::vector<AttachmentIndex> attachment_indexes_;
  // The open chunk: its records, their time span, and per channel (log time, offset) pairs.
  OpenChunk chunk_;
  bool chunk_has_messages_ = false;
  std::future<BuiltChunk> building_;
  std::vector<uint32_t> sequences_;
  uint64_t message_count_ = 0, start_ns_ = 0, end_ns_ = 0;
  double background_cpu_s_ = 0;
};

}  // namespace smart::record
