// A reader that hears only admitted writers (smart/dds/admission.hpp): the decision itself, and
// over real DDS a stranger's flood that never displaces the admitted writer's keep-last sample.
#include "smart/dds/admission.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstring>
#include <future>
#include <map>
#include <set>
#include <thread>

#include "smart/dds/waitset.hpp"
#include "smart/dds/wire.hpp"
#include "support/dds_test_support.hpp"

namespace smart::dds {
namespace {

using namespace std::chrono_literals;
using ::testing::HasSubstr;

TEST(WriterAdmission, OpenItHearsEveryoneClosedOnlyTheAdmittedAndCountsTheRest) {
  WriterAdmission a;
  EXPECT_TRUE(a.hear(7));
  a.admit(5);
  a.close();
  EXPECT_TRUE(a.closed());
  EXPECT_TRUE(a.hear(5));
  EXPECT_FALSE(a.hear(7));
  EXPECT_FALSE(a.hear(7));
  for (dds_instance_handle_t h = 100; h < 100 + 2 * WriterAdmission::kMaxWriters; ++h) a.hear(h);
  const auto refused = a.take_refused();
  EXPECT_EQ(refused.at(7), 2u);
  EXPECT_EQ(refused.size(), WriterAdmission::kMaxWriters + 1);  // the rest under handle 0
  EXPECT_EQ(refused.at(0), WriterAdmission::kMaxWriters + 1);
  EXPECT_TRUE(a.take_refused().empty());
}

bool same(const dds_guid_t& a, const dds_guid_t& b) { return std::memcmp(a.v, b.v, 16) == 0; }

// Once both writers matched, admits only `admitted`'s and closes; false if they never matched.
template <class Reader>
bool admit_only(const Reader& reader, WriterAdmission& admission, const Participant& admitted,
                std::chrono::steady_clock::time_point deadline) {
  while (reader.matched_writers().size() < 2) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(5ms);
  }
  dds_guid_t guid;
  if (dds_get_guid(admitted.handle(), &guid) != DDS_RETCODE_OK) return false;
  for (const auto h : reader.matched_writers()) {
    if (const auto who = reader.participant_of(h); who && same(*who, guid)) admission.admit(h);
  }
  admission.close();
  return true;
}

// Issue 25: exclusive ownership handed an instance to the strongest writer even when every
// sample it sent was refused, and a flood displaced the real writer's keep-last sample.
TEST(WriterAdmission, AStrangersFloodNeverDisplacesTheAdmittedWritersSample) {
  Domain domain(test::kAdmissionFlood, test::loopback());
  Participant admitted_p(domain), stranger_p(domain), reader_p(domain);
  const auto qos = find_qos_profile("lan");
  WireWriter<smart_msg_SimStatus> real(admitted_p, qos);
  WireWriter<smart_msg_SimStatus> stranger(stranger_p, qos, 2147483647);
  WriterAdmission admission;
  WireReader<smart_msg_SimStatus> reader(reader_p, qos, admission);
  const auto deadline = std::chrono::steady_clock::now() + 30s;
  ASSERT_TRUE(admit_only(reader, admission, admitted_p, deadline)) << "the writers never matched";
  real.write(smart_msg_SimStatus{0, 1, 2.0, 20, 1, 0, 0.5, 0.1, 10.0, -1, -1});
  uint64_t refused = 0;
  int real_samples = 0;
  for (int i = 0; refused < 1000; ++i) {
    if (i < 1000) stranger.write(smart_msg_SimStatus{0, 1, 3.0, 20, 99, 0, 0.5, 0.1, 1, 2, 3});
    reader.take_each([&](const smart_msg_SimStatus& s) {
      EXPECT_EQ(s.robot_contacts, 1u) << "a stranger's sample reached the reader";
      ++real_samples;
    });
    for (const auto& [writer, n] : admission.take_refused()) refused += n;
    ASSERT_LT(std::chrono::steady_clock::now(), deadline) << refused << " refused so far";
    if (i >= 1000) std::this_thread::sleep_for(1ms);
  }
  while (real_samples == 0) {
    ASSERT_LT(std::chrono::steady_clock::now(), deadline) << "the admitted sample was lost";
    reader.take_each([&](const smart_msg_SimStatus& s) {
      EXPECT_EQ(s.robot_contacts, 1u);
      ++real_samples;
    });
    std::this_thread::sleep_for(1ms);
  }
  EXPECT_EQ(real_samples, 1);
  EXPECT_EQ(refused, 1000u);
}

// On an exclusively owned topic, a stronger stranger whose samples the admission refuses owns
// nothing: the filter runs before ownership is decided.
TEST(WriterAdmission, AStrongerStrangerRefusedByTheFilterOwnsNothingOnAnExclusiveTopic) {
  Domain domain(test::kAdmissionOwnership, test::loopback());
  Participant admitted_p(domain), stranger_p(domain), reader_p(domain);
  const auto qos = find_qos_profile("lan");
  WireWriter<smart_msg_Progress> real(admitted_p, qos);  // host strength
  WireWriter<smart_msg_Progress> stranger(stranger_p, qos, 2147483647);
  WriterAdmission admission;
  WireReader<smart_msg_Progress> reader(reader_p, qos, admission);
  const auto deadline = std::chrono::steady_clock::now() + 30s;
  ASSERT_TRUE(admit_only(reader, admission, admitted_p, deadline)) << "the writers never matched";
  uint64_t refused = 0;
  for (int i = 0; i < 100; ++i) stranger.write(smart_msg_Progress{3, 1, 50, -1});
  while (refused < 100) {
    for (const auto& [writer, n] : admission.take_refused()) refused += n;
    ASSERT_LT(std::chrono::steady_clock::now(), deadline) << refused << " refused so far";
    std::this_thread::sleep_for(1ms);
  }
  int32_t last = -2;
  for (int32_t seq = 0; last != 9; seq = std::min(seq + 1, 9)) {
    if (seq <= 9) real.write(smart_msg_Progress{3, 1, seq, -1});
    reader.take_each([&](const smart_msg_Progress& p) { last = p.finished_seq; });
    ASSERT_LT(std::chrono::steady_clock::now(), deadline) << "the admitted writer went unheard";
    std::this_thread::sleep_for(1ms);
  }
  EXPECT_EQ(last, 9);
}

// By rule (issue 25, "bind every stream to the participant the run admitted"): writers proven
// with the run's key are heard from their very first sample, whether they matched while the
// reader was being made or later; a stranger that copies a member's proof into its own writer is
// refused (the proof names the member's participant) and, though strongest, owns nothing; a
// member of another role is ignored without being counted as a stranger.
TEST(WriterAdmission, ByRuleProvenWritersAreHeardFromTheirFirstSampleACopiedProofIsNot) {
  Domain domain(test::kAdmissionProof, test::loopback());
  const auto key = wire::parse_run_key("00112233445566778899aabbccddeeff", "test key");
  Participant early_p(domain), late_p(domain), copy_p(domain), sim_p(domain), reader_p(domain);
  early_p.prove(key, "monitor");
  late_p.prove(key, "monitor");
  sim_p.prove(key, "sim");
  reader_p.prove(key, "agent");
  const auto qos = find_qos_profile("lan");
  WireWriter<smart_msg_Progress> early(early_p, qos);  // matched while the reader is made
  auto copied_qos = wire_qos<smart_msg_Progress>(copy_p, qos, 2147483647);
  copied_qos.user_data(early_p.proof());
  Topic<smart_msg_Progress> copy_topic(copy_p, std::string(WireTopic<smart_msg_Progress>::name));
  Writer<smart_msg_Progress> copy(copy_p, copy_topic, copied_qos);
  WireWriter<smart_msg_Progress> sim(sim_p, qos);
  WriterAdmission admission(admit_roles(reader_p, {"monitor"}));
  ASSERT_TRUE(admission.has_rule());
  WireReader<smart_msg_Progress> reader(reader_p, qos, admission);
  WireWriter<smart_msg_Progress> late(late_p, qos);  // matched after: the listener decides
  for (auto* w : {&early, &late}) ASSERT_TRUE(w->wait_for_readers(1, 30s));
  early.write(smart_msg_Progress{1, 1, 0, -1});  // each member's very first sample
  late.write(smart_msg_Progress{2, 1, 0, -1});
  const auto deadline = std::chrono::steady_clock::now() + 30s;
  while (reader.matched_writers().size() < 4) {
    ASSERT_LT(std::chrono::steady_clock::now(), deadline) << "the writers never matched";
    std::this_thread::sleep_for(5ms);
  }
  for (int i = 0; i < 100; ++i) {
    copy.write(smart_msg_Progress{3, 1, 50, -1});
    sim.write(smart_msg_Progress{3, 1, 60, -1});
  }
  uint64_t refused = 0;
  std::set<dds_instance_handle_t> refused_writers;
  std::map<uint32_t, int32_t> heard;
  for (int32_t seq = 0; heard[3] != 9 || refused < 100; seq = std::min(seq + 1, 9)) {
    early.write(smart_msg_Progress{3, 1, seq, -1});
    reader.take_each([&](const smart_msg_Progress& p) {
      EXPECT_LT(p.finished_seq, 50) << "a stranger's or another role's sample was heard";
      heard[p.robot_id] = p.finished_seq;
    });
    for (const auto& [writer, n] : admission.take_refused()) {
      refused += n;
      refused_writers.insert(writer);
    }
    ASSERT_LT(std::chrono::steady_clock::now(), deadline) << refused << " refused so far";
    std::this_thread::sleep_for(1ms);
  }
  EXPECT_EQ(heard.count(1), 1u) << "the first sample of a writer matched at creation was lost";
  EXPECT_EQ(heard.count(2), 1u) << "the first sample of a writer matched later was lost";
  EXPECT_EQ(refused, 100u);  // the copy's; the sim's samples are ignored, not counted
  EXPECT_EQ(refused_writers.size(), 1u);
}

// Regression (CI, stop 42: a `smart run` hung at its end, another's sim at its start): attaching
// a reader to a wait set set its status mask, and Cyclone 0.10's dds_set_status_mask holds the
// reader's lock while it waits for the reader's running listeners; the admission's listener
// (a writer matched or left) asks the reader for the writer's data and waited for that lock. Now
// a wait set waits on a reader's data through a read condition and never sets its mask: the
// attach returns while the listener is still running (held inside the rule until it is done).
TEST(WriterAdmission, AttachingAReaderToAWaitSetNeverWaitsForItsAdmissionListener) {
  Domain domain(test::kAdmissionListenerAttach, test::loopback());
  Participant reader_p(domain), writer_p(domain);
  std::promise<void> entered, release;
  auto released = release.get_future().share();
  std::atomic<bool> first{true};
  WriterAdmission admission([&](const dds_builtintopic_endpoint_t&) {
    if (first.exchange(false)) {
      entered.set_value();
      released.wait();
    }
    return Verdict::kAdmit;
  });
  const auto qos = find_qos_profile("lan");
  WireReader<smart_msg_Progress> reader(reader_p, qos, admission);
  // A writer made in this process is matched on the thread that makes it: that thread runs the
  // reader's listener, and stays in the rule.
  std::thread maker([&] { WireWriter<smart_msg_Progress> writer(writer_p, qos); });
  entered.get_future().wait();
  auto attached = std::async(std::launch::async, [&] {
    WaitSet ws(reader_p);
    ws.attach_status(reader.handle(), DDS_DATA_AVAILABLE_STATUS, 1);
  });
  const bool returned = attached.wait_for(30s) == std::future_status::ready;
  release.set_value();
  maker.join();
  attached.get();
  EXPECT_TRUE(returned) << "attaching waited for the admission listener (the deadlock)";
}

// The listener may run for a writer before the reader is made (Cyclone refuses the reader's
// handle until then): that failed lookup never undoes the verdict decide_matched() reaches on the
// making thread; once the reader is made, a failed lookup means the writer left.
TEST(WriterAdmission, AFailedLookupBeforeTheReaderIsMadeNeverForgetsAnAdmittedWriter) {
  Domain domain(test::kAdmissionLookupBeforeMade, test::loopback());
  Participant p(domain);  // Cyclone's handles in this process, so a bad one is only refused
  WriterAdmission admission([](const dds_builtintopic_endpoint_t&) { return Verdict::kAdmit; });
  admission.admit(42);
  dds_subscription_matched_status_t status{};
  status.last_publication_handle = 42;
  WriterAdmission::on_matched(0, status, &admission);  // no such reader (yet)
  EXPECT_TRUE(admission.admitted(42));
  admission.decide_matched(0);  // the reader is made (no writers matched on this handle)
  WriterAdmission::on_matched(0, status, &admission);
  EXPECT_FALSE(admission.admitted(42));
}

// Per robot (issue 25: "an insider key is its robot's only"): a writer in robot 3's partition is
// heard for robot 3 only, and though strongest it seizes no other robot's instance: the sim
// host's samples for robot 4 still arrive; a sim host's writer speaks for any robot, a wildcard
// writer's for none. Without a run key every writer is a member.
TEST(WriterAdmission, PerRobotAWriterIsHeardOnlyForItsRobotsAndSeizesNoOtherInstance) {
  Domain domain(test::kRobotSpeakers, test::loopback());
  Participant agent_p(domain, "r1"), sim_p(domain, "r1"), stranger_p(domain, "*"),
      reader_p(domain, "r1");
  const auto qos = find_qos_profile("lan");
  auto agent_qos = wire_qos<smart_msg_Progress>(agent_p, qos, 2147483647);
  agent_qos.partitions({agent_p.robot_partition(3)});
  Topic<smart_msg_Progress> agent_topic(agent_p, std::string(WireTopic<smart_msg_Progress>::name));
  Writer<smart_msg_Progress> agent(agent_p, agent_topic, agent_qos);
  WireWriter<smart_msg_Progress> sim(sim_p, qos);
  WireWriter<smart_msg_Progress> stranger(stranger_p, qos);
  const auto admission = WriterAdmission::per_robot(reader_p, {"sim", "agent"});
  WireReader<smart_msg_Progress> reader(reader_p, qos, *admission);
  for (auto* w : {&agent, static_cast<Writer<smart_msg_Progress>*>(&sim),
                  static_cast<Writer<smart_msg_Progress>*>(&stranger)}) {
    ASSERT_TRUE(w->wait_for_readers(1, 30s));
  }
  for (int i = 0; i < 100; ++i) {
    agent.write(smart_msg_Progress{4, 1, 50, -1});  // not its robot, strongest
    stranger.write(smart_msg_Progress{6, 1, 50, -1});
  }
  agent.write(smart_msg_Progress{3, 1, 7, -1});  // its own robot
  std::map<uint32_t, int32_t> heard;
  std::map<std::string, uint64_t> misspoken;  // by reason
  uint64_t refused = 0;
  const auto deadline = std::chrono::steady_clock::now() + 30s;
  const auto done = [&] {
    uint64_t n = 0;
    for (const auto& [why, k] : misspoken) n += k;
    return heard[4] == 9 && heard[3] == 7 && n >= 200;
  };
  for (int32_t seq = 0; !done(); seq = std::min(seq + 1, 9)) {
    sim.write(smart_msg_Progress{4, 1, seq, -1});
    reader.take_each([&](const smart_msg_Progress& p) {
      EXPECT_NE(p.finished_seq, 50) << "robot " << p.robot_id << ": a sample it may not speak for";
      heard[p.robot_id] = p.finished_seq;
    });
    for (const auto& [writer, n] : admission->take_misspoken()) {
      ASSERT_TRUE(admission->speaks(writer));
      misspoken[speaks_only(*admission->speaks(writer))] += n;
    }
    for (const auto& [writer, n] : admission->take_refused()) refused += n;
    ASSERT_LT(std::chrono::steady_clock::now(), deadline) << "robot 4 at " << heard[4];
    std::this_thread::sleep_for(1ms);
  }
  ASSERT_EQ(misspoken.size(), 2u);
  for (const auto& [why, n] : misspoken) {
    EXPECT_EQ(n, 100u) << why;
    EXPECT_THAT(why, ::testing::AnyOf(HasSubstr("speaks for robot(s) 3 only"),
                                      HasSubstr("outside this run's partition")));
  }
  EXPECT_EQ(refused, 0u);  // no run key: every writer is a member
}

}  // namespace
}  // namespace smart::dds
