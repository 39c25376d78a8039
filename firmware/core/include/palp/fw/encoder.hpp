// SPDX-License-Identifier: Apache-2.0
// The linear encoder (POSIC ID1102L, quadrature, paper §II-A): position, velocity, index.
//
// The board's quadrature timer gives a 16-bit count that wraps. Every control tick the core
// reads it and extends it to a signed 32-bit position in counts: 1 count = 1 um, counts increase
// toward +z (into the specimen). The extension takes the wrapped 16-bit difference since the
// previous tick, so it is exact as long as the coil moves fewer than 32 768 counts (32.8 mm)
// per tick (at 20 kHz that would be 655 m/s). The 32-bit position spans +-2147 m.
//
// Velocity: the first difference (counts per tick / dt), low-passed by a first-order filter
// with cut-off kEncoderVelocityCutoff_Hz = 200 Hz, discretised exactly for the tick period:
//     v += alpha (delta / dt - v),   alpha = 1 - exp(-2 pi fc dt).
// A constant speed is then reached as 1 - exp(-2 pi fc t) (time constant 0.80 ms); at the 20 Hz
// top of the paper's sweeps the lag is 5.7 deg. At 1 um resolution one count per tick is
// 20 mm/s at 20 kHz, so the raw difference is coarse at low speed; the filter averages it.
//
// Index: when the board sees the index pulse it calls latch_index() (the position now) or, if
// its timer captured the 16-bit count at the pulse, latch_index_at(captured) (the position at
// the pulse, extended relative to the last update). The latch holds until clear_index().
#pragma once

#include <cstdint>

namespace palp::fw {

inline constexpr float kEncoderVelocityCutoff_Hz = 200.0f;

class Encoder {
 public:
  explicit Encoder(float velocity_cutoff_Hz = kEncoderVelocityCutoff_Hz);

  /// Starts tracking: `timer_count` is the hardware count now and maps to `position_counts`.
  /// Velocity and the index latch are cleared.
  void reset(std::uint16_t timer_count, std::int32_t position_counts = 0);

  /// One control tick: the hardware count now and the tick period (s).
  void update(std::uint16_t timer_count, float dt_s);

  /// Extended position, counts (1 um), +z into the specimen.
  std::int32_t position_counts() const { return position_counts_; }
  /// Low-passed velocity, counts/s (= um/s), +z into the specimen.
  float velocity_counts_per_s() const { return velocity_counts_per_s_; }
  /// Counts moved in the last update() (signed).
  std::int32_t last_step_counts() const { return last_step_counts_; }

  void latch_index();
  void latch_index_at(std::uint16_t timer_count_at_index);
  bool index_latched() const { return index_latched_; }
  std::int32_t index_position_counts() const { return index_position_counts_; }
  void clear_index() { index_latched_ = false; }

 private:
  float cutoff_Hz_;
  float alpha_ = 0.0f;
  float alpha_dt_s_ = 0.0f;  // dt alpha was computed for; 0: not yet
  std::uint16_t last_timer_count_ = 0;
  std::int32_t position_counts_ = 0;
  std::int32_t last_step_counts_ = 0;
  float velocity_counts_per_s_ = 0.0f;
  std::int32_t index_position_counts_ = 0;
  bool index_latched_ = false;
};

}  // namespace palp::fw
