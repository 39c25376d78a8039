// SPDX-License-Identifier: Apache-2.0
// A fixed-capacity single-producer single-consumer ring of bytes: the device core's two stream
// buffers between the USB interrupt and the main loop (device.hpp). Received bytes: the USB
// interrupt produces, the app's link_read() consumes; bytes to send: link_write() produces, the
// USB interrupt consumes.
//
// As palp::fw::SpscQueue (firmware/core), two free-running 32-bit indices, each written by one
// side only (acquire/release), so it needs no critical section on a Cortex-M4; unlike it, bytes
// move in runs (memcpy-sized pieces, not one atomic step per byte), and the consumer can copy
// bytes out without taking them (peek) and take them later (drop): the IN pipe drops a packet's
// bytes only once the host has taken the packet. No heap: the N bytes live in the object; N is a
// power of two, all N usable.
#pragma once

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <cstring>

namespace palp::usb {

template <std::size_t N>
class ByteRing {
  static_assert(N >= 2 && (N & (N - 1)) == 0, "ByteRing capacity must be a power of two");
  static_assert(N <= (std::size_t{1} << 31), "ByteRing capacity must fit the 32-bit indices");

 public:
  static constexpr std::size_t capacity() { return N; }

  /// Bytes waiting. Exact on the consumer side; at most this many on the producer side.
  std::size_t size() const {
    return head_.load(std::memory_order_acquire) - tail_.load(std::memory_order_acquire);
  }
  /// Room for bytes. Exact on the producer side; at least this much on the consumer side.
  std::size_t room() const { return N - size(); }

  /// Producer: appends up to n bytes; returns how many it took (fewer when the ring fills).
  std::size_t push(const std::uint8_t* bytes, std::size_t n) {
    const std::uint32_t head = head_.load(std::memory_order_relaxed);
    const std::uint32_t tail = tail_.load(std::memory_order_acquire);
    const std::size_t free = N - static_cast<std::size_t>(head - tail);
    if (n > free) n = free;
    if (n == 0) return 0;
    copy_in(head, bytes, n);
    head_.store(head + static_cast<std::uint32_t>(n), std::memory_order_release);
    return n;
  }

  /// Consumer: copies up to n bytes, starting `offset` bytes after the oldest, into out without
  /// taking them; returns how many it copied.
  std::size_t peek(std::size_t offset, std::uint8_t* out, std::size_t n) const {
    const std::uint32_t tail = tail_.load(std::memory_order_relaxed);
    const std::uint32_t head = head_.load(std::memory_order_acquire);
    const std::size_t waiting = static_cast<std::size_t>(head - tail);
    if (offset >= waiting) return 0;
    if (n > waiting - offset) n = waiting - offset;
    if (n == 0) return 0;
    copy_out(tail + static_cast<std::uint32_t>(offset), out, n);
    return n;
  }

  /// Consumer: the byte `offset` after the oldest (offset < size()).
  std::uint8_t at(std::size_t offset) const {
    return bytes_[(tail_.load(std::memory_order_relaxed) + offset) & kMask];
  }

  /// Consumer: takes (forgets) the n oldest bytes; n <= size().
  void drop(std::size_t n) {
    tail_.store(tail_.load(std::memory_order_relaxed) + static_cast<std::uint32_t>(n),
                std::memory_order_release);
  }

  /// Consumer: moves up to n of the oldest bytes into out; returns how many.
  std::size_t pop(std::uint8_t* out, std::size_t n) {
    n = peek(0, out, n);
    drop(n);
    return n;
  }

 private:
  static constexpr std::uint32_t kMask = static_cast<std::uint32_t>(N - 1);

  void copy_in(std::uint32_t at, const std::uint8_t* bytes, std::size_t n) {
    const std::size_t start = at & kMask;
    const std::size_t first = n < N - start ? n : N - start;  // up to the end of the storage
    std::memcpy(bytes_.data() + start, bytes, first);
    std::memcpy(bytes_.data(), bytes + first, n - first);
  }
  void copy_out(std::uint32_t at, std::uint8_t* out, std::size_t n) const {
    const std::size_t start = at & kMask;
    const std::size_t first = n < N - start ? n : N - start;
    std::memcpy(out, bytes_.data() + start, first);
    std::memcpy(out + first, bytes_.data(), n - first);
  }

  std::array<std::uint8_t, N> bytes_{};
  std::atomic<std::uint32_t> head_{0};  // next byte to write; written by the producer only
  std::atomic<std::uint32_t> tail_{0};  // oldest byte; written by the consumer only
};

}  // namespace palp::usb
