// Contract: Reader<T> receives samples of T. take()/read() return a LoanedSamples<T> that lends
// Cyclone's own sample memory (no copy) and returns the loan when destroyed; each Sample says
// whether it carries valid data or only an instance-state change (disposed, no writers).
// An optional data-available callback runs on a Cyclone listener thread: keep it short and
// thread-safe. Move-only; the callback is never invoked after the Reader is destroyed.
#pragma once

#include <dds/dds.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "smart/dds/admission.hpp"
#include "smart/dds/entity.hpp"
#include "smart/dds/error.hpp"
#include "smart/dds/participant.hpp"
#include "smart/dds/qos.hpp"
#include "smart/dds/status.hpp"
#include "smart/dds/topic.hpp"

namespace smart::dds {

template <class T>
class Sample {
 public:
  Sample(const T* data, const dds_sample_info_t* info) : data_(data), info_(info) {}
  bool valid() const { return info_->valid_data; }
  // Only meaningful when valid(); for invalid samples only the key fields are set.
  const T& data() const { return *data_; }
  const dds_sample_info_t& info() const { return *info_; }
  bool alive() const { return info_->instance_state == DDS_IST_ALIVE; }
  bool disposed() const { return info_->instance_state == DDS_IST_NOT_ALIVE_DISPOSED; }
  bool no_writers() const { return info_->instance_state == DDS_IST_NOT_ALIVE_NO_WRITERS; }

 private:
  const T* data_;
  const dds_sample_info_t* info_;
};

template <class T>
class LoanedSamples {
 public:
  LoanedSamples(dds_entity_t reader, std::vector<void*> buffers,
                std::vector<dds_sample_info_t> infos, int32_t count)
      : reader_(reader), buffers_(std::move(buffers)), infos_(std::move(infos)), count_(count) {}
  LoanedSamples(LoanedSamples&& o) noexcept
      : reader_(o.reader_),
        buffers_(std::move(o.buffers_)),
        infos_(std::move(o.infos_)),
        count_(std::exchange(o.count_, 0)) {}
  LoanedSamples& operator=(LoanedSamples&&) = delete;
  LoanedSamples(const LoanedSamples&) = delete;
  ~LoanedSamples() {
    if (count_ > 0) (void)dds_return_loan(reader_, buffers_.data(), count_);
  }

  std::size_t size() const { return static_cast<std::size_t>(count_); }
  bool empty() const { return count_ == 0; }
  Sample<T> operator[](std::size_t i) const {
    return Sample<T>(static_cast<const T*>(buffers_[i]), &infos_[i]);
  }

  class iterator {
   public:
    iterator(const LoanedSamples* s, std::size_t i) : s_(s), i_(i) {}
    Sample<T> operator*() const { return (*s_)[i_]; }
    iterator& operator++() {
      ++i_;
      return *this;
    }
    bool operator!=(const iterator& o) const { return i_ != o.i_; }

   private:
    const LoanedSamples* s_;
    std::size_t i_;
  };
  iterator begin() const { return iterator(this, 0); }
  iterator end() const { return iterator(this, size()); }

 private:
  dds_entity_t reader_;
  std::vector<void*> buffers_;
  std::vector<dds_sample_info_t> infos_;
  int32_t count_;
};

// A writer as a reader knows it (matched publication data).
struct Publication {
  dds_guid_t participant;
  int32_t strength = 0;  // 0 when the writer has no exclusive ownership
};

template <class T>
class Reader {
 public:
  using Callback = std::function<void()>;

