#include "smart/dds/domain.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "smart/dds/error.hpp"
#include "smart/dds/participant.hpp"
#include "support/dds_test_support.hpp"

namespace smart::dds {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

TEST(CycloneConfig, LoopbackIsLoNoMulticastUnicastPeer) {
  const auto xml = render_cyclone_config(DomainConfig::loopback());
  EXPECT_THAT(xml, HasSubstr("<NetworkInterface name=\"lo\"/>"));
  EXPECT_THAT(xml, HasSubstr("<AllowMulticast>false</AllowMulticast>"));
  EXPECT_THAT(xml, HasSubstr("<Peer address=\"127.0.0.1\"/>"));
  EXPECT_THAT(xml, Not(HasSubstr("XmitLossiness")));
}

TEST(CycloneConfig, TransportTimersAndLoss) {
  DomainConfig c;
  c.transport.heartbeat_interval = Millis(20);
  c.transport.nack_delay = Millis(5);
  c.transport.loss_per_mille = 200;
  const auto xml = render_cyclone_config(c);
  EXPECT_THAT(xml, HasSubstr("<HeartbeatInterval>20 ms</HeartbeatInterval>"));
  EXPECT_THAT(xml, HasSubstr("<NackDelay>5 ms</NackDelay>"));
  EXPECT_THAT(xml, HasSubstr("<XmitLossiness>200</XmitLossiness>"));
}

TEST(CycloneConfig, NetworkModeLeavesInterfaceChoiceToCyclone) {
  const auto xml = render_cyclone_config(DomainConfig::network());
  EXPECT_THAT(xml, Not(HasSubstr("NetworkInterface")));
  EXPECT_THAT(xml, HasSubstr("<AllowMulticast>default</AllowMulticast>"));
}

TEST(CycloneConfig, RejectsLossOutOfRange) {
  DomainConfig c;
  c.transport.loss_per_mille = 1001;
  EXPECT_THROW(render_cyclone_config(c), ConfigError);
}

TEST(Domain, CreatingTheSameDomainTwiceInOneProcessIsAClearError) {
  Domain a(test::kDomainCreateTwice, test::loopback());
  Participant p(a);
  EXPECT_EQ(p.domain_id(), test::kDomainCreateTwice);
  try {
    Domain b(test::kDomainCreateTwice, test::loopback());
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("creating DDS domain 101"));
    EXPECT_THAT(e.what(), HasSubstr("share the Domain object"));
    EXPECT_LT(e.code(), 0);
  }
}

}  // namespace
}  // namespace smart::dds
