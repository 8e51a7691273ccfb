// The memory uploads may hold at once (smart/serve/upload_budget.hpp): leases take as bytes
// arrive, fail past the budget without taking, and give back what they held when they end.
#include "smart/serve/upload_budget.hpp"

#include <gtest/gtest.h>

#include <optional>

namespace smart::serve {
namespace {

TEST(UploadBudget, LeasesShareItAndGiveBackWhenTheyEnd) {
  UploadBudget budget(100);
  {
    UploadBudget::Lease a(budget);
    std::optional<UploadBudget::Lease> b(std::in_place, budget);
    EXPECT_TRUE(a.take(60));
    EXPECT_TRUE(b->take(30));
    EXPECT_FALSE(b->take(11));  // 60 + 30 + 11 > 100: refused, nothing taken
    EXPECT_EQ(b->held(), 30u);
    EXPECT_EQ(budget.in_use(), 90u);
    EXPECT_TRUE(b->take(10));
    b.reset();  // an upload that ended (or failed) gives back what it held
    EXPECT_EQ(budget.in_use(), 60u);
    EXPECT_TRUE(a.take(40));
    EXPECT_FALSE(a.take(1));
  }
  EXPECT_EQ(budget.in_use(), 0u);
}

}  // namespace
}  // namespace smart::serve
