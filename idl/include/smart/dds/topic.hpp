// Contract: Topic<T> is a typed DDS topic for an idlc-generated C type T. T must have a
// TopicTraits<T> specialisation (see SMART_DDS_TOPIC_TYPE) naming its topic descriptor.
#pragma once

#include <dds/dds.h>

#include <string>

#include "smart/dds/entity.hpp"
#include "smart/dds/error.hpp"
#include "smart/dds/participant.hpp"
#include "smart/dds/qos.hpp"

namespace smart::dds {

template <class T>
struct TopicTraits;  // static const dds_topic_descriptor_t* descriptor();

template <class T>
class Topic {
 public:
  Topic(const Participant& participant, const std::string& name, const Qos* qos = nullptr)
      : name_(name),
        entity_(check(dds_create_topic(participant.handle(), TopicTraits<T>::descriptor(),
                                       name.c_str(), qos ? qos->get() : nullptr, nullptr),
                      "creating topic '" + name + "'")) {}

  dds_entity_t handle() const { return entity_.handle(); }
  const std::string& name() const { return name_; }

 private:
  std::string name_;
  Entity entity_;
};

}  // namespace smart::dds

// Declares the idlc-generated C type CType usable as Topic<CType> (its descriptor is
// CType##_desc). Use at global scope.
#define SMART_DDS_TOPIC_TYPE(CType)                                             \
  namespace smart::dds {                                                        \
  template <>                                                                   \
  struct TopicTraits<CType> {                                                   \
    static const dds_topic_descriptor_t* descriptor() { return &CType##_desc; } \
  };                                                                            \
  }
