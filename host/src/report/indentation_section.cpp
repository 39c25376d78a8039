// SPDX-License-Identifier: Apache-2.0
// The indentation section (sections.hpp): the run rebuilt from its result directory and analysed
// again (indentation_run_of), drawn as the paper's Fig. 4(a) and 6(a):
//   indentation-force-depth  F_o–δ of every repetition (plateau means, load and unload), the
//                            linear/Hertz/Sneddon fits, each with its contact point;
//   indentation-mean-sd      the loading branches' mean ± s.d. over repetitions, the chosen
//                            model, δ0 where it reaches the bias force F_0 and its tangent there;
// and result.json's analysed numbers with their s.e. and s.d. as a table.
//
// Depth: δ = z − z_c with the chosen model's z_c; F_o = K_f (i − I_c) − k_v (z − z_c). A model
// with its own contact point z_m predicts, in that frame, F_o = k_v (z_c − z_m) + M(z − z_m)
// [+ its offset], which is what its curve shows.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "palp/error.hpp"
#include "palp/indent.hpp"
#include "report/curve_points.hpp"
#include "report/section_format.hpp"
#include "report/sections.hpp"
#include "report/vega_build.hpp"

namespace palp::report {

namespace indentation_figures {

namespace an = analysis;
using nlohmann::json;

constexpr int kWidth = 560, kHeight = 360;
constexpr int kFitPoints = 160;

const char* model_label(an::Model m) {
  switch (m) {
    case an::Model::linear: return "linear fit";
    case an::Model::hertz: return "Hertz fit";
    case an::Model::sneddon: return "Sneddon fit";
  }
  return "fit";
}

std::string model_colour(an::Model m) {
  switch (m) {
    case an::Model::linear: return vega::colour(1);   // vermillion
    case an::Model::hertz: return vega::colour(0);    // blue
    case an::Model::sneddon: return vega::colour(2);  // green
  }
  return vega::colour(6);
}

// A repetition's grey (the repetitions stay apart without competing with the fits' colours).
std::string rep_colour(std::size_t index) {
  static const char* greys[] = {"#9a9a9a", "#7a7a7a", "#b4b4b4", "#5f5f5f", "#c8c8c8"};
  return greys[index % (sizeof greys / sizeof *greys)];
}

std::vector<const an::ModelFit*> fits_of(const an::IndentationResult& r) {
  std::vector<const an::ModelFit*> out;
  for (const auto* f : {&r.linear, &r.hertz, &r.sneddon})
    if (*f) out.push_back(&**f);
  return out;
}

// The model's F_o in the chosen model's depth frame (see the top of the file).
double model_Fo_N(const an::ModelFit& f, double depth_m, double zc_m, double kv_N_per_m) {
  const double own = depth_m - (f.contact_z_m - zc_m);
  return kv_N_per_m * (zc_m - f.contact_z_m) + f.force_N(std::max(own, 0.0)) + f.offset_N.value_or(0.0);
}

std::string fit_line_text(const an::ModelFit& f) {
  std::string s = std::string(model_label(f.model)) + ": ";
  if (f.k_N_per_m) s += "k = " + format_number(*f.k_N_per_m * 1e-3) + " N/mm";
  if (f.Estar_Pa) s += "E* = " + format_number(*f.Estar_Pa * 1e-3) + " kPa";
  s += ", z_c = " + format_number(f.contact_z_m * 1e3, 5) + " mm, R² = " + format_number(f.r2, 5);
  return s;
}

struct Frame {
  const an::IndentationResult& result;
  const an::ModelFit& chosen;
  const an::IndentationParams& params;
  an::Curve curve;
  Eigen::VectorXd Fo_N;
  double zc_m = 0;
  double max_depth_m = 0;  // deepest loading plateau
};

json force_depth_figure_spec(const Frame& f) {
  json s = vega::spec(kWidth, kHeight);
  vega::Extent x, y;
  std::vector<std::string> labels, colours;
  const auto reps = repetitions_of(f.curve);
  const auto groups = plateau_groups(f.curve);
  std::vector<json> rep_marks;
  for (std::size_t r = 0; r < reps.size(); ++r) {
    std::vector<double> d, F, loading;
    for (const auto& g : groups) {
      if (g.rep != reps[r]) continue;
      d.push_back((group_mean(f.curve.z_m, g) - f.zc_m) * 1e3);
      F.push_back(group_mean(f.Fo_N, g));
      loading.push_back(g.loading ? 1.0 : 0.0);
    }
    x.add(d);
    y.add(F);
    const std::string data = "rep" + std::to_string(r + 1);
    vega::add_data(s, data, vega::rows({{"delta_mm", d}, {"F_o_N", F}, {"loading", loading}}));
    const std::string label = "repetition " + std::to_string(r + 1);
    labels.push_back(label);
    colours.push_back(rep_colour(r));
    rep_marks.push_back(vega::line(data, "x", "delta_mm", "y", "F_o_N",
                                   {colours.back(), 1.0, {}, 0.8}, data + "_line"));
    json pts = vega::symbols(data, "x", "delta_mm", "y", "F_o_N", colours.back(), 16, "circle",
                             data + "_points");
    pts["encode"]["enter"]["fillOpacity"] = {{"signal", "datum.loading ? 0.7 : 0"}};
    vega::add_tooltip(pts, {{"δ (mm)", "delta_mm"}, {"F_o (N)", "F_o_N"}});
    rep_marks.push_back(std::move(pts));
  }
  // the fits, each from its own contact point to the deepest plateau
  std::vector<json> fit_marks;
  json contacts = json::array();
  for (const an::ModelFit* m : fits_of(f.result)) {
    const double from_m = m->contact_z_m - f.zc_m;
    std::vector<double> d, F;
    for (int k = 0; k <= kFitPoints; ++k) {
      const double depth = from_m + (f.max_depth_m - from_m) * k / kFitPoints;
      d.push_back(depth * 1e3);
      F.push_back(model_Fo_N(*m, depth, f.zc_m, f.params.spring_N_per_m));
    }
    x.add(d);
    y.add(F);
    const std::string name = std::string("fit_") + an::model_name(m->model);
    vega::add_data(s, name, vega::rows({{"delta_mm", d}, {"F_o_N", F}}));
    labels.push_back(model_label(m->model));
    colours.push_back(model_colour(m->model));
    vega::Stroke stroke{colours.back(), 2.0, {}, 1.0};
    if (m->model == an::Model::sneddon) stroke.dash = {6, 3};
    fit_marks.push_back(vega::line(name, "x", "delta_mm", "y", "F_o_N", stroke, name + "_line"));
    contacts.push_back({{"model", model_label(m->model)},
                        {"delta_mm", from_m * 1e3},
                        {"F_o_N", F.front()},
                        {"z_c_mm", m->contact_z_m * 1e3},
                        {"z_c_se_mm", m->contact_z_se_m * 1e3},
                        {"colour", colours.back()}});
  }
  vega::add_data(s, "contacts", contacts);
  vega::add_scale(s, vega::linear_scale("x", x, vega::Range::width));
  vega::add_scale(s, vega::linear_scale("y", y, vega::Range::height, true));
  vega::add_scale(s, vega::colour_scale("series", labels, colours));
  vega::add_axes(s, "x", "δ (mm)", "y", "F_o (N)");
  s["legends"].push_back(vega::legend("series"));
  for (auto& m : rep_marks) vega::add_mark(s, std::move(m));
  for (auto& m : fit_marks) vega::add_mark(s, std::move(m));
  json contact_marks = vega::symbols("contacts", "x", "delta_mm", "y", "F_o_N", "#000", 70,
                                     "diamond", "contact_points");
  contact_marks["encode"]["enter"]["fill"] = {{"field", "colour"}};
  contact_marks["encode"]["enter"]["stroke"] = {{"value", "#000"}};
  contact_marks["encode"]["enter"]["fillOpacity"] = {{"value", 1.0}};
  vega::add_tooltip(contact_marks, {{"model", "model"}, {"contact z_c (mm)", "z_c_mm"},
                                    {"s.e. (mm)", "z_c_se_mm"}});
  vega::add_mark(s, std::move(contact_marks));
  std::vector<std::string> lines;
  for (const an::ModelFit* m : fits_of(f.result)) lines.push_back(fit_line_text(*m));
  lines.push_back(std::string("lowest AIC: ") + model_label(f.chosen.model) +
                  "; ◆ contact points; ● loading ○ unloading");
  vega::add_mark(s, vega::corner_text(lines, "bottom-right", "#222", "fit_parameters"));
  return s;
}

json mean_sd_figure_spec(const Frame& f) {
  json s = vega::spec(kWidth, kHeight);
  constexpr int kGrid = 120;
  Eigen::VectorXd grid(kGrid + 1);
  for (int k = 0; k <= kGrid; ++k) grid[k] = f.max_depth_m * k / kGrid;
  const an::RepetitionStats st = an::repetition_mean_sd(f.curve, f.params, f.zc_m, grid);
  std::vector<double> d, mean, lo, hi, count;
  for (Eigen::Index k = 0; k < grid.size(); ++k) {
    if (st.count[k] == 0) continue;
    d.push_back(grid[k] * 1e3);
    mean.push_back(st.mean_N[k]);
    lo.push_back(st.mean_N[k] - st.sd_N[k]);
    hi.push_back(st.mean_N[k] + st.sd_N[k]);
    count.push_back(st.count[k]);
  }
  vega::Extent x, y;
  x.add(d);
  y.add(lo);
  y.add(hi);
  vega::add_data(s, "mean_sd", vega::rows({{"delta_mm", d}, {"mean_N", mean}, {"lo_N", lo},
                                           {"hi_N", hi}, {"reps", count}}));
  std::vector<double> md, mF;
  for (int k = 0; k <= kFitPoints; ++k) {
    const double depth = f.max_depth_m * k / kFitPoints;
    md.push_back(depth * 1e3);
    mF.push_back(model_Fo_N(f.chosen, depth, f.zc_m, f.params.spring_N_per_m));
  }
  y.add(mF);
  vega::add_data(s, "model", vega::rows({{"delta_mm", md}, {"F_o_N", mF}}));
  const double F0 = f.result.F0_N;
  const auto& d0 = f.result.delta0_m;
  const auto& kt = f.result.k_tangent_at_delta0_N_per_m;
  const bool tangent = d0 && kt;
  if (tangent) {
    const double half = 0.25 * f.max_depth_m;
    const double a = std::max(0.0, *d0.value - half), b = std::min(f.max_depth_m, *d0.value + half);
    vega::add_data(s, "tangent",
                   vega::rows({{"delta_mm", {a * 1e3, b * 1e3}},
                               {"F_o_N", {F0 + *kt.value * (a - *d0.value), F0 + *kt.value * (b - *d0.value)}}}));
    y.add(F0);
  }
  std::vector<std::string> labels = {"mean ± s.d.", model_label(f.chosen.model)};
  std::vector<std::string> colours = {vega::colour(5), model_colour(f.chosen.model)};
  if (tangent) {
    labels.push_back("tangent at F_0");
    colours.push_back(vega::colour(3));
  }
  vega::add_scale(s, vega::linear_scale("x", x, vega::Range::width));
  vega::add_scale(s, vega::linear_scale("y", y, vega::Range::height, true));
  vega::add_scale(s, vega::colour_scale("series", labels, colours));
  vega::add_axes(s, "x", "δ (mm)", "y", "F_o (N)");
  s["legends"].push_back(vega::legend("series"));
  vega::add_mark(s, vega::band("mean_sd", "x", "delta_mm", "y", "lo_N", "hi_N", colours[0], 0.3,
                               "sd_band"));
  json mean_line = vega::line("mean_sd", "x", "delta_mm", "y", "mean_N", {colours[0], 2.0, {}, 1.0},
                              "mean_line");
  vega::add_mark(s, std::move(mean_line));
  vega::add_mark(s, vega::line("model", "x", "delta_mm", "y", "F_o_N",
                               {colours[1], 1.8, {6, 3}, 1.0}, "model_line"));
  std::vector<std::string> lines = {"F_0 = " + format_number(F0) + " N (bias " +
                                    format_number(f.params.bias_current_A) + " A)"};
  if (tangent) {
    const vega::Stroke guide{"#555", 1.0, {3, 3}, 0.9};
    vega::add_mark(s, vega::vertical_rule("x", *d0.value * 1e3, guide, "delta0_rule"));
    vega::add_mark(s, vega::horizontal_rule("y", F0, guide, "F0_rule"));
    vega::add_mark(s, vega::line("tangent", "x", "delta_mm", "y", "F_o_N",
                                 {colours[2], 2.2, {}, 1.0}, "tangent_line"));
    vega::add_data(s, "delta0", vega::rows({{"delta_mm", {*d0.value * 1e3}}, {"F_o_N", {F0}},
                                            {"k_t_N_per_mm", {*kt.value * 1e-3}}}));
    json dot = vega::symbols("delta0", "x", "delta_mm", "y", "F_o_N", "#000", 60, "circle",
                             "delta0_point");
    vega::add_tooltip(dot, {{"δ0 (mm)", "delta_mm"}, {"F_0 (N)", "F_o_N"},
                            {"k_t (N/mm)", "k_t_N_per_mm"}});
    vega::add_mark(s, std::move(dot));
    vega::add_mark(s, vega::text("x", *d0.value * 1e3, "y", 0.0, "δ0", "#333", 4, -6, "left",
                                 "delta0_label"));
    lines.push_back("δ0 = " + format_number(*d0.value * 1e3) + " mm, k_t(δ0) = " +
                    format_number(*kt.value * 1e-3) + " N/mm");
  } else {
    lines.push_back("no δ0: " + (d0 ? kt.reason : d0.reason));
  }
  vega::add_mark(s, vega::corner_text(lines, "bottom-right", "#222", "bias_text"));
  return s;
}

// One table row: quantity, unit, value, s.e., s.d. (result.json's key, `<key>_se`, `<key>_sd`).
std::vector<std::string> parameter_row(const json& a, const std::string& quantity,
                                       const std::string& unit, const std::string& key,
                                       double scale = 1.0) {
  std::string value = format_cell(a, key, scale, 5);
  if (value == "—" && !reason_of(a, key).empty()) value += " (" + reason_of(a, key) + ")";
  return {quantity, unit, value, format_cell(a, key + "_se", scale), format_cell(a, key + "_sd", scale)};
}

Table parameter_table(const json& a) {
  Table t;
  t.id = "indentation-parameters";
  t.title = "Indentation parameters";
  t.columns = {"quantity", "unit", "value", "s.e.", "s.d."};
  t.rows = {
      parameter_row(a, "contact point z_c", "mm", "contact_point_mm"),
      parameter_row(a, "k (linear fit)", "N/mm", "k_linear_N_per_mm"),
      parameter_row(a, "R² (linear)", "", "r2_linear"),
      parameter_row(a, "E* (Hertz fit)", "kPa", "E_star_hertz_Pa", 1e-3),
      parameter_row(a, "R² (Hertz)", "", "r2_hertz"),
      parameter_row(a, "E* (Sneddon fit)", "kPa", "E_star_sneddon_Pa", 1e-3),
      parameter_row(a, "R² (Sneddon)", "", "r2_sneddon"),
      {"model (lowest AIC)", "", format_cell(a, "model_by_aic"), "", ""},
      parameter_row(a, "F_0 (bias force)", "N", "F0_N"),
      parameter_row(a, "δ0 (depth at F_0)", "mm", "delta0_mm"),
      parameter_row(a, "k_t at δ0", "N/mm", "k_tangent_N_per_mm"),
      parameter_row(a, "k_fd (window)", "N/mm", "k_fd_N_per_mm"),
      parameter_row(a, "k (window LSQ)", "N/mm", "k_ls_window_N_per_mm"),
      parameter_row(a, "k_fd (paper's depth origin)", "N/mm", "k_fd_paper_N_per_mm"),
  };
  if (a.contains("k_at_depth_N_per_mm") && a["k_at_depth_N_per_mm"].is_object()) {
    const json& k = a["k_at_depth_N_per_mm"];
    for (auto it = k.begin(); it != k.end(); ++it) {
      if (it.key().find("_se") != std::string::npos || it.key().find("_sd") != std::string::npos ||
          it.key().find("_reason") != std::string::npos)
        continue;
      std::string depth = it.key();
      std::replace(depth.begin(), depth.end(), '_', ' ');
      t.rows.push_back(parameter_row(k, "k_t at " + depth, "N/mm", it.key()));
    }
  }
  t.rows.push_back({"repetitions", "", format_cell(a, "repetitions"), "", ""});
  t.caption = "From result.json's analysis: s.e. is the fit's standard error (the delta method for "
              "δ0 and the tangents), s.d. the spread over repetitions; — where a value cannot be "
              "computed (the reason beside it).";
  return t;
}

}  // namespace indentation_figures

Section indentation_section(const LoadedResult& result) {
  namespace fig = indentation_figures;
  const IndentationRun run = indentation_run_of(result);  // RecordingError for another experiment
  Section s;
  s.id = "indentation";
  s.title = "Indentation " + result.dir.filename().string();
  const nlohmann::json numbers = result.summary.value("analysis", nlohmann::json::object());
  const analysis::ModelFit* chosen = run.analysis ? analysis::chosen_fit(*run.analysis) : nullptr;
  if (!chosen) {
    s.text = "No force–depth figure: " +
             (run.analysis ? run.analysis->fit_reason : run.analysis_reason);
    if (numbers.is_object()) s.tables.push_back(fig::parameter_table(numbers));
    return s;
  }
  fig::Frame frame{*run.analysis, *chosen, run.settings.analysis, curve_of(run.recording), {}, 0, 0};
  frame.zc_m = chosen->contact_z_m;
  frame.Fo_N = analysis::object_force_N(frame.curve, frame.params, frame.zc_m);
  for (const auto& g : plateau_groups(frame.curve))
    if (g.loading) frame.max_depth_m = std::max(frame.max_depth_m, group_mean(frame.curve.z_m, g) - frame.zc_m);
  const int reps = static_cast<int>(repetitions_of(frame.curve).size());
  s.text = std::to_string(reps) + " repetition" + (reps == 1 ? "" : "s") + ", fitted on " +
           analysis::fit_on_name(run.analysis->fitted_on) + "; depth δ from the " +
           fig::model_label(chosen->model) + "'s contact point z_c = " +
           format_number(frame.zc_m * 1e3, 6) + " mm.";
  s.figures.push_back({"indentation-force-depth", "Object force against depth, with the fits",
                       "F_o = K_f (i − I_c) − k_v (z − z_c) of every repetition (the staircase's "
                       "plateau means, loading and unloading) and the linear, Hertz and Sneddon "
                       "fits of the loading branches, each from its own contact point (◆).",
                       fig::force_depth_figure_spec(frame)});
  s.figures.push_back({"indentation-mean-sd", "Mean ± s.d. over repetitions, δ0 and the tangent",
                       "The loading branches' mean F_o and its s.d. over repetitions on a common "
                       "depth grid, the chosen model, the depth δ0 where it reaches the bias force "
                       "F_0 and its tangent stiffness there.",
                       fig::mean_sd_figure_spec(frame)});
  s.tables.push_back(fig::parameter_table(numbers));
  return s;
}

}  // namespace palp::report
