// SPDX-License-Identifier: Apache-2.0
// Contact-point latency independence (docs/reliability.md section 7): the traced contact point
// is the tip apex at rest (the TCP plus the coil's stroke, both read after the arm stopped) moved
// back by the detection force's indentation, so how late the arm stops must not move it. Traced
// with palp-sim linked in (virtual time) with the host's reaction latency (palp-sim
// --reaction-latency-ms) and the robot's contact-input latency (--robot-input-latency-ms) varied
// over 0..50 ms.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "palp/probe.hpp"
#include "palp/robot.hpp"
#include "palp/sim_inproc.hpp"
#include "palp/trace.hpp"
#include "trace_sim.hpp"

namespace palp::trace_latency_test {

namespace rb = proto::rb;

struct Latency {
  double reaction_ms = 0, input_ms = 0;
};

TracedSurface trace_with(Latency l) {
  sim::InprocOptions o;
  o.phantom = "pad_2d";
  o.robot = true;
  o.reaction_latency_ms = l.reaction_ms;
  o.robot_input_latency_ms = l.input_ms;
  sim::InprocSimulator sim(o);
  Probe probe(sim.transport());
  auto robot = connect_robot(sim.robot_uri());
  return trace_surface(probe, *robot, trace_test::sim_rig(sim), trace_test::pad_plan(3));
}

double mean_detection_force_N(const TracedSurface& s) {
  double sum = 0;
  for (const TracePoint& p : s.points) sum += p.detection_force_N;
  return sum / static_cast<double>(s.points.size());
}

// With both latencies at 50 ms the arm pushes the coil further before it stops (a larger detection
// force): the latencies did take effect. Which path stopped each approach is printed. Before the fixes in Toucher this failed twice: a
// robot input later than the gap between re-arming the watch and the next approach stopped that
// approach at once on the previous contact's line (input 50 ms: "no contact", then busy), and a
// search overtravel of 0.5 mm (10 mm/s x 50 ms) ate the fixed 0.5 mm back-off, so the slow
// approach started in contact (17 um off at 50/50 ms).
TEST(TraceLatency, ContactPointsAgreeWithin20umForReactionAndRobotInputLatenciesOf0To50ms) {
  const TracedSurface base = trace_with({0, 0});
  ASSERT_TRUE(base.complete) << base.stopped_because;
  const Latency cases[] = {{50, 0}, {0, 50}, {50, 50}, {20, 20}};
  for (const Latency& l : cases) {
    SCOPED_TRACE("reaction " + std::to_string(std::lround(l.reaction_ms)) + " ms, robot input " +
                 std::to_string(std::lround(l.input_ms)) + " ms");
    const TracedSurface s = trace_with(l);
    ASSERT_TRUE(s.complete) << s.stopped_because;
    ASSERT_EQ(s.points.size(), base.points.size());
    double worst_m = 0;
    int by_input = 0;  // approaches the robot's own input stopped (the others: the host's stop)
    for (std::size_t k = 0; k < s.points.size(); ++k) {
      const TracePoint& p = s.points[k];
      const TracePoint& b = base.points[k];
      ASSERT_TRUE(p.ok) << p.reason;
      worst_m = std::max(worst_m, std::hypot(p.x_m - b.x_m, p.y_m - b.y_m, p.z_m - b.z_m));
      if (p.guard_fired & rb::bit(rb::GuardSource::digital_input)) ++by_input;
    }
    EXPECT_LT(worst_m, 20e-6);
    if (l.reaction_ms == 50 && l.input_ms == 50) {
      EXPECT_GT(mean_detection_force_N(s), mean_detection_force_N(base) + 1e-3);
    }
    std::printf("reaction %.0f ms, robot input %.0f ms: contact points within %.2f um of 0/0 ms; mean detection "
                "force %.2f mN (0/0 ms: %.2f mN); %d of %zu stopped by the robot's input\n",
                l.reaction_ms, l.input_ms, worst_m * 1e6, mean_detection_force_N(s) * 1e3,
                mean_detection_force_N(base) * 1e3, by_input, s.points.size());
  }
}

}  // namespace palp::trace_latency_test
