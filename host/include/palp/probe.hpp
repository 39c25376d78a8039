// SPDX-License-Identifier: Apache-2.0
// The probe client: one connection to one probe controller (hardware or palp-sim).
//
//   palp::Probe probe("sim://127.0.0.1:7070");          // connects and runs the handshake
//   probe.configure_stream({.rate_Hz = 1000});
//   probe.start_stream();
//   probe.run(palp::RampProgram{...}, 60s);             // load, start, wait for the end
//   while (auto item = probe.next(100ms)) { ... }       // samples and gap records, in order
//
// Units are SI (A, s, m, Pa). The program and parameter structs are the protocol's own messages
// (protocol/SPEC.md §10): their field names carry their units (current_A, dwell_s, _counts where
// 1 count = 1 µm).
//
// Thread-safety: every method may be called from any thread; requests are serialised (one in
// flight per connection). next()/drain() are meant for one consumer thread. One I/O thread per
// connection reads the transport, answers the waiting request, queues samples and events, and
// sends the heartbeat (every heartbeat_timeout/5 of the device's announced timeout).
//
// Back-pressure: the stream queue holds ConnectOptions::queue_items items. When it is full the
// I/O thread never blocks (it must keep reading replies and feeding the heartbeat): it drops the
// newest samples and delivers one Gap{source = host_queue} for them as soon as there is room, and
// counts them in health().host_queue_dropped.
//
// Lost replies: a request that only reads (GetStatus, GetHealth, GetParams, GetCalibration,
// GetProgramStatus, Ping) or that ends in the same state however often it runs (ProgramStop,
// StreamStop, Heartbeat, StreamConfigure, SetParams, SetCalibration, Load*) is sent again with
// the same seq when its reply does not come, at every quarter of its timeout; the first reply
// answers it (health().requests_resent counts the copies). start_stream() asks the status
// whether a StreamStart whose Ack was lost was taken. Any other request's lost reply (start(),
// clear_fault(), commit_calibration(), enter_bootloader()) is a TimeoutError: the protocol has no rule that a device
// recognises a repeated seq, and a second execution of these differs from the first.
//
// Connecting: a stream a previous host left running is stopped (it would refuse this host's
// StreamConfigure busy); a program it left is not touched (the device's heartbeat watchdog ends
// it, and the latched fault refuses this host's next program start, naming the fault).
//
// Shutdown: the destructor and close() stop any program, a contact hold and the stream
// (make_safe()), so the device is left with zero coil current, then close the transport; every
// error path of the SDK's experiments does the same before it propagates.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "palp/error.hpp"
#include "palp/health.hpp"
#include "palp/protocol/messages.hpp"
#include "palp/stream.hpp"
#include "palp/transport.hpp"

