// SPDX-License-Identifier: Apache-2.0
// palpctl analyze: re-analyse recordings without a device.
//   analyze indentation --input run.csv   the quasi-static analysis (palp/analysis/indentation.hpp)
//   analyze pressure --input run.csv      each channel's pressure against force, hysteresis
//   analyze boyle                         the enclosed-volume change from a pressure rise
// Lab units at the command line and in the output (mm, N/mm, Pa, mm^3); the SDK is SI.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>

#include "common.hpp"
#include "export_hdf5.hpp"
#include "palp/indent.hpp"
#include "palp/result.hpp"
#include "palp/analysis/indentation.hpp"
#include "palp/analysis/pressure.hpp"
#include "palp/error.hpp"
#include "palp/pressure_analysis.hpp"
#ifdef PALP_HAVE_HDF5
#include "palp/hdf5.hpp"
#endif
#include "palp/recording.hpp"

namespace palpctl {

namespace {

namespace an = palp::analysis;

struct AnalyzeCli {
  std::string input;
  double kf_N_per_A = 2.918, ic_A = 0.5, kv_N_per_mm = 0.0439, tip_radius_mm = 2.5, poisson = 0.5;
  double bias_current_A = 1.0, bias_force_N = 0.0, thickness_mm = 0.0;
  bool unbonded = false;
  bool kf_table = false;
  CLI::Option* bias_force_opt = nullptr;
  CLI::Option* thickness_opt = nullptr;
};

struct BoyleCli {
  std::string input;
  double pressure_change_Pa = 0.0, channel_diameter_mm = 5.0, tube_bore_mm = 1.5875,
         tube_length_mm = 500.0, ambient_Pa = palp::analysis::kAmbientPressurePa;
  std::vector<double> channel_length_mm;
};

an::IndentationParams params_of(const AnalyzeCli& o) {
  an::IndentationParams p;
  p.force_constant_N_per_A = o.kf_N_per_A;
  p.contact_current_A = o.ic_A;
  p.spring_N_per_m = o.kv_N_per_mm * 1e3;
  p.tip_radius_m = o.tip_radius_mm * 1e-3;
  p.poisson = o.poisson;
  p.bias_current_A = o.bias_force_opt != nullptr && o.bias_force_opt->count() > 0
                         ? o.ic_A + o.bias_force_N / o.kf_N_per_A
                         : o.bias_current_A;
  if (o.thickness_opt != nullptr && o.thickness_opt->count() > 0)
    p.thickness = an::Thickness{o.thickness_mm * 1e-3,
                                o.unbonded ? an::Bonding::unbonded : an::Bonding::bonded};
  return p;
}

/// The SDK's analysis params (palp::indentation_params_json) with the recording and --kf-table.
json params_json(const AnalyzeCli& o, const an::IndentationParams& p) {
  json j = palp::indentation_params_json(p);
  j["input"] = o.input;
  j["kf_table"] = o.kf_table;
  return j;
}

/// A recording as the analysis's curve, with the analysis's data problems as RecordingErrors
/// naming the file and the lines (exit code 1, as the reader's own errors).
struct Loaded {
  palp::Recording rec;
  an::Curve curve;
  std::vector<std::size_t> lines;
  std::size_t line_of(std::size_t row) const { return row < lines.size() ? lines[row] : 0; }
};

Loaded load(const std::string& file, const an::IndentationParams& p) {
  Loaded l;
#ifdef PALP_HAVE_HDF5
  if (palp::is_hdf5_file(file)) {
    l.rec = palp::read_recording_hdf5(file);  // no text lines: problems name the file alone
  } else
#endif
  {
    if (std::filesystem::path(file).extension() == ".h5" && !hdf5_available())
      throw palp::ConfigError(file + ": this palpctl was built without HDF5 and reads no .h5 (install "
                                     "libhdf5-dev, scripts/install-deps, and build again)");
    l.rec = palp::read_recording(file);
    l.lines = palp::recording_row_lines(file);
  }
  l.curve = palp::curve_of(l.rec);  // with i_cmd_A when recorded: the staircase's plateaus
  // no contact: name the line with the highest current
  Eigen::Index top = 0;
  const double i_max = l.curve.i_A.maxCoeff(&top);
  if (i_max < p.contact_current_A)
    throw palp::RecordingError(file, l.line_of(static_cast<std::size_t>(top)),
                               "no contact: the highest current, i_A = " + fmt(i_max) +
                                   " A here, stays below the contact current I_c = " +
                                   fmt(p.contact_current_A) + " A (--ic-A)");
  // too few points in contact on the loading branches: name their lines
  std::vector<int> contact;
  for (int k : an::loading_branch(l.curve).loading)
    if (l.curve.i_A[k] >= p.contact_current_A) contact.push_back(k);
  if (contact.empty())  // (no lines to name: e.g. every loading sample below I_c)
    throw palp::RecordingError(file, 0,
                               "too few points: no loading sample at i_A >= I_c = " +
                                   fmt(p.contact_current_A) + " A, the fits need at least " +
                                   std::to_string(p.min_points));
  if (static_cast<int>(contact.size()) < p.min_points) {
    // a CSV's file lines; an .h5 has none, so its rows (from 0)
    const bool rows = l.lines.empty();
    const auto a = rows ? static_cast<std::size_t>(contact.front()) : l.line_of(static_cast<std::size_t>(contact.front()));
    const auto b = rows ? static_cast<std::size_t>(contact.back()) : l.line_of(static_cast<std::size_t>(contact.back()));
    const std::string what = rows ? " (row" : " (line";
    throw palp::RecordingError(
        file, 0,
        "too few points: " + std::to_string(contact.size()) + " loading sample" +
            (contact.size() == 1 ? "" : "s") + " at i_A >= I_c = " + fmt(p.contact_current_A) +
            " A" + what + (a == b ? " " + std::to_string(a) : "s " + std::to_string(a) + "-" +
                                                                  std::to_string(b)) +
            "), the fits need at least " + std::to_string(p.min_points));
  }
  return l;
}

// --- JSON helpers: a value in lab units, or null with its reason ---------------------------

void put(json& j, const std::string& key, const an::Value& v, double scale) {
  if (v) {
    j[key] = *v.value * scale;
  } else {
    j[key] = nullptr;
    j[key + "_reason"] = v.reason;
  }
}

void print_or_json(const Context& ctx, const json& j) {
  if (ctx.json) print_json(j);
  else print_text(j);
}

/// The K_f table of the recording's sidecar into p when --kf-table asks for it.
void kf_table_of(const AnalyzeCli& o, const Loaded& l, an::IndentationParams& p) {
  if (!o.kf_table) return;
  if (!l.rec.sidecar) throw palp::ConfigError(o.input + ": --kf-table needs the recording's sidecar (none found)");
  try {
    palp::use_kf_table_of(*l.rec.sidecar, p);
  } catch (const palp::ConfigError& e) {
    throw palp::ConfigError(o.input + ": " + e.what());
  }
}

int analyze_indentation(const Context& ctx, const AnalyzeCli& o) {
  an::IndentationParams p = params_of(o);
  const Loaded l = load(o.input, p);
  kf_table_of(o, l, p);
  const an::IndentationResult r = an::analyze_indentation(l.curve, p);
  const an::RepetitionSummary reps = an::analyze_repetitions(l.curve, p);
  // the SDK's summary: what palpctl indent prints and result.json holds
  json j = palp::indentation_summary_json(r, &reps, p);
  j["params"] = params_json(o, p);
  print_or_json(ctx, j);
  return kOk;
}

/// The pressure channels the recording has: (channel 1..6, its samples as a column).
std::vector<std::pair<int, const std::vector<double>*>> pressure_channels(const Loaded& l,
                                                                          const std::string& file) {
  std::vector<std::pair<int, const std::vector<double>*>> out;
  for (std::size_t ch = 0; ch < 6; ++ch)
    if (l.rec.p_Pa[ch]) out.emplace_back(static_cast<int>(ch) + 1, &*l.rec.p_Pa[ch]);
  if (out.empty()) throw palp::RecordingError(file, 0, "no pressure column (p1_Pa .. p6_Pa)");
  return out;
}

int analyze_pressure(const Context& ctx, const AnalyzeCli& o) {
  an::IndentationParams p = params_of(o);
  const Loaded l = load(o.input, p);
  kf_table_of(o, l, p);
  pressure_channels(l, o.input);  // none: an error naming the file before the fits run
  const an::IndentationResult r = an::analyze_indentation(l.curve, p);
  an::PressureResult pr;
  try {  // the SDK's pressure-force test (what palp::indent does), on this contact point
    pr = palp::pressure_analysis_of(l.rec, p, r);
  } catch (const palp::DataError& e) {
    throw palp::RecordingError(o.input, 0, e.what());
  }
  json j;
  j["params"] = params_json(o, p);
  j["force"] = std::string("object force F_o = K_f (i - I_c) - k_v (z - z_c), samples at i >= I_c on "
                           "the loading branches; z_c of the ") + an::model_name(*r.chosen) + " fit";
  j.update(palp::pressure_summary_json(pr));  // the SDK's summary (what palpctl indent writes)
  if (ctx.json) {
    print_json(j);
    return kOk;
  }
  auto cell = [](const json& v) { return v.is_number() ? fmt(v.get<double>()) : std::string("-"); };
  std::printf("%s: contact point %s mm (%s fit), %d loading samples at i_A >= I_c\n", o.input.c_str(),
              fmt(pr.contact_z_m * 1e3).c_str(), an::model_name(*r.chosen), pr.n_loading);
  std::printf("channel  slope_Pa_per_N          r2     rise_Pa  hysteresis_ratio\n");
  for (const auto& ch : j["channels"])
    std::printf("%7d  %14s  %10s  %10s  %16s\n", ch["channel"].get<int>(), cell(ch["slope_Pa_per_N"]).c_str(),
                cell(ch["r2"]).c_str(), cell(ch["rise_Pa"]).c_str(), cell(ch["hysteresis_ratio"]).c_str());
  return kOk;
}

// --- boyle -----------------------------------------------------------------------------------

/// The paper's pad (§V-A, §V-D): channels 1-3 deep (100 mm), 4-6 shallow (90 mm).
double pad_channel_length_mm(int channel) { return channel <= 3 ? 100.0 : 90.0; }

json boyle_row(const BoyleCli& o, double dP_Pa, double length_mm) {
  an::ChannelGeometry g;
  g.channel_diameter_m = o.channel_diameter_mm * 1e-3;
  g.channel_length_m = length_mm * 1e-3;
  g.tube_bore_m = o.tube_bore_mm * 1e-3;
  g.tube_length_m = o.tube_length_mm * 1e-3;
  const double V1 = an::enclosed_volume_m3(g);
  const an::BoyleResult b = an::boyle_volume_change(V1, dP_Pa, o.ambient_Pa);
  const double mm3 = 1e9;
  return {{"pressure_change_Pa", dP_Pa},
          {"channel_length_mm", length_mm},
          {"enclosed_volume_mm3", b.V1_m3 * mm3},
          {"P2_Pa", b.P2_Pa},
          {"volume_change_isothermal_mm3", b.dV_isothermal_m3 * mm3},
          {"volume_change_adiabatic_mm3", b.dV_adiabatic_m3 * mm3}};
}

int analyze_boyle(const Context& ctx, const BoyleCli& o, bool from_file) {
  json j;
  j["params"] = {{"channel_diameter_mm", o.channel_diameter_mm},
                 {"tube_bore_mm", o.tube_bore_mm},
                 {"tube_length_mm", o.tube_length_mm},
                 {"ambient_Pa", o.ambient_Pa},
                 {"law", "isothermal P1 V1 = P2 V2 (adiabatic P V^1.4 as the bound)"}};
  json rows = json::array();
  if (!from_file) {
    const double L = o.channel_length_mm.empty() ? 90.0 : o.channel_length_mm.front();
    rows.push_back(boyle_row(o, o.pressure_change_Pa, L));
  } else {
    an::IndentationParams p;  // the paper's I_c: the recording must reach contact
    p.min_points = 1;
    const Loaded l = load(o.input, p);
    const auto channels = pressure_channels(l, o.input);
    if (o.channel_length_mm.size() > 1 && o.channel_length_mm.size() != 6)
      throw palp::ConfigError("--channel-length-mm takes 1 value (every channel) or 6 (channels 1-6), got " +
                              std::to_string(o.channel_length_mm.size()));
    j["params"]["input"] = o.input;
    j["params"]["pressure"] = "mean over repetitions of each channel's pressure at the repetition's "
                              "highest current (the maximum force)";
    // each repetition's sample of peak current (the first, on a plateau)
    std::vector<Eigen::Index> peaks;
    for (Eigen::Index k = 0, b = 0; k <= l.curve.i_A.size(); ++k) {
      if (k < l.curve.i_A.size() && l.curve.rep[k] == l.curve.rep[b]) continue;
      Eigen::Index top = 0;
      l.curve.i_A.segment(b, k - b).maxCoeff(&top);
      peaks.push_back(b + top);
      b = k;
    }
    for (const auto& [ch, col] : channels) {
      std::vector<an::Value> at_peak;
      for (Eigen::Index k : peaks) at_peak.push_back(an::Value::of((*col)[static_cast<std::size_t>(k)]));
      const an::MeanSd m = an::mean_sd(at_peak);
      const double L = o.channel_length_mm.empty()       ? pad_channel_length_mm(ch)
                       : o.channel_length_mm.size() == 1 ? o.channel_length_mm.front()
                                                         : o.channel_length_mm[static_cast<std::size_t>(ch - 1)];
      json row = {{"channel", ch}};
      row.update(boyle_row(o, *m.mean.value, L));
      put(row, "pressure_change_Pa_sd", m.sd, 1.0);
      row["repetitions"] = m.n;
      rows.push_back(row);
    }
  }
  j["channels"] = rows;
  if (ctx.json) {
    print_json(j);
  } else {
    for (const auto& r : rows) {
      if (r.contains("channel")) std::printf("channel %d: ", r["channel"].get<int>());
      std::printf("dP %.6g Pa, V1 %.6g mm3, dV %.6g mm3 isothermal (%.6g mm3 adiabatic)\n",
                  r["pressure_change_Pa"].get<double>(), r["enclosed_volume_mm3"].get<double>(),
                  r["volume_change_isothermal_mm3"].get<double>(),
                  r["volume_change_adiabatic_mm3"].get<double>());
    }
  }
  return kOk;
}

void add_indentation_options(CLI::App* cmd, AnalyzeCli& o) {
  cmd->add_option("--input", o.input, "The recording (run.csv; its sidecar is read when present; or run.h5, docs/hdf5-format.md)")
      ->required();
  cmd->add_option("--kf-N-per-A", o.kf_N_per_A, "Force constant K_f, N/A")
      ->check(kPositive)->capture_default_str();
  cmd->add_option("--ic-A", o.ic_A, "Contact threshold current I_c, A")
      ->check(CLI::Range(-4.0, 4.0))->capture_default_str();
  cmd->add_option("--kv-N-per-mm", o.kv_N_per_mm, "Return springs k_v, N/mm")
      ->check(kNonNegative)->capture_default_str();
  cmd->add_option("--tip-radius-mm", o.tip_radius_mm, "Tip radius R, mm")
      ->check(kPositive)->capture_default_str();
  cmd->add_option("--poisson", o.poisson, "Poisson's ratio of the specimen (E = E* (1 - nu^2))")
      ->check(CLI::Range(0.0, 0.5))->capture_default_str();
  auto* bias_i = cmd->add_option("--bias-current-A", o.bias_current_A,
                                 "Bias current I_0 of the operating point F_0 = K_f (I_0 - I_c), A")
                     ->check(CLI::Range(-4.0, 4.0))->capture_default_str();
  o.bias_force_opt = cmd->add_option("--bias-force-N", o.bias_force_N,
                                     "Bias force F_0 instead of --bias-current-A, N")
                         ->check(kPositive)->excludes(bias_i);
  o.thickness_opt = cmd->add_option("--thickness-mm", o.thickness_mm,
                                    "Sample thickness for the finite-thickness correction, mm "
                                    "(default: none, a half-space)")
                        ->check(kPositive);
  cmd->add_flag("--kf-table", o.kf_table,
                "Use the K_f(stroke) table of the recording's calibration at each sample's stroke "
                "position instead of the constant --kf-N-per-A (needs the sidecar's stroke origin)");
  cmd->add_flag("--unbonded", o.unbonded,
                "The sample lies loose on its support (default: bonded); with --thickness-mm")
      ->needs(o.thickness_opt);
}

}  // namespace

void add_analyze_command(CLI::App& app, Context& ctx) {
  auto* cmd = app.add_subcommand("analyze", "Analyse recordings (no device needed)");
  cmd->require_subcommand(1, 1);

  auto ind = std::make_shared<AnalyzeCli>();
  auto* indentation = cmd->add_subcommand(
      "indentation", "Quasi-static indentation: linear, Hertz and Sneddon fits with the contact "
                     "point, model choice by AIC, delta0, tangent and window stiffness");
  add_indentation_options(indentation, *ind);
  indentation->callback([&ctx, ind] { ctx.action = [&ctx, ind] { return analyze_indentation(ctx, *ind); }; });

  auto pr = std::make_shared<AnalyzeCli>();
  auto* pressure = cmd->add_subcommand(
      "pressure", "Each pressure channel against the object force on the loading branch: slope, "
                  "R^2, rise, load/unload hysteresis");
  add_indentation_options(pressure, *pr);
  pressure->callback([&ctx, pr] { ctx.action = [&ctx, pr] { return analyze_pressure(ctx, *pr); }; });

  auto bo = std::make_shared<BoyleCli>();
  auto* boyle = cmd->add_subcommand(
      "boyle", "Enclosed-volume change of a channel and its tube from a pressure rise "
               "(isothermal Boyle's law; the adiabatic value as the bound)");
  auto* dp = boyle->add_option("--pressure-change-Pa", bo->pressure_change_Pa,
                               "The pressure rise above ambient, Pa");
  auto* in = boyle->add_option("--input", bo->input,
                               "A recording instead: each channel's pressure at the maximum force")
                 ->excludes(dp);
  boyle->add_option("--channel-diameter-mm", bo->channel_diameter_mm, "Channel diameter, mm")
      ->check(kPositive)->capture_default_str();
  boyle->add_option("--channel-length-mm", bo->channel_length_mm,
                    "Channel length, mm: one value, or 6 for channels 1-6 with --input (default: "
                    "90; with --input the paper's pad, channels 1-3 100 and 4-6 90)")
      ->check(kPositive);
  boyle->add_option("--tube-bore-mm", bo->tube_bore_mm, "Tube inner diameter, mm (1/16 in)")
      ->check(kPositive)->capture_default_str();
  boyle->add_option("--tube-length-mm", bo->tube_length_mm, "Tube length, mm (0: no tube)")
      ->check(kNonNegative)->capture_default_str();
  boyle->add_option("--ambient-Pa", bo->ambient_Pa, "Ambient (absolute) pressure P1, Pa")
      ->check(kPositive)->capture_default_str();
  boyle->callback([&ctx, bo, dp, in] {
    if (dp->count() == 0 && in->count() == 0)
      throw CLI::ValidationError("analyze boyle", "give --pressure-change-Pa or --input");
    const bool from_file = in->count() > 0;
    ctx.action = [&ctx, bo, from_file] { return analyze_boyle(ctx, *bo, from_file); };
  });

  auto mp = std::make_shared<AnalyzeCli>();
  auto mc = std::make_shared<double>(0.1);
  auto* map = cmd->add_subcommand(
      "map", "A saved map (palpctl map) re-analysed point by point from its recordings with these "
             "options: the k_fd stiffness grid and its soft and stiff rows and columns");
  add_indentation_options(map, *mp);
  map->get_option("--input")->description("The map's directory (map.json, points/r<row>_c<column>/), or the "
                                          "map exported as one HDF5 file (palpctl export --format hdf5)");
  map->add_option("--contrast", *mc, "A line is soft (stiff) when its mean is this fraction below (above) "
                                     "the median line's")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  map->callback([&ctx, mp, mc] {
    ctx.action = [&ctx, mp, mc] { return analyze_map_command(ctx, mp->input, params_of(*mp), mp->kf_table, *mc); };
  });

  add_analyze_sweep_commands(cmd, ctx);
}

}  // namespace palpctl
