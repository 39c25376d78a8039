// SPDX-License-Identifier: Apache-2.0
// Nonparametric frequency responses (frequency_response.hpp) against synthetic recordings built
// from the device's exact program waveforms (program_schedule.hpp, multisine.hpp): a known
// linear G(jw) in steady state on every line, the stream decimated 20 from 20 kHz, the program
// starting between two samples, i_cmd quantised to the stream's 0.2 mA, seeded noise.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <random>

#include "palp/analysis/frequency_response.hpp"
#include "palp/error.hpp"
#include "palp/fw/multisine_synth.hpp"
#include "palp/fw/program_kinds.hpp"
#include "palp/fw/programs.hpp"
#include "palp/protocol/multisine.hpp"
#include "palp/protocol/program_schedule.hpp"
#include "palp/protocol/stream.hpp"

namespace {

namespace an = palp::analysis;
namespace proto = palp::proto;
using cplx = std::complex<double>;
using ::testing::HasSubstr;

constexpr double kTwoPi = 6.283185307179586476925;
constexpr std::uint32_t kRate = 20000;
constexpr std::int64_t kDecimation = 20;
constexpr double kKf = 2.918;

/// The paper's free-air probe: G = 1 / (k - m w^2 + j b w), m/N (passive: Im G <= 0).
cplx g_true(double f_Hz) {
  const double w = kTwoPi * f_Hz;
  return 1.0 / cplx(43.9 - 0.161 * w * w, 1.38 * w);
}
/// The current loop's response from i_cmd to i_A: a little gain and lag.
cplx c_loop(double f_Hz) { return 0.98 * std::polar(1.0, -0.002 * f_Hz); }

struct Synth {
  std::int64_t stream_start_tick = 12345 * kDecimation;  // the stream's first sample
  std::int64_t program_offset_ticks = 8013;  // program start - stream start: not on a sample
  double after_s = 0.3;                       // recorded after the program
  double z0_m = 0.0123;                       // mean position
  double noise_i_A = 0, noise_z_m = 0;
  double quadratic_per_m = 0;  // z - z0 += this (z - z0)^2
  unsigned seed = 20261123;
  std::int64_t t0() const { return stream_start_tick + program_offset_ticks; }
};

/// A recording of `program_ticks` program ticks. drive(k) gives, for program tick k, the
/// commanded deviation from the offset and the complex per-line terms of the linear response:
/// i_cmd = offset + u, i_A = offset + Re sum I_n, z = z0 + Re sum G_n Kf I_n.
struct Drive {
  double u = 0;
  cplx i = 0, z = 0;  // already summed: Re{i} and Re{z}
};
template <class F>
palp::Recording record(const Synth& s, double offset_A, std::int64_t program_ticks, F drive) {
  std::mt19937 rng(s.seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  palp::Recording rec;
  const std::int64_t end = s.program_offset_ticks + program_ticks +
                           static_cast<std::int64_t>(s.after_s * kRate);
  for (std::int64_t t = 0; t < end; t += kDecimation) {
    const std::int64_t tick = s.stream_start_tick + t;
    const std::int64_t k = tick - s.t0();
    Drive d;
    if (k >= 0 && k < program_ticks) d = drive(k);
    const double i_cmd = offset_A + d.u;
    double dz = d.z.real();
    dz += s.quadratic_per_m * dz * dz;
    palp::RecordingRow row;
    row.sample_index = static_cast<std::uint64_t>(t / kDecimation);
    row.t_s = static_cast<double>(tick * 1'000'000 / kRate) / 1e6;
    row.i_cmd_A = std::round(i_cmd / proto::kCurrentLsb_A) * proto::kCurrentLsb_A;
    row.i_A = offset_A + d.i.real() + s.noise_i_A * normal(rng);
    row.z_mm = (s.z0_m + dz + s.noise_z_m * normal(rng)) * 1e3;
    rec.append(row);
  }
  return rec;
}

// ---- stepped sine ---------------------------------------------------------------------------

struct SweepLineTicks {
  std::int64_t begin, end;
  std::uint32_t increment;
};
std::vector<SweepLineTicks> sweep_schedule(const proto::LoadSweep& m) {
  const proto::SweepPlan p = proto::sweep_plan(m, kRate);
  std::vector<SweepLineTicks> v;
  std::int64_t t = 0;
  for (std::uint32_t j = 0; j < p.lines; ++j) {
    const proto::SweepLine l = proto::sweep_line(p, j);
    const auto n = static_cast<std::int64_t>(proto::sweep_line_ticks(l));
    v.push_back({t, t + n, l.increment});
    t += n;
  }
  return v;
}

double realised_Hz(std::uint32_t increment) { return increment * double{kRate} / 4294967296.0; }

palp::Recording sweep_recording(const proto::LoadSweep& m, const Synth& s) {
  const auto lines = sweep_schedule(m);
  std::size_t j = 0;
  return record(s, m.offset_A, lines.back().end, [&](std::int64_t k) {
    while (k >= lines[j].end) ++j;
    const double f = realised_Hz(lines[j].increment);
    const auto phase = static_cast<std::uint32_t>(
        static_cast<std::uint64_t>(k - lines[j].begin) * lines[j].increment);
    const cplx e = std::polar(1.0, kTwoPi * (phase / 4294967296.0));
    // the command is A sin(theta) = Re{-j A e^{j theta}}
    const cplx I = cplx(0, -1) * static_cast<double>(m.amplitude_A) * c_loop(f);
    Drive d;
    d.u = (cplx(0, -1) * static_cast<double>(m.amplitude_A) * e).real();
    d.i = I * e;
    d.z = g_true(f) * kKf * I * e;
    return d;
  });
}

proto::LoadSweep short_sweep() {  // 2, 2.5, ... 6 Hz
  proto::LoadSweep m;
  m.start_Hz = 2.0f;
  m.stop_Hz = 6.0f;
  m.step_Hz = 0.5f;
  return m;
}

TEST(SteppedSineFrf, NoiseFreePaperSweepGivesEveryLineToOnePartIn1e9) {
  const proto::LoadSweep m;  // the paper's: 2 ... 20 Hz by 0.05 Hz, 361 lines
  const Synth s;
  const an::Frf frf = an::stepped_sine_frf(sweep_recording(m, s), m, kRate);
  ASSERT_EQ(frf.lines.size(), 361u);
  EXPECT_EQ(frf.method, "stepped_sine");
  EXPECT_DOUBLE_EQ(frf.line_spacing_Hz, 0.05f);
  EXPECT_DOUBLE_EQ(frf.device_time_s, an::program_duration_s(m, kRate));
  const auto lines = sweep_schedule(m);
  double worst = 0;
  for (std::size_t j = 0; j < lines.size(); ++j) {
    const an::FrfLine& l = frf.lines[j];
    const double f = realised_Hz(lines[j].increment);
    EXPECT_DOUBLE_EQ(l.f_Hz, f);
    const cplx I = cplx(0, -1) * static_cast<double>(m.amplitude_A) * c_loop(f);  // exact phases
    worst = std::max(worst, std::abs(l.G_m_per_N - g_true(f)) / std::abs(g_true(f)));
    EXPECT_LT(std::abs(l.F_N - kKf * I), 1e-9 * std::abs(kKf * I)) << j;
    EXPECT_NEAR(l.z_mean_m, s.z0_m, 1e-6) << j;
    EXPECT_LE(l.G_m_per_N.imag(), 0.0) << j;
  }
  EXPECT_LT(worst, 1e-9);
}

TEST(SteppedSineFrf, WithNoiseEveryLineIsWithinItsSigmaAndSigmaIsTheScatter) {
  const proto::LoadSweep m;
  Synth s;
  s.noise_i_A = 2e-3;   // the plant's current-sense noise
  s.noise_z_m = 1e-6;   // an encoder count
  const an::Frf frf = an::stepped_sine_frf(sweep_recording(m, s), m, kRate);
  double chi2 = 0;
  for (const an::FrfLine& l : frf.lines) {
    const cplx e = l.G_m_per_N - g_true(l.f_Hz);
    ASSERT_GT(l.sigma_m_per_N, 0.0);
    EXPECT_LT(std::abs(e.real()), 4.5 * l.sigma_m_per_N) << l.f_Hz;
    EXPECT_LT(std::abs(e.imag()), 4.5 * l.sigma_m_per_N) << l.f_Hz;
    chi2 += std::norm(e) / (l.sigma_m_per_N * l.sigma_m_per_N);
  }
  const double reduced = chi2 / (2.0 * static_cast<double>(frf.lines.size()));
  EXPECT_GT(reduced, 0.85);  // 722 components: +-0.05 at one sigma
  EXPECT_LT(reduced, 1.15);
}

TEST(SteppedSineFrf, AProgramStartingBeforeTheFirstSampleIsFound) {
  // the experiment keeps only the samples with program_running set: the first sample is
  // already inside the program, the start up to one sample interval before it
  const proto::LoadSweep m = short_sweep();
  Synth s;
  s.program_offset_ticks = -13;
  const an::Frf frf = an::stepped_sine_frf(sweep_recording(m, s), m, kRate);
  ASSERT_EQ(frf.lines.size(), 9u);
  for (const an::FrfLine& l : frf.lines)
    EXPECT_LT(std::abs(l.G_m_per_N - g_true(l.f_Hz)), 1e-9 * std::abs(g_true(l.f_Hz)));
}

TEST(SteppedSineFrf, AControlRateTheDeviceDoesNotRunIsAConfigError) {
  const proto::LoadSweep m = short_sweep();
  const palp::Recording rec = sweep_recording(m, Synth{});
  try {
    an::stepped_sine_frf(rec, m, 1000);  // the stream's rate, not the control rate
    FAIL();
  } catch (const palp::ConfigError& e) {
    EXPECT_STREQ(e.what(), "stepped_sine_frf: control rate 1000 Hz is not one the device runs at "
                           "(20000 or 40000 Hz)");
  }
}

TEST(SteppedSineFrf, SamplesOffTheControlTickGridAreADataError) {
  const proto::LoadSweep m = short_sweep();
  palp::Recording rec = sweep_recording(m, Synth{});
  rec.t_s[1] = rec.t_s[0] + 25e-6;  // half a tick at 20 kHz
  try {
    an::stepped_sine_frf(rec, m, kRate);
    FAIL();
  } catch (const palp::DataError& e) {
    EXPECT_STREQ(e.what(), "stepped_sine_frf: t_s at sample 1 (12.345025 s) is not on the "
                           "control-tick grid of 20000 Hz: is the control rate right?");
  }
}

TEST(SteppedSineFrf, ATruncatedRecordingIsADataErrorNamingTheTimes) {
  const proto::LoadSweep m = short_sweep();
  const Synth s;
  palp::Recording whole = sweep_recording(m, s), rec;
  const double end_s = static_cast<double>(s.t0()) / kRate + 20.0;  // well inside the sweep
  for (std::size_t k = 0; k < whole.size() && whole.t_s[k] <= end_s; ++k)
    rec.append({.sample_index = k, .t_s = whole.t_s[k], .i_cmd_A = (*whole.i_cmd_A)[k],
                .i_A = whole.i_A[k], .z_mm = whole.z_mm[k]});
  // the stream starts at tick 246900 (12.345 s); the program 8013 ticks later (12.74565 s)
  const double duration = an::program_duration_s(m, kRate);
  EXPECT_GT(duration, 20.0);
  char expected[200];
  std::snprintf(expected, sizeof expected,
                "stepped_sine_frf: the recording ends at %.6f s, before the program does "
                "(%.6f s; it started at 12.745650 s)",
                rec.t_s.back(), 12.74565 + duration);
  try {
    an::stepped_sine_frf(rec, m, kRate);
    FAIL();
  } catch (const palp::DataError& e) {
    EXPECT_EQ(std::string(e.what()), expected);
    EXPECT_THAT(e.what(), HasSubstr("the recording ends at 32.745000 s"));
  }
}

TEST(SteppedSineFrf, ARecordingWithoutTheCommandedCurrentOrWithANaNIsADataError) {
  const proto::LoadSweep m = short_sweep();
  palp::Recording rec = sweep_recording(m, Synth{});
  rec.i_cmd_A.reset();
  EXPECT_THROW(an::stepped_sine_frf(rec, m, kRate), palp::DataError);
  rec = sweep_recording(m, Synth{});
  rec.z_mm[100] = std::nan("");
  try {
    an::stepped_sine_frf(rec, m, kRate);
    FAIL();
  } catch (const palp::DataError& e) {
    EXPECT_STREQ(e.what(), "stepped_sine_frf: z_mm is not a finite number at sample 100");
  }
}

// ---- multisine --------------------------------------------------------------------------------

/// The lines as the device plays them: harmonic and phase (turns).
struct MsLine {
  std::uint32_t h;
  double phase_turns;
};
std::vector<MsLine> ms_lines(const proto::LoadMultisine& m) {
  const std::uint32_t K = proto::multisine_line_count(m.line_first, m.line_last, m.line_step);
  std::vector<MsLine> v;
  for (std::uint32_t n = 0; n < K; ++n)
    v.push_back({m.line_first + n * m.line_step,
                 proto::multisine_phase_turns(m.phase_mode, m.phase_seed, n, K) / 4294967296.0});
  return v;
}

/// Periodic steady state of G from the first tick (a linear system driven periodically).
palp::Recording multisine_recording(const proto::LoadMultisine& m, const Synth& s) {
  const auto lines = ms_lines(m);
  const std::uint32_t P = proto::multisine_period_ticks(m.fundamental_Hz, kRate);
  const double A = m.line_amplitude_A;
  return record(s, m.offset_A, std::int64_t{m.periods} * P, [&](std::int64_t k) {
    Drive d;
    for (const MsLine& l : lines) {
      const double f = l.h * double{kRate} / P;
      const double turns = static_cast<double>((l.h * static_cast<std::uint64_t>(k)) % P) / P;
      const cplx e = std::polar(1.0, kTwoPi * (turns + l.phase_turns));
      d.u += A * e.real();
      d.i += A * c_loop(f) * e;
      d.z += g_true(f) * kKf * A * c_loop(f) * e;
    }
    return d;
  });
}

proto::LoadMultisine small_multisine() {  // 0.5 Hz fundamental, 25 lines 2.5 ... 50.5 Hz
  proto::LoadMultisine m;
  m.fundamental_Hz = 0.5f;
  m.line_first = 5;
  m.line_last = 101;
  m.line_step = 4;
  m.line_amplitude_A = 0.01f;
  m.periods = 11;
  return m;
}

TEST(MultisineFrf, NoiseFreeDefaultProgramGivesTheExcitedLinesExactly) {
  proto::LoadMultisine m;  // the default: 0.05 Hz, lines 41 ... 397 by 4 (90), 3 periods
  const Synth s;
  const an::Frf frf = an::multisine_frf(multisine_recording(m, s), m, kRate);
  ASSERT_EQ(frf.lines.size(), 90u);
  EXPECT_EQ(frf.method, "multisine");
  EXPECT_DOUBLE_EQ(frf.line_spacing_Hz, 0.2);
  EXPECT_DOUBLE_EQ(frf.device_time_s, 60.0);
  EXPECT_DOUBLE_EQ(frf.device_time_s, an::program_duration_s(m, kRate));
  const auto lines = ms_lines(m);
  for (std::size_t n = 0; n < lines.size(); ++n) {
    const an::FrfLine& l = frf.lines[n];
    EXPECT_DOUBLE_EQ(l.f_Hz, lines[n].h * 0.05);
    EXPECT_LT(std::abs(l.G_m_per_N - g_true(l.f_Hz)), 1e-9 * std::abs(g_true(l.f_Hz))) << n;
    // phasors against the period's start: the program's own line phases
    const cplx F = kKf * static_cast<double>(m.line_amplitude_A) * c_loop(l.f_Hz) *
                   std::polar(1.0, kTwoPi * lines[n].phase_turns);
    EXPECT_LT(std::abs(l.F_N - F), 1e-9 * std::abs(F)) << n;
  }
  ASSERT_TRUE(frf.distortion);
  EXPECT_LT(frf.distortion->even_ratio, 1e-9);
  EXPECT_LT(frf.distortion->odd_ratio, 1e-9);
  EXPECT_FALSE(frf.distortion->too_large);
}

TEST(MultisineFrf, WithNoiseSigmaMatchesTheScatterOfTheLines) {
  const proto::LoadMultisine m = small_multisine();  // 10 measured periods
  Synth s;
  s.noise_i_A = 2e-3;
  s.noise_z_m = 2e-6;
  double sum_e2 = 0, sum_s2 = 0;
  int outside = 0;
  for (unsigned seed = 1; seed <= 4; ++seed) {  // 4 x 25 lines x 2 components
    s.seed = seed;
    const an::Frf frf = an::multisine_frf(multisine_recording(m, s), m, kRate);
    for (const an::FrfLine& l : frf.lines) {
      const cplx e = l.G_m_per_N - g_true(l.f_Hz);
      sum_e2 += std::norm(e);
      sum_s2 += 2 * l.sigma_m_per_N * l.sigma_m_per_N;
      const double s3 = 3 * l.sigma_m_per_N;
      outside += std::abs(e.real()) > s3 || std::abs(e.imag()) > s3;
    }
    EXPECT_GT(frf.distortion->noise_rms_m, 0.0);
  }
  const double ratio = std::sqrt(sum_e2 / sum_s2);  // rms error / rms sigma
  EXPECT_GT(ratio, 0.85);
  EXPECT_LT(ratio, 1.15);
  EXPECT_LE(outside, 6);  // of 200 components; 9 % of sigmas from 9 dof stretch the tails
}

TEST(MultisineFrf, AQuadraticNonlinearityShowsAsEvenDistortionNotOdd) {
  const proto::LoadMultisine m = small_multisine();
  Synth s;
  s.quadratic_per_m = 20.0;  // z - z0 += 20/m (z - z0)^2: a few % at ~1 mm
  const an::Frf small = an::multisine_frf(multisine_recording(m, s), m, kRate);
  ASSERT_TRUE(small.distortion);
  EXPECT_GT(small.distortion->even_ratio, 0.005);
  EXPECT_LT(small.distortion->even_ratio, 0.05);
  EXPECT_LT(small.distortion->odd_ratio, 1e-9);
  EXPECT_FALSE(small.distortion->too_large);
  EXPECT_EQ(small.distortion->warning, "");

  s.quadratic_per_m = 200.0;
  const an::Frf large = an::multisine_frf(multisine_recording(m, s), m, kRate);
  EXPECT_NEAR(large.distortion->even_ratio, 10 * small.distortion->even_ratio,
              0.01 * large.distortion->even_ratio);  // proportional
  EXPECT_LT(large.distortion->odd_ratio, 1e-9);
  EXPECT_TRUE(large.distortion->too_large);
  EXPECT_THAT(large.distortion->warning, HasSubstr("the multisine's even-order distortion is "));
  EXPECT_THAT(large.distortion->warning, HasSubstr("(limit 5.0 %)"));
}

TEST(MultisineFrf, APeriodWithAGapInTheStreamIsLeftOutAndNoted) {
  const proto::LoadMultisine m = small_multisine();
  const Synth s;
  palp::Recording whole = multisine_recording(m, s), rec;
  // period 5 runs from 12.74565 + 5 x 2 s; ten samples lost in its middle
  for (std::size_t k = 0; k < whole.size(); ++k)
    if (whole.t_s[k] < 23.5 || whole.t_s[k] >= 23.51)
      rec.append({.sample_index = k, .t_s = whole.t_s[k], .i_cmd_A = (*whole.i_cmd_A)[k],
                  .i_A = whole.i_A[k], .z_mm = whole.z_mm[k]});
  ASSERT_EQ(rec.size() + 10, whole.size());
  const an::Frf frf = an::multisine_frf(rec, m, kRate);
  EXPECT_THAT(frf.notes, ::testing::Contains("period 5 (from 22.745650 s) has a gap in the "
                                             "stream: left out"));
  for (const an::FrfLine& l : frf.lines)
    EXPECT_LT(std::abs(l.G_m_per_N - g_true(l.f_Hz)), 1e-9 * std::abs(g_true(l.f_Hz)));
}

TEST(MultisineFrf, ATruncatedRecordingAndAStreamNotDividingThePeriodAreDataErrors) {
  proto::LoadMultisine m = small_multisine();
  m.periods = 3;
  const Synth s;
  palp::Recording whole = multisine_recording(m, s), rec;
  for (std::size_t k = 0; k < whole.size() && whole.t_s[k] < 16.0; ++k)
    rec.append({.sample_index = k, .t_s = whole.t_s[k], .i_cmd_A = (*whole.i_cmd_A)[k],
                .i_A = whole.i_A[k], .z_mm = whole.z_mm[k]});
  try {
    an::multisine_frf(rec, m, kRate);
    FAIL();
  } catch (const palp::DataError& e) {
    EXPECT_STREQ(e.what(), "multisine_frf: the recording ends at 15.999000 s, before the program "
                           "does (18.745650 s; it started at 12.745650 s)");
  }
  m.fundamental_Hz = 0.3f;  // 66667 ticks: no whole number of 20-tick samples
  try {
    an::multisine_frf(whole, m, kRate);
    FAIL();
  } catch (const palp::DataError& e) {
    EXPECT_STREQ(e.what(), "multisine_frf: the stream's sample interval (20 ticks) does not "
                           "divide the period (66667 ticks): choose a decimation that divides "
                           "it");
  }
}

TEST(MultisineUnitPeak, ASingleLineIsOne) {
  proto::LoadMultisine m = small_multisine();
  m.line_last = m.line_first;
  m.phase_mode = proto::PhaseMode::zero;
  EXPECT_NEAR(an::multisine_unit_peak(m, kRate), 1.0, 1e-12);
  m.phase_mode = proto::PhaseMode::random_seeded;  // a tick lands within 2 pi 5 / 40000 rad
  EXPECT_NEAR(an::multisine_unit_peak(m, kRate), 1.0, 1e-7);
}

TEST(MultisineUnitPeak, EqualsABruteForceEvaluationOverThePeriod) {
  for (proto::PhaseMode mode : {proto::PhaseMode::random_seeded, proto::PhaseMode::schroeder,
                                proto::PhaseMode::zero}) {
    proto::LoadMultisine m = small_multisine();
    m.phase_mode = mode;
    const auto lines = ms_lines(m);
    const std::uint32_t P = proto::multisine_period_ticks(m.fundamental_Hz, kRate);
    double peak = 0;
    for (std::uint32_t k = 0; k < P; ++k) {
      double x = 0;
      for (const MsLine& l : lines)
        x += std::cos(kTwoPi * (static_cast<double>(std::uint64_t{l.h} * k % P) / P +
                                l.phase_turns));
      peak = std::max(peak, std::abs(x));
    }
    EXPECT_NEAR(an::multisine_unit_peak(m, kRate), peak, 1e-10 * peak);
    if (mode == proto::PhaseMode::zero) {
      EXPECT_NEAR(peak, 25.0, 1e-9);  // all lines at t = 0
    }
  }
}

TEST(MultisineUnitPeak, MatchesTheFirmwaresSetPointsOverOnePeriod) {
  // the device's ProgramRunner played for one period: its largest |set-point - offset| is the
  // unit peak times the line amplitude, within the generator's stated error bound
  for (std::uint32_t rate : {20000u, 40000u}) {
    proto::LoadMultisine m = small_multisine();
    m.phase_mode = proto::PhaseMode::schroeder;
    palp::fw::ProgramRunner runner;
    std::uint8_t field = 0;
    ASSERT_EQ(runner.load(m, rate, field), proto::ErrorCode::ok);
    ASSERT_EQ(runner.start(0, 0), proto::ErrorCode::ok);
    const std::uint32_t P = proto::multisine_period_ticks(m.fundamental_Hz, rate);
    double device_peak = 0;
    for (std::uint32_t k = 0; k < P; ++k) {
      const palp::fw::ProgramStep st = runner.step(k, 0);
      device_peak = std::max(device_peak, std::abs(double{st.current_A} - m.offset_A));
    }
    const double bound = palp::fw::multisine_error_bound(
        palp::fw::MultisineProgram::lines_of(m, rate), rate);
    const double A = m.line_amplitude_A;
    const double peak = an::multisine_unit_peak(m, rate);
    EXPECT_NEAR(device_peak / A, peak, bound + 1e-5 * peak) << rate;  // + the f32 current
    EXPECT_GT(peak, 5.0);  // Schroeder phases: far below the 25 of aligned lines
    EXPECT_LT(peak, 12.0);
  }
}

}  // namespace
