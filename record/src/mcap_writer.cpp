#include "smart/record/mcap_writer.hpp"

#include <zstd.h>

#include <stdexcept>

#include "mcap_format.hpp"
#include "smart/common/memory.hpp"

namespace smart::record {

namespace {

using namespace mcap;  // NOLINT(google-build-using-namespace): the format's own names

template <class T>
void le(std::string& out, T v) {
  for (std::size_t i = 0; i < sizeof(T); ++i) {
    out.push_back(static_cast<char>(static_cast<uint64_t>(v) >> (8 * i) & 0xff));
  }
}
void str(std::string& out, std::string_view s) {
  le(out, static_cast<uint32_t>(s.size()));
  out.append(s);
}
// A record: opcode, u64 length, content.
std::string record(uint8_t op, std::string_view content) {
  std::string r;
  r.reserve(kRecordHeader + content.size());
  r.push_back(static_cast<char>(op));
  le(r, static_cast<uint64_t>(content.size()));
  r.append(content);
  return r;
}
std::string compress_zstd(std::string_view in, int level) {
  std::string out(ZSTD_compressBound(in.size()), '\0');
  const std::size_t n = ZSTD_compress(out.data(), out.size(), in.data(), in.size(), level);
  if (ZSTD_isError(n)) {
    throw std::runtime_error(std::string("MCAP chunk: zstd failed: ") + ZSTD_getErrorName(n));
  }
  out.resize(n);
  return out;
}

}  // namespace

McapWriter::McapWriter(ByteSink& sink, McapOptions options)
    : sink_(sink), options_(std::move(options)) {
  put(kMagic);
  std::string h;
  str(h, options_.profile);
  str(h, options_.library);
  put(record(kHeader, h));
}

void McapWriter::put(std::string_view bytes) {
  sink_.write(bytes);
  data_crc_ = crc(data_crc_, bytes);
  offset_ += bytes.size();
}

uint16_t McapWriter::add_schema(std::string_view name, std::string_view encoding,
                                std::string_view data) {
  if (finished_) throw std::logic_error("MCAP: add_schema after finish");
  if (schemas_.size() >= kMaxIds) throw std::length_error("MCAP: more than 65535 schemas");
  schemas_.push_back({std::string(name), std::string(encoding), std::string(data)});
  const auto id = static_cast<uint16_t>(schemas_.size());
  chunk_.records += schema_record(id);
  return id;
}

uint16_t McapWriter::add_channel(const McapChannel& channel) {
  if (finished_) throw std::logic_error("MCAP: add_channel after finish");
  if (channels_.size() >= kMaxIds) {
    throw std::length_error("MCAP: more than 65535 channels (" + channel.topic + ")");
  }
  if (channel.schema_id > schemas_.size()) {
    throw std::logic_error("MCAP: channel " + channel.topic + " names schema " +
                           std::to_string(channel.schema_id) + ", which was not added");
  }
  channels_.push_back(channel);
  channel_counts_.push_back(0);
  sequences_.push_back(0);
  const auto id = static_cast<uint16_t>(channels_.size());
  chunk_.records += channel_record(id);
  return id;
}

std::string McapWriter::schema_record(uint16_t id) const {
  const auto& s = schemas_[id - 1U];
  std::string c;
  le(c, id);
  str(c, s.name);
  str(c, s.encoding);
  str(c, s.data);
  return record(kSchema, c);
}

std::string McapWriter::channel_record(uint16_t id) const {
  const auto& ch = channels_[id - 1U];
  std::string c, meta;
  le(c, id);
  le(c, ch.schema_id);
  str(c, ch.topic);
  str(c, ch.message_encoding);
  for (const auto& [k, v] : ch.metadata) {
    str(meta, k);
    str(meta, v);
  }
  str(c, meta);
  return record(kChannel, c);
}

void McapWriter::write(uint16_t channel_id, uint64_t log_time_ns, uint64_t publish_time_ns,
                       std::string_view data) {
  if (finished_) throw std::logic_error("MCAP: write after finish");
  if (channel_id == 0 || channel_id > channels_.size()) {
    throw std::logic_error("MCAP: message on channel " + std::to_string(channel_id) +
                           ", which was not added");
  }
  if (!chunk_has_messages_) chunk_.start_ns = chunk_.end_ns = log_time_ns;
  chunk_.start_ns = std::min(chunk_.start_ns, log_time_ns);
  chunk_.end_ns = std::max(chunk_.end_ns, log_time_ns);
  chunk_has_messages_ = true;
  if (message_count_ == 0) start_ns_ = end_ns_ = log_time_ns;
  start_ns_ = std::min(start_ns_, log_time_ns);
  end_ns_ = std::max(end_ns_, log_time_ns);
  auto& r = chunk_.records;
  chunk_.index[channel_id].emplace_back(log_time_ns, r.size());
  // The Message record in place: opcode, length, channel, sequence, log and publish time, data.
  r.push_back(static_cast<char>(kMessage));
  le(r, static_cast<uint64_t>(22 + data.size()));
  le(r, channel_id);
  le(r, sequences_[channel_id - 1U]++);
  le(r, log_time_ns);
  le(r, publish_time_ns);
  r.append(data);
  ++channel_counts_[channel_id - 1U];
  ++message_count_;
  if (r.size() >= options_.chunk_bytes) flush_chunk();
}

McapWriter::~McapWriter() {
  if (building_.valid()) building_.wait();
}

void McapWriter::attach(std::string_view name, std::string_view media_type, std::string_view data,
                        uint64_t log_time_ns) {
  if (finished_) throw std::logic_error("MCAP: attach after finish");
  flush_chunk();  // attachments live between chunks
  drain_built();
  std::string c;
  le(c, log_time_ns);
  le(c, log_time_ns);  // create time
  str(c, name);
  str(c, media_type);
  le(c, static_cast<uint64_t>(data.size()));
  c.append(data);
  le(c, crc(0, c));  // over every field before it
  const std::string r = record(kAttachment, c);
  attachment_indexes_.push_back(
      {offset_, r.size(), log_time_ns, data.size(), std::string(name), std::string(media_type)});
  put(r);
}

McapWriter::BuiltChunk McapWriter::build_chunk(const OpenChunk& chunk, bool compress, int level,
                                               bool own_thread) {
  BuiltChunk b;
  const std::string body = compress ? compress_zstd(chunk.records, level) : std::string();
  const std::string_view stored = compress ? std::string_view(body) : chunk.records;
  std::string c;
  le(c, chunk.start_ns);
  le(c, chunk.end_ns);
  le(c, static_cast<uint64_t>(chunk.records.size()));
  le(c, crc(0, chunk.records));
  str(c, compress ? "zstd" : "");
  le(c, static_cast<uint64_t>(stored.size()));
  c.append(stored);
  b.bytes = record(kChunk, c);
  b.chunk_length = b.bytes.size();
  for (const auto& [channel, entries] : chunk.index) {
    std::string mi, list;
    le(mi, channel);
    for (const auto& [t, off] : entries) {
      le(list, t);
      le(list, off);
    }
    str(mi, list);
    const std::string r = record(kMessageIndex, mi);
    b.index_lengths.emplace_back(channel, r.size());
    b.bytes += r;
  }
  b.crc = crc(0, b.bytes);
  b.compressed_size = stored.size();
  b.uncompressed_size = chunk.records.size();
  b.start_ns = chunk.start_ns;
  b.end_ns = chunk.end_ns;
  if (own_thread) b.thread_cpu_s = common::thread_cpu_seconds();  // std::async: a fresh thread
  return b;
}

void McapWriter::put_built(const BuiltChunk& b) {
  ChunkIndex index{b.start_ns, b.end_ns, offset_,           b.chunk_length,
                   {},         0,        b.compressed_size, b.uncompressed_size};
  uint64_t at = offset_ + b.chunk_length;
  for (const auto& [channel, length] : b.index_lengths) {
    index.index_offsets[channel] = at;
    at += length;
  }
  index.index_length = b.bytes.size() - b.chunk_length;
  sink_.write(b.bytes);
  // The chunk's CRC was taken on the other thread: joined to the running one (zlib).
  data_crc_ =
      static_cast<uint32_t>(crc32_combine(data_crc_, b.crc, static_cast<z_off_t>(b.bytes.size())));
  offset_ += b.bytes.size();
  background_cpu_s_ += b.thread_cpu_s;
  chunk_indexes_.push_back(std::move(index));
}

void McapWriter::drain_built() {
  if (building_.valid()) put_built(building_.get());
}

void McapWriter::flush_chunk() {
  drain_built();
  if (chunk_.records.empty()) return;
  OpenChunk full = std::move(chunk_);
  chunk_ = OpenChunk{};
  chunk_.records.reserve(options_.chunk_bytes + (options_.chunk_bytes >> 3));
  chunk_has_messages_ = false;
  if (options_.background_chunks) {
    building_ = std::async(std::launch::async, &McapWriter::build_chunk, std::move(full),
                           options_.compress, options_.zstd_level, true);
  } else {
    put_built(build_chunk(full, options_.compress, options_.zstd_level, false));
  }
}

std::string McapWriter::statistics_record() const {
  std::string c, counts;
  le(c, message_count_);
  le(c, static_cast<uint16_t>(schemas_.size()));
  le(c, static_cast<uint32_t>(channels_.size()));
  le(c, static_cast<uint32_t>(attachment_indexes_.size()));
  le(c, uint32_t{0});  // metadata
  le(c, static_cast<uint32_t>(chunk_indexes_.size()));
  le(c, start_ns_);
  le(c, end_ns_);
  for (std::size_t i = 0; i < channels_.size(); ++i) {
    le(counts, static_cast<uint16_t>(i + 1));
    le(counts, channel_counts_[i]);
  }
  str(c, counts);
  return record(kStatistics, c);
}

std::string McapWriter::chunk_index_record(const ChunkIndex& ci) const {
  std::string c, offsets;
  le(c, ci.start_ns);
  le(c, ci.end_ns);
  le(c, ci.offset);
  le(c, ci.length);
  for (const auto& [channel, off] : ci.index_offsets) {
    le(offsets, channel);
    le(offsets, off);
  }
  str(c, offsets);
  le(c, ci.index_length);
  str(c, options_.compress ? "zstd" : "");
  le(c, ci.compressed_size);
  le(c, ci.uncompressed_size);
  return record(kChunkIndex, c);
}

std::string McapWriter::attachment_index_record(const AttachmentIndex& a) {
  std::string c;
  le(c, a.offset);
  le(c, a.length);
  le(c, a.log_time_ns);
  le(c, a.log_time_ns);  // create time
  le(c, a.data_size);
  str(c, a.name);
  str(c, a.media_type);
  return record(kAttachmentIndex, c);
}

std::vector<McapWriter::ChannelCount> McapWriter::channel_counts() const {
  std::vector<ChannelCount> out;
  for (std::size_t i = 0; i < channels_.size(); ++i) {
    const auto& ch = channels_[i];
    out.push_back(
        {ch.topic, ch.schema_id ? schemas_[ch.schema_id - 1U].name : "", channel_counts_[i]});
  }
  return out;
}

void McapWriter::finish() {
  if (finished_) return;
  flush_chunk();
  drain_built();
  std::string end;
  le(end, data_crc_);
  put(record(kDataEnd, end));
  write_summary();
  finished_ = true;
}

void McapWriter::write_summary() {
  const uint64_t summary_start = offset_;
  uint32_t summary_crc = 0;
  std::vector<std::string> offsets;
  auto put_summary = [&](const std::string& r) {  // not in the data CRC: in the summary's
    sink_.write(r);
    summary_crc = crc(summary_crc, r);
    offset_ += r.size();
  };
  auto group = [&](uint8_t op, const std::vector<std::string>& records) {
    if (records.empty()) return;
    const uint64_t start = offset_;
    for (const auto& r : records) put_summary(r);
    std::string so;
    le(so, op);
    le(so, start);
    le(so, offset_ - start);
    offsets.push_back(record(kSummaryOffset, so));
  };
  std::vector<std::string> schemas, channels, chunks, attachments;
  for (std::size_t i = 1; i <= schemas_.size(); ++i) {
    schemas.push_back(schema_record(static_cast<uint16_t>(i)));
  }
  for (std::size_t i = 1; i <= channels_.size(); ++i) {
    channels.push_back(channel_record(static_cast<uint16_t>(i)));
  }
  for (const auto& ci : chunk_indexes_) chunks.push_back(chunk_index_record(ci));
  for (const auto& a : attachment_indexes_) attachments.push_back(attachment_index_record(a));
  group(kSchema, schemas);
  group(kChannel, channels);
  group(kStatistics, {statistics_record()});
  group(kChunkIndex, chunks);
  group(kAttachmentIndex, attachments);
  const uint64_t offsets_start = offset_;
  for (const auto& r : offsets) put_summary(r);
  // The footer's CRC covers the summary, the offsets and the footer up to this field.
  std::string footer;
  footer.push_back(static_cast<char>(kFooter));
  le(footer, uint64_t{20});
  le(footer, summary_start);
  le(footer, offsets_start);
  summary_crc = crc(summary_crc, footer);
  le(footer, summary_crc);
  sink_.write(footer);
  sink_.write(kMagic);
  offset_ += footer.size() + kMagic.size();
}

}  // namespace smart::record
