#include "smart/common/memory.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <memory>

namespace smart::common {
namespace {

TEST(PeakRss, GrowsWithMemoryTouchedAndNeverShrinks) {
  const double before = peak_rss_mb();
  EXPECT_GT(before, 1.0);  // a test program is larger than 1 MB
  constexpr std::size_t kBytes = 96u << 20;
  {
    auto block = std::make_unique<char[]>(kBytes);
    std::memset(block.get(), 1, kBytes);  // touched pages are resident
    EXPECT_EQ(block[kBytes - 1], 1);
  }
  const double after = peak_rss_mb();
  EXPECT_GT(after, before + 90.0);
  EXPECT_GE(peak_rss_mb(), after);  // a high-water mark: freeing does not lower it
}

}  // namespace
}  // namespace smart::common
