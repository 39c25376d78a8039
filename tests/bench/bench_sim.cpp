// SPDX-License-Identifier: Apache-2.0
// palp-sim's speed on one core: the firmware core and the physical model together, per control
// tick, in the scenario issue 16 sets its target on: a 400-line multisine (0.25..100 Hz, 0.5 mA
// a line about a 1.0 A bias, as the contact identification runs it) with the probe in contact,
// and the full stream on (all channels at the stream's maximum rate, 10 kHz); the host side only
// drains the bytes. Phantoms: solid_1d at position 3 (the identification's site, no pressure
// channels) and pad_2d at row 8, column 8 (all six pressure channels loaded).
// Prints ns per tick and x_realtime (simulated seconds per wall second) at 20 and 40 kHz; the
// target is x_realtime >= 200 at 20 kHz and >= 100 at 40 kHz.
#include <benchmark/benchmark.h>

#include <memory>
#include <string>

#include "multisine_scenario.hpp"

namespace {

using namespace palp;

struct Site {
  const char* phantom;
  double x_m, y_m;
};
constexpr Site kSites[] = {{"solid_1d", 0.027, 0.0}, {"pad_2d", 0.080, 0.075}};

void BM_SimulationTick(benchmark::State& state) {
  const auto rate_Hz = static_cast<std::uint32_t>(state.range(0));
  const Site& site = kSites[state.range(1)];
  const auto sim = sim::test::make_scenario_simulation(site.phantom, site.x_m, site.y_m, 1);
  sim::Simulation& s = *sim;
  auto& plant = static_cast<sim::ModelPlant&>(s.plant()).model();
  sim::test::start_multisine_scenario(s, rate_Hz);
  std::uint64_t wall = 0;
  // 1 ms of virtual time per step, with a heartbeat so the watchdog stays fed
  auto run_ms = [&] {
    const std::uint32_t ran = s.run(rate_Hz / 1000, wall);
    wall += 1000;
    sim::test::send_frame(s, proto::Heartbeat{}, 6, wall);
    benchmark::DoNotOptimize(s.take_device_bytes());
    return ran;
  };
  for (int k = 0; k < 500; ++k) run_ms();  // settle into contact
  std::uint64_t ticks = 0;
  for (auto _ : state) ticks += run_ms();
  state.counters["ns_per_tick"] = benchmark::Counter(
      static_cast<double>(ticks), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["x_realtime"] =
      benchmark::Counter(static_cast<double>(ticks) / rate_Hz, benchmark::Counter::kIsRate);
  static std::string why;
  if (s.controller().faulted()) {
    why = "the controller faulted: reason " +
          std::to_string(static_cast<int>(s.controller().fault()));
    state.SkipWithError(why.c_str());
  } else if (!(plant.contact_force_N() > 0.0)) {
    why = std::string("the probe is not in contact on ") + site.phantom;
    state.SkipWithError(why.c_str());
  }
}

BENCHMARK(BM_SimulationTick)
    ->ArgNames({"rate_Hz", "pad_2d"})
    ->Args({20000, 0})
    ->Args({20000, 1})
    ->Args({40000, 0})
    ->Args({40000, 1})
    ->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
