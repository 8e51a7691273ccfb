// The keystore's pure parts: the policy documents.
#include "smart/security/keystore.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace smart::security {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

const Grant& grant_of(const std::vector<Grant>& grants, const std::string& identity) {
  for (const auto& g : grants) {
    if (g.identity == identity) return g;
  }
  ADD_FAILURE() << "no grant for " << identity;
  return grants.front();
}

TEST(Security, AViewerMayReadEverythingAndPublishNothing) {
  const auto grants = role_grants({4});
  ASSERT_EQ(grants.size(), 5u);  // monitor, sim, viewer, planner, agent-4
  const auto viewer =
      permissions_xml(grant_of(grants, "viewer"), "2026-01-01T00:00:00", "2027-01-01T00:00:00");
  EXPECT_THAT(viewer, HasSubstr("<subject_name>CN=viewer,O=SMART-DDS</subject_name>"));
  EXPECT_THAT(viewer, HasSubstr("<subscribe><topics><topic>*</topic></topics>"));
  EXPECT_THAT(viewer, Not(HasSubstr("<publish>")));
  EXPECT_THAT(viewer, HasSubstr("<default>DENY</default>"));
  const auto agent = permissions_xml(grant_of(grants, "agent-4"), "a", "b");
  EXPECT_THAT(agent, HasSubstr("CN=agent-4"));
  EXPECT_THAT(agent, HasSubstr("<publish><topics><topic>smart/progress</topic><topic>smart/state"));
  EXPECT_THAT(agent, Not(HasSubstr("<topic>smart/action</topic></topics><partitions><partition>*"
                                   "</partition></partitions></publish>")));
}

// Issue 25: an agent-<id> key spoke for every robot. It may publish in its robot's partitions
// only (idl/smart.idl, "Runs"); subscribing stays open (windows and clock are the run's).
TEST(Security, AnAgentPublishesOnlyInItsOwnRobotsPartitions) {
  const auto grants = role_grants({4, 12});
  const auto agent = permissions_xml(grant_of(grants, "agent-12"), "a", "b");
  EXPECT_THAT(agent, HasSubstr("CN=agent-12"));
  EXPECT_THAT(agent, HasSubstr("<topic>smart/state</topic></topics><partitions><partition>"
                               "smart.run.*.robot.12</partition></partitions></publish>"));
  EXPECT_THAT(agent, Not(HasSubstr("robot.4<")));
  EXPECT_THAT(agent, HasSubstr("</topics><partitions><partition>*</partition></partitions>"
                               "</subscribe>"));
  const auto sim = permissions_xml(grant_of(grants, "sim"), "a", "b");
  EXPECT_THAT(sim, HasSubstr("</topics><partitions><partition>*</partition></partitions>"
                             "</publish>"));
}

// Issue 28: the lifelong planner over DDS has an identity of its own, the only one that may
// announce a planner and answer windows; it reads the problem and the requests, nothing else.
TEST(Security, OnlyThePlannerIdentityAnswersWindows) {
  const auto grants = role_grants({4});
  const auto planner = permissions_xml(grant_of(grants, "planner"), "a", "b");
  EXPECT_THAT(planner, HasSubstr("<publish><topics><topic>smart/planner</topic><topic>"
                                 "smart/plan_reply</topic></topics>"));
  EXPECT_THAT(planner, HasSubstr("<subscribe><topics><topic>smart/plan_problem</topic><topic>"
                                 "smart/plan_request</topic></topics>"));
  for (const auto& g : grants) {
    if (g.identity == "planner") continue;
    for (const auto& topic : g.publish) {
      EXPECT_NE(topic, "smart/plan_reply") << g.identity;
      EXPECT_NE(topic, "smart/planner") << g.identity;
    }
  }
  const auto monitor = permissions_xml(grant_of(grants, "monitor"), "a", "b");
  EXPECT_THAT(monitor, HasSubstr("<topic>smart/plan_problem</topic><topic>smart/plan_request"));
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
