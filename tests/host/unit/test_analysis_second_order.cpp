// SPDX-License-Identifier: Apache-2.0
// The second-order fit on synthetic responses of known m, b, k: exact without noise, unbiased and
// with honest standard errors under noise (where the linear start is biased), a normalised cost
// that rejects a wrong model, and the input checks with their exact text.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <random>
#include <vector>

#include "palp/analysis/second_order.hpp"
#include "palp/error.hpp"

namespace {

namespace an = palp::analysis;
using cd = std::complex<double>;

struct Truth {
  double m, b, k;
  double omega_n() const { return std::sqrt(k / m); }
  double zeta() const { return b / (2.0 * std::sqrt(k * m)); }
};
constexpr Truth kFreeAir{0.161, 1.38, 43.9};
constexpr Truth kContact{0.175, 3.0, 790.0};

double w_of(double f) { return 2.0 * std::numbers::pi * f; }

/// Lines from f0 to f1 (inclusive) every df of G(jw) times `shape`, plus complex noise of sd
/// sigma in Re and in Im (seeded); sigma_m_per_N is set to `sigma` (or `given_sigma` if >= 0).
template <class Shape>
std::vector<an::FrfLine> lines_of(const Truth& t, double sigma, unsigned seed, Shape shape,
                                  double df = 0.2, double f0 = 2.0, double f1 = 20.0) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::vector<an::FrfLine> out;
  const int n = static_cast<int>(std::lround((f1 - f0) / df));
  for (int i = 0; i <= n; ++i) {
    an::FrfLine l;
    l.f_Hz = f0 + df * i;
    const double w = w_of(l.f_Hz);
    l.G_m_per_N = shape(w) / cd(t.k - t.m * w * w, t.b * w);
    l.G_m_per_N += sigma * cd(noise(rng), noise(rng));
    l.sigma_m_per_N = sigma;
    out.push_back(l);
  }
  return out;
}
std::vector<an::FrfLine> lines_of(const Truth& t, double sigma, unsigned seed = 1) {
  return lines_of(t, sigma, seed, [](double) { return cd(1.0, 0.0); });
}

TEST(SecondOrderFit, RecoversMBKExactlyWithoutNoise) {
  for (const Truth& t : {kFreeAir, kContact}) {
    std::vector<an::FrfLine> lines = lines_of(t, 0.0);
    for (an::FrfLine& l : lines) l.sigma_m_per_N = 1e-6;  // weights, but exact data
    const an::SecondOrderFit fit = an::fit_second_order(lines);
    EXPECT_NEAR(fit.m_kg / t.m, 1.0, 1e-9);
    EXPECT_NEAR(fit.b_N_s_per_m / t.b, 1.0, 1e-9);
    EXPECT_NEAR(fit.k_N_per_m / t.k, 1.0, 1e-9);
    EXPECT_NEAR(fit.omega_n_rad_per_s / t.omega_n(), 1.0, 1e-9);
    EXPECT_NEAR(fit.zeta / t.zeta(), 1.0, 1e-9);
    EXPECT_TRUE(fit.converged);
    EXPECT_EQ(fit.lines, 91u);
    ASSERT_TRUE(fit.normalized_cost);
    EXPECT_LT(*fit.normalized_cost, 1e-12);
    EXPECT_NEAR(std::abs(fit.G(7.3) - 1.0 / cd(t.k - t.m * w_of(7.3) * w_of(7.3), t.b * w_of(7.3))),
                0.0, 1e-9 * std::abs(fit.G(7.3)));
  }
}

TEST(SecondOrderFit, WithoutSigmaTheCostIsUnknownAndTheFitStillExact) {
  std::vector<an::FrfLine> lines = lines_of(kContact, 0.0);
  const an::SecondOrderFit fit = an::fit_second_order(lines);
  EXPECT_NEAR(fit.omega_n_rad_per_s / kContact.omega_n(), 1.0, 1e-9);
  EXPECT_NEAR(fit.zeta / kContact.zeta(), 1.0, 1e-9);
  EXPECT_FALSE(fit.normalized_cost.has_value());
  EXPECT_TRUE(fit.adequate);
}

