#include "smart/dds/waitset.hpp"

#include "smart/dds/error.hpp"
#include "smart/dds/qos.hpp"

namespace smart::dds {

GuardCondition::GuardCondition(const Participant& participant)
    : entity_(check(dds_create_guardcondition(participant.handle()), "creating guard condition")) {}

void GuardCondition::set(bool triggered) {
  check(dds_set_guardcondition(entity_.handle(), triggered), "setting guard condition");
}

bool GuardCondition::triggered() const {
  bool t = false;
  check(dds_read_guardcondition(entity_.handle(), &t), "reading guard condition");
  return t;
}

ReadCondition::ReadCondition(dds_entity_t reader, uint32_t mask)
    : entity_(check(dds_create_readcondition(reader, mask), "creating read condition")) {}

WaitSet::WaitSet(const Participant& participant)
    : entity_(check(dds_create_waitset(participant.handle()), "creating wait set")) {}

void WaitSet::attach_status(dds_entity_t entity, uint32_t status_mask, dds_attach_t tag) {
  if (status_mask == DDS_DATA_AVAILABLE_STATUS) {
    const dds_entity_t c = dds_create_readcondition(
        entity, DDS_NOT_READ_SAMPLE_STATE | DDS_ANY_VIEW_STATE | DDS_ANY_INSTANCE_STATE);
    if (c > 0) {  // a reader (anything else has no read condition: its status, below)
      conditions_.emplace_back(c);
      attach(c, tag);
      return;
    }
  }
  check(dds_set_status_mask(entity, status_mask), "enabling status for wait set");
  attach(entity, tag);
}

void WaitSet::attach(dds_entity_t condition, dds_attach_t tag) {
  check(dds_waitset_attach(entity_.handle(), condition, tag), "attaching to wait set");
}

void WaitSet::detach(dds_entity_t entity_or_condition) {
  check(dds_waitset_detach(entity_.handle(), entity_or_condition), "detaching from wait set");
}

std::vector<dds_attach_t> WaitSet::wait(std::chrono::milliseconds timeout) {
  std::vector<dds_attach_t> triggered(16);
  const auto n = check(dds_waitset_wait(entity_.handle(), triggered.data(), triggered.size(),
                                        to_dds_duration(timeout)),
                       "waiting on wait set");
  triggered.resize(std::min<std::size_t>(static_cast<std::size_t>(n), triggered.size()));
  return triggered;
}

}  // namespace smart::dds
