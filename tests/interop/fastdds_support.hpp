// Shared by the Fast DDS stand-ins for ROS 2 nodes (fastdds_*.cpp): a participant that
// discovers SMART-DDS's Cyclone participants as they are configured by default: loopback only,
// unicast, UDPv4 on 127.0.0.1 (no shared memory, which Cyclone cannot use), with the initial
// peers at the RTPS well-known metatraffic unicast ports of participant indices 0..9
// (PB 7400, DG 250, PG 2, d1 10: RTPS 2.x, the rule Cyclone follows too).
#pragma once

#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>
#include <fastrtps/utils/IPLocator.h>

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <memory>

namespace smart::interop {

inline eprosima::fastdds::dds::DomainParticipant* make_loopback_participant(int domain,
                                                                            const char* name) {
  eprosima::fastdds::dds::DomainParticipantQos pqos;
  pqos.name(name);
  auto udp = std::make_shared<eprosima::fastdds::rtps::UDPv4TransportDescriptor>();
  udp->interfaceWhiteList.push_back("127.0.0.1");
  pqos.transport().user_transports.push_back(udp);
  pqos.transport().use_builtin_transports = false;
  for (uint32_t index = 0; index < 10; ++index) {
    eprosima::fastrtps::rtps::Locator_t peer;
    eprosima::fastrtps::rtps::IPLocator::setIPv4(peer, 127, 0, 0, 1);
    peer.port = 7400 + 250 * static_cast<uint32_t>(domain) + 10 + 2 * index;
    pqos.wire_protocol().builtin.initialPeersList.push_back(peer);
  }
  return eprosima::fastdds::dds::DomainParticipantFactory::get_instance()->create_participant(
      domain, pqos);
}

}  // namespace smart::interop
