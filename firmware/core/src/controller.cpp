// SPDX-License-Identifier: Apache-2.0
// Controller: the control tick, the main-loop service and the transmit path. Command dispatch is
// in controller_dispatch.cpp.
#include "palp/fw/controller.hpp"

#include <cmath>

namespace palp::fw {

namespace {

// value / lsb rounded to the nearest i16 and saturated; single precision only, since the
// Cortex-M4F has no double-precision FPU and this runs in the tick.
std::int16_t scaled(float value, float per_lsb) {
  float v = value * per_lsb;
  if (!(v < 32767.0f)) return v != v ? 0 : 32767;
  if (!(v > -32768.0f)) return -32768;
  v += v >= 0.0f ? 0.5f : -0.5f;
  return static_cast<std::int16_t>(v);
}
constexpr float kPerCurrentLsb = static_cast<float>(1.0 / proto::kCurrentLsb_A);
constexpr float kPerPressureLsb = static_cast<float>(1.0 / proto::kPressureLsb_Pa);
constexpr float kPerVoltageLsb = static_cast<float>(1.0 / proto::kVoltageLsb_V);

constexpr std::uint16_t bit(proto::StatusBit b) {
  return static_cast<std::uint16_t>(1u << static_cast<unsigned>(b));
}

}  // namespace

Controller::Controller(const DeviceIdentity& identity) : identity_(identity) {
  apply_params(params_);
  apply_calibration(calibration_);
  // the stream starts with the catalogue's default configuration (all channels, 10 kHz), slowed
  // to the board's max_stream_rate_Hz if that is lower
  proto::StreamConfig ignored;
  std::uint8_t field = 255;
  streamer_.configure(proto::StreamConfigure{}, params_.control_rate_Hz, ignored, field);
  pressure_.set_decimation(streamer_.config().decimation);
  fit_stream_to_max_rate();
}

std::uint64_t Controller::us_of_tick(std::uint64_t tick) const {
  // an event a tick before the latest rate change (emitted after it) is at most a few ticks
  // older than the anchor: it takes the anchor's time rather than wrapping around
  if (tick < time_base_.tick) return time_base_.us;
  return time_base_.us_of(tick, params_.control_rate_Hz);
}

std::uint64_t Controller::device_time_us() const { return us_of_tick(tick_); }

void Controller::tick(const TickInputs& in, TickOutputs& out) {
  const float dt = dt_s();
  const std::uint64_t now = tick_;
  counters_.control_overruns += in.missed_ticks;

  // sensors
  if (!encoder_started_) {
    encoder_.reset(in.encoder_timer, 0);
    encoder_started_ = true;
  } else {
    encoder_.update(in.encoder_timer, dt);
  }
  const std::int32_t z = encoder_.position_counts();
  i_meas_A_ = apply_current_calibration(in.i_sense_A, calibration_.current_offset_A,
                                        calibration_.current_gain);
  pressure_.add(in.pressure_codes);
  SensorReadings readings;
  readings.i_sense_A = in.i_sense_A;
  readings.i_measured_A = i_meas_A_;
  readings.encoder_counts = z;
  readings.encoder_step_counts = encoder_.last_step_counts();
  readings.v_applied_V = v_cmd_V_;  // last tick's output, applied until now
  readings.supply_V = in.supply_V;
  readings.driver_fault = in.driver_fault;
  readings.dt_s = dt;

  // program, then safety (which owns the only set-point the loop may use)
  const ProgramStep step = programs_.step(now, z);
  SafetyInputs si;
  si.i_request_A = step.current_A;
  si.i_measured_A = i_meas_A_;
  si.encoder_counts = z;
  si.program_running = step.running;
  si.dt_s = dt;
  si.watchdog_now_us = in.watchdog_now_us;
  si.sensor = monitor_.update(readings);
  const SafetyVerdict verdict = safety_.check(si);
  clamped_ = verdict.clamped;

  if (verdict.new_fault != proto::FaultReason::none) {
    TickEvent e;
    e.kind = TickEvent::Kind::fault;
    e.tick = now;
    e.reason = verdict.new_fault;
    e.detail = safety_.fault_detail();
    push_event(e);
    if (programs_.abort_fault(now)) {
      TickEvent f;
      f.kind = TickEvent::Kind::finished;
      f.tick = now;
      f.end = proto::ProgramEnd::fault;
      f.program = programs_.kind();
      f.repetitions = programs_.repetitions_done();
      push_event(f);
    }
  } else if (step.finished) {
    if (step.contact) {
      TickEvent c;
      c.kind = TickEvent::Kind::contact;
      c.tick = now;
      c.encoder = step.contact_count;
      c.armed = programs_.armed_count();
      c.sample_index = streamer_.running() ? streamer_.next_index() : 0;
      push_event(c);
      if (params_.contact_output != proto::ContactOutputMode::disabled) {
        contact_line_ = true;
        contact_line_until_tick_ =
            now + static_cast<std::uint64_t>(params_.contact_output_hold_ms) *
                      params_.control_rate_Hz / 1000;
      }
    }
    TickEvent f;
    f.kind = TickEvent::Kind::finished;
    f.tick = now;
    f.end = step.end;
    f.program = programs_.kind();
    f.repetitions = programs_.repetitions_done();
    push_event(f);
  }

  // current loop; a tripped latch means zero volts this very tick
  i_set_A_ = verdict.i_set_A;
  if (verdict.tripped) {
    loop_.reset();
    v_cmd_V_ = 0.0f;
  } else {
    v_cmd_V_ = loop_.update(i_set_A_, i_meas_A_, dt);
  }
  out.v_coil_V = v_cmd_V_;

  // contact-output line: asserted while the contact is latched, at least the hold time
  if (contact_line_ && !programs_.contact_latched() && now >= contact_line_until_tick_)
    contact_line_ = false;
  const bool level = contact_line_;
  out.contact_line = params_.contact_output == proto::ContactOutputMode::active_low ? !level : level;

  // stream
  std::uint32_t index = 0;
  if (streamer_.sample_due(index)) {
    IndexedSample s;
    s.index = index;
    s.sample.i_cmd = scaled(i_set_A_, kPerCurrentLsb);
    s.sample.i_meas = scaled(i_meas_A_, kPerCurrentLsb);
    s.sample.encoder = z;
    const auto& p = pressure_.pressure_Pa();
    for (std::size_t k = 0; k < 6; ++k) s.sample.pressure[k] = scaled(p[k], kPerPressureLsb);
    s.sample.status = status_bits();
    s.sample.v_cmd = scaled(v_cmd_V_, kPerVoltageLsb);
    samples_.push(s);  // a full queue loses the sample; the streamer sees the missing index
  }
  ++tick_;
}

std::uint16_t Controller::status_bits() const {
  std::uint16_t s = 0;
  if (programs_.running()) s |= bit(proto::StatusBit::program_running);
  if (safety_.tripped()) s |= bit(proto::StatusBit::fault_latched);
  if (programs_.contact_latched()) s |= bit(proto::StatusBit::contact_latched);
  if (loop_.saturated()) s |= bit(proto::StatusBit::voltage_saturated);
  if (clamped_) s |= bit(proto::StatusBit::current_clamped);
  if (safety_.heartbeat_armed()) s |= bit(proto::StatusBit::heartbeat_armed);
  if (safety_.i2t_warning()) s |= bit(proto::StatusBit::i2t_warning);
  return s;
}

void Controller::push_event(const TickEvent& e) {
  if (!events_.push(e)) ++counters_.events_dropped;
}

void Controller::emit_event(const TickEvent& e) {
  const std::uint64_t t = us_of_tick(e.tick);
  switch (e.kind) {
    case TickEvent::Kind::fault: {
      proto::EventFault m;
      m.time_us = t;
      m.reason = e.reason;
      m.detail = e.detail;
      send(m, device_seq_++, 0);
      break;
    }
    case TickEvent::Kind::contact: {
      proto::EventContact m;
      m.time_us = t;
      m.encoder_count = e.encoder;
      m.armed_count = e.armed;
      m.sample_index = e.sample_index;
      send(m, device_seq_++, 0);
      break;
    }
    case TickEvent::Kind::finished: {
      proto::EventProgramFinished m;
      m.time_us = t;
      m.kind = e.program;
      m.end = e.end;
      m.repetitions_done = e.repetitions;
      send(m, device_seq_++, 0);
      break;
    }
  }
}

void Controller::service() {
  // events first: they are rare and the host reacts to them
  while (const TickEvent* e = events_.peek()) {
    emit_event(*e);
    events_.drop_front();
  }
  IndexedSample s;
  while (samples_.pop(s)) streamer_.accept(s);
  // a batch that does not fit waits in the backlog (not a drop): the streamer retries
  auto emit = [&](const auto& m) {
    if (!send(m, device_seq_, 0, /*count_drop=*/false)) return false;
    ++device_seq_;
    return true;
  };
  streamer_.pump(emit, !streamer_.running());
}

std::size_t Controller::transmit(std::uint8_t* out, std::size_t capacity) {
  return tx_.pop_n(out, capacity);
}

proto::Health Controller::health() const {
  proto::Health h;
  const proto::RejectCounters& r = reader_.counters();
  h.device_time_us = device_time_us();
  h.frames_rx = r[proto::Reject::ok];
  h.frames_tx = counters_.frames_tx;
  h.rx_bad_cobs = r[proto::Reject::bad_cobs];
  h.rx_bad_crc = r[proto::Reject::bad_crc];
  h.rx_oversize = r[proto::Reject::oversize];
  h.rx_truncated = r[proto::Reject::truncated];
  h.rx_length_mismatch = r[proto::Reject::length_mismatch];
  h.rx_unsupported_major = r[proto::Reject::unsupported_major];
  h.rx_unknown_message = r[proto::Reject::unknown_message];
  h.rx_short_payload = r[proto::Reject::short_payload];
  h.rx_bad_field = r[proto::Reject::bad_field];
  const StreamCounters& s = streamer_.counters();
  h.isr_queue_overflows = s.isr_queue_overflows;
  h.stream_backlog_depth = static_cast<std::uint32_t>(streamer_.backlog());
  h.stream_backlog_max = s.stream_backlog_max;
  h.stream_samples_lost = s.stream_samples_lost;
  h.usb_in_not_drained = 0;  // counted by a USB board; palp-sim stalls instead
  h.tx_frames_dropped = counters_.tx_frames_dropped + counters_.events_dropped;
  h.control_overruns = counters_.control_overruns;
  h.stream_gaps = s.stream_gaps;
  return h;
}

}  // namespace palp::fw
