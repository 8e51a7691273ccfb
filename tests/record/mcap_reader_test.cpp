#include "smart/record/mcap_reader.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <vector>

#include "smart/record/mcap_writer.hpp"

namespace smart::record {
namespace {

using ::testing::HasSubstr;

// Everything the reader reports, as text.
struct Seen : McapVisitor {
  std::vector<std::string> log;
  void header(std::string_view profile, std::string_view library) override {
    log.push_back("header " + std::string(profile) + " " + std::string(library));
  }
  void schema(const McapSchemaInfo& s) override {
    log.push_back("schema " + std::to_string(s.id) + " " + s.name + " " + s.encoding + " " +
                  s.data);
  }
  void channel(const McapChannelInfo& c) override {
    log.push_back("channel " + std::to_string(c.id) + " " + c.topic + " schema " +
                  std::to_string(c.schema_id) + " " + c.message_encoding +
                  " qos=" + (c.metadata.count("qos") ? c.metadata.at("qos") : ""));
  }
  void message(const McapMessageView& m) override {
    log.push_back("message " + m.channel.topic + " #" + std::to_string(m.sequence) +
                  " t=" + std::to_string(m.log_time_ns) + " " + std::string(m.data));
  }
  void attachment(const McapAttachmentView& a) override {
    log.push_back("attachment " + std::string(a.name) + " " + std::string(a.media_type) + " " +
                  std::string(a.data));
  }
};

std::string small_file(bool compress, std::size_t chunk_bytes = 1 << 20) {
  StringSink sink;
  McapOptions o;
  o.compress = compress;
  o.chunk_bytes = chunk_bytes;
  McapWriter w(sink, o);
  const auto s = w.add_schema("T", "ros2msg", "int32 a");
  const auto c = w.add_channel({s, "/a", "cdr", {{"qos", "q"}}});
  w.write(c, 10, 10, "one");
  w.attach("notes.txt", "text/plain", "hello");
  w.write(c, 20, 20, "two");
  w.finish();
  return sink.bytes();
}

std::vector<std::string> read_all(const std::string& bytes, const McapLimits& limits = {}) {
  StringSource source(bytes);
  Seen seen;
  read_mcap(source, seen, "f.mcap", limits);
  return seen.log;
}

std::string error_of(const std::string& bytes, const McapLimits& limits = {}) {
  try {
    (void)read_all(bytes, limits);
  } catch (const McapError& e) {
    return e.what();
  }
  return "";
}

TEST(McapReader, ReadsBackWhatTheWriterWroteInFileOrder) {
  const std::vector<std::string> want = {
      "header ros2 smart-dds",
      "schema 1 T ros2msg int32 a",
      "channel 1 /a schema 1 cdr qos=q",
      "message /a #0 t=10 one",
      "attachment notes.txt text/plain hello",
      "message /a #1 t=20 two",
  };
  EXPECT_EQ(read_all(small_file(true)), want);
  EXPECT_EQ(read_all(small_file(false)), want);
  EXPECT_EQ(read_all(small_file(true, 1)), want);  // a chunk per message
}

TEST(McapReader, AFileCutAnywhereIsAnErrorNamingWhereItEnds) {
  const std::string file = small_file(true);
  for (std::size_t n = 0; n < file.size(); ++n) {
    const std::string e = error_of(file.substr(0, n));
    ASSERT_THAT(e, HasSubstr("f.mcap: ")) << "cut at " << n;
    if (n >= 8) {
      ASSERT_THAT(e, HasSubstr("cut short")) << "cut at " << n;
    }
  }
  EXPECT_THAT(error_of(file.substr(0, file.size() - 30)),
              HasSubstr("ends at byte " + std::to_string(file.size() - 30)));
}

TEST(McapReader, EveryByteChangedIsReadOrRefusedNeverACrash) {
  const std::string file = small_file(true);
  std::size_t refused = 0;
  for (std::size_t i = 0; i < file.size(); ++i) {
    for (const char flip : {'\x01', '\x80', '\xff'}) {
      std::string bad = file;
      bad[i] = static_cast<char>(bad[i] ^ flip);
      try {
        (void)read_all(bad);
      } catch (const McapError&) {
        ++refused;
      }
    }
  }
  // CRCs cover every byte but the CRC fields' own: nearly every change is caught.
  EXPECT_GT(refused, file.size() * 3 * 9 / 10);
}

TEST(McapReader, ChecksTheChunkAndDataCrcs) {
  std::string file = small_file(false);
  const auto at = file.find("one");
  file[at] = 'O';
  EXPECT_THAT(error_of(file), HasSubstr("Chunk record: its records' CRC-32 does not match"));
  std::string attached = small_file(false);
  attached[attached.find("hello")] = 'j';
  EXPECT_THAT(error_of(attached), HasSubstr("attachment notes.txt: its CRC-32 does not match"));
}

TEST(McapReader, RefusesChunksAndRecordsLargerThanItsLimits) {
  EXPECT_THAT(error_of(small_file(true), {.max_chunk_bytes = 16}),
              HasSubstr("bytes uncompressed, more than this reader takes (16)"));
  EXPECT_THAT(error_of(small_file(true), {.max_record_bytes = 8}),
              HasSubstr("more than this reader takes (8)"));
}

TEST(McapReader, ALengthPastTheEndAllocatesNothingAndIsNamed) {
  std::string file = small_file(true).substr(0, 8 + 9);  // magic and a Header's opening
  file[8 + 1 + 7] = '\x7f';                              // length ~ 2^63
  EXPECT_THAT(error_of(file), HasSubstr("more than this reader takes"));
  EXPECT_THAT(error_of(file, {.max_record_bytes = ~uint64_t{0}}), HasSubstr("cut short"));
}

TEST(McapReader, RefusesAFileThatIsNotMcap) {
  EXPECT_THAT(error_of("t_s,robot\n0,0\n"), HasSubstr("does not start with the MCAP magic"));
}

// A file built by hand: records outside chunks, no CRCs (0: not given).
std::string le(uint64_t v, std::size_t bytes) {
  std::string out;
  for (std::size_t i = 0; i < bytes; ++i) out.push_back(static_cast<char>(v >> (8 * i) & 0xff));
  return out;
}
std::string rec(uint8_t op, const std::string& content) {
  return std::string(1, static_cast<char>(op)) + le(content.size(), 8) + content;
}
std::string hand_file(const std::string& records) {
  const std::string magic("\x89MCAP0\r\n", 8);
  return magic + rec(0x01, le(4, 4) + "ros2" + le(0, 4)) + records + rec(0x0F, le(0, 4)) +
         rec(0x02, le(0, 8) + le(0, 8) + le(0, 4)) + magic;
}

TEST(McapReader, ReadsMessagesOutsideChunks) {
  const std::string channel =
      rec(0x04, le(3, 2) + le(0, 2) + le(2, 4) + "/b" + le(4, 4) + "json" + le(0, 4));
  const std::string message = rec(0x05, le(3, 2) + le(9, 4) + le(5, 8) + le(5, 8) + "{}");
  EXPECT_EQ(read_all(hand_file(channel + message)),
            (std::vector<std::string>{"header ros2 ",
                                      "channel 3 /b schema 0 json qos=", "message /b #9 t=5 {}"}));
}

TEST(McapReader, RefusesMessagesOnChannelsNotDefinedBeforeThem) {
  const std::string message = rec(0x05, le(7, 2) + le(0, 4) + le(1, 8) + le(1, 8) + "x");
  EXPECT_THAT(error_of(hand_file(message)),
              HasSubstr("a message on channel 7, which is not defined before it"));
}

TEST(McapReader, RefusesAChannelNamingAnUndefinedSchemaAndARedefinedSchema) {
  const std::string channel =
      rec(0x04, le(1, 2) + le(4, 2) + le(2, 4) + "/b" + le(0, 4) + le(0, 4));
  EXPECT_THAT(error_of(hand_file(channel)), HasSubstr("names schema 4, which is not defined"));
  auto schema = [](const std::string& data) {
    return rec(0x03, le(1, 2) + le(1, 4) + "T" + le(1, 4) + "x" + le(data.size(), 4) + data);
  };
  EXPECT_EQ(read_all(hand_file(schema("a") + schema("a"))).size(), 2u);  // repeated alike: fine
  EXPECT_THAT(error_of(hand_file(schema("a") + schema("b"))),
              HasSubstr("schema 1 is defined again differently"));
}

TEST(McapReader, AStringLongerThanItsRecordIsNamedByField) {
  const std::string channel = rec(0x04, le(1, 2) + le(0, 2) + le(1000, 4) + "/b");
  EXPECT_THAT(error_of(hand_file(channel)),
              HasSubstr("Channel record: topic needs 1000 bytes but 2 are left in the record"));
}

TEST(McapReader, RefusesCompressionsItDoesNotRead) {
  const std::string chunk =
      rec(0x06, le(0, 8) + le(0, 8) + le(0, 8) + le(0, 4) + le(3, 4) + "lz4" + le(0, 8));
  EXPECT_THAT(error_of(hand_file(chunk)), HasSubstr("compression 'lz4' is not read here"));
}

}  // namespace
}  // namespace smart::record