namespace palp {

using namespace std::chrono_literals;

using HoldProgram = proto::LoadHold;
using RampProgram = proto::LoadRamp;
using SineProgram = proto::LoadSine;
using SweepProgram = proto::LoadSweep;
using MultisineProgram = proto::LoadMultisine;
using ContactWatchProgram = proto::LoadContactWatch;
using Params = proto::Params;
using Calibration = proto::Calibration;

/// Who the device is (from its DeviceInfo).
struct DeviceInfo {
  std::string serial, board, git_hash;
  std::string firmware_version;  ///< "major.minor.patch"
  int protocol_major = 0, protocol_minor = 0;
  std::uint32_t schema_hash = 0;
  std::uint32_t capabilities = 0;  ///< proto::Capability bits
  double max_current_A = 0;
  double control_rate_Hz = 0;     ///< in force: DeviceInfo's at connect, then set_params()'s
  double max_stream_rate_Hz = 0;
  double heartbeat_timeout_s = 0;
  std::size_t max_payload = 0;
  bool has(proto::Capability c) const { return (capabilities >> static_cast<unsigned>(c)) & 1u; }
};

/// The handshake's outcome (an incompatible one throws VersionError instead).
struct Handshake {
  bool missing_features = false;
  std::vector<std::string> missing;  ///< "Message" or "Message.field" this SDK has, the device lacks
  std::string message;               ///< one paragraph for a person
};

struct ConnectOptions {
  std::chrono::milliseconds timeout = 2000ms;  ///< default for every request's reply
  std::size_t queue_items = 1u << 20;          ///< stream queue capacity (samples + gaps)
  bool reconnect = true;  ///< restore the session after a lost link (URI-opened transports only)
  std::chrono::milliseconds reconnect_for = 5000ms;  ///< then give up with ConnectionError
  std::string host_software;                   ///< sent in Hello; default "palp-sdk <version>"
};

/// The device's status, SI units.
struct Status {
  double t_device_s = 0;
  proto::DeviceState state = proto::DeviceState::idle;
  proto::FaultReason fault = proto::FaultReason::none;
  proto::ProgramKind program = proto::ProgramKind::none;
  proto::ProgramState program_state = proto::ProgramState::idle;
  double i_cmd_A = 0, i_A = 0, z_m = 0;
  std::int32_t encoder_counts = 0;
  double i2t_fraction = 0;
  bool streaming = false;
  std::uint16_t status_bits = 0;
};

/// How a program ended.
struct ProgramResult {
  proto::ProgramKind kind = proto::ProgramKind::none;
  proto::ProgramEnd end = proto::ProgramEnd::completed;
  double t_device_s = 0;
  int repetitions_done = 0;
};

/// The fault latch.
struct FaultInfo {
  proto::FaultReason reason = proto::FaultReason::none;
  double t_device_s = 0;      ///< when it tripped (0 when not seen as an event)
  std::int32_t detail = 0;
  std::string text;           ///< "travel_limit: the encoder left [travel_min, travel_max]"
};

/// A contact-watch firing.
struct ContactEvent {
  double t_device_s = 0;
  std::int32_t encoder_counts = 0, armed_counts = 0;
  std::uint64_t sample_index = 0;
};

/// What the calibration helpers did (the recording sidecar keeps it).
struct ZeroingRecord {
  std::string what;        ///< "current_offset" or "pressure_zero" or "home"
  double t_device_s = 0;
  std::vector<double> values;  ///< the offsets set (A, or Pa per channel, or the origin in m)
  bool committed = false;  ///< written to flash (only palpctl calibrate does that)
};

class Probe {
 public:
  /// Connects to the device a URI names (see transport.hpp) and runs the handshake. Throws
  /// ConfigError (bad URI), ConnectionError (absent), TimeoutError (no DeviceInfo reply) or
  /// VersionError (incompatible: the message names both versions and the fix).
  explicit Probe(const std::string& uri, ConnectOptions options = {});
  /// The same over a transport the application opened (a test double, the in-process
  /// simulator's transport: palp/sim_inproc.hpp); uri() is the transport's. Reconnect is off for
  /// it whatever options.reconnect says: the SDK cannot reopen a transport it did not open, so a
  /// lost link makes every later device call throw ConnectionError saying so, and the
  /// application constructs a new Probe with a new transport. Throws as the URI constructor
  /// does (ConfigError for a null transport).
  Probe(std::unique_ptr<Transport> transport, ConnectOptions options = {});
  ~Probe();
  Probe(Probe&&) noexcept;
  Probe& operator=(Probe&&) noexcept;
  Probe(const Probe&) = delete;
  Probe& operator=(const Probe&) = delete;

  const DeviceInfo& info() const;
  const Handshake& handshake() const;
  const std::string& uri() const;

  Status status();
  /// Fresh device counters (a GetHealth round trip) with this connection's host counters.
  HealthCounters health();

  Params params();
  void set_params(const Params& p);
  Calibration calibration();
  /// Replaces the calibration in RAM; only commit_calibration() writes flash.
  void set_calibration(const Calibration& c);
  void commit_calibration();

