// SPDX-License-Identifier: Apache-2.0
// The repetition of each sample of a staircase ramp (the recording's rep column), found from the
// commanded current as the samples stream in: the device counts repetitions but does not stamp
// them on samples. It follows firmware/core's schedule (SPEC.md, LoadRamp): with unload a
// repetition climbs from start_A, comes back down and holds start_A for one more dwell, and the
// next one begins after that dwell; without unload the next one begins where the current drops
// back to start_A. A displacement limit only turns the climb early, so it is followed too.
// Samples outside the program (program_running clear) keep the repetition they are next to.
#pragma once

#include <algorithm>

#include "palp/probe.hpp"

namespace palp::experiment {

class RampReps {
 public:
  explicit RampReps(const palp::RampProgram& m)
      : start_A_(m.start_A),
        sign_(m.stop_A >= m.start_A ? 1.0 : -1.0),
        tol_A_(std::max(0.5 * static_cast<double>(m.step_A), 0.0003)),  // 1.5 LSB of i_cmd
        dwell_s_(m.dwell_s),
        unload_(m.unload != 0),
        last_rep_(std::max(0, static_cast<int>(m.repetitions) - 1)) {}

  int operator()(const palp::Sample& s) {
    constexpr unsigned kRunning = 1u << static_cast<unsigned>(palp::proto::StatusBit::program_running);
    if ((s.status & kRunning) == 0) return rep_;
    const double x = sign_ * (s.i_cmd_A - start_A_);  // height above the start level
    if (!started_) {
      started_ = true;
      prev_ = x;
      return rep_;
    }
    switch (phase_) {
      case Phase::climb:
        if (x < prev_ - tol_A_) {
          if (!unload_) {
            next_rep();
          } else if (x <= tol_A_) {
            phase_ = Phase::bottom;
            bottom_t_s_ = s.t_device_s;
          } else {
            phase_ = Phase::descend;
          }
        }
        break;
      case Phase::descend:
        if (x <= tol_A_) {
          phase_ = Phase::bottom;
          bottom_t_s_ = s.t_device_s;
        }
        break;
      case Phase::bottom:
        // the start level is held one dwell to end this repetition, then the next one begins
        if (s.t_device_s >= bottom_t_s_ + dwell_s_ - 1e-9) {
          next_rep();
          phase_ = Phase::climb;
        }
        break;
    }
    prev_ = x;
    return rep_;
  }

 private:
  enum class Phase { climb, descend, bottom };
  void next_rep() { rep_ = std::min(rep_ + 1, last_rep_); }

  double start_A_, sign_, tol_A_, dwell_s_;
  bool unload_;
  int last_rep_;
  int rep_ = 0;
  bool started_ = false;
  double prev_ = 0;
  Phase phase_ = Phase::climb;
  double bottom_t_s_ = 0;
};

}  // namespace palp::experiment
