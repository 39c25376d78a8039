// SPDX-License-Identifier: Apache-2.0
#include "report_plots_synth.hpp"

#include <cmath>
#include <complex>
#include <random>
#include <system_error>
#include <vector>
#include <unistd.h>

#include "palp/analysis/dynamics.hpp"
#include "palp/analysis/second_order.hpp"
#include "palp/identification_result.hpp"
#include "palp/indent.hpp"
#include "report/vega_build.hpp"
#include "test_analysis_synth.hpp"
#include "test_result_synth.hpp"

namespace palp_test::report {

namespace fs = std::filesystem;
namespace an = palp::analysis;

double interpolate(const nlohmann::json& rows, const std::string& x_field,
                   const std::string& y_field, double x) {
  for (std::size_t k = 1; k < rows.size(); ++k) {
    const double x0 = rows[k - 1][x_field], x1 = rows[k][x_field];
    if (x0 <= x && x <= x1) {
      const double y0 = rows[k - 1][y_field], y1 = rows[k][y_field];
      return x1 == x0 ? y0 : y0 + (y1 - y0) * (x - x0) / (x1 - x0);
    }
  }
  throw std::out_of_range(x_field + " = " + std::to_string(x) + " outside the data");
}

fs::path fresh_dir(const std::string& name) {
  // removed when the test program ends
  static struct Created {
    std::vector<fs::path> dirs;
    ~Created() {
      std::error_code ec;
      for (const auto& d : dirs) fs::remove_all(d, ec);
    }
  } created;
  const fs::path d = fs::temp_directory_path() / ("palp-report-plots-" + std::to_string(::getpid()) + "-" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  created.dirs.push_back(d);
  return d;
}

nlohmann::json known_outlined_heat_map() {
  namespace vega = palp::report::vega;
  std::vector<vega::HeatCell> cells;
  for (int r = 1; r <= 9; ++r)
    for (int c = 1; c <= 9; ++c) {
      const double k = (c == 2 || c == 5 || c == 8 ? 0.3 : 0.6) + 0.01 * r;
      cells.push_back({r, c, k, {{"href", "#r" + std::to_string(r) + "c" + std::to_string(c)}}});
    }
  vega::HeatMapStyle style;
  style.value_title = "k_fd (N/mm)";
  style.format = ".2f";
  nlohmann::json s = vega::heat_map(9, 9, cells, style);
  vega::outline_columns(s, {2, 5, 8}, vega::colour(1), "soft", "soft_columns");
  vega::outline_rows(s, {9}, vega::colour(0), "stiff", "stiff_rows");
  return s;
}

fs::path write_known_indentation(const fs::path& dir) {
  return palp::write_result(dir, palp_test::synthetic_run(), palp::Overwrite::yes);
}

double known_omega_n() { return std::sqrt(kK_N_per_m / kM_kg); }
double known_b() { return 2.0 * kZeta * std::sqrt(kK_N_per_m * kM_kg); }

namespace {

fs::path write_identification(const fs::path& dir, double noise_fraction) {
  constexpr double kPi = 3.14159265358979323846;
  an::Frf frf;
  frf.method = "stepped_sine";
  frf.line_spacing_Hz = 0.5;
  const auto G = [](double f) {
    const double w = 2 * kPi * f;
    return 1.0 / std::complex<double>(kK_N_per_m - kM_kg * w * w, known_b() * w);
  };
  // σ: the noise added, or 2 % of the resonance's |G| for the noise-free lines
  const double sigma = (noise_fraction > 0 ? noise_fraction : 0.02) * std::abs(G(8.0));
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, noise_fraction * std::abs(G(8.0)));
  for (double f = 0.5; f <= 40.0 + 1e-9; f += 0.5)
    frf.lines.push_back({f, G(f) + std::complex<double>(noise(rng), noise(rng)), sigma, {}, {}, 0});
  const an::SecondOrderFit fit = an::fit_second_order(frf.lines);

  palp::IdentificationRun run;
  run.frf = frf;
  run.fit = fit;
  for (int k = 0; k < 4; ++k) {  // the writer needs samples; the figures read frf.csv
    palp::RecordingRow row;
    row.sample_index = static_cast<std::uint64_t>(k);
    row.t_s = 1e-3 * k;
    row.i_A = 1.0;
    row.z_mm = 12.0;
    run.recording.append(row);
  }
  palp::Sidecar side;
  side.program = {{"kind", "sweep"}};
  run.recording.sidecar = side;
  const an::InstrumentDynamics inst;  // the paper's m_v, b_v, k_v
  nlohmann::json a = palp::sweep_summary_json(frf, fit);
  a["params"] = {{"mv_kg", inst.m_v_kg}, {"bv_N_s_per_m", inst.b_v_N_s_per_m}, {"kv_N_per_mm", 0.0439}};
  a["viscoelastic"] = palp::viscoelastic_json(an::viscoelastic_from(frf.lines, inst, 1.0e-3, 2.5e-3));
  return palp::write_identification_result(dir, run, a, palp::Overwrite::yes);
}

}  // namespace

fs::path write_known_identification(const fs::path& dir) { return write_identification(dir, 0.0); }

fs::path write_paper_like_identification(const fs::path& dir) { return write_identification(dir, 0.005); }

fs::path write_paper_like_indentation(const fs::path& dir) {
  an::test::SynthSpec spec;
  spec.object_force = [](double d) {
    return d > 0 ? 4.0 / 3.0 * palp_test::kEstar * std::sqrt(palp_test::kR) * std::pow(d, 1.5) : 0.0;
  };
  spec.contact_z_m = 25e-3;
  spec.i_top_A = 1.5;
  spec.i_step_A = 0.01;
  spec.reps = 3;
  spec.samples_per_level = 25;
  spec.noise_A = 3e-3;
  spec.quantum_m = 1e-6;
  spec.natural_Hz = 10.0;
  spec.command_column = true;
  const an::Curve c = an::test::synth_curve(spec);
  palp::IndentationRun run;
  run.settings = palp::IndentationSettings::preset(palp::IndentationPreset::two_d);
  run.settings.stop_A = 1.5;
  run.settings.step_A = 0.01;
  run.device.serial = "SYNTH-0002";
  run.program.repetitions_done = 3;
  std::mt19937 rng(11);
  std::normal_distribution<double> noise(0.0, 1.5);
  double previous_i = 0;
  bool unloading = false;
  for (Eigen::Index k = 0; k < c.z_m.size(); ++k) {
    palp::RecordingRow row;
    row.sample_index = static_cast<std::uint64_t>(k);
    row.t_s = 1e-3 * static_cast<double>(k);
    row.i_cmd_A = c.i_cmd_A[k];
    row.i_A = c.i_A[k];
    row.z_mm = c.z_m[k] * 1e3;
    row.rep = c.rep[k] - 1;
    if (k > 0 && c.rep[k] != c.rep[k - 1]) unloading = false;
    if (c.i_cmd_A[k] < previous_i) unloading = true;
    previous_i = c.i_cmd_A[k];
    const double Fo = spec.object_force(c.z_m[k] - spec.contact_z_m);
    // channels 1..6: 60, 25, 10, 15, 35, 90 Pa/N, reading 8 % higher on the way back
    const double slopes[6] = {60, 25, 10, 15, 35, 90};
    for (std::size_t m = 0; m < 6; ++m)
      row.p_Pa[m] = slopes[m] * Fo * (unloading ? 1.08 : 1.0) + noise(rng);
    run.recording.append(row);
  }
  palp::Sidecar side;
  side.program = {{"kind", "ramp"}};
  run.recording.sidecar = side;
  palp::analyze_run(run);
  return palp::write_result(dir, run, palp::Overwrite::yes);
}

palp::TracedSurface known_trace() {
  palp::TracedSurface s;
  s.plan_name = "known-plane";
  s.rows = 4;
  s.columns = 5;
  s.complete = true;
  s.normals_from_grid = true;
  const double tilt = kTraceTiltDeg * 3.14159265358979323846 / 180.0;
  for (int r = 1; r <= s.rows; ++r)
    for (int c = 1; c <= s.columns; ++c) {
      palp::TracePoint p;
      p.row = r;
      p.column = c;
      p.ok = !(r == 2 && c == 3);
      if (!p.ok) p.reason = "no contact within 15.000 mm of travel";
      p.x_m = 0.010 * (c - 1);
      p.y_m = 0.010 * (r - 1);
      p.z_m = 0.010 + 0.0005 * (c - 1);
      p.normal[0] = -std::sin(tilt);
      p.normal[1] = 0.0;
      p.normal[2] = std::cos(tilt);
      p.tilt_rad = tilt;
      s.points.push_back(p);
    }
  s.resume_index = s.points.size();
  return s;
}

}  // namespace palp_test::report