  Reader(const Participant& participant, const Topic<T>& topic, const Qos& qos,
         Callback on_data_available = nullptr)
      : topic_name_(topic.name()) {
    dds_listener_t* listener = nullptr;
    if (on_data_available) {
      callback_ = std::make_unique<Callback>(std::move(on_data_available));
      listener = dds_create_listener(callback_.get());
      dds_lset_data_available(listener, &Reader::trampoline);
    }
    create(participant, topic, qos, listener);
  }
  // A reader whose writers `admission` decides by its rule (admission.hpp) as they match; the
  // admission must outlive the reader.
  Reader(const Participant& participant, const Topic<T>& topic, const Qos& qos,
         WriterAdmission& admission)
      : topic_name_(topic.name()) {
    dds_listener_t* listener = nullptr;
    if (admission.has_rule()) {
      listener = dds_create_listener(nullptr);
      dds_lset_subscription_matched_arg(listener, &WriterAdmission::on_matched, &admission, false);
    }
    create(participant, topic, qos, listener);
    admission.decide_matched(entity_.handle());
  }
  Reader(Reader&& o) noexcept = default;
  Reader& operator=(Reader&& o) noexcept {
    if (this != &o) {
      entity_.reset();  // stop callbacks before their target goes away
      topic_name_ = std::move(o.topic_name_);
      callback_ = std::move(o.callback_);
      entity_ = std::move(o.entity_);
    }
    return *this;
  }
  ~Reader() { entity_.reset(); }

  // Removes up to `max` samples from the reader cache.
  LoanedSamples<T> take(std::size_t max = 256) { return get(max, true); }
  // Like take() but leaves the samples in the cache (marked read).
  LoanedSamples<T> read(std::size_t max = 256) { return get(max, false); }

  // Takes everything available, calling fn(const T&) for each valid sample; returns the count.
  template <class Fn>
  std::size_t take_each(Fn&& fn) {
    return take_each_from([&](const T& data, dds_instance_handle_t) { fn(data); });
  }

  // Like take_each, with the sender: fn(const T&, dds_instance_handle_t publication), the
  // handle of the writer that wrote the sample (sample info, DDS spec 2.2.2.5.5).
  template <class Fn>
  std::size_t take_each_from(Fn&& fn) {
    return take_each_info(
        [&](const T& data, const dds_sample_info_t& info) { fn(data, info.publication_handle); });
  }

  // Like take_each, with the whole sample info: fn(const T&, const dds_sample_info_t&) (its
  // writer, source timestamp, ...).
  template <class Fn>
  std::size_t take_each_info(Fn&& fn) {
    std::size_t n = 0;
    for (;;) {
      auto samples = take();
      if (samples.empty()) return n;
      for (auto s : samples) {
        if (s.valid()) {
          fn(s.data(), s.info());
          ++n;
        }
      }
    }
  }

  // A matched writer's participant and ownership strength, or nothing when the writer is no
  // longer matched (it left, or was never seen).
  std::optional<Publication> publication(dds_instance_handle_t handle) const {
    dds_builtintopic_endpoint_t* e = dds_get_matched_publication_data(entity_.handle(), handle);
    if (e == nullptr) return std::nullopt;
    Publication p{e->participant_key, 0};
    if (e->qos != nullptr && !dds_qget_ownership_strength(e->qos, &p.strength)) p.strength = 0;
    dds_builtintopic_free_endpoint(e);
    return p;
  }
  // The partitions of a matched writer's publisher (none: it left); a writer in the wildcard
  // "smart.run.*" reaches every run's readers and shows that pattern here.
  std::optional<std::vector<std::string>> partitions_of(dds_instance_handle_t handle) const {
    dds_builtintopic_endpoint_t* e = dds_get_matched_publication_data(entity_.handle(), handle);
    if (e == nullptr) return std::nullopt;
    auto out = qos_partitions(e->qos);
    dds_builtintopic_free_endpoint(e);
    return out;
  }
  std::optional<dds_guid_t> participant_of(dds_instance_handle_t handle) const {
    const auto p = publication(handle);
    return p ? std::optional<dds_guid_t>(p->participant) : std::nullopt;
  }
  // The writers matched now (publication handles).
  std::vector<dds_instance_handle_t> matched_writers() const {
    std::vector<dds_instance_handle_t> handles(64);
    for (;;) {
      const auto n = dds_get_matched_publications(entity_.handle(), handles.data(), handles.size());
      check(n, "matched publications of '" + topic_name_ + "'");
      if (static_cast<std::size_t>(n) <= handles.size()) {
        handles.resize(static_cast<std::size_t>(n));
        return handles;
      }
      handles.resize(static_cast<std::size_t>(n));
    }
  }
  bool writer_matched(dds_instance_handle_t handle) const {
    return publication(handle).has_value();
  }
  // The writer is matched and at least as strong as `strength`.
  bool writer_at_least(dds_instance_handle_t handle, int32_t strength) const {
    const auto p = publication(handle);
    return p && p->strength >= strength;
  }

