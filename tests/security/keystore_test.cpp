// The keystore's pure parts: the policy documents.
#include "smart/security/keystore.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace smart::security {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

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

// Issue 25: an agent-<id> key spoke for every robot. It may publish in its robot's partitions
// only (idl/smart.idl, "Runs"); subscribing stays open (windows and clock are the run's).
TEST(Security, AnAgentPublishesOnlyInItsOwnRobotsPartitions) {
  const auto grants = role_grants({4, 12});
  const auto agent = permissions_xml(grants[4], "a", "b");
  EXPECT_THAT(agent, HasSubstr("CN=agent-12"));
  EXPECT_THAT(agent, HasSubstr("<topic>smart/state</topic></topics><partitions><partition>"
                               "smart.run.*.robot.12</partition></partitions></publish>"));
  EXPECT_THAT(agent, Not(HasSubstr("robot.4<")));
  EXPECT_THAT(agent, HasSubstr("</topics><partitions><partition>*</partition></partitions>"
                               "</subscribe>"));
  const auto sim = permissions_xml(grants[1], "a", "b");
  EXPECT_THAT(sim, HasSubstr("</topics><partitions><partition>*</partition></partitions>"
                             "</publish>"));
}

TEST(Security, GovernanceRequiresAuthenticationAndEncryptsEveryTopic) {
  const auto g = governance_xml();
  EXPECT_THAT(g, HasSubstr("<allow_unauthenticated_participants>false"));
  EXPECT_THAT(g, HasSubstr("<data_protection_kind>ENCRYPT"));
  EXPECT_THAT(g, HasSubstr("<topic_expression>*</topic_expression>"));
  EXPECT_THAT(g, HasSubstr("<max>230</max>"));  // Cyclone rejects a range past domain 230
}

}  // namespace
}  // namespace smart::security
