// SPDX-License-Identifier: Apache-2.0
// The contact identifications side by side (issues 7 and 24): the paper's stepped sine, the 60 s
// multisine and the 16 s contact_multisine_fast, on palp-sim at 1.0 A against the plant's own
// small-signal linearisation there. Sites: the three 1D objects at position 3, the pad's row 5
// at column 4 (bulk) and column 5 (over shallow channel 5), and pad_2d_damping's inclusion at
// row 5, column 4; the floating tip just touches each. Prints for each method, site and
// amplitude the device time, the wall time, the lines, and the errors of omega_n and zeta in per
// cent (counters).
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <string>

#include "palp/identification.hpp"
#include "palp/plant/linearisation.hpp"
#include "palp/plant/phantom.hpp"
#include "palp/plant/plant.hpp"
#include "sim_process.hpp"

namespace {

struct Site {
  const char* phantom;
  double x_mm, y_mm;
};
constexpr Site kSites[] = {{"insert_1d", 27, 0}, {"solid_1d", 27, 0},  {"hollow_1d", 27, 0},
                           {"pad_2d", 40, 45},   {"pad_2d", 50, 45},   {"pad_2d_damping", 40, 45}};

/// The plant with the mount where the floating tip (25 mm of stroke) just touches the site,
/// linearised at bias_A; mount_z_mm gets the mount's z (as palp-sim is started below).
palp::plant::Linearisation reference(const Site& site, double bias_A, double& mount_z_mm) {
  palp::plant::Plant plant(palp::plant::PlantConfig{},
                           palp::plant::load_shipped_phantom(site.phantom));
  plant.set_mount(site.x_mm * 1e-3, site.y_mm * 1e-3, -0.05);
  const double z_m = plant.site_touch().apex_z_m - 0.025;
  plant.set_mount(site.x_mm * 1e-3, site.y_mm * 1e-3, z_m);
  mount_z_mm = z_m * 1e3;
  return palp::plant::linearise(plant, bias_A);
}

/// range(0): the site (kSites), range(1): the amplitude in mA (0: the preset's own).
void identify(benchmark::State& state, palp::IdentificationPreset preset) {
  const Site& site = kSites[state.range(0)];
  auto s = palp::IdentificationSettings::preset(preset);
  if (state.range(1) > 0) s.amplitude_A = static_cast<double>(state.range(1)) / 1000.0;
  double z_mm = 0;
  const auto ref = reference(site, s.bias_A, z_mm);
  state.SetLabel(std::string(site.phantom) + " (" + std::to_string(std::lround(site.x_mm)) +
                 ", " + std::to_string(std::lround(site.y_mm)) + ") mm");
  palp::sim::test::SimProcess sim({"--phantom", site.phantom, "--mount-mm",
                                   std::to_string(site.x_mm), std::to_string(site.y_mm),
                                   std::to_string(z_mm)},
                                  false);
  if (!sim.ok()) {
    state.SkipWithError(("palp-sim did not start: " + sim.banner()).c_str());
    return;
  }
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
  state.counters["device_time_s"] = run.frf->device_time_s;
  state.counters["wall_s"] = wall_s;
  state.counters["amplitude_mA"] = 1e3 * s.amplitude_A;
  state.counters["lines"] = static_cast<double>(run.frf->lines.size());
  state.counters["omega_n_rad_per_s"] = run.fit->omega_n_rad_per_s;
  state.counters["omega_n_err_pct"] =
      100 * (run.fit->omega_n_rad_per_s / ref.omega_n_rad_per_s - 1);
  state.counters["zeta"] = run.fit->zeta;
  state.counters["zeta_err_pct"] = 100 * (run.fit->zeta / ref.zeta - 1);
  state.counters["zeta_se_pct"] = 100 * run.fit->zeta_se / run.fit->zeta;
  state.counters["ref_omega_n_rad_per_s"] = ref.omega_n_rad_per_s;
  state.counters["ref_zeta"] = ref.zeta;
}

void BM_IdentifySteppedSine(benchmark::State& state) {
  identify(state, palp::IdentificationPreset::contact_stepped);
}
void BM_IdentifyMultisine(benchmark::State& state) {
  identify(state, palp::IdentificationPreset::contact_multisine);
}
void BM_IdentifyMultisineFast(benchmark::State& state) {
  identify(state, palp::IdentificationPreset::contact_multisine_fast);
}

void every_site(benchmark::internal::Benchmark* b, int amplitude_mA) {
  for (int k = 0; k < static_cast<int>(std::size(kSites)); ++k) b->Args({k, amplitude_mA});
}

// the paper's stepped sine on the solid only (~687 s of device time); the 60 s multisine at its
// own 0.1 A (the paper's amplitude) and at the small-signal 0.03 A on every site; the fast one
// at its own 0.03 A on every site
BENCHMARK(BM_IdentifySteppedSine)->Args({1, 0})->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK(BM_IdentifyMultisine)
    ->Apply([](auto* b) { every_site(b, 0); })
    ->Apply([](auto* b) { every_site(b, 30); })
    ->Iterations(1)
    ->Unit(benchmark::kSecond);
BENCHMARK(BM_IdentifyMultisineFast)
    ->Apply([](auto* b) { every_site(b, 0); })
    ->Iterations(1)
    ->Unit(benchmark::kSecond);

}  // namespace

BENCHMARK_MAIN();
