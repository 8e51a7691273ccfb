// Contract: a queue of T with random access whose slots are reused. push_back() returns a slot
// holding whatever the last element there held (the caller overwrites what it needs: a lifelong
// graph's node keeps its edge lists' storage instead of freeing and allocating it per action);
// pop_front()/pop_back() only move the bounds. Storage doubles when full (a power of two, at
// least 8 slots) and never shrinks, so memory settles at the longest queue. Index 0 is the front.
// boost::circular_buffer destroys popped elements and constructs pushed ones, and a std::deque of
// 136-byte nodes allocated a block every three; the live ADG appends a quarter million nodes a
// window at 10 000 robots (docs/performance.md).
#pragma once

#include <algorithm>
#include <cassert>
#include <cstddef>
#include <utility>
#include <vector>

namespace smart::monitor {

template <class T>
class Ring {
 public:
  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  std::size_t capacity() const { return slots_.size(); }

  T& operator[](std::size_t i) {
    assert(i < size_);
    return slots_[(head_ + i) & (slots_.size() - 1)];
  }
  const T& operator[](std::size_t i) const {
    assert(i < size_);
    return slots_[(head_ + i) & (slots_.size() - 1)];
  }
  T& front() { return (*this)[0]; }
  const T& front() const { return (*this)[0]; }
  T& back() { return (*this)[size_ - 1]; }

  // Room for `n` elements without moving any later.
  void reserve(std::size_t n) {
    if (n <= slots_.size()) return;
    std::size_t cap = std::max<std::size_t>(8, slots_.size());
    while (cap < n) cap *= 2;
    std::vector<T> grown(cap);
    for (std::size_t i = 0; i < size_; ++i) grown[i] = std::move((*this)[i]);
    slots_ = std::move(grown);
    head_ = 0;
  }
  T& push_back() {
    reserve(size_ + 1);
    ++size_;
    return back();
  }
  void pop_front() {
    assert(size_ > 0);
    head_ = (head_ + 1) & (slots_.size() - 1);
    --size_;
  }
  void pop_back() {
    assert(size_ > 0);
    --size_;
  }

 private:
  std::vector<T> slots_;
  std::size_t head_ = 0;
  std::size_t size_ = 0;
};

}  // namespace smart::monitor
