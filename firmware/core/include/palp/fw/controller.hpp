// SPDX-License-Identifier: Apache-2.0
// The probe controller: every decision the firmware makes, with no hardware access. A board
// (STM32G474, QEMU, palp-sim) calls tick() at the control rate with the raw sensor values and
// applies the coil voltage it returns; it hands received bytes to receive(), sends what
// transmit() gives, and calls service() from its main loop.
//
// Contexts: tick() is the control interrupt; receive(), service() and transmit() are the main
// loop. Samples and events cross from tick() to the main loop through SPSC queues. A command acts
// on the tick's state between two ticks: receive() holds the board's TickGuard (which masks the
// control interrupt) from the moment a decoded request is handled until its reply is built, and
// only then encodes the reply with the tick free; a handler releases it meanwhile for work that
// reads only the message or main-loop state (controller_dispatch.cpp). A Load* request's program
// is synthesised into the runner's staging slot with the tick free (a 400-line multisine:
// ~25 000 instructions, 3-4 ticks) and adopted in a short held section (an index flip).
// Decoding, the reply's encoding and service()/transmit() never hold the guard;
// load_calibration_block() and set_identity() hold it for what they change. palp-sim sets no
// guard (one thread calls everything).
//
// Time: device time is the tick count over the control rate (exact), anchored at the last rate
// change (SetParams.control_rate_Hz) so it runs on continuously across it; the host heartbeat
// watchdog runs on the separate watchdog clock the board passes in (MCU timer, or wall time in
// palp-sim).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "palp/fw/calibration.hpp"
#include "palp/fw/current_loop.hpp"
#include "palp/fw/encoder.hpp"
#include "palp/fw/pressure.hpp"
#include "palp/fw/programs.hpp"
#include "palp/fw/ring.hpp"
#include "palp/fw/safety.hpp"
#include "palp/fw/sensor_monitor.hpp"
#include "palp/fw/spsc_queue.hpp"
#include "palp/fw/streamer.hpp"
#include "palp/protocol/frame.hpp"
#include "palp/protocol/handshake.hpp"

namespace palp::fw {

/// Who the device is (DeviceInfo). The protocol fields default to this build's; palp-sim's
/// control channel may announce others to test a host's verdicts.
struct DeviceIdentity {
  const char* board = "unknown";
  const char* serial = "";
  const char* git_hash = "";
  std::uint8_t fw_major = 0, fw_minor = 1, fw_patch = 0;
  std::uint32_t capabilities = 0;
  proto::ProtocolVersion protocol = proto::kThisProtocol;
  /// The highest stream sample rate this board carries (its link's bandwidth), advertised in
  /// DeviceInfo.max_stream_rate_Hz; a faster StreamConfigure is refused stream_too_fast. The
  /// core produces at most Streamer::kMaxRate_Hz: a board may lower the limit, not raise it
  /// (values outside 1 ... kMaxRate_Hz count as the nearest end).
  std::uint32_t max_stream_rate_Hz = Streamer::kMaxRate_Hz;
};

/// How a board keeps tick() from running while a command mutates its state: hold() masks the
/// control interrupt, release() unmasks it (a tick that fell due meanwhile runs then, late by at
/// most the held section: the longest is measured in firmware/core/README.md). Default: none
/// (palp-sim: one thread). The controller never nests hold() and always pairs it with release()
/// before receive() returns.
struct TickGuard {
  void (*hold)(void* ctx) = nullptr;
  void (*release)(void* ctx) = nullptr;
  void* ctx = nullptr;
};

/// One control tick's raw inputs.
struct TickInputs {
  float i_sense_A = 0.0f;                 ///< current-sense reading before calibration
  std::uint16_t encoder_timer = 0;        ///< the encoder timer's 16-bit count
  PressureChannels::Codes pressure_codes{};  ///< six 12-bit ADC codes
  std::uint64_t watchdog_now_us = 0;      ///< the watchdog's own clock
  float supply_V = kDefaultSupply_V;      ///< measured H-bridge supply (sensor_monitor.hpp)
  bool driver_fault = false;              ///< the H-bridge driver's fault line, asserted
  /// Control ticks that fell due since the previous tick() but never ran (the board's timer
  /// interrupt was still pending when the next expiry came): counted in
  /// Health.control_overruns. The tick index and device time count only ticks that ran.
  std::uint32_t missed_ticks = 0;
};

/// What the board applies until the next tick.
struct TickOutputs {
  float v_coil_V = 0.0f;     ///< average coil voltage (PWM duty x supply)
  bool contact_line = false; ///< level of the contact-output line to the robot
};

/// Health counters the core keeps besides the frame reader's and the streamer's.
struct ControllerCounters {
  std::uint32_t frames_tx = 0;
  std::uint32_t tx_frames_dropped = 0;   ///< frames that did not fit the transmit buffer
  std::uint32_t events_dropped = 0;      ///< events lost at the ISR event queue
  std::uint32_t control_overruns = 0;
};

class Controller {
 public:
  static constexpr std::size_t kSampleQueue = 256;   ///< ISR queue, samples
  static constexpr std::size_t kEventQueue = 16;     ///< ISR queue, events
  static constexpr std::size_t kTxBytes = 8192;      ///< transmit buffer (about 8 frames)