  // --- programs ---------------------------------------------------------------------------
  void load(const HoldProgram& p);
  void load(const RampProgram& p);
  void load(const SineProgram& p);
  void load(const SweepProgram& p);
  void load(const MultisineProgram& p);
  void load(const ContactWatchProgram& p);
  void start();
  void stop();
  /// Waits for the running program to end. Throws TimeoutError, or FaultError when it ended by
  /// a fault. The end is the EventProgramFinished; when that event is lost, GetProgramStatus,
  /// asked every 250 ms, shows it (then t_device_s is when it was seen, repetitions_done the
  /// status's repetition).
  ProgramResult wait(std::chrono::milliseconds timeout);
  /// load + start + wait.
  template <class P>
  ProgramResult run(const P& program, std::chrono::milliseconds timeout) {
    load(program);
    start();
    return wait(timeout);
  }
  proto::ProgramStatus program_status();
  /// The contact watch's firing, when one has come since the last start(); waits up to timeout.
  std::optional<ContactEvent> wait_contact(std::chrono::milliseconds timeout);

  FaultInfo fault();
  void clear_fault();

  /// Sends EnterBootloader with its magic (SPEC.md §6.2) and waits for its Ack: the controller
  /// then reboots into its ROM bootloader (the STM32 enumerates as the DFU device 0483:df11,
  /// palp/flash.hpp). Afterwards this Probe is closed as by close() but without make_safe(): the
  /// device has left. The device refuses it with DeviceError busy while a program runs (call
  /// make_safe() first). Sent once: a lost Ack is a TimeoutError (the device may have left).
  void enter_bootloader();

  // --- streaming --------------------------------------------------------------------------
  /// Configures the stream. Throws ConfigError, before anything is sent, when the rate does not
  /// divide the control rate or exceeds the device's maximum, or when the stream's byte rate
  /// exceeds what the transport carries (the message gives both numbers).
  StreamInfo configure_stream(const StreamSettings& s);
  void start_stream();
  void stop_stream();
  const StreamInfo& stream_info() const;
  /// The next sample or gap, waiting up to timeout; nullopt when none came.
  std::optional<StreamItem> next(std::chrono::milliseconds timeout);
  /// Moves up to max queued items into out (appended); returns how many. Does not wait.
  std::size_t drain(std::vector<StreamItem>& out, std::size_t max = SIZE_MAX);
  /// Items go to this callback instead of the queue, in order, on the I/O thread: keep it short
  /// and do not call this Probe's methods from it (their replies are read by the same thread).
  /// It is never called while the SDK holds a lock that next()/drain() take, so it may take the
  /// application's own locks. Items queued before it was set are handed to it first. Pass an
  /// empty function to go back to the queue.
  void on_stream(std::function<void(const StreamItem&)> callback);
  ClockMapping clock() const;

  // --- calibration helpers (RAM only; the recording sidecar keeps what they did) -----------
  /// With the coil idle (0 A), averages the measured current for `seconds` and sets the
  /// current-sense offset so it reads zero. Returns the new offset, A.
  double zero_current_offset(double seconds = 0.5);
  /// With the probe unloaded, averages each pressure channel and sets its offset. Returns Pa.
  std::vector<double> zero_pressure(double seconds = 0.5);
  /// Pulls the coil against its rear end stop (hold_current_A < 0), waits until it rests, and
  /// sets the stroke origin there. Returns the origin's encoder count.
  std::int32_t home(double hold_current_A = -0.3, double seconds = 1.0);
  const std::vector<ZeroingRecord>& zeroing() const;

  /// The safe state, from any state this or an earlier host left: stops any program and a
  /// contact hold (ProgramStop) and the stream (StreamStop), then reads the status and returns
  /// it, showing no program running and 0 A commanded. Both stops are resent with the same seq
  /// when their reply is lost. Throws DeviceError when the status still shows a program or a
  /// current, and as every request does (a latched fault does not refuse it).
  Status make_safe();

  /// make_safe() (its errors ignored: a lost link leaves the current to the device's heartbeat
  /// watchdog) and closes. Safe to call twice. Afterwards info(),
  /// handshake() and uri() still answer; every device call throws ConnectionError. A moved-from
  /// Probe may only be destroyed or assigned to.
  void close();

 private:
  void stop_stale_stream();
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// This SDK's version, "major.minor.patch".
const char* sdk_version();

}  // namespace palp
