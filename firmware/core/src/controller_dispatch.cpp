// SPDX-License-Identifier: Apache-2.0
// Controller: the host's requests. Every request is answered with its catalogue reply, Ack or
// Nak (SPEC.md §6.2). Until a compatible Hello only the frozen requests are served; every valid
// request of an open session feeds the heartbeat watchdog. When several refusals apply, the
// first in this order wins (SPEC.md §6.3): the frame reader's unknown_message and bad_payload,
// wrong_direction, the Hello gate (hello_required, incompatible_host), then each request's own
// checks in the order the handler below makes them.
//
// The tick guard (controller.hpp): handle() holds it from the Hello gate to the reply, which
// releases it before encoding. Handlers whose costly part reads only the message or main-loop
// state release it for that part: CommitCalibration (the CRC), SetCalibration (the checks),
// SetParams and StreamConfigure (the stream's figures), Load* (the synthesis, load_program()).
#include <algorithm>
#include <type_traits>

#include "palp/fw/controller.hpp"

namespace palp::fw {

namespace {
template <class M, class... Ms>
constexpr bool is_one_of = (std::is_same_v<M, Ms> || ...);

constexpr bool is_frozen(proto::MessageId id) { return proto::is_frozen_id(static_cast<std::uint8_t>(id)); }
}  // namespace

void Controller::receive(const std::uint8_t* data, std::size_t size,
                         std::uint64_t watchdog_now_us) {
  reader_.feed_messages(
      data, size,
      [&](const proto::FrameHeader& h, const auto& m) { handle(h, m, watchdog_now_us); },
      [&](proto::Reject r, const proto::FrameHeader* h) {
        if (h == nullptr) return;  // frame-level: no header to answer (SPEC.md §4.5)
        nak(*h, r == proto::Reject::unknown_message ? proto::ErrorCode::unknown_message
                                                    : proto::ErrorCode::bad_payload);
      });
}

void Controller::hold() {
  if (held_) return;
  if (guard_.hold != nullptr) guard_.hold(guard_.ctx);
  held_ = true;
}

void Controller::release() {
  if (!held_) return;
  held_ = false;
  if (guard_.release != nullptr) guard_.release(guard_.ctx);
}

template <class M>
void Controller::handle(const proto::FrameHeader& h, const M& m, std::uint64_t wd_now_us) {
  hold();
  dispatch(h, m, wd_now_us);
  release();
}

template <class M>
void Controller::load_program(const proto::FrameHeader& h, const M& m) {
  using namespace proto;
  // busy is the first refusal (SPEC.md §6.3); the tick may end the program, never start one
  if (programs_.running()) return nak(h, ErrorCode::busy, 255, busy_detail());
  release();  // the synthesis (up to ~25 000 instructions) runs with the tick free
  std::uint8_t field = 255;
  const ErrorCode e = programs_.stage(m, params_.control_rate_Hz, field);
  if (e != ErrorCode::ok) return nak(h, e, field);  // the loaded program stays as it was
  hold();
  const ErrorCode a = programs_.adopt_staged();
  if (a != ErrorCode::ok) return nak(h, a, 255, busy_detail());
  program_rate_Hz_ = params_.control_rate_Hz;
  ack(h);
}

std::uint32_t Controller::max_stream_rate_Hz() const {
  return std::clamp<std::uint32_t>(identity_.max_stream_rate_Hz, 1, Streamer::kMaxRate_Hz);
}

std::uint16_t Controller::min_stream_decimation(std::uint32_t control_rate_Hz) const {
  const std::uint32_t max = max_stream_rate_Hz();
  return static_cast<std::uint16_t>((control_rate_Hz + max - 1) / max);
}

void Controller::fit_stream_to_max_rate() {
  const std::uint16_t min = min_stream_decimation(params_.control_rate_Hz);
  if (streamer_.running() || streamer_.config().decimation >= min) return;
  proto::StreamConfigure sc;
  sc.channels = streamer_.config().channels;
  sc.decimation = min;
  sc.batch_samples = streamer_.config().batch_samples;
  proto::StreamConfig ignored;
  std::uint8_t field = 255;
  hold();
  streamer_.configure(sc, params_.control_rate_Hz, ignored, field, max_stream_rate_Hz());
  pressure_.set_decimation(streamer_.config().decimation);
  release();
}

void Controller::set_identity(const DeviceIdentity& identity) {
  identity_ = identity;
  fit_stream_to_max_rate();
}

void Controller::ack(const proto::FrameHeader& request) {
  proto::Ack a;
  a.request_id = request.id;
  reply(request, a);
}

void Controller::nak(const proto::FrameHeader& request, proto::ErrorCode error,
                     std::uint8_t field_index, std::int32_t detail) {
  proto::Nak n;
  n.request_id = request.id;
  n.error = error;
  n.field_index = field_index;
  n.detail = detail;
  reply(request, n);
}

std::int32_t Controller::busy_detail() const {
  return static_cast<std::int32_t>(programs_.running() ? programs_.kind() : proto::ProgramKind::none);
}

proto::DeviceInfo Controller::device_info() const {
  proto::DeviceInfo d;
  d.protocol_major = identity_.protocol.major;
  d.protocol_minor = identity_.protocol.minor;
  d.schema_hash = identity_.protocol.schema_hash;
  d.fw_major = identity_.fw_major;
  d.fw_minor = identity_.fw_minor;
  d.fw_patch = identity_.fw_patch;
  d.git_hash = identity_.git_hash;
  d.board = identity_.board;
  d.serial = identity_.serial;
  d.capabilities = identity_.capabilities;
  d.max_current_A = 4.0f;
  d.control_rate_Hz = params_.control_rate_Hz;
  d.max_stream_rate_Hz = max_stream_rate_Hz();
  d.heartbeat_timeout_ms = params_.heartbeat_timeout_ms;
  d.max_payload = static_cast<std::uint16_t>(proto::kMaxPayload);
  d.state = device_state();
  return d;
}

proto::DeviceState Controller::device_state() const {
  return session_ == Session::incompatible ? proto::DeviceState::incompatible
         : safety_.tripped()               ? proto::DeviceState::faulted
         : programs_.running()             ? proto::DeviceState::running
                                           : proto::DeviceState::idle;
}

proto::Status Controller::status() const {
  proto::Status s;
  s.device_time_us = device_time_us();
  s.state = device_state();
  s.fault = safety_.fault();
  s.program_kind = programs_.kind();
  s.program_state = programs_.state();
  s.i_cmd_A = i_set_A_;
  s.i_A = i_meas_A_;
  s.encoder_count = encoder_.position_counts();
  s.i2t_fraction = safety_.i2t_fraction();
  s.streaming = streamer_.running() ? 1 : 0;
  s.status_bits = status_bits();
  return s;
}

void Controller::apply_params(const proto::Params& p) {
  params_ = p;
  safety_.configure(p);
  loop_.set_supply_V(p.supply_V);
  monitor_.configure(p.supply_V, calibration_.stroke_origin_counts);
}

void Controller::apply_calibration(const CalibrationData& c) {
  calibration_ = c;
  monitor_.configure(params_.supply_V, c.stroke_origin_counts);
  PressureCalibration pc;
  pc.offset_Pa = c.pressure_offset_Pa;
  pc.gain = c.pressure_gain;
  pressure_.set_calibration(pc);
}

CalibrationStatus Controller::load_calibration_block(const std::uint8_t* data, std::size_t size) {
  const CalibrationLoad l = load_calibration({data, size});
  if (l.status == CalibrationStatus::ok) {
    hold();
    apply_calibration(l.data);
    release();
  }
  return l.status;
}

template <class M>
void Controller::dispatch(const proto::FrameHeader& h, const M& m, std::uint64_t wd_now_us) {
  using namespace proto;
  if constexpr (std::is_same_v<M, Hello>) {
    // every Hello judges anew: a compatible one opens the session or keeps it open (programs and
    // the stream go on), an incompatible one closes it
    const Verdict v = judge({m.host_major, m.host_minor, m.host_schema_hash}, identity_.protocol);
    session_ = v.compatibility == Compatibility::incompatible ? Session::incompatible : Session::open;
  }
  // only a host in an open session keeps the coil energised: a peer that never said Hello, or an
  // incompatible one, does not feed the watchdog
  if (session_ == Session::open) safety_.feed(wd_now_us);

  if constexpr (M::kDirection == Direction::D2H) {
    nak(h, ErrorCode::wrong_direction);
    return;
  } else {
    if (session_ != Session::open && !is_frozen(M::kId)) {
      nak(h, session_ == Session::none ? ErrorCode::hello_required : ErrorCode::incompatible_host);
      return;
    }
    std::uint8_t field = 255;

    if constexpr (std::is_same_v<M, Hello>) {
      reply(h, device_info());
    } else if constexpr (std::is_same_v<M, GetDeviceInfo>) {
      reply(h, device_info());
    } else if constexpr (std::is_same_v<M, EnterBootloader>) {
      if (m.magic != kBootloaderMagic)
        return nak(h, ErrorCode::bad_magic, field_index_of<&EnterBootloader::magic>());
      if (programs_.running()) return nak(h, ErrorCode::busy, 255, busy_detail());
      bootloader_requested_ = true;
      ack(h);
    } else if constexpr (std::is_same_v<M, Ping>) {
      Pong p;
      p.nonce = m.nonce;
      p.host_time_us = m.host_time_us;
      p.device_time_us = device_time_us();
      reply(h, p);
    } else if constexpr (std::is_same_v<M, Heartbeat>) {
      ack(h);
    } else if constexpr (std::is_same_v<M, GetStatus>) {
      reply(h, status());
    } else if constexpr (std::is_same_v<M, GetHealth>) {
      reply(h, health());
    } else if constexpr (std::is_same_v<M, GetParams>) {
      reply(h, params_);
    } else if constexpr (std::is_same_v<M, SetParams>) {
      const int bad = m.first_out_of_range();
      if (bad >= 0) return nak(h, ErrorCode::out_of_range, static_cast<std::uint8_t>(bad));
      if (m.control_rate_Hz != 20000 && m.control_rate_Hz != 40000)
        return nak(h, ErrorCode::out_of_range, field_index_of<&SetParams::control_rate_Hz>());
      if (m.travel_min_counts >= m.travel_max_counts)
        return nak(h, ErrorCode::out_of_range, field_index_of<&SetParams::travel_min_counts>());
      if (programs_.running() || streamer_.running()) return nak(h, ErrorCode::busy, 255, busy_detail());
      release();  // only this loop starts a program or the stream: nothing can become busy now
      const Params p = fields_as<Params>(m);
      const std::uint32_t old_rate = params_.control_rate_Hz;
      const bool new_rate = p.control_rate_Hz != old_rate;
      StreamConfig stream;
      bool restream = false;
      if (new_rate) {
        // keep the stream's sample rate: scale its decimation with the tick rate, within the
        // rate limit and the u16 (a stream slower than 40 kHz / 65535 = 0.61 Hz stays at 0.61 Hz)
        StreamConfigure sc;
        sc.channels = streamer_.config().channels;
        sc.batch_samples = streamer_.config().batch_samples;
        const std::uint32_t scaled =
            static_cast<std::uint32_t>(streamer_.config().decimation) * p.control_rate_Hz / old_rate;
        sc.decimation = static_cast<std::uint16_t>(
            std::clamp<std::uint32_t>(scaled, min_stream_decimation(p.control_rate_Hz), 65535));
        restream = Streamer::check(sc, p.control_rate_Hz, stream, field, max_stream_rate_Hz()) ==
                   ErrorCode::ok;
      }
      hold();
      // device time runs on across a rate change: anchor it at this tick
      if (new_rate) time_base_ = {tick_, device_time_us()};
      apply_params(p);
      if (restream) {
        streamer_.apply(stream, p.control_rate_Hz);
        pressure_.set_decimation(stream.decimation);
      }
      reply(h, params_);
    } else if constexpr (std::is_same_v<M, GetCalibration>) {
      reply(h, to_proto(calibration_));
    } else if constexpr (std::is_same_v<M, SetCalibration>) {
      release();  // the checks read only the message
      CalibrationData c;
      const int bad = from_proto(fields_as<Calibration>(m), c);
      if (bad >= 0) return nak(h, ErrorCode::calibration_invalid, static_cast<std::uint8_t>(bad));
      hold();
      apply_calibration(c);
      release();
      reply(h, to_proto(calibration_));
    } else if constexpr (std::is_same_v<M, CommitCalibration>) {
      release();  // calibration_, committed_ and commits_ are the main loop's
      committed_ = serialize_calibration(calibration_);
      ++commits_;
      ack(h);
    } else if constexpr (is_one_of<M, LoadHold, LoadRamp, LoadSine, LoadSweep, LoadMultisine,
                                   LoadContactWatch>) {
      load_program(h, m);
    } else if constexpr (std::is_same_v<M, ProgramStart>) {
      if (safety_.tripped())
        return nak(h, ErrorCode::faulted, 255, static_cast<std::int32_t>(safety_.fault()));
      // a program is timed in ticks of the rate it was loaded for: after a rate change, reload
      if (program_rate_Hz_ != 0 && program_rate_Hz_ != params_.control_rate_Hz)
        return nak(h, ErrorCode::no_program, 255, 1);
      const ErrorCode e = programs_.start(tick_, encoder_.position_counts());
      if (e != ErrorCode::ok)
        return nak(h, e, 255, e == ErrorCode::busy ? busy_detail() : 0);
      loop_.reset();
      ack(h);
    } else if constexpr (std::is_same_v<M, ProgramStop>) {
      const ProgramKind kind = programs_.kind();
      if (programs_.stop(tick_)) {
        TickEvent f;
        f.kind = TickEvent::Kind::finished;
        f.tick = tick_;
        f.end = ProgramEnd::stopped_by_host;
        f.program = kind;
        f.repetitions = programs_.repetitions_done();
        ack(h);
        emit_event(f);
        return;
      }
      ack(h);
    } else if constexpr (std::is_same_v<M, GetProgramStatus>) {
      reply(h, programs_.status(tick_));
    } else if constexpr (std::is_same_v<M, StreamConfigure>) {
      if (streamer_.running()) return nak(h, ErrorCode::busy, 255, busy_detail());
      release();  // the checks and the figures (double arithmetic) read only the message
      StreamConfig c;
      const std::uint32_t max = max_stream_rate_Hz();
      const ErrorCode e = Streamer::check(m, params_.control_rate_Hz, c, field, max);
      // stream_too_fast names the limit (SPEC.md §9.1)
      if (e != ErrorCode::ok)
        return nak(h, e, field, e == ErrorCode::stream_too_fast ? static_cast<std::int32_t>(max) : 0);
      hold();
      streamer_.apply(c, params_.control_rate_Hz);
      pressure_.set_decimation(m.decimation);
      reply(h, c);
    } else if constexpr (std::is_same_v<M, StreamStart>) {
      pressure_.restart();
      streamer_.start(tick_, time_base_);
      ack(h);
    } else if constexpr (std::is_same_v<M, StreamStop>) {
      streamer_.stop();
      ack(h);
    } else if constexpr (std::is_same_v<M, FaultClear>) {
      switch (safety_.clear(wd_now_us, monitor_.cause_present(safety_.fault()))) {
        case ClearResult::cleared:
        case ClearResult::not_latched:
          ack(h);
          break;
        case ClearResult::cause_persists:
          nak(h, ErrorCode::fault_persists, 255, static_cast<std::int32_t>(safety_.fault()));
          break;
      }
    } else {
      static_assert(sizeof(M) == 0, "a host-to-device message without a handler");
    }
  }
}

}  // namespace palp::fw