  explicit Controller(const DeviceIdentity& identity);

  // --- control interrupt -----------------------------------------------------------------------
  void tick(const TickInputs& in, TickOutputs& out);

  // --- main loop -------------------------------------------------------------------------------
  /// Bytes from the host. Every valid request feeds the heartbeat watchdog at watchdog_now_us.
  void receive(const std::uint8_t* data, std::size_t size, std::uint64_t watchdog_now_us);
  /// Moves samples and events from the tick into frames. Call often (every few ticks).
  void service();
  /// Up to capacity bytes for the host; returns how many were written into out.
  std::size_t transmit(std::uint8_t* out, std::size_t capacity);
  std::size_t tx_pending() const { return tx_.size(); }

  // --- for the board ---------------------------------------------------------------------------
  std::uint32_t control_rate_Hz() const { return params_.control_rate_Hz; }
  std::uint64_t ticks() const { return tick_; }
  std::uint64_t device_time_us() const;
  const proto::Params& params() const { return params_; }
  const CalibrationData& calibration() const { return calibration_; }
  /// Loads a calibration block read from flash at boot; returns its status (a bad block keeps
  /// the defaults and is reported, never silently replaced).
  CalibrationStatus load_calibration_block(const std::uint8_t* data, std::size_t size);
  /// The block CommitCalibration last wrote (the board copies it to flash), and a counter that
  /// changes at every commit.
  const CalibrationBlock& committed_block() const { return committed_; }
  std::uint32_t commits() const { return commits_; }
  bool bootloader_requested() const { return bootloader_requested_; }
  /// A new identity; a lower max_stream_rate_Hz also slows a configured stream that would exceed
  /// it (to the fastest rate allowed) unless it runs.
  void set_identity(const DeviceIdentity& identity);
  const DeviceIdentity& identity() const { return identity_; }
  /// The stream rate limit in force (DeviceIdentity::max_stream_rate_Hz within 1 ...
  /// Streamer::kMaxRate_Hz, 20 kHz).
  std::uint32_t max_stream_rate_Hz() const;
  /// The guard receive() holds around every change of the tick's state (see TickGuard). Set it
  /// before the control interrupt starts.
  void set_tick_guard(const TickGuard& guard) { guard_ = guard; }
  /// Ends the host's session: until its next compatible Hello only the frozen requests are
  /// served (SPEC.md §6.2). A board calls it when a connection ends or a new one begins
  /// (palp-sim: every new client); on USB the host re-Hellos instead.
  void end_session() { session_ = Session::none; }
  /// True after a compatible Hello, until end_session() or an incompatible Hello.
  bool session_open() const { return session_ == Session::open; }
  bool faulted() const { return safety_.tripped(); }
  proto::FaultReason fault() const { return safety_.fault(); }
  proto::Health health() const;

 private:
  struct TickEvent {
    enum class Kind : std::uint8_t { fault, contact, finished } kind = Kind::fault;
    std::uint64_t tick = 0;
    proto::FaultReason reason = proto::FaultReason::none;
    std::int32_t detail = 0;
    proto::ProgramEnd end = proto::ProgramEnd::completed;
    proto::ProgramKind program = proto::ProgramKind::none;
    std::uint16_t repetitions = 0;
    std::int32_t encoder = 0;
    std::int32_t armed = 0;
    std::uint32_t sample_index = 0;
  };

