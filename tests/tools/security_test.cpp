// The keystore's pure parts: robot id lists and the policy documents.
#include "smart/tools/security.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace smart::tools {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

TEST(Security, IdListsTakeIdsAndRangesAndNameTheBadPart) {
  EXPECT_EQ(parse_id_list("0-3,7"), (std::vector<uint32_t>{0, 1, 2, 3, 7}));
  EXPECT_EQ(parse_id_list("5"), (std::vector<uint32_t>{5}));
  for (const char* bad : {"", "3-1", "a", "1,,2", "-4", "2x", "0-4294967296"}) {
    EXPECT_THROW(parse_id_list(bad), std::invalid_argument) << bad;
  }
  try {
    parse_id_list("0-3,x");
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("'x' in '0-3,x' is not a robot id or range"));
  }
}

TEST(Security, AViewerMayReadEverythingAndPublishNothing) {
  const auto grants = role_grants({4});
  ASSERT_EQ(grants.size(), 4u);
  const auto viewer = permissions_xml(grants[2], "2026-01-01T00:00:00", "2027-01-01T00:00:00");
  EXPECT_THAT(viewer, HasSubstr("<subject_name>CN=viewer,O=SMART-DDS</subject_name>"));
  EXPECT_THAT(viewer, HasSubstr("<subscribe><topics><topic>*</topic></topics>"));
  EXPECT_THAT(viewer, Not(HasSubstr("<publish>")));
  EXPECT_THAT(viewer, HasSubstr("<default>DENY</default>"));
  const auto agent = permissions_xml(grants[3], "a", "b");
  EXPECT_THAT(agent, HasSubstr("CN=agent-4"));
  EXPECT_THAT(agent, HasSubstr("<publish><topics><topic>smart/progress</topic><topic>smart/state"));
  EXPECT_THAT(agent, Not(HasSubstr("<topic>smart/action</topic></topics><partitions><partition>*"
                                   "</partition></partitions></publish>")));
}

TEST(Security, GovernanceRequiresAuthenticationAndEncryptsEveryTopic) {
  const auto g = governance_xml();
  EXPECT_THAT(g, HasSubstr("<allow_unauthenticated_participants>false"));
  EXPECT_THAT(g, HasSubstr("<data_protection_kind>ENCRYPT"));
  EXPECT_THAT(g, HasSubstr("<topic_expression>*</topic_expression>"));
  EXPECT_THAT(g, HasSubstr("<max>230</max>"));  // Cyclone rejects a range past domain 230
}

}  // namespace
}  // namespace smart::tools
