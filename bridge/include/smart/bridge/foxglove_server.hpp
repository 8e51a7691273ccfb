// Contract: the socket edge of the Foxglove bridge: a WebSocket server (Boost.Beast, Debian's
// libboost-dev) speaking foxglove.websocket.v1 (foxglove_protocol.hpp) to Foxglove, Lichtblick or
// any ws-protocol client. It listens on `bind` (loopback by default: a bridge is opened to the
// network only on purpose) and port (0: any free one, see port()); each client gets serverInfo and
// the channels at once, then the messages of the channels it subscribed to, and at once the last
// message of a latched channel (the map, the markers). One I/O thread serves every client;
// publish() and time() may be called from any thread. A slow client's queue holds at most
// max_queue frames: the oldest are dropped (a viewer wants the newest poses), so the bridge never
// grows with a stalled client. Client input is untrusted: frames over 64 KiB close the
// connection, anything else is answered by status messages (foxglove_protocol.hpp); at most
// max_clients at once.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "smart/bridge/foxglove_protocol.hpp"

namespace smart::bridge {

struct ServerOptions {
  std::string bind = "127.0.0.1";
  uint16_t port = 0;
  std::string name = "smart-dds bridge";
  std::size_t max_queue = 512;
  std::size_t max_clients = 32;
  std::vector<uint32_t> latched;  // channels whose last message a new subscriber gets
};

class FoxgloveServer {
 public:
  // Throws std::runtime_error naming the address when it cannot listen there.
  FoxgloveServer(ServerOptions options, std::vector<Channel> channels);
  ~FoxgloveServer();
  FoxgloveServer(const FoxgloveServer&) = delete;
  FoxgloveServer& operator=(const FoxgloveServer&) = delete;
  uint16_t port() const;
  // More channels, advertised to every client now and to later ones at connection; `latched`:
  // their last message reaches new subscribers.
  void add_channels(std::vector<Channel> channels, bool latched);
  void publish(uint32_t channel, uint64_t stamp_ns, std::string payload);
  void time(uint64_t time_ns);

 private:
  struct Impl;
  std::shared_ptr<Impl> impl_;
};

}  // namespace smart::bridge
