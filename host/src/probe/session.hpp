// SPDX-License-Identifier: Apache-2.0
// One connection to one controller: the transport, the handshake, the I/O thread, the request
// that is waiting for its reply, events, the stream, the heartbeat, the clock fit and reconnect.
// probe.cpp puts the public API on top of it.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <variant>

#include "palp/probe.hpp"
#include "palp/protocol/frame.hpp"
#include "palp/transport.hpp"
#include "probe/clock_fit.hpp"
#include "probe/stream_assembler.hpp"
#include "probe/stream_queue.hpp"

namespace palp::detail {

using Reply = std::variant<std::monostate, proto::DeviceInfo, proto::Ack, proto::Nak, proto::Pong,
                           proto::Status, proto::Health, proto::Params, proto::Calibration,
                           proto::ProgramStatus, proto::StreamConfig>;

using Clock = std::chrono::steady_clock;
double now_s();  ///< host steady clock, seconds

/// Events as the I/O thread saw them; each kind counts up so a waiter can ask for "one after N".
struct EventLog {
  std::uint64_t finished = 0, contact = 0, fault = 0;
  ProgramResult last_finished;
  ContactEvent last_contact;
  FaultInfo last_fault;
};

/// Requests sent again, with the same seq, when their reply does not come: those that only read,
/// and those that leave the device in the same state however often it executes them (a stop; a
/// load, a configuration or a setting with the same values: refused busy by every copy when a
/// program or the stream runs, taken by every copy otherwise). SPEC §4.2 and §6.2 give no rule
/// that a device recognises a repeated seq (and answers it from a cache without executing it
/// again), so a request whose second execution differs from the first is sent once:
/// ProgramStart (a copy is refused busy), StreamStart (a copy restarts the stream), FaultClear
/// (a copy could clear a fault that tripped in between), CommitCalibration (a second flash
/// write), EnterBootloader. Its lost reply is a TimeoutError (Probe::start_stream asks the
/// status whether it was taken).
template <class Req>
inline constexpr bool kResendable =
    std::is_same_v<Req, proto::GetStatus> || std::is_same_v<Req, proto::GetHealth> ||
    std::is_same_v<Req, proto::GetParams> || std::is_same_v<Req, proto::GetCalibration> ||
    std::is_same_v<Req, proto::GetProgramStatus> || std::is_same_v<Req, proto::GetDeviceInfo> ||
    std::is_same_v<Req, proto::Ping> || std::is_same_v<Req, proto::Heartbeat> ||
    std::is_same_v<Req, proto::ProgramStop> || std::is_same_v<Req, proto::StreamStop> ||
    std::is_same_v<Req, proto::StreamConfigure> || std::is_same_v<Req, proto::SetParams> ||
    std::is_same_v<Req, proto::SetCalibration> || std::is_same_v<Req, proto::LoadHold> ||
    std::is_same_v<Req, proto::LoadRamp> || std::is_same_v<Req, proto::LoadSine> ||
    std::is_same_v<Req, proto::LoadSweep> || std::is_same_v<Req, proto::LoadMultisine> ||
    std::is_same_v<Req, proto::LoadContactWatch>;
/// How often a resendable request goes out within its timeout (every timeout / kSendAttempts).
inline constexpr int kSendAttempts = 4;

class Session {
 public:
  /// Opens the transport the URI names; a lost link reopens it (ConnectOptions::reconnect).
  Session(const std::string& uri, const ConnectOptions& options);
  /// Over a transport the application opened; a lost link is never reopened (probe.hpp).
  Session(std::unique_ptr<Transport> transport, const ConnectOptions& options);
  ~Session();

