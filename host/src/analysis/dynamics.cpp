// SPDX-License-Identifier: Apache-2.0
// From a fitted second-order model to the paper's quantities and the contact moduli (see
// dynamics.hpp).
#include "palp/analysis/dynamics.hpp"

#include <cmath>
#include <numbers>
#include <sstream>

#include "palp/analysis/contact_models.hpp"
#include "palp/error.hpp"
#include "number_text.hpp"

namespace palp::analysis {

namespace {

void require_positive(const char* function, const char* what, double v, const char* unit) {
  if (!(v > 0) || !std::isfinite(v))
    throw ConfigError(std::string(function) + ": " + what + " must be positive (got " + detail::number_text(v) +
                      (unit[0] != '\0' ? " " : "") + unit + ")");
}

void require_non_negative(const char* function, const char* what, double v) {
  if (!(v >= 0) || !std::isfinite(v))
    throw ConfigError(std::string(function) + ": " + what + " must not be negative (got " +
                      detail::number_text(v) + ")");
}

/// Relative standard error of a product of powers of independent factors:
/// sqrt(sum (power_i * se_i / x_i)^2).
double relative_se(std::initializer_list<double> relative_terms) {
  double s = 0;
  for (const double t : relative_terms) s += t * t;
  return std::sqrt(s);
}

}  // namespace

FreeAirResult free_air_from(double omega_n_rad_per_s, double zeta, double k_v_N_per_m,
                            double omega_n_se, double zeta_se) {
  constexpr const char* fn = "free_air_from";
  require_positive(fn, "omega_n", omega_n_rad_per_s, "rad/s");
  require_positive(fn, "zeta", zeta, "");
  require_positive(fn, "k_v", k_v_N_per_m, "N/m");
  require_non_negative(fn, "the standard error of omega_n", omega_n_se);
  require_non_negative(fn, "the standard error of zeta", zeta_se);
  FreeAirResult r;
  r.omega_n_rad_per_s = omega_n_rad_per_s;
  r.zeta = zeta;
  r.k_v_N_per_m = k_v_N_per_m;
  r.m_v_kg = k_v_N_per_m / (omega_n_rad_per_s * omega_n_rad_per_s);
  r.b_v_N_s_per_m = 2.0 * zeta * k_v_N_per_m / omega_n_rad_per_s;
  const double rel_w = omega_n_se / omega_n_rad_per_s, rel_z = zeta_se / zeta;
  r.m_v_kg_se = r.m_v_kg * 2.0 * rel_w;
  r.b_v_N_s_per_m_se = r.b_v_N_s_per_m * relative_se({rel_z, rel_w});
  return r;
}

Decomposition decompose(const SecondOrderFit& fit, double k_o_N_per_m,
                        const InstrumentDynamics& instrument, double k_o_se_N_per_m) {
  constexpr const char* fn = "decompose";
  require_positive(fn, "the fit's omega_n", fit.omega_n_rad_per_s, "rad/s");
  require_positive(fn, "the fit's zeta", fit.zeta, "");
  require_positive(fn, "k_o", k_o_N_per_m, "N/m");
  require_non_negative(fn, "the standard error of k_o", k_o_se_N_per_m);
  const double wn = fit.omega_n_rad_per_s;
  Decomposition d;
  d.k_o_N_per_m = k_o_N_per_m;
  d.k_eff_N_per_m = instrument.k_v_N_per_m + k_o_N_per_m;
  d.m_eff_kg = d.k_eff_N_per_m / (wn * wn);
  d.b_total_N_s_per_m = 2.0 * fit.zeta * d.k_eff_N_per_m / wn;
  d.b_o_N_s_per_m = d.b_total_N_s_per_m - instrument.b_v_N_s_per_m;
  d.m_o_kg = d.m_eff_kg - instrument.m_v_kg;
  const double rel_k = k_o_se_N_per_m / d.k_eff_N_per_m;
  const double rel_w = fit.omega_n_rad_per_s_se / wn, rel_z = fit.zeta_se / fit.zeta;
  d.m_eff_kg_se = d.m_eff_kg * relative_se({rel_k, 2.0 * rel_w});
  d.b_total_N_s_per_m_se = d.b_total_N_s_per_m * relative_se({rel_k, rel_z, rel_w});
  d.b_o_N_s_per_m_se = d.b_total_N_s_per_m_se;  // b_v is taken as known
  return d;
}

Viscoelastic viscoelastic_from(std::span<const FrfLine> lines, const InstrumentDynamics& instrument,
                               double delta0_m, double tip_radius_m) {
  constexpr const char* fn = "viscoelastic_from";
  require_positive(fn, "delta0", delta0_m, "m");
  require_positive(fn, "the tip radius", tip_radius_m, "m");
  Viscoelastic v;
  v.delta0_m = delta0_m;
  v.tip_radius_m = tip_radius_m;
  v.contact_radius_m = sneddon_contact_radius_m(delta0_m, tip_radius_m);
  if (delta0_m > tip_radius_m / 2) {
    v.flagged = true;
    v.flag_reason = "delta0 = " + detail::number_text(delta0_m * 1e3) + " mm is more than half the tip radius (" +
                    detail::number_text(tip_radius_m * 1e3) +
                    " mm): the moduli rest on the contact radius of a deep indentation (a = " +
                    detail::number_text(v.contact_radius_m * 1e3) + " mm from the Sneddon sphere)";
  }
  const double two_a = 2.0 * v.contact_radius_m;
  v.lines.reserve(lines.size());
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const FrfLine& l = lines[i];
    if (l.G_m_per_N == std::complex<double>(0, 0) || !std::isfinite(std::abs(l.G_m_per_N)))
      throw ConfigError(std::string(fn) + ": line " + std::to_string(i + 1) + " (f_Hz " +
                        detail::number_text(l.f_Hz) + ") has G = " + (l.G_m_per_N == 0.0 ? "0" : "a non-finite value"));
    const double w = 2.0 * std::numbers::pi * l.f_Hz;
    const std::complex<double> instrument_D(
        instrument.k_v_N_per_m - instrument.m_v_kg * w * w, instrument.b_v_N_s_per_m * w);
    const std::complex<double> k_star = 1.0 / l.G_m_per_N - instrument_D;
    ViscoelasticLine out;
    out.f_Hz = l.f_Hz;
    out.k_storage_N_per_m = k_star.real();
    out.k_loss_N_per_m = k_star.imag();
    out.E_storage_Pa = k_star.real() / two_a;
    out.E_loss_Pa = k_star.imag() / two_a;
    out.tan_delta = k_star.imag() / k_star.real();
    v.lines.push_back(out);
  }
  return v;
}

}  // namespace palp::analysis
