// The link model's arrivals: delay, jitter bounds, losses repaired by retransmissions, order.
#include "smart/wire/link.hpp"

#include <gtest/gtest.h>

namespace smart::wire {
namespace {

TEST(Link, ASampleArrivesItsDelayLater) {
  LinkChannel c({250, 0, 0, 100, false}, 1, 0);
  EXPECT_DOUBLE_EQ(c.arrival_s(3, 10.0), 10.25);
  EXPECT_DOUBLE_EQ(c.arrival_s(3, 11.0), 11.25);
  EXPECT_FALSE(LinkChannel({}, 1, 0).active());
}

TEST(Link, JitterStaysWithinItsBoundsAndIsTheSameForTheSameSeed) {
  LinkChannel a({500, 200, 0, 100, true}, 7, 1), b({500, 200, 0, 100, true}, 7, 1),
      other({500, 200, 0, 100, true}, 8, 1);
  bool differs = false;
  for (int i = 0; i < 1000; ++i) {
    const double t = a.arrival_s(2, i);
    EXPECT_GE(t - i, 0.3 - 1e-12);
    EXPECT_LE(t - i, 0.7 + 1e-12);
    EXPECT_DOUBLE_EQ(t, b.arrival_s(2, i));
    differs = differs || t != other.arrival_s(2, i);
  }
  EXPECT_TRUE(differs);
}

TEST(Link, LossesCostRetransmissionsAtTheirRateAndOrderIsKeptUnlessReorderIsAllowed) {
  LinkChannel lossy({0, 0, 200, 100, true}, 3, 0);
  double extra = 0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) extra += lossy.arrival_s(0, 0.0);
  // Each retransmission follows another loss with p = 0.2: 0.2 / (1 - 0.2) = 0.25 per sample.
  EXPECT_NEAR(extra / n, 0.25 * 0.1, 0.002);
  LinkChannel fifo({500, 400, 0, 100, false}, 5, 0);
  double last = 0;
  for (int i = 0; i < 200; ++i) {
    const double t = fifo.arrival_s(1, 0.01 * i);  // sent faster than the jitter
    EXPECT_GE(t, last);
    last = t;
  }
}

TEST(Link, ToJsonNamesBothDirectionsAndTheSeed) {
  LinkModel l;
  l.to_host.delay_ms = 5;
  l.seed = 4;
  const auto j = to_json(l);
  EXPECT_EQ(j["to_host"]["delay_ms"], 5.0);
  EXPECT_EQ(j["to_monitor"]["delay_ms"], 0.0);
  EXPECT_EQ(j["seed"], 4);
  EXPECT_TRUE(l.active());
}

}  // namespace
}  // namespace smart::wire
