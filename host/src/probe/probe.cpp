// SPDX-License-Identifier: Apache-2.0
// palp::Probe: the public API over a Session.
#include "palp/probe.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <thread>

#include "palp/protocol/stream.hpp"
#include "probe/probe_impl.hpp"
#include "probe/stream_check.hpp"

namespace palp {

using detail::Session;

const char* sdk_version() { return PALP_SDK_VERSION; }

const char* gap_source_name(GapSource s) {
  switch (s) {
    case GapSource::isr_queue: return "isr_queue";
    case GapSource::stream_backlog: return "stream_backlog";
    case GapSource::usb_in: return "usb_in";
    case GapSource::transport: return "transport";
    case GapSource::host_queue: return "host_queue";
    case GapSource::reconnect: return "reconnect";
  }
  return "unknown";
}

namespace {

template <class T>
T expect(detail::Reply&& r, const char* request) {
  if (auto* v = std::get_if<T>(&r)) return std::move(*v);
  throw ProtocolError(std::string("the device answered ") + request +
                      " with another message than the protocol says");
}

}  // namespace

DeviceInfo detail::device_info_from(const proto::DeviceInfo& d) {
  auto text = [](const auto& s) { return std::string(s.bytes.data(), s.length()); };
  DeviceInfo i;
  i.serial = text(d.serial);
  i.board = text(d.board);
  i.git_hash = text(d.git_hash);
  i.firmware_version = std::to_string(d.fw_major) + "." + std::to_string(d.fw_minor) + "." +
                       std::to_string(d.fw_patch);
  i.protocol_major = d.protocol_major;
  i.protocol_minor = d.protocol_minor;
  i.schema_hash = d.schema_hash;
  i.capabilities = d.capabilities;
  i.max_current_A = d.max_current_A;
  i.control_rate_Hz = d.control_rate_Hz;
  i.max_stream_rate_Hz = d.max_stream_rate_Hz;
  i.heartbeat_timeout_s = d.heartbeat_timeout_ms * 1e-3;
  i.max_payload = d.max_payload;
  return i;
}

Probe::Probe(const std::string& uri, ConnectOptions options) : impl_(std::make_unique<Impl>()) {
  impl_->session = std::make_unique<Session>(uri, options);
  impl_->info = detail::device_info_from(impl_->session->device_info());
  impl_->handshake = impl_->session->handshake();
  impl_->uri = uri;
  stop_stale_stream();
}

Probe::Probe(std::unique_ptr<Transport> transport, ConnectOptions options)
    : impl_(std::make_unique<Impl>()) {
  impl_->session = std::make_unique<Session>(std::move(transport), options);
  impl_->info = detail::device_info_from(impl_->session->device_info());
  impl_->handshake = impl_->session->handshake();
  impl_->uri = impl_->session->uri();
  stop_stale_stream();
}

// A stream running when a Probe connects was started by a previous host (one host at a time:
// a new connection is a new host); left running it would refuse this host's StreamConfigure and
// SetParams busy. A program it left is not touched: the heartbeat watchdog ends it with a
// latched fault this host is told about when it starts one.
void Probe::stop_stale_stream() {
  Session& s = impl_->s();
  if (!status().streaming) return;
  expect<proto::Ack>(s.request(proto::StreamStop{}, s.default_timeout()), "StreamStop");
  s.stream_stopped();
}

Probe::~Probe() {
  try {
    close();
  } catch (...) {  // a destructor never throws; close() already did what it could
  }
}
Probe::Probe(Probe&&) noexcept = default;
Probe& Probe::operator=(Probe&&) noexcept = default;

Session& Probe::Impl::s() {
  if (!session) throw ConnectionError("this Probe is closed");
  return *session;
}

const DeviceInfo& Probe::info() const { return impl_->info; }
const Handshake& Probe::handshake() const { return impl_->handshake; }
const std::string& Probe::uri() const { return impl_->uri; }

Status Probe::status() {
  Session& s = impl_->s();
  const auto st = expect<proto::Status>(s.request(proto::GetStatus{}, s.default_timeout()), "GetStatus");
  Status out;
  out.t_device_s = static_cast<double>(st.device_time_us) * 1e-6;
  out.state = st.state;
  out.fault = st.fault;
  out.program = st.program_kind;
  out.program_state = st.program_state;
  out.i_cmd_A = st.i_cmd_A;
  out.i_A = st.i_A;
  out.encoder_counts = st.encoder_count;
  out.z_m = st.encoder_count * 1e-6;
  out.i2t_fraction = st.i2t_fraction;
  out.streaming = st.streaming != 0;
  out.status_bits = st.status_bits;
  return out;
}

HealthCounters Probe::health() {
  Session& s = impl_->s();
  s.set_device_health(expect<proto::Health>(s.request(proto::GetHealth{}, s.default_timeout()), "GetHealth"));
  return s.health_snapshot();
}

Params Probe::params() {
  Session& s = impl_->s();
  return expect<proto::Params>(s.request(proto::GetParams{}, s.default_timeout()), "GetParams");
}

void Probe::set_params(const Params& p) {
  Session& s = impl_->s();
  // field by field from the catalogue: does not compile when the two messages' fields differ
  const auto in_force = expect<proto::Params>(
      s.request(proto::fields_as<proto::SetParams>(p), s.default_timeout()), "SetParams");
  s.set_heartbeat_timeout_ms(in_force.heartbeat_timeout_ms);
  // the rate in force from now on: configure_stream() derives the decimation from it
  impl_->info.control_rate_Hz = in_force.control_rate_Hz;
}

Calibration Probe::calibration() {
  Session& s = impl_->s();
  return expect<proto::Calibration>(s.request(proto::GetCalibration{}, s.default_timeout()),
                                    "GetCalibration");
}

void Probe::set_calibration(const Calibration& c) {
  Session& s = impl_->s();
  expect<proto::Calibration>(
      s.request(proto::fields_as<proto::SetCalibration>(c), s.default_timeout()), "SetCalibration");
}

void Probe::commit_calibration() {
  Session& s = impl_->s();
  expect<proto::Ack>(s.request(proto::CommitCalibration{}, s.default_timeout()), "CommitCalibration");
}

template <class M>
static void load_program(Session& s, const M& m) {
  expect<proto::Ack>(s.request(m, s.default_timeout()), M::kName);
}
void Probe::load(const HoldProgram& p) { load_program(impl_->s(), p); }
void Probe::load(const RampProgram& p) { load_program(impl_->s(), p); }
void Probe::load(const SineProgram& p) { load_program(impl_->s(), p); }
void Probe::load(const SweepProgram& p) { load_program(impl_->s(), p); }
void Probe::load(const MultisineProgram& p) { load_program(impl_->s(), p); }
void Probe::load(const ContactWatchProgram& p) { load_program(impl_->s(), p); }

void Probe::start() {
  Session& s = impl_->s();
  const detail::EventLog before = s.events();
  impl_->finished_before_start = before.finished;
  impl_->contact_before_start = before.contact;
  expect<proto::Ack>(s.request(proto::ProgramStart{}, s.default_timeout()), "ProgramStart");
}

void Probe::stop() {
  Session& s = impl_->s();
  expect<proto::Ack>(s.request(proto::ProgramStop{}, s.default_timeout()), "ProgramStop");
}

ProgramResult Probe::wait(std::chrono::milliseconds timeout) {
  Session& s = impl_->s();
  const std::uint64_t after = impl_->finished_before_start;
  const auto finished = [&](const detail::EventLog& e) { return e.finished > after; };
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  std::optional<ProgramResult> result;
  while (!result) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (s.wait_event(std::clamp(left, std::chrono::milliseconds(0), std::chrono::milliseconds(250)), finished)) {
      result = s.events().last_finished;
      break;
    }
    // EventProgramFinished is a device frame like any other and may be lost: every 250 ms the
    // program's status says whether it ended (after start() it is running until it does)
    const proto::ProgramStatus ps = program_status();
    if (finished(s.events())) {
      result = s.events().last_finished;
    } else if (ps.state == proto::ProgramState::finished) {
      result = ProgramResult{ps.kind, ps.end, status().t_device_s, ps.repetition};
    } else if (std::chrono::steady_clock::now() >= deadline) {
      throw TimeoutError("the program to finish on " + s.uri() + " (ProgramStatus: " +
                             std::to_string(ps.elapsed_us) + " us elapsed)",
                         static_cast<double>(timeout.count()) / 1000.0, s.health_snapshot());
    }
  }
  if (result->end == proto::ProgramEnd::fault) {
    const FaultInfo f = fault();
    throw FaultError("the program ended by a fault: " + f.text, static_cast<std::uint16_t>(f.reason));
  }
  return *result;
}

