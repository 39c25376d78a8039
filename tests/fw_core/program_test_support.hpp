// SPDX-License-Identifier: Apache-2.0
// Shared by the program tests: loading with checks, the paper's programs as Load* messages.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>

#include "palp/fw/programs.hpp"

namespace palp::fw::test {

inline constexpr double kTwoPi = 6.283185307179586476925;
inline constexpr std::uint32_t kRate = 20000;
inline constexpr float kDt = 1.0f / 20000.0f;  // one control tick, s
inline constexpr std::uint64_t kT0 = 1000000;  // ProgramStart tick: programs count from here

template <class Message>
ProgramRunner loaded(const Message& m, std::uint32_t rate = kRate) {
  ProgramRunner r;
  std::uint8_t field = 0;
  EXPECT_EQ(r.load(m, rate, field), proto::ErrorCode::ok);
  return r;
}

template <class Message>
std::uint8_t refused_field(const Message& m,
                           proto::ErrorCode expected = proto::ErrorCode::out_of_range) {
  ProgramRunner r;
  std::uint8_t field = 0;
  EXPECT_EQ(r.load(m, kRate, field), expected);
  EXPECT_EQ(r.state(), proto::ProgramState::idle);
  return field;
}

// §V-A: 0.5 -> 3 A by 0.01 A every 25 ms, unloaded symmetrically, 3 repetitions
inline proto::LoadRamp paper_2d_ramp() {
  proto::LoadRamp m;
  m.start_A = 0.5f;
  m.stop_A = 3.0f;
  m.step_A = 0.01f;
  m.dwell_s = 0.025f;
  m.repetitions = 3;
  m.unload = 1;
  return m;
}

// 400 lines of 5 mA, 0.25 ... 100 Hz: the costliest multisine to load and to run
inline proto::LoadMultisine four_hundred_line_multisine() {
  proto::LoadMultisine m;
  m.fundamental_Hz = 0.25f;
  m.line_first = 1;
  m.line_last = 400;
  m.line_step = 1;
  m.line_amplitude_A = 0.005f;
  return m;
}

inline proto::LoadSine sine_5Hz(std::uint32_t cycles) {
  proto::LoadSine m;
  m.offset_A = 1.0f;
  m.amplitude_A = 0.1f;
  m.frequency_Hz = 5.0f;
  m.cycles = cycles;
  return m;
}

}  // namespace palp::fw::test
