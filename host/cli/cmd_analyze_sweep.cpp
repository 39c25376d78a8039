// SPDX-License-Identifier: Apache-2.0
// palpctl analyze sweep | freeair: frequency responses analysed without a device.
//   analyze sweep --input FILE    a recording (its sidecar gives the program) or a table
//                                 (f_Hz,re_m_per_N,im_m_per_N or f_Hz,mag_m_per_N,phase_deg), or
//                                 an .h5 export of either recording or identification result
//   analyze freeair --omega-n-rad-per-s W --zeta Z --kv-N-per-mm K    m_v and b_v (paper §IV-B)
#include <filesystem>
#include <iostream>
#include <memory>

#include "palp/analysis/frf_table.hpp"
#include "palp/error.hpp"
#include "palp/identification_result.hpp"
#include "palp/recording.hpp"
#include "export_hdf5.hpp"
#ifdef PALP_HAVE_HDF5
#include "palp/hdf5.hpp"
#endif
#include "sweep_options.hpp"

namespace palpctl {

namespace {

namespace an = palp::analysis;

struct AnalyzeSweepCli {
  SweepCli sweep = SweepCli::of(palp::IdentificationSettings::preset(palp::IdentificationPreset::contact_multisine));
  bool free_air = false;
  CLI::App* cmd = nullptr;
  bool given(const char* option) const { return cmd->get_option(option)->count() > 0; }
};

bool is_hdf5_input(const std::string& input) {
#ifdef PALP_HAVE_HDF5
  return palp::is_hdf5_file(input);
#else
  return std::filesystem::path(input).extension() == ".h5";
#endif
}

/// The recording --input names: a CSV recording, or an HDF5 file palpctl exported from a
/// recording or from an identification's result directory (its recording, with the sidecar
/// that holds the identification's settings).
palp::Recording recording_of(const std::string& input) {
#ifdef PALP_HAVE_HDF5
  if (palp::is_hdf5_file(input)) {
    const std::string content = palp::hdf5_content(input);
    if (content == palp::kHdf5ContentRecording) return palp::read_recording_hdf5(input);
    if (content == palp::kHdf5ContentIdentification || content == palp::kHdf5ContentResult) {
      palp::LoadedResult r = content == palp::kHdf5ContentIdentification
                                 ? palp::read_identification_hdf5(input).result
                                 : palp::read_result_hdf5(input);
      if (r.experiment != "identification" || r.recordings.empty())
        throw palp::ConfigError(input + ": a " + r.experiment +
                                " result, not an identification: analyze it with `palpctl analyze " +
                                (r.experiment == "indentation" ? "indentation" : "map") + "`");
      return std::move(r.recordings.front().second);
    }
    throw palp::ConfigError(input + ": an HDF5 file of a " + content +
                            ", not a recording or an identification");
  }
#else
  if (std::filesystem::path(input).extension() == ".h5" && !hdf5_available())
    throw palp::ConfigError(input + ": this palpctl was built without HDF5 and reads no .h5 (install "
                                    "libhdf5-dev, scripts/install-deps, and build again)");
#endif
  return palp::read_recording(input);
}

int analyze_sweep(const Context& ctx, const AnalyzeSweepCli& a) {
  SweepCli o = a.sweep;
  an::Frf frf;
  std::optional<an::SecondOrderFit> fit;  // a recording's, fitted with the settings it was run with
  std::optional<double> bias;
  bool free_air = a.free_air;
  if (!is_hdf5_input(o.input) && an::is_frf_table(o.input)) {
    frf = an::read_frf_table(o.input);
    if (a.given("--bias-current-A")) bias = o.bias_A;
  } else {
    palp::Recording rec = recording_of(o.input);
    palp::IdentificationRun run;
    const bool from_sidecar = rec.sidecar && rec.sidecar->extra.contains("identification");
    if (from_sidecar) {
      run = palp::identification_run_of(rec);
    } else {
      run.settings = settings_of(o);
      run.settings.in_contact = !a.free_air;
      run.settings.validate();
      run.control_rate_Hz = static_cast<std::uint32_t>(o.control_rate_Hz);
      run.recording = std::move(rec);
    }
    // the analysis constants given on the command line win over the sidecar's
    if (a.given("--kf-N-per-A")) run.settings.frf.force_constant_N_per_A = o.kf_N_per_A;
    o.kf_N_per_A = run.settings.frf.force_constant_N_per_A;
    if (!a.given("--kv-N-per-mm")) o.kv_N_per_mm = run.settings.instrument.k_v_N_per_m * 1e-3;
    free_air = free_air || !run.settings.in_contact;
    bias = run.settings.bias_A;
    palp::analyze_identification(run);
    if (!run.frf || !run.fit) throw palp::ConfigError("analyze sweep: " + run.analysis_reason);
    frf = *run.frf;
    fit = *run.fit;
  }
  if (!fit) fit = an::fit_second_order(frf.lines);
  const json j = analysis_json(o, frf, *fit, bias, free_air);
  if (ctx.json) print_json(j);
  else print_analysis(j);
  return kOk;
}

struct FreeAirCli {
  double omega_n = 0, zeta = 0, kv_N_per_mm = 0.0439, omega_n_se = 0, zeta_se = 0;
};

int analyze_freeair(const Context& ctx, const FreeAirCli& o) {
  const auto r = an::free_air_from(o.omega_n, o.zeta, o.kv_N_per_mm * 1e3, o.omega_n_se, o.zeta_se);
  json j = {{"params",
             {{"omega_n_rad_per_s", o.omega_n}, {"zeta", o.zeta}, {"kv_N_per_mm", o.kv_N_per_mm}}},
            {"m_kg", r.m_v_kg},
            {"m_kg_se", r.m_v_kg_se},
            {"b_N_s_per_m", r.b_v_N_s_per_m},
            {"b_N_s_per_m_se", r.b_v_N_s_per_m_se},
            {"free_air", palp::free_air_json(r)}};
  if (ctx.json) {
    print_json(j);
  } else {
    std::printf("m_v %.6g kg, b_v %.6g N s/m (k_v %.6g N/mm, omega_n %.6g rad/s, zeta %.6g)\n", r.m_v_kg,
                r.b_v_N_s_per_m, o.kv_N_per_mm, o.omega_n, o.zeta);
  }
  return kOk;
}

}  // namespace

void add_analyze_sweep_commands(CLI::App* analyze, Context& ctx) {
  auto a = std::make_shared<AnalyzeSweepCli>();
  auto* sweep = analyze->add_subcommand(
      "sweep", "A frequency response: a sweep recording (the program from its sidecar, else from "
               "these options) or a table; the second-order fit (SK + Levenberg-Marquardt) with "
               "standard errors and adequacy, and with --static the paper's decomposition");
  a->cmd = sweep;
  sweep->add_option("--input", a->sweep.input,
                    "A recording (sweep.csv) or a table with header f_Hz,re_m_per_N,im_m_per_N or "
                    "f_Hz,mag_m_per_N,phase_deg (optional 4th column sigma_m_per_N)")
      ->required();
  add_program_options(sweep, a->sweep);
  add_analysis_options(sweep, a->sweep);
  sweep->add_option("--control-rate-Hz", a->sweep.control_rate_Hz,
                    "The device's control rate, for a recording without a sidecar")
      ->check(CLI::IsMember({20000.0, 40000.0}))
      ->capture_default_str();
  sweep->add_flag("--free-air", a->free_air, "The response is free air: print m_v and b_v with k_v");
  sweep->callback([&ctx, a] { ctx.action = [&ctx, a] { return analyze_sweep(ctx, *a); }; });

  auto f = std::make_shared<FreeAirCli>();
  auto* freeair = analyze->add_subcommand(
      "freeair", "The instrument's moving mass and damping from a free-air omega_n and zeta and the "
                 "springs' k_v: m = k_v / omega_n^2, b = 2 zeta k_v / omega_n (paper §IV-B)");
  freeair->add_option("--omega-n-rad-per-s", f->omega_n, "Free-air natural frequency, rad/s")
      ->required()->check(kPositive);
  freeair->add_option("--zeta", f->zeta, "Free-air damping ratio")->required()->check(kPositive);
  freeair->add_option("--kv-N-per-mm", f->kv_N_per_mm, "Return springs k_v, N/mm")
      ->check(kPositive)->capture_default_str();
  freeair->add_option("--omega-n-rad-per-s-se", f->omega_n_se, "Its standard error, rad/s")->check(kNonNegative);
  freeair->add_option("--zeta-se", f->zeta_se, "Its standard error")->check(kNonNegative);
  freeair->callback([&ctx, f] { ctx.action = [&ctx, f] { return analyze_freeair(ctx, *f); }; });
}

}  // namespace palpctl
