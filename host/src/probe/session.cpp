// SPDX-License-Identifier: Apache-2.0
// The probe session: handshake, I/O thread, replies, events, heartbeat, clock fit, reconnect.
#include "probe/session.hpp"

#include <cstdio>

#include "palp/protocol/handshake.hpp"
#include "palp/protocol/verdict_text.hpp"
#include "probe/exchange.hpp"
#include "probe/log.hpp"

namespace palp::detail {

double now_s() {
  return std::chrono::duration<double>(Clock::now().time_since_epoch()).count();
}

namespace {

template <class E>
const char* enum_doc(E value) {
  for (const auto& v : proto::EnumInfo<E>::values)
    if (v.value == static_cast<std::uint32_t>(value)) return v.doc;
  return "a value this SDK does not know";
}
template <class E>
std::string enum_text(E value) {
  const char* n = proto::enum_name(value);
  return n ? n : "#" + std::to_string(static_cast<unsigned>(value));
}

/// Sends Hello and reads until the DeviceInfo reply comes (exchange.hpp).
proto::DeviceInfo hello(Transport& t, const std::string& host_software, std::uint16_t seq,
                        std::chrono::milliseconds timeout) {
  proto::Hello h;
  h.host_major = proto::kProtocolMajor;
  h.host_minor = proto::kProtocolMinor;
  h.host_schema_hash = proto::kSchemaHash;
  h.host_software.assign(host_software.c_str());
  const auto r = exchange<proto::DeviceInfo>(
      t, h, seq, timeout, "the DeviceInfo reply to Hello",
      "(is it a palp controller, and is its firmware running?)", kSendAttempts);
  if (const auto* info = std::get_if<proto::DeviceInfo>(&r)) return *info;
  throw ProtocolError("the device answered Hello with a Nak from " + t.uri());
}

Handshake judge_or_throw(const proto::DeviceInfo& d) {
  const proto::ProtocolVersion device{d.protocol_major, d.protocol_minor, d.schema_hash};
  const proto::Verdict v = proto::judge(proto::kThisProtocol, device);
  Handshake hs;
  if (v.compatibility == proto::Compatibility::compatible_missing_features)
    hs.missing = proto::missing_feature_names(d.protocol_minor);
  hs.missing_features = !hs.missing.empty();
  hs.message = proto::describe_verdict(v, proto::kThisProtocol, d, hs.missing);
  if (v.compatibility == proto::Compatibility::incompatible) throw VersionError(hs.message);
  return hs;
}

}  // namespace

std::string nak_text(const char* request, const proto::FieldInfo* fields, std::size_t nfields,
                     const proto::Nak& nak) {
  std::string s = std::string(request) + " refused: " + enum_text(nak.error) + " (" +
                  enum_doc(nak.error) + ")";
  if (nak.field_index != 255) {
    s += ", field ";
    s += nak.field_index < nfields ? fields[nak.field_index].name
                                   : "#" + std::to_string(nak.field_index);
  }
  if (nak.error == proto::ErrorCode::faulted || nak.error == proto::ErrorCode::fault_persists)
    s += "; latched fault: " + enum_text(static_cast<proto::FaultReason>(nak.detail));
  // detail names the running program, none when only the stream runs (SPEC §6.3): a stream
  // left running by an earlier host read "running: none"
  if (nak.error == proto::ErrorCode::busy)
    s += nak.detail != 0 ? "; running: " + enum_text(static_cast<proto::ProgramKind>(nak.detail))
                         : std::string("; the stream is running (no program)");
  return s;
}

Session::Session(const std::string& uri, const ConnectOptions& options)
    : uri_(uri), options_(options), queue_(options.queue_items) {
  transport_ = open_transport(uri, options_.timeout);
  handshake_and_start();
}

Session::Session(std::unique_ptr<Transport> transport, const ConnectOptions& options)
    : options_(options), queue_(options.queue_items) {
  if (!transport) throw ConfigError("palp::Probe: the transport given is null");
  uri_ = transport->uri();
  transport_ = std::move(transport);
  reopenable_ = false;
  handshake_and_start();
}

void Session::handshake_and_start() {
  if (options_.host_software.empty()) options_.host_software = std::string("palp-sdk ") + sdk_version();
  transport_bytes_per_s_ = transport_->max_device_bytes_per_s();
  device_ = hello(*transport_, options_.host_software, seq_++, options_.timeout);
  handshake_ = judge_or_throw(device_);
  heartbeat_ms_ = device_.heartbeat_timeout_ms;
  detail::log(LogLevel::info, "connected to " + uri_ + ": device " +
                                  std::string(device_.serial.bytes.data(), device_.serial.length()));
  io_ = std::thread([this] { io_loop(); });
}

Session::~Session() { shutdown(); }

void Session::shutdown() {
  stop_ = true;
  if (io_.joinable()) io_.join();
  std::lock_guard lock(mu_);
  if (dead_.empty()) dead_ = "the connection to " + uri_ + " was closed";
  transport_.reset();
  cv_.notify_all();
}

void Session::throw_timeout(const std::string& what, std::chrono::milliseconds t) const {
  throw TimeoutError(what + " from " + uri_, static_cast<double>(t.count()) / 1000.0,
                     health_snapshot());
}

EventLog Session::events() const {
  std::lock_guard lock(mu_);
  return events_;
}

HealthCounters Session::health_snapshot() const {
  HealthCounters h;
  {
    std::lock_guard lock(mu_);
    if (device_health_valid_) {
      const proto::Health& d = device_health_;
      h.device_valid = true;
      h.device_time_us = d.device_time_us;
      h.device_frames_rx = d.frames_rx;
      h.device_frames_tx = d.frames_tx;
      h.device_rx_rejected = d.rx_bad_cobs + d.rx_bad_crc + d.rx_oversize + d.rx_truncated +
                             d.rx_length_mismatch + d.rx_unsupported_major +
                             d.rx_unknown_message + d.rx_short_payload + d.rx_bad_field;
      h.isr_queue_overflows = d.isr_queue_overflows;
      h.stream_backlog_max = d.stream_backlog_max;
      h.stream_samples_lost = d.stream_samples_lost;
      h.usb_in_not_drained = d.usb_in_not_drained;
      h.tx_frames_dropped = d.tx_frames_dropped;
      h.control_overruns = d.control_overruns;
      h.device_stream_gaps = d.stream_gaps;
    }
    h.host_frames_rx = reader_counters_[proto::Reject::ok];
    h.host_rx_rejected = reader_counters_.rejected() + assembler_.rejected();
    h.reconnects = reconnects_;
    h.requests_resent = resends_;
  }
  queue_.count_into(h);
  return h;
}

void Session::set_device_health(const proto::Health& h) {
  std::lock_guard lock(mu_);
  device_health_ = h;
  device_health_valid_ = true;
}

ClockMapping Session::clock() const {
  std::lock_guard lock(mu_);
  return clock_.mapping();
}

void Session::set_heartbeat_timeout_ms(std::uint32_t ms) {
  std::lock_guard lock(mu_);
  heartbeat_ms_ = ms;
}

void Session::stream_configured(const proto::StreamConfigure& c) {
  std::lock_guard lock(mu_);
  stream_config_ = c;
}

void Session::stream_started() {
  std::lock_guard lock(mu_);
  assembler_.restart();
  streaming_ = true;
}

void Session::stream_stopped() {
  std::lock_guard lock(mu_);
  streaming_ = false;
}

// ---- the I/O thread ----------------------------------------------------------------------------

void Session::io_loop() {
  std::array<std::uint8_t, 16384> buf;
  while (!stop_) {
    std::shared_ptr<Transport> t;
    {
      std::lock_guard lock(mu_);
      t = transport_;
    }
    try {
      const std::size_t n = t->read(buf, std::chrono::milliseconds(5));
      if (n > 0) on_bytes(buf.data(), n);
      service_timers();
    } catch (const ConnectionError& e) {
      t.reset();  // link_lost lets the session's copy go too
      link_lost(e.what());
      if (!options_.reconnect || !reopenable_) {
        std::lock_guard lock(mu_);
        dead_ = "the link to " + uri_ + " was lost (" + e.what() +
                (reopenable_ ? ") and ConnectOptions::reconnect is off: connect again"
                             : ") and a transport given to the Probe is never reopened: "
                               "construct the Probe again with a new transport");
        detail::log(LogLevel::error, dead_);
        cv_.notify_all();
        return;
      }
      detail::log(LogLevel::warning, "the link to " + uri_ + " was lost (" + e.what() + "): reconnecting");
      if (!reconnect(e.what())) return;
    } catch (const TimeoutError&) {
      // a heartbeat write that could not go out in time: the read side will tell if it is gone
    }
  }
}

void Session::on_bytes(const std::uint8_t* data, std::size_t n) {
  std::vector<StreamItem> items;
  reader_.feed_messages(
      data, n, [&](const proto::FrameHeader& h, const auto& m) {
        using M = std::decay_t<decltype(m)>;
        if constexpr (std::is_same_v<M, proto::SampleBatch>) {
          std::lock_guard lock(mu_);
          const ClockMapping map = clock_.mapping();
          assembler_.batch(m, [&](double d) { return map.to_host_s(d); }, items);
        } else {
          on_message(h, m);
        }
      },
      [](proto::Reject) {});
  {
    std::lock_guard lock(mu_);
    reader_counters_ = reader_.counters();
  }
  if (!items.empty()) queue_.push(items);
}

template <class M>
void Session::on_message(const proto::FrameHeader& h, const M& m) {
  if constexpr (std::is_constructible_v<Reply, M> && !std::is_same_v<M, std::monostate>) {
    if (h.flags & proto::kFlagResponse) on_reply(h, Reply(m));
  } else if constexpr (std::is_same_v<M, proto::EventProgramFinished>) {
    std::lock_guard lock(mu_);
    events_.last_finished = {m.kind, m.end, static_cast<double>(m.time_us) * 1e-6,
                             m.repetitions_done};
    ++events_.finished;
    cv_.notify_all();
  } else if constexpr (std::is_same_v<M, proto::EventContact>) {
    std::lock_guard lock(mu_);
    events_.last_contact = {static_cast<double>(m.time_us) * 1e-6, m.encoder_count, m.armed_count,
                            m.sample_index};
    ++events_.contact;
    cv_.notify_all();
  } else if constexpr (std::is_same_v<M, proto::EventFault>) {
    std::lock_guard lock(mu_);
    events_.last_fault = {m.reason, static_cast<double>(m.time_us) * 1e-6, m.detail,
                          enum_text(m.reason) + ": " + enum_doc(m.reason)};
    ++events_.fault;
    cv_.notify_all();
  } else if constexpr (std::is_same_v<M, proto::EventStreamGap>) {
    std::lock_guard lock(mu_);
    assembler_.device_gap(m);
  }
  // anything else a device sends unasked (a request id, say) is ignored: it is counted by the
  // frame reader and changes nothing
}

void Session::on_reply(const proto::FrameHeader& h, Reply&& r) {
  std::unique_lock lock(mu_);
  if (waiting_seq_ && *waiting_seq_ == h.seq) {
    reply_ = std::move(r);
    reply_ready_ = true;
    cv_.notify_all();
    return;
  }
  const auto it = async_.find(h.seq);
  if (it == async_.end()) {
    ++stray_replies_;  // a late reply to a request that timed out
    return;
  }
  const Async a = it->second;
  async_.erase(it);
  if (const auto* pong = std::get_if<proto::Pong>(&r)) {
    clock_.add(a.sent_s, static_cast<double>(pong->device_time_us) * 1e-6, now_s());
  } else if (const auto* health = std::get_if<proto::Health>(&r)) {
    device_health_ = *health;
    device_health_valid_ = true;
  }
}

void Session::service_timers() {
  const double t = now_s();
  double hb_period, ping_period;
  {
    std::lock_guard lock(mu_);
    hb_period = heartbeat_ms_ * 1e-3 / 5.0;
    // a quick burst of pings at first gives the clock fit its points, then one every 200 ms
    ping_period = pings_sent_ < 8 ? 0.01 : 0.2;
  }
  if (t - last_heartbeat_s_ >= hb_period) {
    last_heartbeat_s_ = t;
    send_async(proto::Heartbeat{}, AsyncKind::heartbeat);
  }
  if (t - last_ping_s_ >= ping_period) {
    last_ping_s_ = t;
    ++pings_sent_;
    proto::Ping p;
    p.nonce = static_cast<std::uint32_t>(pings_sent_);
    p.host_time_us = static_cast<std::uint64_t>(t * 1e6);
    send_async(p, AsyncKind::ping);
  }
  if (t - last_health_s_ >= 1.0) {
    last_health_s_ = t;
    send_async(proto::GetHealth{}, AsyncKind::health);
  }
}

// ---- losing and restoring the link ------------------------------------------------------------

void Session::link_lost(const std::string& why) {
  std::lock_guard lock(mu_);
  link_up_ = false;
  // the lost transport is closed before anything reopens the URI: a tty stays locked, and a
  // replugged USB-serial adapter gets its old name back only once the last fd on it is closed
  transport_.reset();
  if (waiting_seq_)
    reply_error_ = "the link to " + uri_ + " was lost while waiting for a reply (" + why + ")" +
                   (options_.reconnect && reopenable_ ? "; the SDK is restoring the session: retry" : "");
  async_.clear();
  cv_.notify_all();
}

bool Session::reconnect(const std::string& why) {
  const auto give_up = Clock::now() + options_.reconnect_for;
  std::string last = why;
  while (!stop_ && Clock::now() < give_up) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    try {
      auto t = std::shared_ptr<Transport>(open_transport(uri_, options_.timeout));
      const proto::DeviceInfo d = hello(*t, options_.host_software, seq_++, options_.timeout);
      if (std::string(d.serial.bytes.data(), d.serial.length()) !=
          std::string(device_.serial.bytes.data(), device_.serial.length())) {
        last = "another device answers at " + uri_;
        continue;
      }
      judge_or_throw(d);
      std::optional<proto::StreamConfigure> cfg;
      bool streaming = false;
      {
        std::lock_guard lock(mu_);
        transport_ = t;
        device_ = d;
        reader_ = proto::FrameReader{};
        clock_.reset();
        pings_sent_ = 0;
        ++reconnects_;
        cfg = stream_config_;
        streaming = streaming_;
        if (streaming) assembler_.reconnected();
      }
      // restore the session: the stream as it was configured and running
      if (cfg) send_async(*cfg, AsyncKind::restore);
      if (cfg && streaming) send_async(proto::StreamStart{}, AsyncKind::restore);
      detail::log(LogLevel::info, "the link to " + uri_ + " was restored" +
                                      (streaming ? " and the stream restarted" : std::string()));
      std::lock_guard lock(mu_);
      link_up_ = true;
      cv_.notify_all();
      return true;
    } catch (const VersionError& e) {
      last = e.what();
      break;
    } catch (const Error& e) {
      last = e.what();
    }
  }
  std::lock_guard lock(mu_);
  dead_ = "the link to " + uri_ + " was lost (" + why + ") and could not be restored within " +
          std::to_string(options_.reconnect_for.count()) + " ms: " + last;
  detail::log(LogLevel::error, dead_);
  cv_.notify_all();
  return false;
}

}  // namespace palp::detail
