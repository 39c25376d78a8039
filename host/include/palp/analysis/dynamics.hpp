// SPDX-License-Identifier: Apache-2.0
// From a fitted second-order model to what the paper reports (issue 7; paper §III-A, §IV-B;
// analysis-notes.md "Viscoelastic outputs"): the instrument's own m_v, b_v from free air, the
// effective mass and the object's damping in contact, and beyond the paper the complex contact
// stiffness with E'(w), E''(w) and tan delta. SI units.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "palp/analysis/frf.hpp"
#include "palp/analysis/second_order.hpp"

namespace palp::analysis {

/// The instrument's own dynamics (paper §IV-B free-air values; k_v from §II-A).
struct InstrumentDynamics {
  double m_v_kg = 0.1609;
  double b_v_N_s_per_m = 1.379;
  double k_v_N_per_m = 43.9;
};

/// Free air: m_v = k_v / w_n^2, b_v = 2 zeta k_v / w_n (the paper's route, with the spring's
/// stiffness), standard errors by the delta method (omega_n and zeta taken as independent).
struct FreeAirResult {
  double omega_n_rad_per_s = 0, zeta = 0, k_v_N_per_m = 0;
  double m_v_kg = 0, b_v_N_s_per_m = 0;
  double m_v_kg_se = 0, b_v_N_s_per_m_se = 0;
};
/// ConfigError for non-positive omega_n, zeta or k_v, or negative standard errors.
FreeAirResult free_air_from(double omega_n_rad_per_s, double zeta, double k_v_N_per_m,
                            double omega_n_se = 0, double zeta_se = 0);

/// Contact decomposition with the static tangent stiffness k_o at the same bias (paper §IV-B):
/// k_eff = k_v + k_o, m_eff = k_eff / w_n^2, b_total = 2 zeta k_eff / w_n, b_o = b_total - b_v,
/// m_o = m_eff - m_v. m_eff folds any viscoelastic stiffening into an apparent mass (as the
/// paper computes it); the fit's own m and k are reported beside it. Standard errors by the
/// delta method from k_o_se and the fit's omega_n and zeta errors, taken as independent (their
/// correlation in a fit is small, ~0.05-0.2); b_v is taken as known.
struct Decomposition {
  double k_o_N_per_m = 0, k_eff_N_per_m = 0;
  double m_eff_kg = 0, b_total_N_s_per_m = 0, b_o_N_s_per_m = 0, m_o_kg = 0;
  double m_eff_kg_se = 0, b_total_N_s_per_m_se = 0, b_o_N_s_per_m_se = 0;
};
/// ConfigError for a non-positive k_o or a fit without omega_n.
Decomposition decompose(const SecondOrderFit& fit, double k_o_N_per_m,
                        const InstrumentDynamics& instrument, double k_o_se_N_per_m = 0);

/// The complex contact stiffness at one line and the moduli from it.
struct ViscoelasticLine {
  double f_Hz = 0;
  double k_storage_N_per_m = 0;   ///< k' = Re{F/Z - (k_v - m_v w^2 + j b_v w)}
  double k_loss_N_per_m = 0;      ///< k''
  double E_storage_Pa = 0;        ///< E*' = k' / (2a)
  double E_loss_Pa = 0;           ///< E*'' = k'' / (2a)
  double tan_delta = 0;           ///< k'' / k'
};
struct Viscoelastic {
  double delta0_m = 0, tip_radius_m = 0;
  double contact_radius_m = 0;    ///< a from the Sneddon sphere: delta0 = (a/2) ln((R+a)/(R-a))
  /// delta0 > R/2: the moduli rest on the contact radius of a deep indentation (expected at the
  /// paper's own operating points); `flag_reason` says so.
  bool flagged = false;
  std::string flag_reason;
  std::vector<ViscoelasticLine> lines;
};
/// ConfigError for delta0 <= 0, R <= 0, or a line with G == 0.
Viscoelastic viscoelastic_from(std::span<const FrfLine> lines, const InstrumentDynamics& instrument,
                               double delta0_m, double tip_radius_m);

}  // namespace palp::analysis
