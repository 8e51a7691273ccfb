// Contract: idlc's C sequences (`_maximum`, `_length`, `_buffer`, `_release`) over memory the
// caller owns. borrow(seq, v) points `seq` at v's elements for one write: Cyclone serializes
// from the buffer and, with `_release` false, never frees it (Cyclone DDS C API,
// dds_sequence_t in dds/ddsrt/... "dds_public_impl.h"); v must outlive the write and not grow
// meanwhile. copy_of(seq) copies a received sequence into a vector (a loaned sample's buffer is
// gone once the sample is returned). Header only, no DDS call.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace smart::dds {

template <class Seq, class T>
void borrow(Seq& seq, std::vector<T>& v) {
  seq._length = seq._maximum = static_cast<uint32_t>(v.size());
  seq._buffer = v.empty() ? nullptr : v.data();
  seq._release = false;  // the vector owns the memory, not Cyclone
}

// A fixed array of the caller's (e.g. a marker's two points).
template <class Seq, class T, std::size_t N>
void borrow(Seq& seq, std::array<T, N>& a) {
  seq._length = seq._maximum = static_cast<uint32_t>(N);
  seq._buffer = a.data();
  seq._release = false;
}

template <class T, class Seq>
std::vector<T> copy_of(const Seq& seq) {
  return seq._length == 0 ? std::vector<T>{}
                          : std::vector<T>(seq._buffer, seq._buffer + seq._length);
}

}  // namespace smart::dds
