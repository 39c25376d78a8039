// SPDX-License-Identifier: Apache-2.0
// The bytes of one USB packet or HID report kept for the next read() when the caller's buffer is
// smaller than a transfer (a transfer cannot be split on the bus): the usb and hid transports'
// shared read-side buffer.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>

namespace palp::detail {

template <std::size_t N>
class Staging {
 public:
  /// Where a transfer into the staging buffer goes (N bytes).
  std::uint8_t* data() { return buf_; }
  bool pending() const { return off_ < len_; }
  /// Keeps the first n bytes of data() (a transfer just made into it) and hands out what fits.
  std::size_t keep(std::size_t n, std::span<std::uint8_t> out) {
    off_ = 0;
    len_ = std::min(n, N);
    return take(out);
  }
  /// Hands out what is kept, as much as fits.
  std::size_t take(std::span<std::uint8_t> out) {
    const std::size_t n = std::min(out.size(), len_ - off_);
    std::memcpy(out.data(), buf_ + off_, n);
    off_ += n;
    return n;
  }

 private:
  std::uint8_t buf_[N] = {};
  std::size_t off_ = 0, len_ = 0;
};

}  // namespace palp::detail
