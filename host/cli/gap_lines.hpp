// SPDX-License-Identifier: Apache-2.0
// palpctl -v's rate limit on stream-gap lines (common.cpp): a lossy link can lose hundreds of
// frames a second, each its own gap and log line. At most `per_window` lines are let through in
// each window (one second in palpctl), opened by the first line after the previous one ended;
// the rest are counted, and the count is handed out with the next line let through, or by
// take_suppressed() at exit. Not thread-safe: the caller locks.
#pragma once

#include <chrono>
#include <cstdint>
#include <optional>

namespace palpctl {

class GapLineLimiter {
 public:
  using Clock = std::chrono::steady_clock;
  GapLineLimiter(int per_window, Clock::duration window)
      : per_window_(per_window), window_(window) {}

  /// A line at `now`: nullopt when it is suppressed (counted), else how many were suppressed
  /// since the last one let through (0: none), which the caller reports before the line.
  std::optional<std::uint64_t> admit(Clock::time_point now) {
    if (!started_ || now - window_start_ >= window_) {
      started_ = true;
      window_start_ = now;
      in_window_ = 0;
    }
    if (in_window_ >= per_window_) {
      ++suppressed_;
      return std::nullopt;
    }
    ++in_window_;
    return take_suppressed();
  }
  /// The lines suppressed since the last one let through, and the count reset.
  std::uint64_t take_suppressed() {
    const std::uint64_t n = suppressed_;
    suppressed_ = 0;
    return n;
  }

 private:
  int per_window_;
  Clock::duration window_;
  bool started_ = false;
  Clock::time_point window_start_{};
  int in_window_ = 0;
  std::uint64_t suppressed_ = 0;
};

}  // namespace palpctl
