#include "smart/wire/link.hpp"

#include <algorithm>

#include "smart/common/seeded.hpp"

namespace smart::wire {

namespace {
// SplitMix64 (Steele, Lea, Flood, OOPSLA 2014), as in agent/uncertainty.cpp: a draw is a hash of
// its coordinates, independent of the order samples are handled in.
uint64_t mix(uint64_t z) {
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

double uniform01(uint64_t seed, uint32_t direction, uint32_t robot, uint64_t index, uint32_t k) {
  const uint64_t h = mix(mix(mix(mix(seed) ^ (uint64_t{direction} << 32 | robot)) ^ index) ^ k);
  return static_cast<double>(h >> 11) * 0x1.0p-53;
}

constexpr int kMaxRetransmits = 16;
}  // namespace

LinkChannel::LinkChannel(LinkDirection d, uint64_t seed, uint32_t direction)
    : d_(d), seed_(seed), direction_(direction) {}

double LinkChannel::arrival_s(uint32_t robot, double sent_s) {
  auto& [index, last] = robots_[robot];
  const uint64_t i = index++;
  double ms = d_.delay_ms + d_.jitter_ms * (2 * uniform01(seed_, direction_, robot, i, 0) - 1);
  for (int k = 1;
       k <= kMaxRetransmits &&
       uniform01(seed_, direction_, robot, i, static_cast<uint32_t>(k)) * 1000 < d_.loss_per_mille;
       ++k) {
    ms += d_.retransmit_ms;
  }
  double at = sent_s + std::max(ms, 0.0) / 1000;
  if (!d_.reorder) at = std::max(at, last);
  last = std::max(last, at);
  return at;
}

nlohmann::json to_json(const LinkModel& l) {
  const auto dir = [](const LinkDirection& d) {
    return nlohmann::json{{"delay_ms", d.delay_ms},
                          {"jitter_ms", d.jitter_ms},
                          {"loss_per_mille", d.loss_per_mille},
                          {"retransmit_ms", d.retransmit_ms},
                          {"reorder", d.reorder}};
  };
  return {{"to_host", dir(l.to_host)}, {"to_monitor", dir(l.to_monitor)}, {"seed", l.seed}};
}

}  // namespace smart::wire
