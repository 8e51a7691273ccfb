// Contract: Writer<T> publishes samples of T on a Topic<T>. write()/dispose() throw Error on
// failure (e.g. a reliable write that stays blocked past max_blocking). Move-only.
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

  void write(const T& sample) {
    check(dds_write(entity_.handle(), &sample), "writing on '" + topic_name_ + "'");
  }
  void write(const T& sample, dds_time_t source_timestamp) {
    check(dds_write_ts(entity_.handle(), &sample, source_timestamp),
          "writing on '" + topic_name_ + "'");
  }
  // Marks the instance whose key is in `sample` as disposed for every reader.
  void dispose(const T& sample) {
    check(dds_dispose(entity_.handle(), &sample), "disposing on '" + topic_name_ + "'");
  }
  void unregister(const T& sample) {
    check(dds_unregister_instance(entity_.handle(), &sample),
          "unregistering on '" + topic_name_ + "'");
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
  std::string topic_name_;
  Entity entity_;
};

}  // namespace smart::dds
