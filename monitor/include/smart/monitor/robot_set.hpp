// Contract: a set of robot ids below a size fixed at construction, taken smallest first
// (take_first), as the switchable tracker tries robots in id order to stay deterministic. Every
// operation costs a few words however large the fleet: a word of bits per 64 robots and, above
// them, a summary bit per word that holds a robot. any(), take_first() and the union with another
// set read the summary first, so a set of a few robots among thousands is not scanned whole.
// (A flat bitset scanned all 16 words of 1000 robots up to four times a try: 11 % of the
// lookahead's instructions in the replay bench, less in a run; docs/execution.md, "A chain's
// cycle checks bounded by the order".) Ids at or past the size are the caller's error (not
// checked: a hot path).
// Pure.
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace smart::monitor {

class RobotSet {
 public:
  static constexpr uint32_t kNone = UINT32_MAX;

  explicit RobotSet(std::size_t robots = 0)
      : words_((robots + 63) / 64, 0), summary_((words_.size() + 63) / 64, 0) {}

  bool test(uint32_t robot) const { return (words_[robot / 64] >> (robot % 64)) & 1U; }
  void set(uint32_t robot) {
    words_[robot / 64] |= bit(robot);
    summary_[robot / 4096] |= bit(robot / 64);
  }
  void reset(uint32_t robot) {
    uint64_t& w = words_[robot / 64];
    w &= ~bit(robot);
    if (w == 0) summary_[robot / 4096] &= ~bit(robot / 64);
  }
  bool any() const {
    for (const uint64_t s : summary_) {
      if (s != 0) return true;
    }
    return false;
  }
  bool none() const { return !any(); }
  // The smallest robot in the set, or kNone.
  uint32_t first() const {
    for (std::size_t k = 0; k < summary_.size(); ++k) {
      if (summary_[k] == 0) continue;
      const std::size_t word = k * 64 + static_cast<std::size_t>(std::countr_zero(summary_[k]));
      return static_cast<uint32_t>(word * 64 +
                                   static_cast<std::size_t>(std::countr_zero(words_[word])));
    }
    return kNone;
  }
  // The smallest robot, taken out of the set (kNone when it is empty).
  uint32_t take_first() {
    const uint32_t robot = first();
    if (robot != kNone) reset(robot);
    return robot;
  }
  // Empties the set, touching only the words that hold robots.
  void clear() {
    each_word([this](std::size_t word) { words_[word] = 0; });
    for (uint64_t& s : summary_) s = 0;
  }
  // Adds the robots of `other` (of the same size), reading only its words that hold robots.
  RobotSet& operator|=(const RobotSet& other) {
    other.each_word([&](std::size_t word) {
      words_[word] |= other.words_[word];
      summary_[word / 64] |= bit(word);
    });
    return *this;
  }

 private:
  static uint64_t bit(std::size_t n) { return uint64_t{1} << (n % 64); }
  template <class F>
  void each_word(F&& f) const {
    for (std::size_t k = 0; k < summary_.size(); ++k) {
      for (uint64_t s = summary_[k]; s != 0; s &= s - 1) {
        f(k * 64 + static_cast<std::size_t>(std::countr_zero(s)));
      }
    }
  }

  std::vector<uint64_t> words_;    // bit r % 64 of word r / 64: robot r
  std::vector<uint64_t> summary_;  // bit w % 64 of word w / 64: words_[w] is not zero
};

}  // namespace smart::monitor
