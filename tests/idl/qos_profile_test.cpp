#include "smart/dds/qos_profile.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "smart/dds/error.hpp"

namespace smart::dds {
namespace {

using ::testing::HasSubstr;

std::string error_of(const std::string& yaml) {
  try {
    parse_qos_profile(yaml, "bad.yaml");
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(QosProfile, ShippedProfilesLoadWithTheirDocumentedSettings) {
  const auto lan = find_qos_profile("lan");
  EXPECT_EQ(lan.name, "lan");
  EXPECT_EQ(lan.transport.loss_per_mille, 0);
  EXPECT_EQ(lan.action.reliability, Reliability::kReliable);
  EXPECT_EQ(lan.action.durability, Durability::kTransientLocal);
  EXPECT_EQ(lan.action.depth, 1);
  EXPECT_FALSE(lan.progress.autodispose);
  EXPECT_EQ(lan.state.reliability, Reliability::kBestEffort);
  EXPECT_EQ(lan.state.deadline, Millis(300));

  const auto wifi = find_qos_profile("wifi");
  EXPECT_EQ(wifi.transport.heartbeat_interval, Millis(50));
  EXPECT_EQ(wifi.transport.nack_delay, Millis(10));

  EXPECT_FALSE(wifi.link.active());  // a real network's profile models nothing

  const auto lossy = find_qos_profile("protocol-loss-test");
  EXPECT_EQ(lossy.transport.loss_per_mille, 200);
  EXPECT_FALSE(lossy.link.active());
  EXPECT_EQ(lossy.transport.heartbeat_interval, Millis(20));
  EXPECT_EQ(lossy.topic(TopicRole::kState).reliability, Reliability::kBestEffort);
}

TEST(QosProfile, TheLinkSectionSetsBothDirectionsAndEachItsOwn) {
  const auto p = parse_qos_profile(
      "name: l\nlink:\n  seed: 3\n  delay_ms: 40\n  jitter_ms: 10\n"
      "  to_monitor:\n    delay_ms: 80\n    reorder: true\n",
      "l.yaml");
  EXPECT_EQ(p.link.seed, 3u);
  EXPECT_DOUBLE_EQ(p.link.to_host.delay_ms, 40);
  EXPECT_DOUBLE_EQ(p.link.to_monitor.delay_ms, 80);
  EXPECT_DOUBLE_EQ(p.link.to_monitor.jitter_ms, 10);  // shared, not overridden
  EXPECT_TRUE(p.link.to_monitor.reorder);
  EXPECT_FALSE(p.link.to_host.reorder);
  EXPECT_FALSE(find_qos_profile("lan").link.active());
  EXPECT_TRUE(find_qos_profile("sim-wifi").link.active());
  EXPECT_DOUBLE_EQ(find_qos_profile("sim-lossy-wifi").link.to_host.loss_per_mille, 200);
  EXPECT_THAT(error_of("name: l\nlink:\n  delay_ms: -5\n"),
              HasSubstr("'link.delay_ms' must be from 0"));
  EXPECT_THAT(error_of("name: l\nlink:\n  to_host:\n    lag_ms: 5\n"), HasSubstr("lag_ms"));
}

TEST(QosProfile, SimStatusHasARoleOfItsOwn) {
  for (const char* name : {"lan", "wifi", "sim-wifi", "sim-lossy-wifi", "protocol-loss-test"}) {
    const auto p = find_qos_profile(name);
    EXPECT_EQ(p.topic(TopicRole::kStatus).reliability, Reliability::kReliable) << name;
    EXPECT_EQ(p.topic(TopicRole::kStatus).durability, Durability::kTransientLocal) << name;
    EXPECT_FALSE(p.status.autodispose) << name;
  }
  const auto p = parse_qos_profile("name: s\ntopics:\n  status:\n    depth: 3\n", "s.yaml");
  EXPECT_EQ(p.status.depth, 3);
  EXPECT_EQ(p.progress, default_qos_profile().progress);  // no longer borrowed from progress
}

// Regressions from fuzzing the QoS YAML: depth 2147483647 aborted inside dds_write,
// deadline_ms: 0 made the monitor spin forever, huge timers failed slowly as "host left".
TEST(QosProfileErrors, ValuesDdsCannotLiveWithAreRefused) {
  EXPECT_THAT(error_of("name: x\ntopics:\n  action:\n    depth: 2147483647\n"),
              HasSubstr("'topics.action.depth' must be >= 1 and <= 10000"));
  EXPECT_THAT(error_of("name: x\ntopics:\n  state:\n    deadline_ms: 0\n"),
              HasSubstr("'topics.state.deadline_ms' must be at least 1 ms"));
  EXPECT_THAT(error_of("name: x\ntransport:\n  heartbeat_interval_ms: 99999999999\n"),
              HasSubstr("is more than an hour"));
  EXPECT_THAT(error_of("name: x\ntopics:\n  clock:\n    liveliness_lease_ms: 0\n"),
              HasSubstr("at least 1 ms"));
}

TEST(QosProfile, LoadsByPath) {
  const auto p = find_qos_profile(std::string(SMART_SOURCE_DIR) + "/config/qos/wifi.yaml");
  EXPECT_EQ(p.name, "wifi");
}

TEST(QosProfile, OmittedTopicsKeepDefaults) {
  const auto p = parse_qos_profile("name: tiny\ntopics:\n  clock:\n    depth: 4\n", "tiny.yaml");
  EXPECT_EQ(p.clock.depth, 4);
  EXPECT_EQ(p.action, default_qos_profile().action);
  EXPECT_EQ(p.state, default_qos_profile().state);
}

// Issue 26: lossy-wifi both modelled a link and dropped real packets; the old name says where
// each half went.
TEST(QosProfileErrors, TheSplitLossyWifiProfileNamesItsSuccessors) {
  try {
    (void)find_qos_profile("lossy-wifi");
    FAIL() << "lossy-wifi must not load";
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("sim-lossy-wifi"));
    EXPECT_THAT(e.what(), HasSubstr("protocol-loss-test"));
  }
  try {
    (void)find_qos_profile("wlan");
    FAIL() << "an unknown profile must not load";
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("sim-wifi"));
  }
}

TEST(QosProfile, DomainConfigCarriesTransport) {
  const auto p = find_qos_profile("protocol-loss-test");
  const auto d = p.domain_config();
  EXPECT_EQ(d.transport.loss_per_mille, 200);
  EXPECT_EQ(d.interfaces, std::vector<std::string>{"lo"});
}

TEST(QosProfileErrors, UnknownKeyNamesFileLineAndKnownKeys) {
  const auto e = error_of("name: x\ntopics:\n  action:\n    reliabilty: reliable\n");
  EXPECT_THAT(e, HasSubstr("bad.yaml:4:5"));
  EXPECT_THAT(e, HasSubstr("unknown key 'reliabilty'"));
  EXPECT_THAT(e, HasSubstr("topics.action"));
  EXPECT_THAT(e, HasSubstr("reliability"));
}

TEST(QosProfileErrors, BadEnumValueListsChoices) {
  const auto e = error_of("name: x\ntopics:\n  state:\n    durability: persistent\n");
  EXPECT_THAT(e, HasSubstr("bad.yaml:4:17"));
  EXPECT_THAT(e, HasSubstr("'persistent'"));
  EXPECT_THAT(e, HasSubstr("transient_local"));
}

TEST(QosProfileErrors, BadNumbersAreRejected) {
  EXPECT_THAT(error_of("name: x\ntopics:\n  action:\n    depth: 0\n"), HasSubstr("must be >= 1"));
  EXPECT_THAT(error_of("name: x\ntopics:\n  action:\n    depth: many\n"),
              HasSubstr("'many' but must be a whole number"));
  EXPECT_THAT(error_of("name: x\ntopics:\n  state:\n    deadline_ms: -5\n"), HasSubstr("negative"));
  EXPECT_THAT(error_of("name: x\ntransport:\n  loss_per_mille: 1200\n"),
              HasSubstr("bad.yaml:3:19"));
}

TEST(QosProfileErrors, SyntaxErrorNamesLine) {
  const auto e = error_of("name: x\ntopics:\n  action: [unclosed\n");
  EXPECT_THAT(e, HasSubstr("bad.yaml:"));
  EXPECT_THAT(e, HasSubstr("YAML syntax error"));
}

TEST(QosProfileErrors, StructureErrors) {
  EXPECT_THAT(error_of("- a\n- b\n"), HasSubstr("must be a YAML mapping"));
  EXPECT_THAT(error_of("description: no name\n"), HasSubstr("missing key 'name'"));
  EXPECT_THAT(error_of("name: x\ntopics:\n  pose: {}\n"), HasSubstr("unknown key 'pose'"));
  EXPECT_THAT(error_of("name: x\ntopics: 3\n"), HasSubstr("'topics' must be a mapping"));
}

TEST(QosProfileErrors, UnknownProfileNameSaysWhereItLooked) {
  try {
    find_qos_profile("carrier-pigeon");
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("carrier-pigeon"));
    EXPECT_THAT(e.what(), HasSubstr("qos/carrier-pigeon.yaml"));
  }
  EXPECT_THROW(find_qos_profile("/nonexistent/x.yaml"), ConfigError);
}

}  // namespace
}  // namespace smart::dds
