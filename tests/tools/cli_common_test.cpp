// The shared command-line pieces: robot id lists.
#include "smart/tools/cli_common.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace smart::tools {
namespace {

using ::testing::HasSubstr;

TEST(CliCommon, IdListsTakeIdsAndRangesAndNameTheBadPart) {
  EXPECT_EQ(parse_id_ranges("0-3,7"), (std::vector<uint32_t>{0, 1, 2, 3, 7}));
  EXPECT_EQ(parse_id_ranges("5"), (std::vector<uint32_t>{5}));
  for (const char* bad : {"", "3-1", "a", "1,,2", "-4", "2x", "0-4294967296", "4,2", "1,1"}) {
    EXPECT_THROW(parse_id_ranges(bad), std::invalid_argument) << bad;
  }
  EXPECT_THAT([] { parse_id_ranges("0-3,x"); },
              ::testing::ThrowsMessage<std::invalid_argument>(
                  HasSubstr("'x' is not a robot index (0..1000000); write e.g. 0-9,12")));
}

}  // namespace
}  // namespace smart::tools