  /// Sends a request and waits for its reply. A floating-point field that is not finite is a
  /// ConfigError naming it, before anything is sent. A Nak becomes DeviceError; no reply in time,
  /// TimeoutError; a lost link, ConnectionError. A kResendable request whose reply is lost is
  /// sent again with the same seq at every timeout / kSendAttempts (the whole wait stays
  /// `timeout`); the first reply with that seq answers it, later copies count as stray.
  template <class Req>
  Reply request(const Req& m, std::chrono::milliseconds timeout);

  const proto::DeviceInfo& device_info() const { return device_; }
  const Handshake& handshake() const { return handshake_; }
  const std::string& uri() const { return uri_; }
  std::chrono::milliseconds default_timeout() const { return options_.timeout; }
  std::uint32_t transport_bytes_per_s() const { return transport_bytes_per_s_; }

  // events
  EventLog events() const;
  /// Waits until pred(events) holds; false on timeout. Throws ConnectionError when the link is
  /// lost for good.
  template <class Pred>
  bool wait_event(std::chrono::milliseconds timeout, Pred&& pred);

  // stream
  void stream_configured(const proto::StreamConfigure& c);
  void stream_started();
  void stream_stopped();
  StreamQueue& queue() { return queue_; }

  HealthCounters health_snapshot() const;
  void set_device_health(const proto::Health& h);
  ClockMapping clock() const;
  void set_heartbeat_timeout_ms(std::uint32_t ms);

  /// Stops the I/O thread and closes the transport.
  void shutdown();

 private:
  enum class AsyncKind { heartbeat, ping, health, restore };
  struct Async {
    AsyncKind kind;
    double sent_s;
  };

  void handshake_and_start();
  void io_loop();
  void on_bytes(const std::uint8_t* data, std::size_t n);
  void on_reply(const proto::FrameHeader& h, Reply&& r);
  template <class M>
  void on_message(const proto::FrameHeader& h, const M& m);
  void service_timers();
  template <class M>
  std::uint16_t send_async(const M& m, AsyncKind kind);
  template <class M>
  void write_message(const M& m, std::uint16_t seq);
  bool reconnect(const std::string& why);
  void link_lost(const std::string& why);
  [[noreturn]] void throw_timeout(const std::string& what, std::chrono::milliseconds t) const;

  std::string uri_;
  ConnectOptions options_;
  std::shared_ptr<Transport> transport_;
  bool reopenable_ = true;  // opened from uri_ (an injected transport cannot be reopened)
  std::uint32_t transport_bytes_per_s_ = 0;
  proto::DeviceInfo device_{};
  Handshake handshake_;
  std::atomic<std::uint16_t> seq_{1};
  proto::FrameReader reader_;  // the I/O thread's own
  proto::RejectCounters reader_counters_{};  // its counters, copied under mu_

  mutable std::mutex mu_;  // guards everything below and the waiting request
  std::condition_variable cv_;
  std::mutex request_mu_;  // one request in flight
  std::mutex write_mu_;
  std::optional<std::uint16_t> waiting_seq_;
  Reply reply_;
  bool reply_ready_ = false;
  std::string reply_error_;  // the link was lost while waiting
  bool link_up_ = true;
  std::string dead_;  // non-empty: the link is gone for good, with the reason
  EventLog events_;
  std::map<std::uint16_t, Async> async_;
  proto::Health device_health_{};
  bool device_health_valid_ = false;
  std::uint64_t reconnects_ = 0;
  std::uint64_t stray_replies_ = 0;
  std::uint64_t resends_ = 0;  // copies of resendable requests sent (guarded by mu_)
  ClockFit clock_;
  StreamAssembler assembler_;
  std::optional<proto::StreamConfigure> stream_config_;
  bool streaming_ = false;
  std::uint32_t heartbeat_ms_ = 500;

  StreamQueue queue_;
  std::atomic<bool> stop_{false};
  double last_heartbeat_s_ = 0, last_ping_s_ = 0, last_health_s_ = 0;
  int pings_sent_ = 0;
  std::thread io_;
};

}  // namespace palp::detail

#include "probe/session_inl.hpp"