  // Writers found whose QoS does not satisfy this reader's (a different QoS profile).
  dds_requested_incompatible_qos_status_t requested_incompatible_qos() const {
    dds_requested_incompatible_qos_status_t s{};
    check(dds_get_requested_incompatible_qos_status(entity_.handle(), &s),
          "incompatible QoS status");
    return s;
  }
  dds_subscription_matched_status_t subscription_matched() const {
    dds_subscription_matched_status_t s{};
    check(dds_get_subscription_matched_status(entity_.handle(), &s), "subscription matched");
    return s;
  }
  dds_liveliness_changed_status_t liveliness_changed() const {
    dds_liveliness_changed_status_t s{};
    check(dds_get_liveliness_changed_status(entity_.handle(), &s), "liveliness changed");
    return s;
  }
  dds_requested_deadline_missed_status_t requested_deadline_missed() const {
    dds_requested_deadline_missed_status_t s{};
    check(dds_get_requested_deadline_missed_status(entity_.handle(), &s), "deadline missed");
    return s;
  }
  dds_sample_lost_status_t sample_lost() const {
    dds_sample_lost_status_t s{};
    check(dds_get_sample_lost_status(entity_.handle(), &s), "sample lost");
    return s;
  }
  // Blocks until transient-local data already written by matched writers has arrived.
  bool wait_for_historical_data(std::chrono::milliseconds timeout) const {
    return dds_reader_wait_for_historical_data(entity_.handle(), to_dds_duration(timeout)) ==
           DDS_RETCODE_OK;
  }
  bool wait_for_writers(uint32_t writers, std::chrono::milliseconds timeout) const {
    return wait_until([&] { return subscription_matched().current_count >= writers; }, timeout);
  }

  dds_entity_t handle() const { return entity_.handle(); }

 private:
  // The callback runs on Cyclone's listener thread, inside C code: an exception must not leave
  // it (std::terminate). Regression: an agent's odometry listener took from its reader while the
  // reader was being deleted at shutdown ("Bad Parameter"), and the process aborted.
  static void trampoline(dds_entity_t reader, void* arg) {
    try {
      (*static_cast<Callback*>(arg))();
    } catch (const std::exception& e) {
      spdlog::warn("DDS listener of reader {}: {} (the callback failed; this sample is dropped)",
                   reader, e.what());
    }
  }

  void create(const Participant& participant, const Topic<T>& topic, const Qos& qos,
              dds_listener_t* listener) {
    const dds_entity_t h =
        dds_create_reader(participant.handle(), topic.handle(), qos.get(), listener);
    if (listener != nullptr) dds_delete_listener(listener);
    entity_ = Entity(check(h, "creating a reader on '" + topic.name() + "'"));
  }

  LoanedSamples<T> get(std::size_t max, bool take) {
    std::vector<void*> buffers(max, nullptr);  // null first entry: Cyclone lends its memory
    std::vector<dds_sample_info_t> infos(max);
    const auto n = take ? dds_take(entity_.handle(), buffers.data(), infos.data(), max,
                                   static_cast<uint32_t>(max))
                        : dds_read(entity_.handle(), buffers.data(), infos.data(), max,
                                   static_cast<uint32_t>(max));
    check(n, (take ? "taking from '" : "reading from '") + topic_name_ + "'");
    return LoanedSamples<T>(entity_.handle(), std::move(buffers), std::move(infos), n);
  }

  std::string topic_name_;
  std::unique_ptr<Callback> callback_;  // heap: its address is the listener argument
  Entity entity_;                       // declared last: deleted first
};

}  // namespace smart::dds
