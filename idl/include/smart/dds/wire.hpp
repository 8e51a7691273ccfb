// Contract: endpoints on the SMART topics made from the one table in topics.hpp: a
// WireWriter<T> / WireReader<T> owns its topic and takes name and QoS (by the topic's role in
// the QosProfile) from there, so no caller repeats either, and put it in the participant's run
// partition. Writers carry the participant's run proof (participant.hpp). They are a Writer<T> /
// Reader<T> in every other respect.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "smart/dds/admission.hpp"
#include "smart/dds/qos_profile.hpp"
#include "smart/dds/reader.hpp"
#include "smart/dds/topics.hpp"
#include "smart/dds/writer.hpp"

namespace smart::dds {

namespace detail {
// Base-from-member: the topic must exist before the Writer/Reader base is built on it.
// A topic entity of its own per endpoint, so that a reader's filter is its own.
template <class T>
struct WireTopicHolder {
  explicit WireTopicHolder(const Participant& p) : topic_(p, std::string(WireTopic<T>::name)) {}
  WireTopicHolder(const Participant& p, WriterAdmission& admission)
      : topic_(p, std::string(WireTopic<T>::name)) {
    dds_topic_filter f{};
    if constexpr (WireTopic<T>::per_robot) {  // the sample's robot too (admission.hpp)
      f.mode = DDS_TOPIC_FILTER_SAMPLE_SAMPLEINFO_ARG;
      f.f.sample_sampleinfo_arg = &WriterAdmission::filter_robot<T>;
    } else {
      f.mode = DDS_TOPIC_FILTER_SAMPLEINFO_ARG;
      f.f.sampleinfo_arg = &WriterAdmission::filter;
    }
    f.arg = &admission;
    check(dds_set_topic_filter_extended(topic_.handle(), &f),
          "setting the writer admission filter on '" + topic_.name() + "'");
  }
  Topic<T> topic_;
};
}  // namespace detail

// The topic's QoS role in the profile, in the participant's run partition, with the topic's
// ownership (a writer's strength; readers ignore it).
template <class T>
Qos wire_qos(const Participant& participant, const QosProfile& profile,
             int32_t strength = kHostStrength) {
  Qos q = profile.topic(WireTopic<T>::role).to_dds();
  q.partition(participant.run_partition());
  if constexpr (WireTopic<T>::exclusive) q.exclusive_ownership(strength);
  if (!participant.proof().empty()) q.user_data(participant.proof());  // readers ignore it
  return q;
}

// A reader's: a per-robot topic is read in the run's partition and in its robots' partitions.
template <class T>
Qos wire_reader_qos(const Participant& participant, const QosProfile& profile) {
  Qos q = wire_qos<T>(participant, profile);
  if constexpr (WireTopic<T>::per_robot) {
    q.partitions({participant.run_partition(), participant.robot_partitions()});
  }
  return q;
}

// Writes with the hosts' ownership strength unless given another (a monitor's); in the run's
// partition, or for a per-robot topic in the partitions of the robots it speaks for.
template <class T>
class WireWriter : private detail::WireTopicHolder<T>, public Writer<T> {
 public:
  WireWriter(const Participant& p, const QosProfile& profile, int32_t strength = kHostStrength)
      : detail::WireTopicHolder<T>(p),
        Writer<T>(p, this->topic_, wire_qos<T>(p, profile, strength)) {}
  WireWriter(const Participant& p, const QosProfile& profile, const std::vector<uint32_t>& robots)
      : detail::WireTopicHolder<T>(p), Writer<T>(p, this->topic_, robots_qos(p, profile, robots)) {}

 private:
  static Qos robots_qos(const Participant& p, const QosProfile& profile,
                        const std::vector<uint32_t>& robots) {
    static_assert(WireTopic<T>::per_robot, "only per-robot topics are written per robot");
    Qos q = wire_qos<T>(p, profile);
    if (robots.empty()) return q;
    std::vector<std::string> names;
    names.reserve(robots.size());
    for (const uint32_t r : robots) names.push_back(p.robot_partition(r));
    q.partitions(names);
    return q;
  }
};

// With an admission (admission.hpp), it hears only the writers admitted there (by hand once
// closed, or by its rule as they match); the admission must outlive the reader.
template <class T>
class WireReader : private detail::WireTopicHolder<T>, public Reader<T> {
 public:
  WireReader(const Participant& p, const QosProfile& profile,
             typename Reader<T>::Callback on_data_available = nullptr)
      : detail::WireTopicHolder<T>(p),
        Reader<T>(p, this->topic_, wire_reader_qos<T>(p, profile), std::move(on_data_available)) {}
  WireReader(const Participant& p, const QosProfile& profile, WriterAdmission& admission)
      : detail::WireTopicHolder<T>(p, admission),
        Reader<T>(p, this->topic_, wire_reader_qos<T>(p, profile), admission) {}
};

}  // namespace smart::dds
