// SPDX-License-Identifier: Apache-2.0
#include "probe/clock_fit.hpp"

#include <algorithm>
#include <cmath>

namespace palp::detail {

void ClockFit::add(double host_send_s, double device_s, double host_recv_s) {
  const Point p{device_s, 0.5 * (host_send_s + host_recv_s), std::max(0.0, host_recv_s - host_send_s)};
  if (mapping_.points >= 2) {
    const double residual = std::fabs(mapping_.to_host_s(p.device_s) - p.host_s);
    const double allowed = 0.5 * p.rtt_s + mapping_.rtt_s + 0.002;
    misfits_ = residual > allowed ? misfits_ + 1 : 0;
    if (misfits_ >= 3) {  // the rate changed: keep only the points that showed it
      std::deque<Point> recent(points_.end() - std::min<std::size_t>(2, points_.size()), points_.end());
      points_.swap(recent);
      misfits_ = 0;
      ++restarts_;
    }
  }
  points_.push_back(p);
  if (points_.size() > kWindow) points_.pop_front();
  refit();
}

void ClockFit::refit() {
  double best = points_.front().rtt_s;
  for (const Point& p : points_) best = std::min(best, p.rtt_s);
  const double keep = 2.0 * best + 0.0005;
  double n = 0, sd = 0, sh = 0;
  for (const Point& p : points_)
    if (p.rtt_s <= keep) { n += 1; sd += p.device_s; sh += p.host_s; }
  const double md = sd / n, mh = sh / n;
  double sdd = 0, sdh = 0;
  for (const Point& p : points_)
    if (p.rtt_s <= keep) {
      sdd += (p.device_s - md) * (p.device_s - md);
      sdh += (p.device_s - md) * (p.host_s - mh);
    }
  // a slope needs device time spread well beyond the timing noise; until then offset only
  const double slope = (n >= 2 && sdd > 0 && std::sqrt(sdd / n) > 50.0 * (best + 1e-6))
                           ? sdh / sdd : 1.0;
  mapping_.drift = slope - 1.0;
  mapping_.offset_s = mh - slope * md;
  mapping_.rtt_s = best;
  mapping_.points = static_cast<std::size_t>(n);
}

}  // namespace palp::detail
