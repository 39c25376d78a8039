#include "report_plots_synth.hpp"

#include <cmath>
#include <complex>
#include <unistd.h>

#include "palp/analysis/dynamics.hpp"
#include "palp/analysis/second_order.hpp"
#include "palp/identification_result.hpp"
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
  const fs::path d = fs::temp_directory_path() / ("palp-report-plots-" + std::to_string(::getpid()) + "-" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

fs::path write_known_indentation(const fs::path& dir) {
  return palp::write_result(dir, palp_test::synthetic_run(), palp::Overwrite::yes);
}

double known_omega_n() { return std::sqrt(kK_N_per_m / kM_kg); }
double known_b() { return 2.0 * kZeta * std::sqrt(kK_N_per_m * kM_kg); }

fs::path write_known_identification(const fs::path& dir) {
  constexpr double kPi = 3.14159265358979323846;
  an::Frf frf;
  frf.method = "stepped_sine";
  frf.line_spacing_Hz = 0.5;
  const auto G = [](double f) {
    const double w = 2 * kPi * f;
    return 1.0 / std::complex<double>(kK_N_per_m - kM_kg * w * w, known_b() * w);
  };
  const double sigma = 0.02 * std::abs(G(8.0));
  for (double f = 0.5; f <= 40.0 + 1e-9; f += 0.5) frf.lines.push_back({f, G(f), sigma, {}, {}, 0});
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
