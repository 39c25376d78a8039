// SPDX-License-Identifier: Apache-2.0
// Fixed-capacity single-producer single-consumer queue: the ISR-to-thread hand-off of the
// firmware core (DESIGN.md "Firmware principles").
//
// One producer (the control ISR) calls push(); one consumer (the main loop) calls pop(), peek()
// and drop_front(). Either side may call size() and empty(). Lock-free: two free-running
// std::atomic<uint32_t> indices, each written by one side only (acquire/release ordering), so it
// needs no critical section on a Cortex-M4 (32-bit atomic loads and stores are single
// instructions there) and works between two threads on the host.
//
// No heap: the N slots live inside the object. N is a power of two, so the free-running indices
// wrap at 2^32 without a glitch and a slot is `index & (N - 1)`. All N slots are usable.
// A full queue refuses the item (push returns false); the producer counts it, e.g. with
// OverflowCounter below, so every lost item has a named place where it was lost.
#pragma once

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>

namespace palp::fw {

template <class T, std::size_t N>
class SpscQueue {
  static_assert(N >= 2 && (N & (N - 1)) == 0, "SpscQueue capacity must be a power of two");
  static_assert(N <= (std::size_t{1} << 31), "SpscQueue capacity must fit the 32-bit indices");
  static_assert(std::atomic<std::uint32_t>::is_always_lock_free);

 public:
  static constexpr std::size_t capacity() { return N; }

  /// Producer: appends a copy of `item`. Returns false (and stores nothing) when full.
  bool push(const T& item) {
    const std::uint32_t head = head_.load(std::memory_order_relaxed);
    const std::uint32_t tail = tail_.load(std::memory_order_acquire);
    if (head - tail >= N) return false;
    slots_[head & kMask] = item;
    head_.store(head + 1u, std::memory_order_release);
    return true;
  }

  /// Consumer: moves the oldest item into `out`. Returns false (out untouched) when empty.
  bool pop(T& out) {
    const std::uint32_t tail = tail_.load(std::memory_order_relaxed);
    const std::uint32_t head = head_.load(std::memory_order_acquire);
    if (head == tail) return false;
    out = slots_[tail & kMask];
    tail_.store(tail + 1u, std::memory_order_release);
    return true;
  }

  /// Consumer: the oldest item without removing it, or nullptr when empty. The pointer stays
  /// valid until the consumer's next pop() or drop_front().
  const T* peek() const {
    const std::uint32_t tail = tail_.load(std::memory_order_relaxed);
    const std::uint32_t head = head_.load(std::memory_order_acquire);
    if (head == tail) return nullptr;
    return &slots_[tail & kMask];
  }

  /// Consumer: removes the oldest item (after peek()). Returns false when empty.
  bool drop_front() {
    const std::uint32_t tail = tail_.load(std::memory_order_relaxed);
    const std::uint32_t head = head_.load(std::memory_order_acquire);
    if (head == tail) return false;
    tail_.store(tail + 1u, std::memory_order_release);
    return true;
  }

  /// Items waiting. Exact on the consumer side; a momentary value anywhere else.
  std::size_t size() const {
    const std::uint32_t tail = tail_.load(std::memory_order_acquire);
    const std::uint32_t head = head_.load(std::memory_order_acquire);
    return static_cast<std::size_t>(head - tail);
  }
  bool empty() const { return size() == 0; }
  bool full() const { return size() >= N; }

 private:
  static constexpr std::uint32_t kMask = static_cast<std::uint32_t>(N - 1);
  std::array<T, N> slots_{};
  std::atomic<std::uint32_t> head_{0};  // next slot to write; written by the producer only
  std::atomic<std::uint32_t> tail_{0};  // next slot to read; written by the consumer only
};

/// Counts the items a producer could not push (a health counter, DESIGN.md "Protocol
/// principles"). The producer calls push() or record(); anyone may read total(); the consumer
/// calls take_new() to learn how many were lost since it last asked (for a gap event).
/// The count wraps at 2^32; take_new() stays exact across the wrap.
class OverflowCounter {
 public:
  /// Producer: pushes `item`; on a full queue counts one overflow. Returns what push returned.
  template <class Queue, class T>
  bool push(Queue& queue, const T& item) {
    if (queue.push(item)) return true;
    record();
    return false;
  }
  /// Producer: counts one lost item.
  void record() {
    total_.store(total_.load(std::memory_order_relaxed) + 1u, std::memory_order_release);
  }
  /// Items lost since construction (wraps at 2^32).
  std::uint32_t total() const { return total_.load(std::memory_order_acquire); }
  /// Consumer: items lost since the previous call.
  std::uint32_t take_new() {
    const std::uint32_t now = total();
    const std::uint32_t fresh = now - reported_;
    reported_ = now;
    return fresh;
  }

 private:
  std::atomic<std::uint32_t> total_{0};  // written by the producer only
  std::uint32_t reported_ = 0;           // consumer only
};

}  // namespace palp::fw
