// Contract: a reader that hears only admitted writers (issue 25: "a rejected sample must never
// hide an accepted one"). Cyclone DDS runs a topic filter with each arriving sample's info
// (dds.h, "Topic filters": publication_handle is its writer) before the sample enters the
// reader's history and before exclusive ownership picks an owner, so a sample from a writer that
// is not admitted can neither displace an admitted writer's sample from a keep-last history,
// nor seize an instance, nor delay it. Refused samples are counted per writer (at most
// kMaxWriters writers; then under handle 0) for the edge to name.
// Two ways to admit:
// - by hand: open (every writer heard) until close(); from then on only the publication handles
//   admit()ted (the monitor binds its clock to the sim host this way);
// - by rule (admit_roles(): the run proof in the writer's USER_DATA, smart/wire/run_proof.hpp):
//   closed from the start; the reader (reader.hpp) asks decide() for each writer from its
//   subscription-matched listener, which Cyclone calls when the writer is matched and before
//   that writer's first sample can reach the reader (ddsi_entity_match.c, reader_add_connection
//   runs before proxy_writer_add_connection), and once after creation for the writers matched
//   while the reader was being made. The listener calls into the reader
//   (dds_get_matched_publication_data), so nothing may hold the reader's lock while waiting for
//   its listeners: Cyclone 0.10's dds_set_status_mask does, hence WaitSet::attach_status waits on
//   a reader through a read condition (waitset.hpp). A proven writer of another role is
//   ignored uncounted (the sim's own ticks on the clock topic an agent reads); everyone else is
//   refused.
// On a per-robot topic (progress, states; idl/smart.idl "Runs") the admission also holds each
// admitted writer to the robots its partitions name (robot_speakers.hpp), sample by sample in
// the same filter, so an insider's key (an agent-<id> identity, the run key) neither moves
// another robot nor seizes its instance; there every writer is decided at match, with the run
// key's rule or, without a key, admitting all.
// The filter and the listener run on Cyclone's threads: the state is behind a mutex.
#pragma once

#include <dds/dds.h>

#include <atomic>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "smart/dds/participant.hpp"
#include "smart/dds/robot_speakers.hpp"

namespace smart::dds {

enum class Verdict { kAdmit, kIgnore, kRefuse };

// Why a rule refused a writer, for the edges' rejection counts.
inline constexpr const char* kNotRunMember =
    "not a member of this run (its writer carries no valid proof of the run's key; every "
    "process of the run needs the same --run-key)";
using AdmitRule = std::function<Verdict(const dds_builtintopic_endpoint_t& writer)>;

// Writers proven (with `participant`'s run key, in its run) in one of `roles` are admitted; a
// proven writer of another role is ignored. Empty (no rule: every writer heard) when the
// participant has no run key.
AdmitRule admit_roles(const Participant& participant, std::vector<std::string> roles);

// A matched endpoint's QoS as admission reads it (nullptr: nothing): its partitions and its
// USER_DATA bytes (the run proof).
std::vector<std::string> qos_partitions(const dds_qos_t* qos);
std::string qos_user_data(const dds_qos_t* qos);

class WriterAdmission {
 public:
  static constexpr std::size_t kMaxWriters = 64;
  WriterAdmission() = default;
  explicit WriterAdmission(AdmitRule rule);
  // For a per-robot topic of `participant`'s run: members with `roles` (every writer without a
  // run key), each heard only for the robots its partitions name.
  static std::unique_ptr<WriterAdmission> per_robot(const Participant& participant,
                                                    std::vector<std::string> roles);
  WriterAdmission(const WriterAdmission&) = delete;
  WriterAdmission& operator=(const WriterAdmission&) = delete;

  void admit(dds_instance_handle_t writer);
  void close();
  bool closed() const;
  bool admitted(dds_instance_handle_t writer) const;
  bool has_rule() const { return static_cast<bool>(rule_); }
  // By rule: decides `writer`, matched on `reader` (once; a writer no longer matched is left).
  void decide(dds_entity_t reader, dds_instance_handle_t writer);
  // By rule: decides every writer matched on `reader` now.
  void decide_matched(dds_entity_t reader);
  // The filter's decision for one sample (counted when refused); with the sample's robot on a
  // per-robot topic.
  bool hear(dds_instance_handle_t writer);
  bool hear(dds_instance_handle_t writer, uint32_t robot);
  // Samples refused since the last call, by writer: from non-members; from members for robots
  // they do not speak for.
  std::map<dds_instance_handle_t, uint64_t> take_refused();
  std::map<dds_instance_handle_t, uint64_t> take_misspoken();
  // Whom an admitted writer speaks for (per-robot topics; nothing: unknown or any).
  std::optional<Speaks> speaks(dds_instance_handle_t writer) const;
  // For dds_set_topic_filter_extended (arg: this).
  static bool filter(const dds_sample_info_t* info, void* self);
  template <class T>
  static bool filter_robot(const void* sample, const dds_sample_info_t* info, void* self) {
    return static_cast<WriterAdmission*>(self)->hear(info->publication_handle,
                                                     static_cast<const T*>(sample)->robot_id);
  }
  // For dds_lset_subscription_matched_arg (arg: this).
  static void on_matched(dds_entity_t reader, dds_subscription_matched_status_t status, void* self);

 private:
  static void count(std::map<dds_instance_handle_t, uint64_t>& m, dds_instance_handle_t writer);
  void forget(dds_instance_handle_t writer);

  AdmitRule rule_;
  std::string run_partition_;  // per-robot topics: the run whose robot partitions count
  mutable std::mutex mutex_;
  std::atomic<bool> reader_made_{false};  // decide_matched() ran: the reader's handle is usable
  bool closed_ = false;
  std::set<dds_instance_handle_t> admitted_, ignored_;
  std::map<dds_instance_handle_t, Speaks> speaks_;
  std::map<dds_instance_handle_t, uint64_t> refused_, misspoken_;
};

}  // namespace smart::dds