proto::ProgramStatus Probe::program_status() {
  Session& s = impl_->s();
  return expect<proto::ProgramStatus>(s.request(proto::GetProgramStatus{}, s.default_timeout()),
                                      "GetProgramStatus");
}

std::optional<ContactEvent> Probe::wait_contact(std::chrono::milliseconds timeout) {
  Session& s = impl_->s();
  const std::uint64_t after = impl_->contact_before_start;
  if (!s.wait_event(timeout, [&](const detail::EventLog& e) { return e.contact > after; }))
    return std::nullopt;
  return s.events().last_contact;
}

FaultInfo Probe::fault() {
  const Status st = status();
  FaultInfo f = impl_->s().events().last_fault;
  if (st.fault == proto::FaultReason::none) return FaultInfo{};
  if (f.reason != st.fault) {
    f = FaultInfo{};
    f.reason = st.fault;
    const char* n = proto::enum_name(st.fault);
    f.text = n ? n : "unknown";
  }
  return f;
}

void Probe::clear_fault() {
  Session& s = impl_->s();
  expect<proto::Ack>(s.request(proto::FaultClear{}, s.default_timeout()), "FaultClear");
}

void Probe::enter_bootloader() {
  Session& s = impl_->s();
  expect<proto::Ack>(s.request(proto::EnterBootloader{proto::kBootloaderMagic}, s.default_timeout()),
                     "EnterBootloader");
  s.shutdown();  // the device is on its way into the ROM bootloader: nothing more to say to it
  impl_->session.reset();
}

