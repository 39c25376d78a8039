// SPDX-License-Identifier: Apache-2.0
// Waveform primitives and the multisine generator, against double-precision references.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "palp/fw/multisine_synth.hpp"
#include "palp/fw/program_kinds.hpp"
#include "palp/fw/waveform.hpp"
#include "palp/protocol/multisine.hpp"
#include "program_test_support.hpp"

namespace palp::fw {
namespace {

using test::kTwoPi;
constexpr double kTurn = 4294967296.0;

double exact_sin(std::uint32_t phase) { return std::sin(kTwoPi * (phase / kTurn)); }

TEST(WaveformSine, TableHoldsSinOfEverySampleAndTheSlopeToTheNextToFloatRounding) {
  const double per_fraction = std::ldexp(1.0, -static_cast<int>(detail::kFractionBits));
  for (std::uint32_t k = 0; k < kSineTableSize; ++k) {
    const double exact = std::sin(kTwoPi * k / kSineTableSize);
    const double next = std::sin(kTwoPi * (k + 1) / kSineTableSize);
    EXPECT_NEAR(detail::kSineTable[k].value, exact, 3.0e-8) << k;
    EXPECT_NEAR(detail::kSineTable[k].slope, (next - exact) * per_fraction, 1e-9 * per_fraction)
        << k;
  }
}

TEST(WaveformSine, InterpolatedSineIsWithinStatedErrorOverEveryPhaseRegion) {
  // every sample interval, at 64 evenly spread points (including the middle, where the
  // interpolation error peaks), plus a dense scan
  double worst = 0.0;
  for (std::uint32_t k = 0; k < kSineTableSize; ++k)
    for (std::uint32_t j = 0; j < 64; ++j) {
      const std::uint32_t p = (k << detail::kFractionBits) + (j << (detail::kFractionBits - 6));
      worst = std::fmax(worst, std::fabs(sin_turns(p) - exact_sin(p)));
    }
  for (std::uint64_t p = 12345; p < (1ull << 32); p += 4099)
    worst = std::fmax(worst, std::fabs(sin_turns(static_cast<std::uint32_t>(p)) -
                                       exact_sin(static_cast<std::uint32_t>(p))));
  std::printf("sine table: worst error %.3g (stated %.3g, h^2/8 = %.4g)\n", worst,
              static_cast<double>(kSineMaxError),
              (kTwoPi / kSineTableSize) * (kTwoPi / kSineTableSize) / 8.0);
  EXPECT_LE(worst, static_cast<double>(kSineMaxError));
  EXPECT_GT(worst, 4.0e-6);  // the bound is tight: h^2/8 = 4.71e-6 is really reached
}

TEST(WaveformSine, CosineIsTheSineAQuarterTurnLater) {
  for (std::uint64_t p = 0; p < (1ull << 32); p += 999983) {
    const auto ph = static_cast<std::uint32_t>(p);
    EXPECT_NEAR(cos_turns(ph), std::cos(kTwoPi * (ph / kTurn)), kSineMaxError);
  }
  EXPECT_EQ(cos_turns(0), 1.0f);
  EXPECT_EQ(sin_turns(kQuarterTurn), 1.0f);
  EXPECT_EQ(sin_turns(kHalfTurn), 0.0f);
}

TEST(WaveformPhase, IncrementIsTheNearestFractionOfATurnPerTick) {
  EXPECT_EQ(proto::phase_increment(5.0f, 20000), 1073742u);  // 5 / 20000 * 2^32 = 1073741.824
  EXPECT_EQ(proto::phase_increment(2.0f, 20000), 429497u);   // 429496.7296
  EXPECT_EQ(proto::phase_increment(2500.0f, 40000), 1u << 28);  // exact
  for (float f : {0.01f, 0.05f, 1.0f, 19.95f, 2000.0f})
    for (std::uint32_t rate : {20000u, 40000u}) {
      const double realised = proto::phase_increment(f, rate) * static_cast<double>(rate) / kTurn;
      EXPECT_LE(std::fabs(realised - f), rate / kTurn / 2.0 + 1e-12) << f << " " << rate;
    }
}

TEST(WaveformPhase, FineIncrementRoundsToTheSameCoarseIncrement) {
  for (float f : {0.01f, 2.0f, 2.05f, 19.95f, 20.0f, 1999.9f})
    EXPECT_EQ(proto::coarse_increment(proto::phase_increment_fine(f, 20000)),
              proto::phase_increment(f, 20000))
        << f;
}

// ---- multisine ------------------------------------------------------------------------------

// x(k) = sum_n cos(2 pi (h_n k / P + phi_n)), exact in double (h_n k mod P in integers).
double reference_sum(const MultisineLines& l, const std::vector<std::uint32_t>& phi,
                     std::uint64_t k) {
  double x = 0.0;
  for (std::uint32_t n = 0; n < l.count; ++n) {
    const std::uint64_t h = l.first + static_cast<std::uint64_t>(n) * l.step;
    const double turns = static_cast<double>((h * k) % l.period_ticks) / l.period_ticks +
                         phi[n] / kTurn;
    x += std::cos(kTwoPi * turns);
  }
  return x;
}

std::vector<std::uint32_t> spec_phases(const MultisineLines& l) {
  std::vector<std::uint32_t> phi(l.count);
  for (std::uint32_t n = 0; n < l.count; ++n)
    phi[n] = proto::multisine_phase_turns(l.phase_mode, l.phase_seed, n, l.count);
  return phi;
}

struct Measured {
  double worst = 0.0;
  double bound = 0.0;
};

// Runs the generator for `ticks` ticks and compares every `stride`-th tick with the reference.
Measured compare_with_reference(const MultisineLines& l, std::uint32_t rate_Hz,
                                std::uint64_t ticks, std::uint64_t stride) {
  MultisineSynth synth;
  synth.configure(l);
  const std::vector<std::uint32_t> phi = spec_phases(l);
  Measured m;
  m.bound = multisine_error_bound(l, rate_Hz);
  for (std::uint64_t k = 0; k < ticks; ++k) {
    const float x = synth.step();
    if (k % stride == 0) m.worst = std::fmax(m.worst, std::fabs(x - reference_sum(l, phi, k)));
  }
  return m;
}

MultisineLines default_lines(std::uint32_t rate_Hz) {
  return MultisineProgram::lines_of(proto::LoadMultisine{}, rate_Hz);
}

TEST(MultisineSynth, Default90LineProgramMatchesTheSpecWaveformWithinTheStatedBound) {
  const MultisineLines l = default_lines(20000);
  ASSERT_EQ(l.count, 90u);
  ASSERT_EQ(l.period_ticks, 400000u);  // 0.05 Hz at 20 kHz
  ASSERT_EQ(l.ticks_per_point, 8u);
  // a whole period and 2000 ticks into the next, every tick
  const Measured m = compare_with_reference(l, 20000, 402000, 1);
  const double amplitude_A = 0.01;
  std::printf("multisine 90 lines: worst %.3g A, bound %.3g A (amplitude 0.01 A)\n",
              m.worst * amplitude_A, m.bound * amplitude_A);
  EXPECT_LE(m.worst, m.bound);
  EXPECT_LT(m.bound * amplitude_A, 2e-4);  // below the 0.2 mA step of the i_cmd channel
}

TEST(MultisineSynth, FourHundredLinesUpTo100HzMatchTheSpecWaveformWithinTheStatedBound) {
  for (std::uint32_t rate : {20000u, 40000u}) {
    MultisineLines l;
    l.count = 400;
    l.first = 1;
    l.step = 1;
    l.period_ticks = rate * 4;  // 0.25 Hz: lines 0.25 ... 100 Hz
    l.ticks_per_point = rate / kMultisineSubRate_Hz;
    l.phase_mode = proto::PhaseMode::schroeder;
    const Measured m = compare_with_reference(l, rate, l.period_ticks + 1000, 3);
    std::printf("multisine 400 lines at %u Hz: worst %.3g, bound %.3g (unit lines)\n", rate,
                m.worst, m.bound);
    EXPECT_LE(m.worst, m.bound) << rate;
  }
}

TEST(MultisineSynth, RandomPhasesAreTheSpecGeneratorsInLineOrder) {
  MultisineLines l = default_lines(20000);
  l.phase_seed = 0xC0FFEE;
  const Measured m = compare_with_reference(l, 20000, 20000, 7);
  EXPECT_LE(m.worst, m.bound);
  // tick 0 is a sub-rate point: only table and rounding errors remain
  MultisineSynth synth;
  synth.configure(l);
  EXPECT_NEAR(synth.step(), reference_sum(l, spec_phases(l), 0), l.count * 6e-6);
}

TEST(MultisineSynth, PhasesAreTheSpecsBitForBitForEveryModeAndLineCount) {
  for (proto::PhaseMode mode :
       {proto::PhaseMode::random_seeded, proto::PhaseMode::schroeder, proto::PhaseMode::zero})
    for (std::uint32_t count : {1u, 2u, 3u, 7u, 64u, 90u, 128u, 399u, 400u}) {
      MultisineLines l;
      l.count = count;
      l.first = 1;
      l.step = 1;
      l.period_ticks = 400000;
      l.ticks_per_point = 8;
      l.phase_mode = mode;
      l.phase_seed = 0x9E3779B9u;
      MultisineSynth synth;
      synth.configure(l);
      for (std::uint32_t n = 0; n < count; ++n)
        ASSERT_EQ(synth.phase_turns(n),
                  proto::multisine_phase_turns(mode, l.phase_seed, n, count))
            << static_cast<int>(mode) << " K " << count << " n " << n;
    }
}

TEST(MultisineSynth, HighestAllowedLineLosesTheStatedAmplitude) {
  // one line at 125 Hz (f Ts = 1/20): in-band amplitude from a DFT over one period
  MultisineLines l;
  l.count = 1;
  l.first = 125;
  l.step = 1;
  l.period_ticks = 20000;  // 1 Hz fundamental at 20 kHz
  l.ticks_per_point = 8;
  MultisineSynth synth;
  synth.configure(l);
  double re = 0.0, im = 0.0, worst = 0.0;
  for (std::uint32_t k = 0; k < l.period_ticks; ++k) {
    const double x = synth.step();
    const double a = kTwoPi * 125.0 * k / l.period_ticks;
    re += x * std::cos(a);
    im += x * std::sin(a);
    worst = std::fmax(worst, std::fabs(x - std::cos(a)));
  }
  const double amplitude = 2.0 * std::hypot(re, im) / l.period_ticks;
  const double stated = multisine_amplitude_error(125.0, 8);
  std::printf("125 Hz line: amplitude error %.4g (stated %.4g), peak error %.4g\n",
              1.0 - amplitude, stated, worst);
  EXPECT_NEAR(stated, 0.0081, 0.0001);
  EXPECT_NEAR(1.0 - amplitude, stated, 1e-5);
  EXPECT_LE(worst, multisine_error_bound(l, 20000));
  EXPECT_NEAR(multisine_amplitude_error(19.85, 8), 2.04e-4, 0.01e-4);  // the default's top line
  EXPECT_NEAR(multisine_amplitude_error(125.0, 16), 0.0082, 0.0001);   // at 40 kHz
}

TEST(MultisineSynth, WorstCase400LinesCostsExactlyFiftyLinesEveryTickAt20kHz) {
  for (std::uint32_t rate : {20000u, 40000u}) {
    MultisineLines l;
    l.count = 400;
    l.first = 1;
    l.step = 1;
    l.period_ticks = rate * 4;
    l.ticks_per_point = rate / kMultisineSubRate_Hz;
    MultisineSynth synth;
    synth.configure(l);
    const std::uint32_t expected = rate == 20000 ? 50 : 25;
    EXPECT_EQ(synth.max_lines_per_step(), expected);
    for (int k = 0; k < 1000; ++k) {
      synth.step();
      ASSERT_EQ(synth.lines_last_step(), expected) << rate << " tick " << k;
    }
  }
}

TEST(MultisineSynth, UnevenLineCountsSpreadWithinOneLinePerTick) {
  MultisineLines l = default_lines(20000);  // 90 lines over 8 ticks: 11 or 12
  MultisineSynth synth;
  synth.configure(l);
  std::uint32_t total = 0;
  for (int k = 0; k < 8; ++k) {
    synth.step();
    EXPECT_GE(synth.lines_last_step(), 11u);
    EXPECT_LE(synth.lines_last_step(), 12u);
    total += synth.lines_last_step();
  }
  EXPECT_EQ(total, 90u);
}

TEST(MultisineSynth, EveryPeriodRepeatsBitForBitWhenThePeriodIsWholeSubRatePoints) {
  MultisineLines l = default_lines(20000);
  l.period_ticks = 20000;  // 1 Hz: 2500 points per period
  MultisineSynth synth;
  synth.configure(l);
  std::vector<float> first(l.period_ticks);
  for (auto& x : first) x = synth.step();
  for (std::uint32_t k = 0; k < 2 * l.period_ticks; ++k)
    ASSERT_EQ(synth.step(), first[k % l.period_ticks]) << k;
}

TEST(MultisineSynth, RewindRestartsTheSameWaveform) {
  MultisineSynth synth;
  synth.configure(default_lines(40000));
  std::vector<float> a(5000);
  for (auto& x : a) x = synth.step();
  synth.rewind();
  for (std::size_t k = 0; k < a.size(); ++k) ASSERT_EQ(synth.step(), a[k]) << k;
}

}  // namespace
}  // namespace palp::fw
