// SPDX-License-Identifier: Apache-2.0
// The pressure section (sections.hpp), the paper's Fig. 5(c): each recorded channel's pressure
// against the object force F_o (the staircase's plateau means, loading and unloading) with its
// regression line over the loading branch and R², and a table of the slopes, the rises and the
// Boyle volume change the rise implies.
//
// The run is rebuilt and analysed again (indentation_run_of), so F_o, the regression and the
// rise are the analysis' own (analysis/pressure.hpp). The enclosed volume of a channel is not in
// the result: ΔV uses the paper's shallow channel (Ø5 mm x 90 mm with 50 cm of 1/16 in tube,
// ChannelGeometry's defaults), as the caption says.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "palp/analysis/pressure.hpp"
#include "palp/indent.hpp"
#include "report/curve_points.hpp"
#include "report/section_format.hpp"
#include "report/sections.hpp"
#include "report/vega_build.hpp"

namespace palp::report {

namespace pressure_figures {

namespace an = analysis;
using nlohmann::json;

const std::vector<double>* channel_column(const Recording& r, int channel) {
  const auto& col = r.p_Pa[static_cast<std::size_t>(channel - 1)];
  return col && col->size() == r.size() ? &*col : nullptr;
}

std::string opt(const an::Value& v, double scale = 1.0, int significant = 4) {
  return v ? format_number(*v.value * scale, significant) : "—";
}

json pressure_force_spec(const IndentationRun& run, const an::PressureResult& pr) {
  const an::Curve c = curve_of(run.recording);
  const Eigen::VectorXd Fo = an::object_force_N(c, run.settings.analysis, pr.contact_z_m);
  const auto groups = plateau_groups(c);
  const auto levels = levels_over_repetitions(c, groups);
  json s = vega::spec(560, 360);
  vega::Extent x, y;
  std::vector<std::string> labels, colours;
  std::vector<json> point_marks, line_marks;
  for (std::size_t n = 0; n < pr.channels.size(); ++n) {
    const an::ChannelPressure& ch = pr.channels[n];
    const std::vector<double>* p = channel_column(run.recording, ch.channel);
    if (!p) continue;
    const Eigen::VectorXd pv = Eigen::Map<const Eigen::VectorXd>(p->data(), static_cast<Eigen::Index>(p->size()));
    // mean ± s.d. over repetitions at each level of the staircase, or each plateau without one
    std::vector<double> F, P, lo, hi, loading;
    const auto add = [&](const std::vector<std::size_t>& members, bool load) {
      double f = 0, m = 0, ss = 0;
      for (std::size_t g : members) {
        f += group_mean(Fo, groups[g]);
        m += group_mean(pv, groups[g]);
      }
      const double count = static_cast<double>(members.size());
      f /= count;
      m /= count;
      for (std::size_t g : members) ss += (group_mean(pv, groups[g]) - m) * (group_mean(pv, groups[g]) - m);
      const double sd = members.size() > 1 ? std::sqrt(ss / (count - 1)) : 0.0;
      F.push_back(f);
      P.push_back(m);
      lo.push_back(m - sd);
      hi.push_back(m + sd);
      loading.push_back(load ? 1.0 : 0.0);
    };
    const auto below_contact = [&](const PointGroup& g) {  // the regression's samples: F >= 0
      return group_mean(c.i_A, g) < run.settings.analysis.contact_current_A;
    };
    if (!levels.empty()) {
      for (const auto& level : levels)
        if (!below_contact(groups[level.groups.front()])) add(level.groups, level.loading);
    } else {
      for (std::size_t g = 0; g < groups.size(); ++g)
        if (!below_contact(groups[g])) add({g}, groups[g].loading);
    }
    x.add(F);
    y.add(lo);
    y.add(hi);
    const std::string id = "p" + std::to_string(ch.channel);
    const std::string colour = vega::colour(static_cast<int>(n));
    vega::add_data(s, id, vega::rows({{"F_o_N", F}, {"p_Pa", P}, {"lo_Pa", lo}, {"hi_Pa", hi},
                                      {"loading", loading}}));
    point_marks.push_back(vega::error_bars(id, "x", "F_o_N", "y", "lo_Pa", "hi_Pa", colour, id + "_sd"));
    json pts = vega::symbols(id, "x", "F_o_N", "y", "p_Pa", colour, 14, "circle", id + "_points");
    // unloading points hollow: the loop between the branches is the channel's hysteresis
    pts["encode"]["enter"]["fillOpacity"] = {{"signal", "datum.loading ? 0.6 : 0"}};
    vega::add_tooltip(pts, {{"F_o (N)", "F_o_N"}, {"p (Pa)", "p_Pa"}, {"mean − s.d. (Pa)", "lo_Pa"},
                            {"mean + s.d. (Pa)", "hi_Pa"}});
    point_marks.push_back(std::move(pts));
    std::string label = "p" + std::to_string(ch.channel);
    if (ch.fit.slope && ch.fit.intercept) {
      const double a = *ch.fit.slope.value, b = *ch.fit.intercept.value;
      const double F_lo = F.empty() ? 0.0 : *std::min_element(F.begin(), F.end());
      const double F_hi = F.empty() ? 1.0 : *std::max_element(F.begin(), F.end());
      vega::add_data(s, id + "_fit", vega::rows({{"F_o_N", {F_lo, F_hi}}, {"p_Pa", {a * F_lo + b, a * F_hi + b}}}));
      line_marks.push_back(vega::line(id + "_fit", "x", "F_o_N", "y", "p_Pa", {colour, 2.0, {}, 1.0},
                                      id + "_regression"));
      label += ": " + format_number(a, 4) + " Pa/N, R² = " + opt(ch.fit.r2, 1.0, 5);
    }
    labels.push_back(label);
    colours.push_back(colour);
  }
  vega::add_scale(s, vega::linear_scale("x", x, vega::Range::width, true));
  vega::add_scale(s, vega::linear_scale("y", y, vega::Range::height));
  vega::add_scale(s, vega::colour_scale("channels", labels, colours));
  vega::add_axes(s, "x", "F_o (N)", "y", "p (Pa)");
  s["legends"].push_back(vega::legend("channels", "channel: slope, R²", "right"));
  for (auto& m : point_marks) vega::add_mark(s, std::move(m));
  for (auto& m : line_marks) vega::add_mark(s, std::move(m));
  vega::add_mark(s, vega::corner_text({"● loading   ○ unloading", "lines: least squares on loading"},
                                      "bottom-right", "#444", "branch_key"));
  return s;
}

Table pressure_table(const an::PressureResult& pr) {
  const double V1 = an::enclosed_volume_m3(an::ChannelGeometry{});
  Table t;
  t.id = "pressure-channels";
  t.title = "Pressure channels against F_o";
  t.columns = {"channel", "slope (Pa/N)", "s.e. (Pa/N)", "intercept (Pa)", "R²",
               "rise (Pa)", "rise s.d. (Pa)", "ΔV isothermal (mm³)", "ΔV adiabatic (mm³)",
               "hysteresis ratio"};
  for (const auto& ch : pr.channels) {
    std::string dv_iso = "—", dv_ad = "—";
    if (ch.rise_Pa && *ch.rise_Pa.value > -an::kAmbientPressurePa) {
      const an::BoyleResult b = an::boyle_volume_change(V1, *ch.rise_Pa.value);
      dv_iso = format_number(b.dV_isothermal_m3 * 1e9);
      dv_ad = format_number(b.dV_adiabatic_m3 * 1e9);
    }
    t.rows.push_back({"p" + std::to_string(ch.channel), opt(ch.fit.slope), opt(ch.fit.slope_se, 1.0, 2),
                      opt(ch.fit.intercept), opt(ch.fit.r2, 1.0, 5), opt(ch.rise_Pa),
                      opt(ch.rise_sd_Pa, 1.0, 2), dv_iso, dv_ad, opt(ch.hysteresis_ratio_mean, 1.0, 3)});
  }
  t.caption = "Slopes by least squares on the loading branches (" + std::to_string(pr.n_loading) +
              " samples at i ≥ I_c); the rise is p at the peak force minus p at first contact, "
              "mean over repetitions. Boyle: ΔV = V1 (1 − P1/(P1 + rise)) with P1 = 101325 Pa and "
              "V1 = " + format_number(V1 * 1e9) + " mm³, the paper's Ø5 mm × 90 mm channel with "
              "50 cm of 1/16 in tube (the result does not hold the channel's volume); the "
              "adiabatic bound uses γ = 1.4.";
  return t;
}

}  // namespace pressure_figures

Section pressure_section(const LoadedResult& result) {
  namespace fig = pressure_figures;
  const IndentationRun run = indentation_run_of(result);  // RecordingError for another experiment
  Section s;
  s.id = "pressure";
  s.title = "Pressure channels " + result.dir.filename().string();
  if (!run.pressure || run.pressure->channels.empty()) {
    s.text = "No pressure figure: " +
             (run.pressure ? std::string("the recording has no pressure channel") : run.pressure_reason) + ".";
    return s;
  }
  s.text = std::to_string(run.pressure->channels.size()) + " channels against the object force F_o "
           "(depth origin z_c = " + format_number(run.pressure->contact_z_m * 1e3, 6) + " mm).";
  s.figures.push_back({"pressure-force", "Channel pressure against object force",
                       "Each channel's gauge pressure against F_o, mean ± s.d. over repetitions at "
                       "each current level of the staircase (filled: loading, hollow: unloading), "
                       "with its least-squares line over the loading branch, its slope and R².",
                       fig::pressure_force_spec(run, *run.pressure)});
  s.tables.push_back(fig::pressure_table(*run.pressure));
  return s;
}

}  // namespace palp::report
