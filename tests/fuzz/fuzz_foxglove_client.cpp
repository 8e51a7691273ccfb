// Fuzz target: what a Foxglove WebSocket client sends to `smart bridge` (bridge/
// foxglove_protocol.hpp ClientSubscriptions): the input is the client's messages joined by
// "\n--8<--\n"; one starting with byte 0x01 is a binary frame, the others text. Nothing a client
// sends may throw or crash: every message gets replies (status texts that are valid JSON) or
// subscriptions, within kMaxSubscriptions.
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "fuzz_input.hpp"
#include "smart/bridge/foxglove_protocol.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  smart::bridge::ClientSubscriptions subs({1, 2, 3, 16, 17});
  constexpr std::string_view kCut = "\n--8<--\n";
  std::size_t at = 0;
  for (int n = 0; n < 64 && at <= text.size(); ++n) {
    const auto cut = std::min(text.find(kCut, at), text.size());
    const auto message = text.substr(at, cut - at);
    const auto out =
        !message.empty() && message[0] == '\x01' ? subs.on_binary() : subs.on_text(message);
    for (const auto& reply : out.replies) {
      if (nlohmann::json::parse(reply, nullptr, false).is_discarded()) std::abort();
    }
    if (subs.size() > smart::bridge::kMaxSubscriptions) std::abort();
    if (n == 0) subs.add_channels({20});
    at = cut + kCut.size();
  }
  return 0;
}
