// SPDX-License-Identifier: Apache-2.0
// Control overruns: ticks a board's timer let fall due without running them (TickInputs::
// missed_ticks) are counted in Health.control_overruns, and the tick that reports them runs as
// any other (device time counts only ticks that ran).
#include <gtest/gtest.h>

#include "controller_bench.hpp"

namespace palp::fw {
namespace {

using test::Bench;

TEST(ControllerOverruns, MissedTicksTheBoardReportsAddUpInHealthControlOverruns) {
  Bench b;
  TickInputs in;
  TickOutputs out;
  b.c_.tick(in, out);
  EXPECT_EQ(b.c_.health().control_overruns, 0u);
  in.missed_ticks = 3;
  b.c_.tick(in, out);
  in.missed_ticks = 0;
  b.c_.tick(in, out);
  in.missed_ticks = 2;
  b.c_.tick(in, out);
  EXPECT_EQ(b.c_.health().control_overruns, 5u);
  EXPECT_EQ(b.c_.ticks(), 4u);  // the missed ones never ran
}

}  // namespace
}  // namespace palp::fw
