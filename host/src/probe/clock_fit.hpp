// SPDX-License-Identifier: Apache-2.0
// Device time to host time from Ping round trips. Each round trip gives one point: the device's
// time when it handled the Ping against the host's mid-point of send and receive, uncertain by
// half the round trip. The fit is a least-squares line over the recent points whose round trip
// is near the best one (queueing only ever adds delay), so host = offset + (1 + drift) * device.
// A point that falls off the line by more than its own uncertainty plus a margin, three times in
// a row, means the rate changed (a simulator's pace, a device reset): the window restarts from
// those points.
#pragma once

#include <cstddef>
#include <deque>

#include "palp/stream.hpp"

namespace palp::detail {

class ClockFit {
 public:
  static constexpr std::size_t kWindow = 32;

  /// A round trip: host send time, device time, host receive time (seconds).
  void add(double host_send_s, double device_s, double host_recv_s);
  void reset() { points_.clear(); mapping_ = {}; misfits_ = 0; }
  const ClockMapping& mapping() const { return mapping_; }
  std::size_t restarts() const { return restarts_; }

 private:
  struct Point {
    double device_s, host_s, rtt_s;
  };
  void refit();

  std::deque<Point> points_;
  ClockMapping mapping_{};
  int misfits_ = 0;
  std::size_t restarts_ = 0;
};

}  // namespace palp::detail
