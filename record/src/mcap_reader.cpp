#include "smart/record/mcap_reader.hpp"

#include <zstd.h>

#include <algorithm>
#include <cstring>
#include <memory>

#include "mcap_format.hpp"

namespace smart::record {

namespace {

using namespace mcap;  // NOLINT(google-build-using-namespace): the format's own names

constexpr std::size_t kPiece = std::size_t{1} << 20;

const char* op_name(uint8_t op) {
  switch (op) {
    case kHeader:
      return "Header";
    case kFooter:
      return "Footer";
    case kSchema:
      return "Schema";
    case kChannel:
      return "Channel";
    case kMessage:
      return "Message";
    case kChunk:
      return "Chunk";
    case kAttachment:
      return "Attachment";
    case kDataEnd:
      return "Data End";
    default:
      return "a";
  }
}

// Where a record is, for its errors: the file's byte, or a chunk's and the record's in it.
struct Where {
  const std::string& source;
  uint64_t offset;
  std::string record;
  [[noreturn]] void fail(const std::string& what) const {
    throw McapError(source + ": byte " + std::to_string(offset) + ": " + record +
                    " record: " + what +
                    "; the file is damaged or not an MCAP recording (https://mcap.dev/spec)");
  }
};

// A record's fields, little-endian, each checked against the bytes left.
class Fields {
 public:
  Fields(std::string_view bytes, const Where& where) : bytes_(bytes), where_(where) {}
  template <class T>
  T num(const char* field) {
    need(sizeof(T), field);
    uint64_t v = 0;
    for (std::size_t i = 0; i < sizeof(T); ++i) {
      v |= uint64_t{static_cast<uint8_t>(bytes_[at_ + i])} << (8 * i);
    }
    at_ += sizeof(T);
    return static_cast<T>(v);
  }
  std::string_view str(const char* field) { return take(num<uint32_t>(field), field); }
  std::string_view bytes64(const char* field) { return take(num<uint64_t>(field), field); }
  std::string_view rest() { return take(bytes_.size() - at_, "rest"); }
  std::string_view take_bytes(uint64_t n, const char* field) { return take(n, field); }
  std::size_t at() const { return at_; }

 private:
  void need(uint64_t n, const char* field) const {
    if (n > bytes_.size() - at_) {
      where_.fail(std::string(field) + " needs " + std::to_string(n) + " bytes but " +
                  std::to_string(bytes_.size() - at_) + " are left in the record");
    }
  }
  std::string_view take(uint64_t n, const char* field) {
    need(n, field);
    const auto out = bytes_.substr(at_, n);
    at_ += n;
    return out;
  }
  std::string_view bytes_;
  const Where& where_;
  std::size_t at_ = 0;
};

class Reader {
 public:
  Reader(ByteSource& source, McapVisitor& visitor, const std::string& name,
         const McapLimits& limits)
      : source_(source), visitor_(visitor), name_(name), limits_(limits) {}
  void run();

 private:
  enum class Section { kData, kSummary };
  std::size_t fill(std::string& out, std::size_t n);
  void expect(std::string& out, std::size_t n, uint64_t record_at, const char* what);
  void read_content(uint8_t op, uint64_t length, uint64_t at);
  void skip_content(uint64_t length, uint64_t at);
  void dispatch(uint8_t op, std::string_view content, const Where& where);
  void header(std::string_view content, const Where& where);
  void footer(std::string_view record, const Where& where);
  void chunk(std::string_view content, const Where& where);
  void chunk_records(std::string_view records, uint64_t chunk_at);
  void schema(std::string_view content, const Where& where);
  void channel(std::string_view content, const Where& where);
  void message(std::string_view content, const Where& where);
  void attachment(std::string_view content, const Where& where);
  void add_crc(std::string_view bytes) {
    (section_ == Section::kData ? data_crc_ : summary_crc_) =
        crc(section_ == Section::kData ? data_crc_ : summary_crc_, bytes);
  }