// ---- streaming -------------------------------------------------------------------------------

StreamInfo Probe::configure_stream(const StreamSettings& st) {
  Session& s = impl_->s();
  const proto::StreamConfigure c =
      detail::check_stream(st, impl_->info.control_rate_Hz, impl_->info.max_stream_rate_Hz,
                           s.transport_bytes_per_s(), s.uri());
  const auto cfg = expect<proto::StreamConfig>(s.request(c, s.default_timeout()), "StreamConfigure");
  s.stream_configured(c);
  StreamInfo& info = impl_->stream;
  info.channels = cfg.channels;
  info.batch_samples = cfg.batch_samples;
  info.period_s = cfg.period_ns * 1e-9;
  info.rate_Hz = cfg.period_ns > 0 ? 1e9 / cfg.period_ns : 0;
  info.wire_bytes_per_s = cfg.wire_bytes_per_s;
  return info;
}

void Probe::start_stream() {
  Session& s = impl_->s();
  s.stream_started();
  try {
    expect<proto::Ack>(s.request(proto::StreamStart{}, s.default_timeout()), "StreamStart");
  } catch (const TimeoutError&) {
    // StreamStart is not resent (a copy would restart the stream): a lost Ack is harmless when
    // the status shows the stream running, and a stream never stops by itself
    if (!status().streaming) throw;
  }
}

void Probe::stop_stream() {
  Session& s = impl_->s();
  expect<proto::Ack>(s.request(proto::StreamStop{}, s.default_timeout()), "StreamStop");
  s.stream_stopped();
}

const StreamInfo& Probe::stream_info() const { return impl_->stream; }

std::optional<StreamItem> Probe::next(std::chrono::milliseconds timeout) {
  return impl_->s().queue().pop(timeout);
}
std::size_t Probe::drain(std::vector<StreamItem>& out, std::size_t max) {
  return impl_->s().queue().drain(out, max);
}
void Probe::on_stream(std::function<void(const StreamItem&)> callback) {
  impl_->s().queue().set_callback(std::move(callback));
}
ClockMapping Probe::clock() const {
  return impl_ && impl_->session ? impl_->session->clock() : ClockMapping{};
}

Status Probe::make_safe() {
  Session& s = impl_->s();
  // ProgramStop ends a running program and drops a contact hold that outlived its watch (the
  // device acknowledges it in every state, SPEC §10.1); both stops are resent on a lost reply
  expect<proto::Ack>(s.request(proto::ProgramStop{}, s.default_timeout()), "ProgramStop");
  expect<proto::Ack>(s.request(proto::StreamStop{}, s.default_timeout()), "StreamStop");
  s.stream_stopped();
  // the set-point is 0 A from the device's next control tick: read until the status shows it
  const auto until = std::chrono::steady_clock::now() + s.default_timeout();
  for (;;) {
    const Status st = status();
    const bool running = st.program_state == proto::ProgramState::running;
    if (!running && st.i_cmd_A == 0.0) return st;
    if (std::chrono::steady_clock::now() > until)
      throw ProtocolError("the device acknowledged ProgramStop but still reports " +
                          (running ? std::string("a running program")
                                   : "a commanded current of " + std::to_string(st.i_cmd_A) + " A"));
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

void Probe::close() {
  if (!impl_ || !impl_->session) return;
  Session& s = *impl_->session;
  // leave the device with zero current whatever state this connection left it in; a request
  // that fails here (the link is gone) leaves it to the device's heartbeat watchdog
  try {
    make_safe();
  } catch (const Error&) {
  }
  s.shutdown();
  impl_->session.reset();
}

}  // namespace palp
