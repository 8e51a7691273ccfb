#include "smart/bridge/foxglove_protocol.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

namespace smart::bridge {
namespace {

using json = nlohmann::json;
using ::testing::HasSubstr;

TEST(FoxgloveProtocol, ServerInfoAndAdvertiseAreTheSpecsJson) {
  const auto info = json::parse(server_info_json("b", "7"));
  EXPECT_EQ(info["op"], "serverInfo");
  EXPECT_EQ(info["capabilities"], json::array({"time"}));
  EXPECT_EQ(info["sessionId"], "7");
  const auto adv = json::parse(advertise_json({{3, "/tf", "tf2_msgs/msg/TFMessage", "x y\n"}}));
  EXPECT_EQ(adv["op"], "advertise");
  EXPECT_EQ(adv["channels"][0], (json{{"id", 3},
                                      {"topic", "/tf"},
                                      {"encoding", "cdr"},
                                      {"schemaName", "tf2_msgs/msg/TFMessage"},
                                      {"schema", "x y\n"},
                                      {"schemaEncoding", "ros2msg"}}));
}

TEST(FoxgloveProtocol, BinaryFramesAreOpcodeThenLittleEndianFields) {
  EXPECT_EQ(message_frame(0x01020304, 0x1122334455667788ULL, "ab"),
            std::string("\x01\x04\x03\x02\x01\x88\x77\x66\x55\x44\x33\x22\x11"
                        "ab",
                        15));
  EXPECT_EQ(time_frame(1), std::string("\x02\x01\x00\x00\x00\x00\x00\x00\x00", 9));
}

TEST(ClientSubscriptions, SubscribesAndUnsubscribesByTheClientsIds) {
  ClientSubscriptions c({1, 2, 3});
  auto out = c.on_text(R"({"op":"subscribe","subscriptions":[{"id":7,"channelId":2},
                                                             {"id":8,"channelId":3}]})");
  EXPECT_TRUE(out.replies.empty());
  EXPECT_EQ(out.subscribed, (std::vector<std::pair<uint32_t, uint32_t>>{{7, 2}, {8, 3}}));
  ASSERT_NE(c.subscription_of(2), nullptr);
  EXPECT_EQ(*c.subscription_of(2), 7u);
  EXPECT_EQ(c.subscription_of(1), nullptr);
  out = c.on_text(R"({"op":"unsubscribe","subscriptionIds":[7]})");
  EXPECT_TRUE(out.replies.empty());
  EXPECT_EQ(c.subscription_of(2), nullptr);
  EXPECT_EQ(c.size(), 1u);
  // A channel advertised later (a robot's plan) can be subscribed to from then on.
  const char* later = R"({"op":"subscribe","subscriptions":[{"id":9,"channelId":20}]})";
  EXPECT_FALSE(c.on_text(later).replies.empty());
  c.add_channels({20});
  EXPECT_EQ(c.on_text(later).subscribed, (std::vector<std::pair<uint32_t, uint32_t>>{{9, 20}}));
}

TEST(ClientSubscriptions, UntrustedInputGetsAStatusAndChangesNothing) {
  ClientSubscriptions c({1});
  auto reply = [&](std::string_view text) {
    const auto out = c.on_text(text);
    EXPECT_TRUE(out.subscribed.empty()) << text;
    return out.replies.empty() ? json() : json::parse(out.replies.at(0));
  };
  EXPECT_THAT(reply("{not json").dump(), HasSubstr("not a foxglove.websocket.v1 message"));
  EXPECT_THAT(reply("[1,2]").dump(), HasSubstr("not a foxglove.websocket.v1 message"));
  EXPECT_THAT(reply(R"({"op":"advertise","channels":[]})").dump(), HasSubstr("unsupported op"));
  EXPECT_THAT(reply(R"({"op":"subscribe","subscriptions":[{"id":-1,"channelId":1}]})").dump(),
              HasSubstr("unsigned integers"));
  EXPECT_THAT(reply(R"({"op":"subscribe","subscriptions":[{"id":1,"channelId":9}]})").dump(),
              HasSubstr("no channel 9"));
  EXPECT_THAT(reply(R"({"op":"unsubscribe","subscriptionIds":["x"]})").dump(),
              HasSubstr("no such subscription"));
  EXPECT_EQ(c.size(), 0u);
  (void)c.on_text(R"({"op":"subscribe","subscriptions":[{"id":1,"channelId":1}]})");
  EXPECT_THAT(reply(R"({"op":"subscribe","subscriptions":[{"id":1,"channelId":1}]})").dump(),
              HasSubstr("already subscribed"));
  EXPECT_EQ(c.size(), 1u);
  EXPECT_THAT(c.on_binary().replies.at(0), HasSubstr("read-only"));
}

// Found by reading the code for the fuzz target: an op of multi-byte characters cut to 64 bytes in
// the middle of one made the status reply's dump() throw, which would have ended the bridge.
TEST(ClientSubscriptions, AnOpCutInAUtf8SequenceGetsAValidStatusNotAnException) {
  ClientSubscriptions c({1});
  std::string op = "x";
  for (int i = 0; i < 35; ++i) op += "\xc3\xa9";  // é
  const auto out = c.on_text(R"({"op":")" + op + R"("})");
  ASSERT_EQ(out.replies.size(), 1u);
  EXPECT_FALSE(json::parse(out.replies[0], nullptr, false).is_discarded());
  EXPECT_THAT(out.replies[0], HasSubstr("unsupported op"));
}

}  // namespace
}  // namespace smart::bridge