  /// A decoded request: dispatch() inside the tick guard, released at the latest on return.
  template <class M>
  void handle(const proto::FrameHeader& h, const M& m, std::uint64_t watchdog_now_us);
  template <class M>
  void dispatch(const proto::FrameHeader& h, const M& m, std::uint64_t watchdog_now_us);
  /// Load*: the busy check held, the synthesis (ProgramRunner::stage) released, the adoption
  /// held.
  template <class M>
  void load_program(const proto::FrameHeader& h, const M& m);
  /// The tick guard: hold() then release(); each a no-op when already in that state.
  void hold();
  void release();
  /// The fewest ticks per sample that keep the stream within max_stream_rate_Hz().
  std::uint16_t min_stream_decimation(std::uint32_t control_rate_Hz) const;
  /// Reconfigures a stream that is not running if it is faster than max_stream_rate_Hz().
  void fit_stream_to_max_rate();
  /// Encodes m into the transmit buffer; false when it does not fit (counted as a dropped frame
  /// unless count_drop is false, for senders that keep the message and retry).
  template <class M>
  bool send(const M& m, std::uint16_t seq, std::uint8_t flags, bool count_drop = true);
  /// A request's answer. It ends the held section (the encoding runs with the tick free), so a
  /// handler makes every change to the tick's state before it replies.
  template <class M>
  bool reply(const proto::FrameHeader& request, const M& m) {
    release();
    return send(m, request.seq, proto::kFlagResponse);
  }
  void ack(const proto::FrameHeader& request);
  void nak(const proto::FrameHeader& request, proto::ErrorCode error,
           std::uint8_t field_index = 255, std::int32_t detail = 0);
  /// Nak.detail of busy: the running program's kind, none when only the stream runs.
  std::int32_t busy_detail() const;
  void apply_params(const proto::Params& p);
  void apply_calibration(const CalibrationData& c);
  proto::DeviceInfo device_info() const;
  proto::DeviceState device_state() const;
  proto::Status status() const;
  std::uint16_t status_bits() const;
  void push_event(const TickEvent& e);
  void emit_event(const TickEvent& e);
  float dt_s() const { return 1.0f / static_cast<float>(params_.control_rate_Hz); }
  std::uint64_t us_of_tick(std::uint64_t tick) const;

  DeviceIdentity identity_;
  proto::Params params_{};
  CalibrationData calibration_{};
  CalibrationBlock committed_{};
  std::uint32_t commits_ = 0;

  CurrentLoop loop_;
  Encoder encoder_;
  PressureChannels pressure_;
  Safety safety_;
  SensorMonitor monitor_;
  ProgramRunner programs_;
  Streamer streamer_;

  std::uint64_t tick_ = 0;   // ticks done
  TimeBase time_base_{};     // the tick and device time of the last control-rate change
  bool encoder_started_ = false;
  float i_set_A_ = 0.0f;     // last tick's clamped set-point
  float i_meas_A_ = 0.0f;    // last tick's calibrated measurement
  float v_cmd_V_ = 0.0f;
  bool clamped_ = false;
  bool contact_line_ = false;
  std::uint64_t contact_line_until_tick_ = 0;
  /// The Hello gate (SPEC.md §6.2): none until a Hello, open after a compatible one,
  /// incompatible after an incompatible one.
  enum class Session : std::uint8_t { none, open, incompatible };
  Session session_ = Session::none;
  std::uint32_t program_rate_Hz_ = 0;  // control rate the loaded program was timed for
  bool bootloader_requested_ = false;
  std::uint16_t device_seq_ = 0;
  TickGuard guard_{};
  bool held_ = false;

  SpscQueue<IndexedSample, kSampleQueue> samples_;
  SpscQueue<TickEvent, kEventQueue> events_;
  Ring<std::uint8_t, kTxBytes> tx_;
  proto::FrameReader reader_;
  ControllerCounters counters_{};

  /// Tests only (tests/fw_core/test_tick_guard.cpp): reads the tick's state to prove that
  /// receive() changes it only inside the guard.
  friend struct TickStateProbe;
};

template <class M>
inline bool Controller::send(const M& m, std::uint16_t seq, std::uint8_t flags, bool count_drop) {
  proto::u8 scratch[proto::kMaxWireFrame];
  const std::size_t n = proto::encode_message(m, seq, flags, scratch, sizeof scratch,
                                              identity_.protocol.major, identity_.protocol.minor);
  if (n == 0 || !tx_.push_n(scratch, n)) {
    if (count_drop) ++counters_.tx_frames_dropped;
    return false;
  }
  ++counters_.frames_tx;
  return true;
}

}  // namespace palp::fw
