#include "smart/hw/vicon.hpp"

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <thread>

namespace smart::hw {
namespace {

ViconObject object(const std::string& name, double x_mm, double y_mm, double yaw) {
  return {name, {x_mm, y_mm, 10}, {0, 0, yaw}};
}

TEST(ViconParser, RoundTripsObjectsAndSkipsOtherItems) {
  auto d = make_vicon_datagram(77, {object("jetbot1", 1500, -250, 0.5), object("b", 1, 2, 3)});
  EXPECT_EQ(d.size(), 256u);  // padded like Tracker's datagrams
  std::string err;
  const auto f = parse_vicon_datagram(d.data(), d.size(), &err);
  ASSERT_TRUE(f) << err;
  EXPECT_EQ(f->frame, 77u);
  ASSERT_EQ(f->objects.size(), 2u);
  EXPECT_EQ(f->objects[0].name, "jetbot1");
  EXPECT_DOUBLE_EQ(f->objects[0].position_mm[1], -250);
  EXPECT_DOUBLE_EQ(f->objects[0].rotation_rad[2], 0.5);
  // An item with id 1 (not an object) is skipped.
  std::vector<uint8_t> other = {1, 0, 0, 0, 1, 5, 2, 0, 0xAA, 0xBB};
  const auto g = parse_vicon_datagram(other.data(), other.size(), &err);
  ASSERT_TRUE(g) << err;
  EXPECT_EQ(g->skipped_items, 1u);
  EXPECT_TRUE(g->objects.empty());
}

TEST(ViconParser, MalformedDatagramsAreErrorsNotCrashes) {
  std::string err;
  const uint8_t tiny[3] = {1, 2, 3};
  EXPECT_FALSE(parse_vicon_datagram(tiny, 3, &err));
  EXPECT_NE(err.find("shorter"), std::string::npos);
  auto d = make_vicon_datagram(1, {object("a", 0, 0, 0)});
  // Truncated in the middle of the object.
  EXPECT_FALSE(parse_vicon_datagram(d.data(), 40, &err));
  // Wrong item size.
  auto wrong = d;
  wrong[6] = 70;
  EXPECT_FALSE(parse_vicon_datagram(wrong.data(), wrong.size(), &err));
  EXPECT_NE(err.find("expected 72"), std::string::npos);
  // NaN (an occluded object in some setups).
  auto nan = make_vicon_datagram(1, {object("a", std::nan(""), 0, 0)});
  EXPECT_FALSE(parse_vicon_datagram(nan.data(), nan.size(), &err));
  EXPECT_NE(err.find("non-finite"), std::string::npos);
  // More items claimed than present.
  auto many = d;
  many[4] = 9;
  EXPECT_FALSE(parse_vicon_datagram(many.data(), 5 + 75, &err));
  // Random bytes never crash.
  std::vector<uint8_t> junk(300);
  for (int seed = 0; seed < 2000; ++seed) {
    for (auto& b : junk) b = static_cast<uint8_t>((b * 31 + seed * 7 + 13) & 0xff);
    (void)parse_vicon_datagram(junk.data(), static_cast<std::size_t>(seed % 300), &err);
  }
}

double now_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

void send_udp(uint16_t port, const std::vector<uint8_t>& d) {
  const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(port);
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ::sendto(fd, d.data(), d.size(), 0, reinterpret_cast<sockaddr*>(&a), sizeof a);
  ::close(fd);
}

// Regression (issue 25 follow-up): an agent with --vicon-port 0 got an ephemeral port that
// another test's DDS domain used for discovery, and counted RTPS packets as malformed frames.
TEST(ViconReceiver, MalformedFramesFromDdsDiscoveryOnAnEphemeralPort) {
  EXPECT_TRUE(rtps_may_use_port(7400));  // domain 0 discovery multicast
  EXPECT_TRUE(rtps_may_use_port(7411));  // domain 0, participant 0 user unicast
  EXPECT_TRUE(rtps_may_use_port(7400 + 250 * 154 + 10 + 2 * 119 + 1));
  EXPECT_FALSE(rtps_may_use_port(7402));
  EXPECT_FALSE(rtps_may_use_port(7400 + 250 * 154 + 9));
  EXPECT_FALSE(rtps_may_use_port(7399));
  // Two receivers at once get two ports, neither a DDS one.
  ViconReceiver a("127.0.0.1", 0, vicon_millimetres(), {"jetbot1"}, now_s);
  ViconReceiver b("127.0.0.1", 0, vicon_millimetres(), {"jetbot1"}, now_s);
  EXPECT_NE(a.port(), b.port());
  EXPECT_FALSE(rtps_may_use_port(a.port())) << a.port();
  EXPECT_FALSE(rtps_may_use_port(b.port())) << b.port();
}

TEST(ViconReceiver, LoopbackUdpPosesAreTransformedCountedAndGoStale) {
  geometry::FrameTransform t = vicon_millimetres();
  t.yaw_rad = M_PI / 2;
  t.translation_m = {1.0, 0.0};
  ViconReceiver rx("127.0.0.1", 0, t, {"jetbot1"}, now_s);
  ASSERT_GT(rx.port(), 0);
  ViconPoseSource src(rx, "jetbot1", 0.2, now_s);
  EXPECT_FALSE(src.read().valid);
  send_udp(rx.port(),
           make_vicon_datagram(1, {object("jetbot1", 2000, 0, 0.1), object("stranger", 0, 0, 0)}));
  send_udp(rx.port(), {1, 2, 3});  // short
  auto nan = make_vicon_datagram(2, {object("jetbot1", std::nan(""), 0, 0)});
  send_udp(rx.port(), nan);
  const auto deadline = now_s() + 5;
  while (rx.stats().datagrams < 3 && now_s() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  const auto p = src.read();
  ASSERT_TRUE(p.valid);
  // (2 m, 0) rotated by 90° is (0, 2), plus the x offset.
  EXPECT_NEAR(p.pose.x_m, 1.0, 1e-9);
  EXPECT_NEAR(p.pose.y_m, 2.0, 1e-9);
  EXPECT_NEAR(p.pose.yaw_rad, 0.1 + M_PI / 2, 1e-9);
  const auto s = rx.stats();
  EXPECT_EQ(s.datagrams, 3u);
  EXPECT_EQ(s.malformed, 2u);
  EXPECT_EQ(s.unknown_names, 1u);
  EXPECT_EQ(s.poses, 1u);
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  EXPECT_FALSE(src.read().valid) << "a pose older than max_age must not be trusted";
}

}  // namespace
}  // namespace smart::hw