  ByteSource& source_;
  McapVisitor& visitor_;
  const std::string& name_;
  McapLimits limits_;
  uint64_t offset_ = 0;  // bytes read from the source
  Section section_ = Section::kData;
  uint32_t data_crc_ = 0, summary_crc_ = 0;
  uint64_t summary_start_ = 0;
  bool have_header_ = false, done_ = false;
  std::string content_, chunk_;
  std::map<uint16_t, McapSchemaInfo> schemas_;
  std::map<uint16_t, McapChannelInfo> channels_;
};

std::size_t Reader::fill(std::string& out, std::size_t n) {
  const std::size_t start = out.size();
  out.resize(start + n);
  std::size_t got = 0;
  while (got < n) {
    const std::size_t r = source_.read(out.data() + start + got, n - got);
    if (r == 0) break;
    got += r;
  }
  out.resize(start + got);
  offset_ += got;
  return got;
}

// Exactly n more bytes of the record that starts at record_at, read in pieces so that a length
// the file does not hold allocates no more than the file has.
void Reader::expect(std::string& out, std::size_t n, uint64_t record_at, const char* what) {
  out.clear();
  while (out.size() < n) {
    const std::size_t want = std::min(kPiece, n - out.size());
    if (fill(out, want) < want) {
      throw McapError(name_ + ": the file ends at byte " + std::to_string(offset_) + " inside " +
                      what + " that starts at byte " + std::to_string(record_at) +
                      ": it is cut short (copied or downloaded in part, or its writer stopped); "
                      "copy it again, or record it again (`smart export mcap`)");
    }
  }
}

void Reader::run() {
  expect(content_, kMagic.size(), 0, "the magic");
  if (std::string_view(content_) != kMagic) {
    throw McapError(name_ +
                    ": does not start with the MCAP magic: not an MCAP file "
                    "(https://mcap.dev/spec); give a recording of `smart run --mcap`");
  }
  add_crc(content_);
  std::string head;
  while (!done_) {
    const uint64_t at = offset_;
    head.clear();
    if (fill(head, 1) == 0) {
      throw McapError(name_ + ": the file ends at byte " + std::to_string(at) +
                      " without its Footer: it is cut short (copied or downloaded in part, or "
                      "its writer stopped); copy it again, or record it again");
    }
    expect(content_, kRecordHeader - 1, at, "a record header");
    head += content_;
    const auto op = static_cast<uint8_t>(head[0]);
    uint64_t length = 0;
    for (std::size_t i = 0; i < 8; ++i) {
      length |= uint64_t{static_cast<uint8_t>(head[1 + i])} << (8 * i);
    }
    if (op == kDataEnd || op == kFooter) {
      // Their own CRCs cover what came before them.
      if (length > 64)
        Where{name_, at, op_name(op)}.fail("its length is " + std::to_string(length));
      expect(content_, length, at, "a record");
      if (op == kFooter) {
        footer(head + content_, Where{name_, at, "Footer"});
      } else {
        dispatch(op, content_, Where{name_, at, "Data End"});
        section_ = Section::kSummary;
        summary_start_ = offset_;
      }
      continue;
    }
    add_crc(head);
    read_content(op, length, at);
  }
}

void Reader::read_content(uint8_t op, uint64_t length, uint64_t at) {
  const Where where{name_, at, op_name(op)};
  if (!have_header_ && op != kHeader) where.fail("the file must start with a Header record");
  const bool wanted =
      section_ == Section::kData && (op == kHeader || op == kSchema || op == kChannel ||
                                     op == kMessage || op == kChunk || op == kAttachment);
  if (!wanted) return skip_content(length, at);  // indexes, statistics, metadata, the summary
  if (length > limits_.max_record_bytes) {
    where.fail("it is " + std::to_string(length) + " bytes, more than this reader takes (" +
               std::to_string(limits_.max_record_bytes) + ")");
  }
  expect(content_, static_cast<std::size_t>(length), at, "a record");
  add_crc(content_);
  dispatch(op, content_, where);
}

void Reader::skip_content(uint64_t length, uint64_t at) {
  std::string piece;
  for (uint64_t left = length; left > 0;) {
    const auto n = static_cast<std::size_t>(std::min<uint64_t>(kPiece, left));
    expect(piece, n, at, "a record");
    add_crc(piece);
    left -= n;
  }
}

void Reader::dispatch(uint8_t op, std::string_view content, const Where& where) {
  switch (op) {
    case kHeader:
      return header(content, where);
    case kSchema:
      return schema(content, where);
    case kChannel:
      return channel(content, where);
    case kMessage:
      return message(content, where);
    case kChunk:
      return chunk(content, where);
    case kAttachment:
      return attachment(content, where);
    case kDataEnd: {
      Fields f(content, where);
      const auto want = f.num<uint32_t>("data_section_crc");
      if (want != 0 && want != data_crc_) {
        where.fail("the data section's CRC-32 is " + std::to_string(data_crc_) + ", not " +
                   std::to_string(want) + " as written");
      }
      return;
    }
    default:
      return;
  }
}

void Reader::header(std::string_view content, const Where& where) {
  if (have_header_) where.fail("a second Header");
  Fields f(content, where);
  const auto profile = f.str("profile");
  const auto library = f.str("library");
  have_header_ = true;
  visitor_.header(profile, library);
}

void Reader::footer(std::string_view record, const Where& where) {
  Fields f(record.substr(kRecordHeader), where);
  const auto summary_start = f.num<uint64_t>("summary_start");
  (void)f.num<uint64_t>("summary_offset_start");
  const auto want = f.num<uint32_t>("summary_crc");
  // The summary's CRC covers the summary section (from the end of Data End, where this reader
  // began its CRC) and the Footer up to this field.
  const uint32_t got = crc(summary_crc_, record.substr(0, kRecordHeader + 16));
  if (want != 0 && summary_start != 0 && summary_start == summary_start_ && want != got) {
    where.fail("the summary's CRC-32 is " + std::to_string(got) + ", not " + std::to_string(want) +
               " as written");
  }
  std::string magic;
  expect(magic, kMagic.size(), offset_, "the closing magic");
  if (magic != kMagic) where.fail("the Footer is not followed by the MCAP magic");
  done_ = true;
}

void Reader::chunk(std::string_view content, const Where& where) {
  Fields f(content, where);
  (void)f.num<uint64_t>("message_start_time");
  (void)f.num<uint64_t>("message_end_time");
  const auto size = f.num<uint64_t>("uncompressed_size");
  const auto want = f.num<uint32_t>("uncompressed_crc");
  const auto compression = f.str("compression");
  const auto records = f.bytes64("records");
  if (size > limits_.max_chunk_bytes) {
    where.fail("it holds " + std::to_string(size) +
               " bytes uncompressed, more than this reader "
               "takes (" +
               std::to_string(limits_.max_chunk_bytes) + ")");
  }
  if (compression.empty()) {
    if (records.size() != size) where.fail("its records are not uncompressed_size bytes");
    chunk_.assign(records);
  } else if (compression == "zstd") {
    chunk_.resize(static_cast<std::size_t>(size));
    const std::size_t n =
        ZSTD_decompress(chunk_.data(), chunk_.size(), records.data(), records.size());
    if (ZSTD_isError(n)) where.fail(std::string("zstd: ") + ZSTD_getErrorName(n));
    if (n != size) where.fail("its records are not uncompressed_size bytes once decompressed");
  } else {
    where.fail("compression '" + std::string(compression) +
               "' is not read here (zstd or none); recompress it with `mcap compress`");
  }
  if (want != 0 && crc(0, chunk_) != want) where.fail("its records' CRC-32 does not match");
  chunk_records(chunk_, where.offset);  // chunks hold no chunks: chunk_ is not reused meanwhile
}

void Reader::chunk_records(std::string_view records, uint64_t chunk_at) {
  for (std::size_t at = 0; at < records.size();) {
    const Where where{name_, chunk_at, "Chunk (its byte " + std::to_string(at) + ")"};
    Fields head(records.substr(at), where);
    const auto op = head.num<uint8_t>("opcode");
    const auto length = head.num<uint64_t>("length");
    const auto content = head.take_bytes(length, "content");
    const Where inner{
        name_, chunk_at,
        "Chunk's " + std::string(op_name(op)) + " (its byte " + std::to_string(at) + ")"};
    if (op == kSchema || op == kChannel || op == kMessage) dispatch(op, content, inner);
    at += head.at();
  }
}

void Reader::schema(std::string_view content, const Where& where) {
  Fields f(content, where);
  McapSchemaInfo s;
  s.id = f.num<uint16_t>("id");
  s.name = f.str("name");
  s.encoding = f.str("encoding");
  s.data = f.str("data");
  if (s.id == 0) where.fail("schema id 0 is reserved (no schema)");
  const auto [it, fresh] = schemas_.try_emplace(s.id, s);
  if (fresh) return visitor_.schema(s);
  if (it->second.name != s.name || it->second.encoding != s.encoding || it->second.data != s.data) {
    where.fail("schema " + std::to_string(s.id) + " is defined again differently");
  }
}

void Reader::channel(std::string_view content, const Where& where) {
  Fields f(content, where);
  McapChannelInfo c;
  c.id = f.num<uint16_t>("id");
  c.schema_id = f.num<uint16_t>("schema_id");
  c.topic = f.str("topic");
  c.message_encoding = f.str("message_encoding");
  const auto meta = f.str("metadata");
  Fields m(meta, where);
  while (m.at() < meta.size()) {
    const auto key = m.str("metadata key");
    c.metadata[std::string(key)] = m.str("metadata value");
  }
  if (c.schema_id != 0 && !schemas_.count(c.schema_id)) {
    where.fail("channel " + c.topic + " names schema " + std::to_string(c.schema_id) +
               ", which is not defined before it");
  }
  const auto [it, fresh] = channels_.try_emplace(c.id, c);
  if (fresh) return visitor_.channel(c);
  if (it->second.schema_id != c.schema_id || it->second.topic != c.topic ||
      it->second.message_encoding != c.message_encoding || it->second.metadata != c.metadata) {
    where.fail("channel " + std::to_string(c.id) + " is defined again differently");
  }
}

void Reader::message(std::string_view content, const Where& where) {
  Fields f(content, where);
  const auto channel = f.num<uint16_t>("channel_id");
  const auto it = channels_.find(channel);
  if (it == channels_.end()) {
    where.fail("a message on channel " + std::to_string(channel) +
               ", which is not defined before it");
  }
  const auto sequence = f.num<uint32_t>("sequence");
  const auto log_time = f.num<uint64_t>("log_time");
  const auto publish_time = f.num<uint64_t>("publish_time");
  visitor_.message(McapMessageView{it->second, sequence, log_time, publish_time, f.rest()});
}

void Reader::attachment(std::string_view content, const Where& where) {
  Fields f(content, where);
  McapAttachmentView a;
  a.log_time_ns = f.num<uint64_t>("log_time");
  a.create_time_ns = f.num<uint64_t>("create_time");
  a.name = f.str("name");
  a.media_type = f.str("media_type");
  a.data = f.bytes64("data");
  const auto covered = content.substr(0, f.at());
  const auto want = f.num<uint32_t>("crc");
  if (want != 0 && crc(0, covered) != want) {
    where.fail("attachment " + std::string(a.name) + ": its CRC-32 does not match");
  }
  visitor_.attachment(a);
}

}  // namespace

void read_mcap(ByteSource& source, McapVisitor& visitor, const std::string& source_name,
               const McapLimits& limits) {
  Reader(source, visitor, source_name, limits).run();
}

std::size_t StringSource::read(char* out, std::size_t n) {
  const std::size_t k = std::min(n, bytes_.size() - at_);
  std::memcpy(out, bytes_.data() + at_, k);
  at_ += k;
  return k;
}

}  // namespace smart::record
