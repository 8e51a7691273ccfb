#include "smart/dds/qos.hpp"

#include <gtest/gtest.h>

namespace smart::dds {
namespace {

TEST(TopicQos, RendersEveryPolicyIntoCycloneQos) {
  TopicQos t;
  t.reliability = Reliability::kReliable;
  t.max_blocking = Millis(250);
  t.history = HistoryKind::kKeepLast;
  t.depth = 3;
  t.durability = Durability::kTransientLocal;
  t.deadline = Millis(300);
  t.lifespan = Millis(2000);
  t.liveliness = LivelinessKind::kManualByParticipant;
  t.liveliness_lease = Millis(1500);
  t.autodispose = false;
  const Qos q = t.to_dds();

  dds_reliability_kind_t rel{};
  dds_duration_t blocking = 0;
  ASSERT_TRUE(dds_qget_reliability(q.get(), &rel, &blocking));
  EXPECT_EQ(rel, DDS_RELIABILITY_RELIABLE);
  EXPECT_EQ(blocking, DDS_MSECS(250));
  dds_history_kind_t hist{};
  int32_t depth = 0;
  ASSERT_TRUE(dds_qget_history(q.get(), &hist, &depth));
  EXPECT_EQ(hist, DDS_HISTORY_KEEP_LAST);
  EXPECT_EQ(depth, 3);
  dds_durability_kind_t dur{};
  ASSERT_TRUE(dds_qget_durability(q.get(), &dur));
  EXPECT_EQ(dur, DDS_DURABILITY_TRANSIENT_LOCAL);
  dds_duration_t deadline = 0;
  ASSERT_TRUE(dds_qget_deadline(q.get(), &deadline));
  EXPECT_EQ(deadline, DDS_MSECS(300));
  dds_duration_t lifespan = 0;
  ASSERT_TRUE(dds_qget_lifespan(q.get(), &lifespan));
  EXPECT_EQ(lifespan, DDS_MSECS(2000));
  dds_liveliness_kind_t lk{};
  dds_duration_t lease = 0;
  ASSERT_TRUE(dds_qget_liveliness(q.get(), &lk, &lease));
  EXPECT_EQ(lk, DDS_LIVELINESS_MANUAL_BY_PARTICIPANT);
  EXPECT_EQ(lease, DDS_MSECS(1500));
  bool autodispose = true;
  ASSERT_TRUE(dds_qget_writer_data_lifecycle(q.get(), &autodispose));
  EXPECT_FALSE(autodispose);
}

TEST(TopicQos, KeepAllBestEffortAndUnsetPoliciesStayUnset) {
  TopicQos t;
  t.reliability = Reliability::kBestEffort;
  t.history = HistoryKind::kKeepAll;
  const Qos q = t.to_dds();
  dds_reliability_kind_t rel{};
  ASSERT_TRUE(dds_qget_reliability(q.get(), &rel, nullptr));
  EXPECT_EQ(rel, DDS_RELIABILITY_BEST_EFFORT);
  dds_history_kind_t hist{};
  ASSERT_TRUE(dds_qget_history(q.get(), &hist, nullptr));
  EXPECT_EQ(hist, DDS_HISTORY_KEEP_ALL);
  dds_duration_t deadline = 0;
  EXPECT_FALSE(dds_qget_deadline(q.get(), &deadline));
  EXPECT_FALSE(dds_qget_lifespan(q.get(), &deadline));
}

TEST(Qos, CopiesAreIndependent) {
  Qos a;
  a.keep_last(5);
  Qos b = a;
  b.keep_last(7);
  int32_t da = 0, db = 0;
  ASSERT_TRUE(dds_qget_history(a.get(), nullptr, &da));
  ASSERT_TRUE(dds_qget_history(b.get(), nullptr, &db));
  EXPECT_EQ(da, 5);
  EXPECT_EQ(db, 7);
  Qos c = std::move(b);
  ASSERT_TRUE(dds_qget_history(c.get(), nullptr, &db));
  EXPECT_EQ(db, 7);
}

TEST(QosNames, AreTheYamlSpellings) {
  EXPECT_EQ(to_string(Reliability::kBestEffort), "best_effort");
  EXPECT_EQ(to_string(Durability::kTransientLocal), "transient_local");
  EXPECT_EQ(to_string(HistoryKind::kKeepAll), "keep_all");
  EXPECT_EQ(to_string(LivelinessKind::kManualByTopic), "manual_by_topic");
}

}  // namespace
}  // namespace smart::dds