// 50 seeds of noise: each fit lies within a few of its own standard errors, the SEs match the
// scatter of the estimates within 30 %, and the cost is ~1. The linear start (dividing by noisy G
// where |G| is small) is biased by many of its spreads, the full fit is not.
void check_noise_statistics(const Truth& t, double sigma) {
  constexpr int kSeeds = 50;
  std::vector<double> wn, z, m_start;
  double se_wn = 0, se_z = 0, se_m = 0, mean_m = 0, cost = 0;
  for (int s = 0; s < kSeeds; ++s) {
    const an::SecondOrderFit fit = an::fit_second_order(lines_of(t, sigma, 100u + static_cast<unsigned>(s)));
    ASSERT_TRUE(fit.converged);
    EXPECT_LT(std::abs(fit.omega_n_rad_per_s - t.omega_n()), 4.5 * fit.omega_n_rad_per_s_se);
    EXPECT_LT(std::abs(fit.zeta - t.zeta()), 4.5 * fit.zeta_se);
    wn.push_back(fit.omega_n_rad_per_s);
    z.push_back(fit.zeta);
    m_start.push_back(fit.m_start_kg);
    se_m += fit.m_kg_se / kSeeds;
    mean_m += fit.m_kg / kSeeds;
    se_wn += fit.omega_n_rad_per_s_se / kSeeds;
    se_z += fit.zeta_se / kSeeds;
    cost += *fit.normalized_cost / kSeeds;
  }
  const auto mean = [](const std::vector<double>& v) {
    double s = 0;
    for (double x : v) s += x;
    return s / static_cast<double>(v.size());
  };
  const auto sd = [&](const std::vector<double>& v) {
    const double mu = mean(v);
    double s = 0;
    for (double x : v) s += (x - mu) * (x - mu);
    return std::sqrt(s / static_cast<double>(v.size() - 1));
  };
  EXPECT_NEAR(sd(wn) / se_wn, 1.0, 0.3);
  EXPECT_NEAR(sd(z) / se_z, 1.0, 0.3);
  EXPECT_NEAR(cost, 1.0, 0.1);
  // unbiased: the mean of 50 within 3 standard errors of a mean
  EXPECT_LT(std::abs(mean(wn) - t.omega_n()), 3.0 * se_wn / std::sqrt(kSeeds));
  EXPECT_LT(std::abs(mean(z) - t.zeta()), 3.0 * se_z / std::sqrt(kSeeds));
  // the linear start (it under-estimates m: 1/G of the noisy high lines shrinks towards 0):
  // its bias is several times the spread of its mean and the fit's own standard error
  const double start_bias = t.m - mean(m_start);
  EXPECT_GT(start_bias, 4.0 * sd(m_start) / std::sqrt(kSeeds));
  EXPECT_GT(start_bias, 3.0 * se_m);
  EXPECT_LT(std::abs(mean_m - t.m), 3.0 * se_m / std::sqrt(kSeeds));  // where the fit is not
}

TEST(SecondOrderFit, FreeAirUnderNoiseIsUnbiasedWithHonestErrorsWhereTheLinearStartIsBiased) {
  check_noise_statistics(kFreeAir, 3e-4);  // 0.7 % of the resonance peak, |G| / 1.3 at 20 Hz
}

TEST(SecondOrderFit, ContactUnderNoiseIsUnbiasedWithHonestErrorsWhereTheLinearStartIsBiased) {
  check_noise_statistics(kContact, 3e-4);  // 6 % of the resonance peak, |G| / 1.7 at 20 Hz
}

