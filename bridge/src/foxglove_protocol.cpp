#include "smart/bridge/foxglove_protocol.hpp"

#include <algorithm>
#include <nlohmann/json.hpp>

namespace smart::bridge {

using json = nlohmann::json;

namespace {
// Text from a client may hold anything (a name cut in the middle of a UTF-8 sequence): never
// let it make dump() throw.
std::string text_of(const json& j) {
  return j.dump(-1, ' ', false, json::error_handler_t::replace);
}

template <class T>
void le(std::string& out, T v) {
  for (std::size_t i = 0; i < sizeof(T); ++i) {
    out.push_back(static_cast<char>(static_cast<uint64_t>(v) >> (8 * i) & 0xff));
  }
}
}  // namespace

std::string server_info_json(std::string_view name, std::string_view session_id) {
  return text_of(json{{"op", "serverInfo"},
                      {"name", name},
                      {"capabilities", {"time"}},
                      {"supportedEncodings", json::array()},
                      {"metadata", json::object()},
                      {"sessionId", session_id}});
}

std::string advertise_json(const std::vector<Channel>& channels) {
  json list = json::array();
  for (const auto& c : channels) {
    list.push_back({{"id", c.id},
                    {"topic", c.topic},
                    {"encoding", c.encoding},
                    {"schemaName", c.schema_name},
                    {"schema", c.schema},
                    {"schemaEncoding", c.schema_encoding}});
  }
  return text_of(json{{"op", "advertise"}, {"channels", list}});
}

std::string status_json(StatusLevel level, std::string_view message) {
  return text_of(json{{"op", "status"}, {"level", static_cast<int>(level)}, {"message", message}});
}

std::string message_frame(uint32_t subscription_id, uint64_t receive_time_ns,
                          std::string_view payload) {
  std::string f;
  f.reserve(13 + payload.size());
  f.push_back(1);
  le(f, subscription_id);
  le(f, receive_time_ns);
  f.append(payload);
  return f;
}

std::string time_frame(uint64_t time_ns) {
  std::string f(1, '\x02');
  le(f, time_ns);
  return f;
}

ClientSubscriptions::ClientSubscriptions(std::vector<uint32_t> channel_ids)
    : channels_(std::move(channel_ids)) {
  std::sort(channels_.begin(), channels_.end());
}

void ClientSubscriptions::add_channels(const std::vector<uint32_t>& channel_ids) {
  channels_.insert(channels_.end(), channel_ids.begin(), channel_ids.end());
  std::sort(channels_.begin(), channels_.end());
}

const uint32_t* ClientSubscriptions::subscription_of(uint32_t channel) const {
  const auto it = by_channel_.find(channel);
  return it == by_channel_.end() ? nullptr : &it->second;
}

ClientSubscriptions::Outcome ClientSubscriptions::on_binary() {
  return {{status_json(StatusLevel::kError,
                       "this bridge is read-only: client publishing is not supported")},
          {}};
}

ClientSubscriptions::Outcome ClientSubscriptions::on_text(std::string_view text) {
  Outcome out;
  const json j = json::parse(text, nullptr, false);
  if (j.is_discarded() || !j.is_object() || !j.contains("op") || !j["op"].is_string()) {
    out.replies.push_back(status_json(
        StatusLevel::kError, "not a foxglove.websocket.v1 message: a JSON object with \"op\""));
    return out;
  }
  const std::string op = j["op"];
  if (op == "subscribe" && j.contains("subscriptions") && j["subscriptions"].is_array()) {
    subscribe(j["subscriptions"], out);
  } else if (op == "unsubscribe" && j.contains("subscriptionIds") &&
             j["subscriptionIds"].is_array()) {
    unsubscribe(j["subscriptionIds"], out);
  } else {
    out.replies.push_back(
        status_json(StatusLevel::kError, "unsupported op '" + op.substr(0, 64) +
                                             "' (or its fields are missing): this bridge "
                                             "takes subscribe {subscriptions: [{id, channelId}]} "
                                             "and unsubscribe {subscriptionIds}"));
  }
  return out;
}

void ClientSubscriptions::subscribe(const json& list, Outcome& out) {
  for (const auto& s : list) {
    if (!s.is_object() || !s.contains("id") || !s["id"].is_number_unsigned() ||
        !s.contains("channelId") || !s["channelId"].is_number_unsigned()) {
      out.replies.push_back(status_json(
          StatusLevel::kError, "a subscription needs id and channelId, unsigned integers"));
      continue;
    }
    const auto id = s["id"].get<uint64_t>(), channel = s["channelId"].get<uint64_t>();
    if (id > UINT32_MAX || !std::binary_search(channels_.begin(), channels_.end(), channel)) {
      out.replies.push_back(status_json(
          StatusLevel::kWarning, "no channel " + std::to_string(channel) + " to subscribe to"));
    } else if (by_id_.count(static_cast<uint32_t>(id)) ||
               by_channel_.count(static_cast<uint32_t>(channel))) {
      out.replies.push_back(status_json(
          StatusLevel::kError, "subscription " + std::to_string(id) + " to channel " +
                                   std::to_string(channel) + ": id or channel already subscribed"));
    } else if (by_id_.size() >= kMaxSubscriptions) {
      out.replies.push_back(status_json(StatusLevel::kError, "too many subscriptions"));
    } else {
      by_id_[static_cast<uint32_t>(id)] = static_cast<uint32_t>(channel);
      by_channel_[static_cast<uint32_t>(channel)] = static_cast<uint32_t>(id);
      out.subscribed.emplace_back(static_cast<uint32_t>(id), static_cast<uint32_t>(channel));
    }
  }
}

void ClientSubscriptions::unsubscribe(const json& list, Outcome& out) {
  for (const auto& v : list) {
    const auto it = v.is_number_unsigned() && v.get<uint64_t>() <= UINT32_MAX
                        ? by_id_.find(static_cast<uint32_t>(v.get<uint64_t>()))
                        : by_id_.end();
    if (it == by_id_.end()) {
      out.replies.push_back(status_json(
          StatusLevel::kWarning, "unsubscribe: no such subscription " + text_of(v).substr(0, 64)));
      continue;
    }
    by_channel_.erase(it->second);
    by_id_.erase(it);
  }
}

}  // namespace smart::bridge
