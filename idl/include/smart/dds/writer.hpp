// Contract: Writer<T> publishes samples of T on a Topic<T>. write()/dispose() throw Error on
// failure (e.g. a reliable write that stays blocked past max_blocking). Move-only.
//
// Every domain runs with Cyclone's write batching on (domain.cpp): a sample is packed into the
// writer's outgoing message and goes out when the writer is flushed. write(), dispose() and
// unregister() flush at once, so they send exactly as without batching; write_batched() leaves
// the sample packed with the ones before it until flush(), so a host publishing a whole fleet's
// states each period sends a few full UDP messages instead of one per robot.
#pragma once

#include <dds/dds.h>

#include <chrono>

#include "smart/dds/entity.hpp"
#include "smart/dds/error.hpp"
#include "smart/dds/participant.hpp"
#include "smart/dds/qos.hpp"
#include "smart/dds/status.hpp"
#include "smart/dds/topic.hpp"

namespace smart::dds {

template <class T>
class Writer {
 public:
  Writer(const Participant& participant, const Topic<T>& topic, const Qos& qos)
      : topic_name_(topic.name()),
        entity_(check(dds_create_writer(participant.handle(), topic.handle(), qos.get(), nullptr),
                      "creating a writer on '" + topic.name() + "'")) {}

  void write(const T& sample) { sent(dds_write(entity_.handle(), &sample), "writing"); }
  void write(const T& sample, dds_time_t source_timestamp) {
    sent(dds_write_ts(entity_.handle(), &sample, source_timestamp), "writing");
  }
  // Packs `sample` for sending; it is sent at the next flush() (or when a message is full).
  void write_batched(const T& sample) {
    const auto rc = dds_write(entity_.handle(), &sample);
    if (rc != DDS_RETCODE_OK) sent(rc, "writing");  // what was packed before still goes out
  }
  // Sends everything written with write_batched() since the last flush.
  void flush() { dds_write_flush(entity_.handle()); }
  // Marks the instance whose key is in `sample` as disposed for every reader.
  void dispose(const T& sample) { sent(dds_dispose(entity_.handle(), &sample), "disposing"); }
  void unregister(const T& sample) {
    sent(dds_unregister_instance(entity_.handle(), &sample), "unregistering");
  }
  // Blocks until every matched reliable reader acknowledged everything written; false on timeout.
  bool wait_for_acks(std::chrono::milliseconds timeout) {
    return dds_wait_for_acks(entity_.handle(), to_dds_duration(timeout)) == DDS_RETCODE_OK;
  }

  dds_publication_matched_status_t publication_matched() const {
    dds_publication_matched_status_t s{};
    check(dds_get_publication_matched_status(entity_.handle(), &s), "publication matched status");
    return s;
  }
  dds_offered_deadline_missed_status_t offered_deadline_missed() const {
    dds_offered_deadline_missed_status_t s{};
    check(dds_get_offered_deadline_missed_status(entity_.handle(), &s), "deadline status");
    return s;
  }
  dds_offered_incompatible_qos_status_t offered_incompatible_qos() const {
    dds_offered_incompatible_qos_status_t s{};
    check(dds_get_offered_incompatible_qos_status(entity_.handle(), &s), "incompatible QoS status");
    return s;
  }
  // Waits until at least `readers` readers are matched.
  bool wait_for_readers(uint32_t readers, std::chrono::milliseconds timeout) const {
    return wait_until([&] { return publication_matched().current_count >= readers; }, timeout);
  }

  dds_entity_t handle() const { return entity_.handle(); }

 private:
  // Flushes (the operation goes out now), then throws if it failed.
  void sent(dds_return_t rc, const char* doing) {
    flush();
    check(rc, std::string(doing) + " on '" + topic_name_ + "'");
  }

  std::string topic_name_;
  Entity entity_;
};

}  // namespace smart::dds
