#include "smart/record/mcap_writer.hpp"

#include <gtest/gtest.h>
#include <zlib.h>
#include <zstd.h>

#include "record/mcap_test_reader.hpp"

namespace smart::record {
namespace {

using test::get;
using test::kMagic;
using test::walk;

uint32_t crc_of(std::string_view b) {
  return static_cast<uint32_t>(crc32_z(0, reinterpret_cast<const Bytef*>(b.data()), b.size()));
}

std::string small_file(bool compress, std::size_t chunk_bytes, int messages) {
  StringSink sink;
  McapWriter w(sink, {"ros2", "test", chunk_bytes, compress, 1});
  const auto s = w.add_schema("pkg/msg/A", "ros2msg", "int32 x\n");
  const auto a = w.add_channel({s, "/a", "cdr", {{"k", "v"}}});
  const auto b = w.add_channel({s, "/b", "cdr"});
  for (int i = 0; i < messages; ++i) {
    w.write(i % 3 == 0 ? b : a, 1000 * static_cast<uint64_t>(i), 0,
            std::string(40, char('a' + i % 26)));
  }
  w.finish();
  return sink.bytes();
}

TEST(McapWriter, FileOpensAndClosesWithTheMagicAndTheFooterPointsAtTheSummary) {
  const std::string f = small_file(true, 256, 30);
  ASSERT_GT(f.size(), 2 * kMagic.size() + 29);
  EXPECT_EQ(std::string_view(f).substr(0, 8), kMagic);
  EXPECT_EQ(std::string_view(f).substr(f.size() - 8), kMagic);
  const std::size_t footer = f.size() - 8 - 29;  // opcode, length, 8 + 8 + 4
  ASSERT_EQ(static_cast<uint8_t>(f[footer]), 0x02);
  const auto summary_start = get<uint64_t>(f, footer + 9);
  const auto offsets_start = get<uint64_t>(f, footer + 17);
  const auto summary_crc = get<uint32_t>(f, footer + 25);
  // The CRC covers the summary through the footer's summary_offset_start.
  EXPECT_EQ(summary_crc,
            crc_of(std::string_view(f).substr(summary_start, footer + 25 - summary_start)));
  const auto summary = walk(f, summary_start, offsets_start);
  std::vector<uint8_t> ops;
  for (const auto& r : summary) ops.push_back(r.op);
  // Schema, 2 channels, statistics, then one chunk index per chunk.
  ASSERT_GE(ops.size(), 5u);
  EXPECT_EQ(ops[0], 0x03);
  EXPECT_EQ(ops[1], 0x04);
  EXPECT_EQ(ops[2], 0x04);
  EXPECT_EQ(ops[3], 0x0B);
  for (std::size_t i = 4; i < ops.size(); ++i) EXPECT_EQ(ops[i], 0x08);
  const auto& stats = summary[3].body;
  EXPECT_EQ(get<uint64_t>(stats, 0), 30u);              // messages
  EXPECT_EQ(get<uint16_t>(stats, 8), 1u);               // schemas
  EXPECT_EQ(get<uint32_t>(stats, 10), 2u);              // channels
  EXPECT_EQ(get<uint32_t>(stats, 22), ops.size() - 4);  // chunks
  EXPECT_EQ(get<uint64_t>(stats, 26), 0u);              // first log time
  EXPECT_EQ(get<uint64_t>(stats, 34), 29000u);          // last
  // Summary offsets name each group where it is.
  const auto offsets = walk(f, offsets_start, footer);
  ASSERT_EQ(offsets.size(), 4u);
  EXPECT_EQ(static_cast<uint8_t>(offsets[0].body[0]), 0x03);
  EXPECT_EQ(get<uint64_t>(offsets[0].body, 1), summary_start);
}

TEST(McapWriter, DataEndHoldsTheCrcOfEverythingBeforeIt) {
  const std::string f = small_file(false, 1 << 20, 5);
  auto recs = walk(f, 8, f.size() - 8);
  std::size_t data_end = 0;
  for (const auto& r : recs) {
    if (r.op == 0x0F) data_end = r.offset;
  }
  ASSERT_GT(data_end, 0u);
  EXPECT_EQ(get<uint32_t>(f, data_end + 9), crc_of(std::string_view(f).substr(0, data_end)));
}

TEST(McapWriter, ChunkIndexesAndMessageIndexesFindEveryMessageInItsChunk) {
  for (const bool compress : {false, true}) {
    const std::string f = small_file(compress, 300, 40);
    const auto recs = walk(f, 8, f.size() - 8);
    std::size_t messages = 0, chunks = 0, indexed = 0;
    std::string records;  // the last chunk's, uncompressed
    for (const auto& r : recs) {
      if (r.op == 0x05) ADD_FAILURE() << "a message outside a chunk";
      if (r.op == 0x07) {  // follows its chunk: each entry points at a message of its channel
        const auto channel = get<uint16_t>(r.body, 0);
        const auto bytes = get<uint32_t>(r.body, 2);
        for (std::size_t e = 6; e < 6 + bytes; e += 16) {
          const auto t = get<uint64_t>(r.body, e);
          const auto off = get<uint64_t>(r.body, e + 8);
          ASSERT_LT(off, records.size());
          EXPECT_EQ(static_cast<uint8_t>(records[off]), 0x05);
          EXPECT_EQ(get<uint16_t>(records, off + 9), channel);
          EXPECT_EQ(get<uint64_t>(records, off + 15), t);
          ++indexed;
        }
      }
      if (r.op != 0x06) continue;
      ++chunks;
      const std::string& c = r.body;
      const auto uncompressed_size = get<uint64_t>(c, 16);
      const auto crc = get<uint32_t>(c, 24);
      const auto comp_len = get<uint32_t>(c, 28);
      const std::string compression = c.substr(32, comp_len);
      const auto size = get<uint64_t>(c, 32 + comp_len);
      records = c.substr(40 + comp_len, size);
      EXPECT_EQ(compression, compress ? "zstd" : "");
      if (compress) {
        std::string out(uncompressed_size, '\0');
        ASSERT_EQ(ZSTD_decompress(out.data(), out.size(), records.data(), records.size()),
                  uncompressed_size);
        records = out;
      }
      EXPECT_EQ(crc, crc_of(records));
      for (const auto& m : walk(records, 0, records.size())) messages += m.op == 0x05;
    }
    EXPECT_EQ(messages, 40u);
    EXPECT_EQ(indexed, 40u);
    EXPECT_GT(chunks, 3u) << "300-byte chunks";
  }
}

TEST(McapWriter, RefusesMessagesOnUnknownChannelsAndAfterFinish) {
  StringSink sink;
  McapWriter w(sink, {});
  EXPECT_THROW(w.write(1, 0, 0, "x"), std::logic_error);
  EXPECT_THROW(w.add_channel({3, "/x", "cdr"}), std::logic_error);
  const auto ch = w.add_channel({0, "/x", "json"});
  w.write(ch, 0, 0, "{}");
  w.finish();
  EXPECT_THROW(w.write(ch, 1, 1, "{}"), std::logic_error);
  EXPECT_EQ(w.messages(), 1u);
}

TEST(McapWriter, RefusesMoreChannelsThanSixteenBitIdsHold) {
  StringSink sink;
  McapWriter w(sink, {});
  for (std::size_t i = 0; i < McapWriter::kMaxIds; ++i) (void)w.add_channel({0, "/t", "cdr"});
  EXPECT_THROW(w.add_channel({0, "/t", "cdr"}), std::length_error);
}

}  // namespace
}  // namespace smart::record
