// SPDX-License-Identifier: Apache-2.0
// A fixed-capacity ring for one thread (no atomics): the stream backlog, the transmit buffer.
// For the ISR-to-thread hand-off use spsc_queue.hpp instead.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>

namespace palp::fw {

template <class T, std::size_t N>
class Ring {
  static_assert(N > 0 && (N & (N - 1)) == 0, "capacity must be a power of two");

 public:
  static constexpr std::size_t capacity = N;
  bool push(const T& v) {
    if (size_ == N) return false;
    items_[(head_ + size_) & (N - 1)] = v;
    ++size_;
    return true;
  }
  bool pop(T& out) {
    if (size_ == 0) return false;
    out = items_[head_];
    head_ = (head_ + 1) & (N - 1);
    --size_;
    return true;
  }
  /// Pushes n items, all or none (false: fewer than n free).
  bool push_n(const T* v, std::size_t n) {
    if (n > N - size_) return false;
    const std::size_t tail = (head_ + size_) & (N - 1);
    const std::size_t first = n < N - tail ? n : N - tail;  // up to the end of the storage
    copy(items_.data() + tail, v, first);
    copy(items_.data(), v + first, n - first);
    size_ += n;
    return true;
  }
  /// Pops up to max items into out, oldest first; returns how many.
  std::size_t pop_n(T* out, std::size_t max) {
    const std::size_t n = max < size_ ? max : size_;
    const std::size_t first = n < N - head_ ? n : N - head_;
    copy(out, items_.data() + head_, first);
    copy(out + first, items_.data(), n - first);
    head_ = (head_ + n) & (N - 1);
    size_ -= n;
    return n;
  }
  /// The newest item (size() > 0).
  T& back() { return items_[(head_ + size_ - 1) & (N - 1)]; }
  /// The k-th oldest item (k < size()).
  const T& at(std::size_t k) const { return items_[(head_ + k) & (N - 1)]; }
  void drop_front(std::size_t n) {
    if (n > size_) n = size_;
    head_ = (head_ + n) & (N - 1);
    size_ -= n;
  }
  void clear() { head_ = size_ = 0; }
  std::size_t size() const { return size_; }
  std::size_t free() const { return N - size_; }
  bool empty() const { return size_ == 0; }

 private:
  // The caller's buffer never overlaps the ring's storage: memcpy, not the memmove std::copy_n
  // becomes (newlib's memmove copies a byte a step when the two are not equally aligned, as a
  // frame's bytes in the transmit ring mostly are: firmware/core/README.md "Cost on the target").
  static void copy(T* to, const T* from, std::size_t n) {
    if constexpr (std::is_trivially_copyable_v<T>) {
      if (n != 0) std::memcpy(to, from, n * sizeof(T));
    } else {
      std::copy_n(from, n, to);
    }
  }

  std::array<T, N> items_{};
  std::size_t head_ = 0;
  std::size_t size_ = 0;
};

}  // namespace palp::fw
