// Contract: the Foxglove WebSocket protocol, server side (foxglove.websocket.v1,
// github.com/foxglove/ws-protocol docs/spec.md), as far as a read-only bridge needs it: the
// serverInfo, advertise and status texts (JSON), the binary Message Data and Time frames
// (opcode 1: u32 subscription id, u64 receive time ns, payload; opcode 2: u64 time ns; little
// endian), and one client's subscriptions, driven by what the client sends. Pure: text in, text
// out, no socket.
// Whatever a client sends is untrusted: a text that is not JSON, an unknown op, a subscription to
// a channel that does not exist or an id already in use, binary frames (this server takes no
// client publishing) each get a status reply naming the problem and change nothing; at most
// kMaxSubscriptions subscriptions per client.
#pragma once

#include <cstdint>
#include <map>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <string_view>
#include <vector>

namespace smart::bridge {

inline constexpr std::string_view kSubprotocol = "foxglove.websocket.v1";
inline constexpr std::size_t kMaxSubscriptions = 4096;

struct Channel {
  uint32_t id = 0;
  std::string topic;
  std::string schema_name;  // "geometry_msgs/msg/PoseArray"
  std::string schema;       // the ros2msg text (record/schemas.hpp)
  std::string schema_encoding = "ros2msg";
  std::string encoding = "cdr";
};

enum class StatusLevel { kInfo = 0, kWarning = 1, kError = 2 };

// capabilities: "time" (the server's clock is the run's sim time).
std::string server_info_json(std::string_view name, std::string_view session_id);
std::string advertise_json(const std::vector<Channel>& channels);
std::string status_json(StatusLevel level, std::string_view message);
std::string message_frame(uint32_t subscription_id, uint64_t receive_time_ns,
                          std::string_view payload);
std::string time_frame(uint64_t time_ns);

class ClientSubscriptions {
 public:
  explicit ClientSubscriptions(std::vector<uint32_t> channel_ids);
  struct Outcome {
    std::vector<std::string> replies;                       // status texts for the client
    std::vector<std::pair<uint32_t, uint32_t>> subscribed;  // (subscription, channel), new ones
  };
  // A text message from the client.
  Outcome on_text(std::string_view text);
  // A binary message from the client (never accepted here).
  Outcome on_binary();
  // Channels advertised later (a fleet's per-robot topics, once its size is known).
  void add_channels(const std::vector<uint32_t>& channel_ids);
  // The client's subscription to a channel, if any.
  const uint32_t* subscription_of(uint32_t channel) const;
  std::size_t size() const { return by_id_.size(); }

 private:
  void subscribe(const nlohmann::json& subscriptions, Outcome& out);
  void unsubscribe(const nlohmann::json& ids, Outcome& out);
  std::vector<uint32_t> channels_;
  std::map<uint32_t, uint32_t> by_id_;       // subscription -> channel
  std::map<uint32_t, uint32_t> by_channel_;  // channel -> subscription
};

}  // namespace smart::bridge