TEST(SecondOrderFit, AThirdOrderSystemIsNotAdequate) {
  // an extra pole at 8 Hz: G = 1 / ((m s^2 + b s + k)(1 + s / w_p))
  const double wp = w_of(8.0);
  const auto lines = lines_of(kContact, 2e-6, 7, [wp](double w) { return 1.0 / cd(1.0, w / wp); });
  const an::SecondOrderFit fit = an::fit_second_order(lines);
  ASSERT_TRUE(fit.normalized_cost);
  EXPECT_GT(*fit.normalized_cost, 100.0);
  EXPECT_FALSE(fit.adequate);
}

TEST(SecondOrderFit, AFrequencyDependentStiffnessIsNotAdequate) {
  // Kelvin-Voigt with k(w) = k (1 + 0.15 ln(w / w_10Hz)): divide G by the extra stiffness ratio
  const Truth t = kContact;
  const auto shape = [&t](double w) {
    const cd D(t.k - t.m * w * w, t.b * w);
    const cd D2(t.k * (1.0 + 0.15 * std::log(w / w_of(10.0))) - t.m * w * w, t.b * w);
    return D / D2;
  };
  const auto lines = lines_of(t, 2e-6, 8, shape);
  const an::SecondOrderFit fit = an::fit_second_order(lines);
  ASSERT_TRUE(fit.normalized_cost);
  EXPECT_GT(*fit.normalized_cost, 100.0);
  EXPECT_FALSE(fit.adequate);
  // the same data with a correctly sized noise model on the true system is adequate
  const an::SecondOrderFit right = an::fit_second_order(lines_of(t, 2e-6, 8));
  EXPECT_TRUE(right.adequate);
}

TEST(SecondOrderFit, PureNoiseEndsWithFinitePositiveParametersAndNotAdequate) {
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 1e-3);
  std::vector<an::FrfLine> lines;
  for (int i = 0; i < 40; ++i) {
    an::FrfLine l;
    l.f_Hz = 2.0 + 0.5 * i;
    l.G_m_per_N = cd(noise(rng), noise(rng));
    l.sigma_m_per_N = 1e-5;
    lines.push_back(l);
  }
  const an::SecondOrderFit fit = an::fit_second_order(lines);
  for (const double v : {fit.m_kg, fit.b_N_s_per_m, fit.k_N_per_m, fit.omega_n_rad_per_s, fit.zeta}) {
    EXPECT_TRUE(std::isfinite(v));
    EXPECT_GT(v, 0.0);
  }
  ASSERT_TRUE(fit.normalized_cost);
  EXPECT_GT(*fit.normalized_cost, 100.0);
  EXPECT_FALSE(fit.adequate);
  EXPECT_LE(fit.lm_iterations, an::SecondOrderOptions{}.max_lm_iterations);
}

TEST(SecondOrderFit, RefusesBadLinesNamingThem) {
  const auto message = [](std::vector<an::FrfLine> lines) {
    try {
      an::fit_second_order(lines);
    } catch (const palp::DataError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  std::vector<an::FrfLine> good = lines_of(kFreeAir, 1e-4);
  EXPECT_EQ(message({good[0], good[1]}), "the second-order fit needs at least 3 lines, got 2");
  auto bad = good;
  bad[2].f_Hz = 0.0;
  EXPECT_EQ(message(bad), "second-order fit: line 3 (f_Hz 0) has a frequency that is not positive");
  bad = good;
  bad[1].G_m_per_N = cd(std::nan(""), 0.0);
  EXPECT_EQ(message(bad), "second-order fit: line 2 (f_Hz 2.2) has a non-finite value");
  bad = good;
  bad[4].sigma_m_per_N = -1e-4;
  EXPECT_EQ(message(bad), "second-order fit: line 5 (f_Hz 2.8) has a negative sigma");
  bad = good;
  bad[3].sigma_m_per_N = 0.0;
  EXPECT_EQ(message(bad),
            "second-order fit: line 4 (f_Hz 2.6) has no sigma where line 1 has one; give every "
            "line a sigma or none");
}

}  // namespace
