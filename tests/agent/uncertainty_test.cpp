// The seeded draws of execution uncertainty: deterministic, at the asked rates, within bounds.
#include "smart/agent/uncertainty.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace smart::agent {
namespace {

TEST(Uncertainty, DrawsAreAFunctionOfTheirCoordinatesOnly) {
  EXPECT_EQ(uniform01(5, 3, 1, 9), uniform01(5, 3, 1, 9));
  EXPECT_NE(uniform01(5, 3, 1, 9), uniform01(6, 3, 1, 9));
  EXPECT_NE(uniform01(5, 3, 1, 9), uniform01(5, 4, 1, 9));
  EXPECT_NE(uniform01(5, 3, 1, 9), uniform01(5, 3, 1, 10));
}

TEST(Uncertainty, StallsHappenAtTheirProbabilityAndNormalsHaveUnitVariance) {
  const Uncertainty u{0.05, 2.0, 0, 0, 11};
  int stalls = 0;
  double sum = 0, sq = 0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    stalls += stalls_before(u, static_cast<uint32_t>(i % 100), static_cast<uint32_t>(i / 100));
    const double z = standard_normal(11, 1, 9, static_cast<uint64_t>(i));
    sum += z, sq += z * z;
  }
  EXPECT_NEAR(double(stalls) / n, 0.05, 0.003);
  EXPECT_NEAR(sum / n, 0.0, 0.01);
  EXPECT_NEAR(sq / n, 1.0, 0.02);
  EXPECT_FALSE(stalls_before({0.5, 0.0, 0, 0, 1}, 0, 0)) << "no stall without a duration";
}

TEST(Uncertainty, FactorsStayWithinTheirBoundsAndAreOneWithoutNoise) {
  const Uncertainty none;
  EXPECT_FALSE(none.any());
  EXPECT_EQ(speed_factor(none, 4), 1.0);
  EXPECT_EQ(slip_factor(none, 4, 100, 0), 1.0);
  const Uncertainty wild{0, 0, 1.0, 0.5, 2};
  EXPECT_TRUE(wild.any());
  for (uint32_t r = 0; r < 1000; ++r) {
    const double f = speed_factor(wild, r);
    EXPECT_GE(f, 0.3);
    EXPECT_LE(f, 1.0);
    const double s = slip_factor(wild, r, r * 7, 1);
    EXPECT_GE(s, 0.5);
    EXPECT_LE(s, 1.5);
  }
  EXPECT_EQ(to_json({0.1, 2, 0, 0, 9})["seed"], 9);
}

// LoRR 2026 delays: events at their per-tick probability (Bernoulli) or rate (Poisson), each
// lasting within [min, max]; Gaussian durations centre on min + mean_ratio x (max - min).
TEST(Uncertainty, DelayEventsHappenAtTheirRateAndLastWithinTheirRange) {
  Uncertainty u;
  u.seed = 4;
  u.delay_probability = 0.02;
  u.delay_min_s = 0.5;
  u.delay_max_s = 1.2;
  EXPECT_TRUE(u.delays());
  EXPECT_TRUE(u.any());
  const int n = 200000;
  int events = 0;
  double sum = 0;
  for (int i = 0; i < n; ++i) {
    const double d = delay_at(u, static_cast<uint32_t>(i % 50), static_cast<uint64_t>(i / 50));
    if (d == 0) continue;
    ++events;
    sum += d;
    EXPECT_GE(d, 0.5);
    EXPECT_LE(d, 1.2);
  }
  EXPECT_NEAR(double(events) / n, 0.02, 0.002);
  EXPECT_NEAR(sum / events, 0.85, 0.02);  // uniform: the middle of the range
  u.delay_std_ratio = 0.1;
  u.delay_mean_ratio = 0.2;
  sum = 0;
  events = 0;
  for (int i = 0; i < n; ++i) {
    const double d = delay_at(u, 3, static_cast<uint64_t>(i));
    if (d > 0) sum += d, ++events;
  }
  EXPECT_NEAR(sum / events, 0.5 + 0.2 * 0.7, 0.02);
  Uncertainty poisson;
  poisson.delay_rate_hz = 0.1;  // 1 - exp(-0.01) per tick
  poisson.delay_max_s = 1;
  events = 0;
  for (int i = 0; i < n; ++i) events += delay_at(poisson, 1, static_cast<uint64_t>(i)) > 0;
  EXPECT_NEAR(double(events) / n, 1 - std::exp(-0.01), 0.001);
  EXPECT_EQ(delay_at(Uncertainty{}, 1, 5), 0.0);
  EXPECT_EQ(to_json(u)["delay_max_s"], 1.2);
  EXPECT_FALSE(to_json(Uncertainty{}).contains("delay_max_s"));
}

}  // namespace
}  // namespace smart::agent
