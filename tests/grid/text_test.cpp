#include "smart/grid/text.hpp"

#include <gtest/gtest.h>

namespace smart::grid {
namespace {

TEST(Text, SplitLinesHandlesCrLfAndMissingFinalNewline) {
  const auto l = split_lines("a\r\nb\n\nc");
  ASSERT_EQ(l.size(), 4u);
  EXPECT_EQ(l[0], "a");
  EXPECT_EQ(l[1], "b");
  EXPECT_EQ(l[2], "");
  EXPECT_EQ(l[3], "c");
  EXPECT_EQ(split_lines("x\n").size(), 1u);
}

TEST(Text, NumbersMustBeWholeTokens) {
  EXPECT_EQ(parse_int(" 42 "), 42);
  EXPECT_EQ(parse_int("+7"), 7);
  EXPECT_EQ(parse_int("-3"), -3);
  EXPECT_FALSE(parse_int("4x"));
  EXPECT_FALSE(parse_int(""));
  EXPECT_FALSE(parse_int("1.5"));
  EXPECT_DOUBLE_EQ(*parse_double("2.25"), 2.25);
  EXPECT_FALSE(parse_double("nan"));
  EXPECT_FALSE(parse_double("inf"));
  EXPECT_FALSE(parse_double("2,5"));
}

TEST(Text, SplitAndTrim) {
  EXPECT_EQ(split("a\tb\t", '\t').size(), 3u);
  EXPECT_EQ(split_whitespace("  a \t b  ").size(), 2u);
  EXPECT_EQ(trim("  x y \r\n"), "x y");
  EXPECT_EQ(excerpt("abcdef", 3), "abc...");
}

}  // namespace
}  // namespace smart::grid
