// SPDX-License-Identifier: Apache-2.0
// The calibration helpers: current-sense offset, pressure zero, homing. They change the
// calibration in RAM only (a recording's sidecar keeps what they did); `palpctl calibrate`
// commits to flash on request.
#include <algorithm>
#include <cmath>
#include <numeric>

#include "probe/probe_impl.hpp"

namespace palp {
namespace {

/// Streams `channels` at 1 kHz for `seconds` and returns the samples; refuses while the
/// application's own stream runs (the helper would steal its samples).
std::vector<Sample> collect(Probe& p, std::uint16_t channels, double seconds, const char* what) {
  if (!(std::isfinite(seconds) && seconds > 0 && seconds <= 600))
    throw ConfigError(std::string(what) + ": seconds must be a finite number in (0, 600] s (got " +
                      std::to_string(seconds) + ")");
  if (p.status().streaming)
    throw ConfigError(std::string(what) + ": stop the stream first (the helper streams on its own)");
  p.configure_stream({.rate_Hz = 1000.0, .channels = channels, .batch_samples = 0});
  p.start_stream();
  std::vector<Sample> out;
  const std::size_t want = static_cast<std::size_t>(std::lround(seconds * 1000.0));
  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::milliseconds(static_cast<long>(seconds * 1000.0) + 10000);
  while (out.size() < want && std::chrono::steady_clock::now() < deadline) {
    if (auto item = p.next(100ms)) {
      if (const Sample* s = std::get_if<Sample>(&*item)) out.push_back(*s);
    }
  }
  p.stop_stream();
  std::vector<StreamItem> rest;
  p.drain(rest);
  if (out.size() < want)
    throw TimeoutError(std::string(what) + ": " + std::to_string(want) + " samples",
                       seconds + 10.0, p.health());
  return out;
}

void require_idle(Probe& p, const char* what) {
  const Status st = p.status();
  if (st.program_state == proto::ProgramState::running)
    throw ConfigError(std::string(what) + ": a program is running; stop it first");
  if (st.fault != proto::FaultReason::none) {
    const char* reason = proto::enum_name(st.fault);
    throw FaultError(std::string(what) + ": the fault latch is set (" + (reason ? reason : "unknown") +
                         "); find its cause, then clear it (palpctl fault clear)",
                     static_cast<std::uint16_t>(st.fault));
  }
}

}  // namespace

// With no program the current loop holds 0 A on the *measured* current, so a sense offset e
// shows up as a real current -e that the loop must drive: the coil voltage settles at
// v = -R e. The offset error is therefore e = mean(i_meas) - mean(v_cmd) / R with the coil's
// resistance R (5.8 Ohm, paper §II-A); the correction folds it into the calibration's offset.
double Probe::zero_current_offset(double seconds) {
  constexpr double kCoilResistance_Ohm = 5.8;
  require_idle(*this, "zero_current_offset");
  const auto samples = collect(*this, channel::i_meas | channel::v_cmd, seconds, "zero_current_offset");
  double i = 0, v = 0;
  for (const Sample& s : samples) {
    i += s.i_A;
    v += s.v_cmd_V;
  }
  i /= static_cast<double>(samples.size());
  v /= static_cast<double>(samples.size());
  const double error_A = i - v / kCoilResistance_Ohm;
  Calibration c = calibration();
  c.current_offset_A = static_cast<float>(c.current_offset_A + error_A / c.current_gain);
  set_calibration(c);
  impl_->zeroing.push_back({"current_offset", samples.back().t_device_s, {c.current_offset_A}, false});
  return c.current_offset_A;
}

std::vector<double> Probe::zero_pressure(double seconds) {
  require_idle(*this, "zero_pressure");
  const auto samples = collect(*this, channel::pressure, seconds, "zero_pressure");
  Calibration c = calibration();
  std::vector<double> offsets(6);
  for (std::size_t k = 0; k < 6; ++k) {
    double m = 0;
    for (const Sample& s : samples) m += s.p_Pa[k];
    m /= static_cast<double>(samples.size());
    c.pressure_offset_Pa[k] = static_cast<float>(c.pressure_offset_Pa[k] + m / c.pressure_gain[k]);
    offsets[k] = c.pressure_offset_Pa[k];
  }
  set_calibration(c);
  impl_->zeroing.push_back({"pressure_zero", samples.back().t_device_s, offsets, false});
  return offsets;
}

std::int32_t Probe::home(double hold_current_A, double seconds) {
  if (!std::isfinite(hold_current_A) || !std::isfinite(seconds))
    throw ConfigError(std::string("home: ") + (std::isfinite(hold_current_A) ? "seconds" : "hold_current_A") +
                      " is not a finite number");
  require_idle(*this, "home");
  if (!(hold_current_A < 0))
    throw ConfigError("home: hold_current_A must be negative (it pulls the coil toward -z, "
                      "against its rear end stop)");
  if (!(seconds >= 0.2)) throw ConfigError("home: hold at least 0.2 s");
  HoldProgram h;
  h.current_A = static_cast<float>(hold_current_A);
  h.duration_s = static_cast<float>(seconds + 0.5);
  load(h);
  start();
  const auto samples = collect(*this, channel::encoder, seconds, "home");
  wait(std::chrono::milliseconds(static_cast<long>(seconds * 1000.0) + 5000));
  // the last fifth must be at rest: the coil sits on its end stop
  const std::size_t from = samples.size() - samples.size() / 5;
  std::int32_t lo = samples[from].encoder_counts, hi = lo;
  for (std::size_t k = from; k < samples.size(); ++k) {
    lo = std::min(lo, samples[k].encoder_counts);
    hi = std::max(hi, samples[k].encoder_counts);
  }
  if (hi - lo > 2)
    throw Error("home: the coil did not come to rest against its end stop (it moved " +
                std::to_string(hi - lo) + " counts in the last " +
                std::to_string(seconds / 5.0) + " s); is the probe blocked or in contact?");
  Calibration c = calibration();
  c.stroke_origin_counts = lo;
  c.stroke_origin_valid = 1;
  set_calibration(c);
  impl_->zeroing.push_back({"home", samples.back().t_device_s, {lo * 1e-6}, false});
  return lo;
}

const std::vector<ZeroingRecord>& Probe::zeroing() const { return impl_->zeroing; }

}  // namespace palp
