// SPDX-License-Identifier: Apache-2.0
// The two contact identifications side by side (issue 7): the paper's stepped sine and the
// multisine, on palp-sim's solid object at position 3 and a 1.0 A bias, against the plant's own
// small-signal linearisation there. Prints for each method and amplitude the device time, the
// wall time, the lines, and the errors of omega_n and zeta in per cent (counters).
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <memory>

#include "palp/identification.hpp"
#include "palp/plant/linearisation.hpp"
#include "palp/plant/phantom.hpp"
#include "palp/plant/plant.hpp"
#include "sim_process.hpp"

namespace {

/// The plant at the sim's site: solid_1d, mount (27, 0, -25) mm, as palp-sim is started below.
const palp::plant::Linearisation& reference() {
  static const palp::plant::Linearisation lin = [] {
    palp::plant::Plant plant(palp::plant::PlantConfig{}, palp::plant::load_shipped_phantom("solid_1d"));
    plant.set_mount(0.027, 0.0, -0.025);
    return palp::plant::linearise(plant, 1.0);
  }();
  return lin;
}

void identify(benchmark::State& state, palp::IdentificationPreset preset) {
  const double amplitude_A = static_cast<double>(state.range(0)) / 1000.0;
  palp::sim::test::SimProcess sim({"--phantom", "solid_1d", "--mount-mm", "27", "0", "-25"}, false);
  if (!sim.ok()) {
    state.SkipWithError(("palp-sim did not start: " + sim.banner()).c_str());
    return;
  }
  auto s = palp::IdentificationSettings::preset(preset);
  s.amplitude_A = amplitude_A;
  palp::IdentificationRun run;
  double wall_s = 0;
  for (auto _ : state) {
    palp::Probe probe(sim.uri());
    const auto t0 = std::chrono::steady_clock::now();
    run = palp::identify(probe, s);
    wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  if (!run.fit || !run.frf) {
    state.SkipWithError(("no fit: " + run.analysis_reason).c_str());
    return;
  }
  const auto& ref = reference();
  state.counters["device_time_s"] = run.frf->device_time_s;
  state.counters["wall_s"] = wall_s;
  state.counters["lines"] = static_cast<double>(run.frf->lines.size());
  state.counters["omega_n_rad_per_s"] = run.fit->omega_n_rad_per_s;
  state.counters["omega_n_err_pct"] = 100 * (run.fit->omega_n_rad_per_s / ref.omega_n_rad_per_s - 1);
  state.counters["zeta"] = run.fit->zeta;
  state.counters["zeta_err_pct"] = 100 * (run.fit->zeta / ref.zeta - 1);
  state.counters["ref_omega_n_rad_per_s"] = ref.omega_n_rad_per_s;
  state.counters["ref_zeta"] = ref.zeta;
}

void BM_IdentifySteppedSine(benchmark::State& state) {
  identify(state, palp::IdentificationPreset::contact_stepped);
}
void BM_IdentifyMultisine(benchmark::State& state) {
  identify(state, palp::IdentificationPreset::contact_multisine);
}

// amplitude in mA: the paper's 0.1 A and the small-signal 0.03 A
BENCHMARK(BM_IdentifySteppedSine)->Arg(100)->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK(BM_IdentifyMultisine)->Arg(100)->Arg(30)->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace

BENCHMARK_MAIN();
