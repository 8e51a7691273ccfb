#include "smart/grid/map_reader.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "smart/grid/problem.hpp"
#include "smart/grid/text_file.hpp"
#include "support/monitor_fixtures.hpp"

namespace smart::grid {
namespace {

using ::testing::HasSubstr;

std::string map_error_of(const std::string& text) {
  try {
    parse_map(text, "m.map");
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(MapReader, ParsesSymbols) {
  const auto g = parse_map("type octile\nheight 2\nwidth 4\nmap\n.G@T\nSOW.\n", "m.map");
  EXPECT_EQ(g.width(), 4);
  EXPECT_EQ(g.height(), 2);
  EXPECT_FALSE(g.blocked({0, 0}));
  EXPECT_FALSE(g.blocked({1, 0}));  // G
  EXPECT_TRUE(g.blocked({2, 0}));   // @
  EXPECT_TRUE(g.blocked({3, 0}));   // T
  EXPECT_FALSE(g.blocked({0, 1}));  // S
  EXPECT_TRUE(g.blocked({1, 1}));   // O
  EXPECT_TRUE(g.blocked({2, 1}));   // W
  EXPECT_FALSE(g.blocked({3, 1}));
}

TEST(MapReader, AcceptsCrLfAndNoFinalNewline) {
  const auto g = parse_map("type octile\r\nheight 1\r\nwidth 2\r\nmap\r\n.@", "m.map");
  EXPECT_TRUE(g.blocked({1, 0}));
}

TEST(MapReaderErrors, UnknownSymbolsAreAllReportedWithLineAndColumn) {
  const auto e = map_error_of("type octile\nheight 2\nwidth 3\nmap\n.x.\n..?\n");
  EXPECT_THAT(e, HasSubstr("m.map:5: unknown map symbol 'x' at column 1"));
  EXPECT_THAT(e, HasSubstr("m.map:6: unknown map symbol '?' at column 2"));
}

TEST(MapReaderErrors, WrongHeader) {
  EXPECT_THAT(map_error_of("version 1\nheight 2\n"), HasSubstr("m.map:1: unexpected header line"));
  EXPECT_THAT(map_error_of("type octile\nheight two\nwidth 3\nmap\n"),
              HasSubstr("m.map:2: 'height two': height must be a positive whole number"));
  EXPECT_THAT(map_error_of("type octile\nheight 1\nmap\n.\n"), HasSubstr("missing 'width W'"));
  EXPECT_THAT(map_error_of("type octile\nheight 1\nwidth 1\n"), HasSubstr("missing 'map'"));
}

TEST(MapReaderErrors, TruncatedAndRaggedRows) {
  EXPECT_THAT(map_error_of("type octile\nheight 3\nwidth 2\nmap\n..\n..\n"),
              HasSubstr("has 2 rows but 'height' is 3; the file may be truncated"));
  EXPECT_THAT(map_error_of("type octile\nheight 2\nwidth 3\nmap\n...\n..\n"),
              HasSubstr("m.map:6: row 1 has 2 symbols but 'width' is 3"));
  EXPECT_THAT(map_error_of("type octile\nheight 1\nwidth 1\nmap\n.\n.\n"),
              HasSubstr("more rows than 'height 1'"));
}

TEST(MapReader, ReadsEveryBenchmarkMap) {
  const auto dir = test::benchmarks_dir() / "maps";
  ASSERT_TRUE(std::filesystem::exists(dir)) << smart::test::no_benchmarks(dir);
  const std::map<std::string, std::pair<int, int>> sizes = {
      {"den312d.map", {65, 81}},
      {"empty-32-32.map", {32, 32}},
      {"maze-32-32-4.map", {32, 32}},
      {"random-32-32-20.map", {32, 32}},
      {"random-64-64-10.map", {64, 64}},
      {"sortation_large.map", {500, 140}},
      {"warehouse-10-20-10-2-1.map", {161, 63}}};
  const std::map<std::string, std::size_t> free = {
      {"warehouse-10-20-10-2-1.map", 5699}, {"sortation_large.map", 54320}, {"den312d.map", 2445}};
  for (const auto& [name, wh] : sizes) {
    const auto g = parse_map(read_text_file(dir / name, "map"), name);
    EXPECT_EQ(g.width(), wh.first) << name;
    EXPECT_EQ(g.height(), wh.second) << name;
    if (free.count(name)) {
      EXPECT_EQ(g.free_cells(), free.at(name)) << name;
    }
  }
  const auto small = parse_map(
      read_text_file(test::benchmarks_dir() / "smart-examples" / "empty-8-8.map", "map"), "e");
  EXPECT_EQ(small.free_cells(), 64u);
}

// Regression: a 100000x100000 header allocated 10 GB before the rows were checked.
TEST(MapReaderErrors, AHugeHeaderIsRefusedBeforeAnythingIsAllocated) {
  EXPECT_THAT(map_error_of("type octile\nheight 100000\nwidth 100000\nmap\n..\n"),
              HasSubstr("more than 100000000 cells"));
  EXPECT_THAT(map_error_of("type octile\nheight 90000\nwidth 1000\nmap\n..\n"),
              HasSubstr("the map has 1 rows but 'height' is 90000"));
}

TEST(TextFile, MissingFileNamesThePath) {
  try {
    read_text_file("/nonexistent/dir/x.map", "map");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("/nonexistent/dir/x.map: cannot open the map file"));
  }
}

}  // namespace
}  // namespace smart::grid
