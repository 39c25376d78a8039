// SPDX-License-Identifier: Apache-2.0
#include "palp/sim/server.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <thread>

namespace palp::sim {

Server::Server(std::unique_ptr<Instrument> instrument, ByteServer device, ByteServer control,
               std::unique_ptr<ModbusServer> robot, double pace)
    : instrument_(std::move(instrument)), device_(std::move(device)), control_(std::move(control)),
      robot_(std::move(robot)), pace_(pace) {
  if ((instrument_->world() != nullptr) != (robot_ != nullptr))
    throw std::invalid_argument(
        "palp-sim Server: a Modbus server needs an instrument with the robot on, and back");
  device_.set_idle_rule(kDeviceIdle);
}

std::string Server::banner() const {
  std::string robot;
  if (robot_) robot = ", robot bridge on " + robot_->address();
  return "palp-sim listening on " + device_.address() + " (device protocol), control on " +
         control_.address() + robot;
}

std::uint64_t Server::wall_us() const {
  return static_cast<std::uint64_t>(
      std::chrono::duration_cast<std::chrono::microseconds>(Clock::now() - t0_).count());
}

std::string Server::set_pace(double factor) {
  pace_ = factor;  // the next step resyncs the anchors
  return "";
}

std::string Server::status_fields() const {
  return " host_lost=" + std::to_string(lost_ ? 1 : 0) +
         " host_dropped_frames=" + std::to_string(dropped_frames_) +
         " refused_clients=" + std::to_string(device_.refused_clients());
}

// The pace counts virtual time from here at this rate and pace: a change of either must not
// count the wall time already past at the new rate (20 -> 40 kHz ran ahead, 40 -> 20 froze).
void Server::resync(double effective_pace) {
  virtual_at_sync_ = instrument_->simulation().ticks();
  wall_at_sync_ = Clock::now();
  rate_at_sync_ = instrument_->simulation().controller().control_rate_Hz();
  pace_at_sync_ = effective_pace;
}

// Ticks to run now: cap_ticks as fast as possible, else no further than wall time allows at the
// pace since the last resync.
std::uint32_t Server::paced_chunk(double effective_pace, std::uint32_t cap_ticks) {
  if (effective_pace <= 0) return cap_ticks;
  const Simulation& sim = instrument_->simulation();
  const double wall_s = std::chrono::duration<double>(Clock::now() - wall_at_sync_).count();
  const double allowed = wall_s * effective_pace * rate_at_sync_;
  const double done = static_cast<double>(sim.ticks() - virtual_at_sync_);
  if (done >= allowed) return 0;
  return allowed - done < cap_ticks ? static_cast<std::uint32_t>(allowed - done) : cap_ticks;
}

void Server::run(const volatile std::sig_atomic_t& stop) {
  while (stop == 0) step();
}

void Server::step() {
  Simulation& sim = instrument_->simulation();
  if (robot_) {
    // the Modbus socket every 0.2 ms of wall time at most: its syscalls would otherwise slow a
    // fast-paced simulation by a third
    const std::uint64_t now_us = wall_us();
    instrument_->world()->set_wall_us(now_us);
    if (now_us - last_robot_poll_us_ >= 200) {
      robot_->poll(*instrument_->world(), now_us);
      last_robot_poll_us_ = now_us;
    }
  }
  const bool backed_up = device_.has_client() && device_.tx_pending() + pending_.size() >= kStallBytes;
  // a host running normally waits on nothing; a stalled or held one, or a lost one at real
  // time, sleeps in poll (so no host never spins a core, whatever the pace)
  const bool wait = backed_up || sim.holding() || lost_;
  const auto ev = device_.poll(wait ? (robot_client() || lost_ ? 1 : 2) : 0);
  const auto now = Clock::now();
  if (ev.connected) {
    sim.controller().end_session();  // a new client opens its own session (Hello)
    host_heard_ = now;
  }
  const std::vector<std::uint8_t> rx = device_.take_received();
  if (!rx.empty()) host_heard_ = now;

  // who is there: a host that neither drains nor has sent anything for the heartbeat timeout is
  // lost (the core's watchdog would have tripped on hardware by now): stall no longer
  const bool any_client = device_.has_client() || robot_client();
  const auto heartbeat = std::chrono::milliseconds(sim.controller().params().heartbeat_timeout_ms);
  const bool silent = now - host_heard_ > heartbeat;
  const bool stall = backed_up && !silent;
  stalled_ = stall;
  lost_ = !any_client || (backed_up && silent);
  const double pace = lost_ ? 1.0 : pace_;
  if (ev.connected || pace != pace_at_sync_ || sim.controller().control_rate_Hz() != rate_at_sync_)
    resync(pace);

  // the host's bytes meet the watchdog's overdue check at their wall time first, as on hardware
  // where the tick never stops: one tick now unless one ran within the last 0.5 ms (a held
  // event ticks not, and its bytes wait for the reaction latency anyway)
  if (!rx.empty()) {
    const std::uint64_t now_us = wall_us();
    if (!sim.holding() && now_us - last_tick_us_ > 500 && sim.run(1, now_us) > 0)
      last_tick_us_ = now_us;
    sim.host_bytes(rx.data(), rx.size(), now_us);
  }
  if (stall) {
    // virtual time stands: when it goes on, it counts from then (no catch-up burst)
    resync(pace);
  } else {
    const std::uint32_t ms = sim.controller().control_rate_Hz() / 1000;  // 1 ms of virtual time
    // a lost host's real time catches up in chunks of up to 10 ms (its steps sleep 1 ms)
    std::uint32_t chunk = paced_chunk(pace, lost_ ? 10 * ms : ms);
    if (chunk == 0 && sim.holding()) chunk = 1;  // a held event's timeout is checked in run()
    if (chunk == 0) {
      if (!lost_) std::this_thread::sleep_for(std::chrono::microseconds(200));
    } else {
      const std::uint64_t now_us = wall_us();
      if (sim.run(chunk, now_us) > 0) last_tick_us_ = now_us;
    }
    if (sim.holding()) resync(pace);  // held virtual time goes on from the release, no burst
  }
  serve_control();
  // device bytes keep their order: whatever the socket buffer refused goes first next time
  const std::vector<std::uint8_t> out = sim.take_device_bytes();
  pending_.insert(pending_.end(), out.begin(), out.end());
  if (!device_.has_client()) pending_.clear();
  if (pending_.empty()) return;
  if (device_.send(pending_.data(), pending_.size())) {
    pending_.clear();
  } else if (lost_) {
    // a lost host's frames are dropped whole (take_device_bytes gives whole frames), so what
    // it reads later still parses and shows the gap in its sample indices
    dropped_frames_ += static_cast<std::uint64_t>(std::count(pending_.begin(), pending_.end(), 0));
    pending_.clear();
  }
}

// One reply line. Whatever it quotes from the line it answers is shown, never sent raw: control
// bytes (and bytes above 0x7e) as \xNN, so nothing reaches the client's terminal.
void Server::reply(const std::string& line) {
  std::string l;
  l.reserve(line.size() + 1);
  for (const char c : line) {
    const auto u = static_cast<unsigned char>(c);
    if (u >= 0x20 && u < 0x7f) {
      l += c;
    } else {
      static const char hex[] = "0123456789abcdef";
      l += "\\x";
      l += hex[u >> 4];
      l += hex[u & 15];
    }
  }
  l += '\n';
  control_.send(reinterpret_cast<const std::uint8_t*>(l.data()), l.size());
}

// Lines of at most kControlLineBytes; a longer one is discarded up to its newline with one
// error reply, and its bytes are never kept (the buffer stays within the bound).
void Server::serve_control() {
  const auto ev = control_.poll(0);
  if (ev.connected || ev.disconnected) {
    std::string().swap(control_line_);
    discarding_line_ = false;
  }
  const std::vector<std::uint8_t> bytes = control_.take_received();
  std::size_t at = 0;
  while (at < bytes.size()) {
    const auto* nl = static_cast<const std::uint8_t*>(
        std::memchr(bytes.data() + at, '\n', bytes.size() - at));
    const std::size_t end = nl ? static_cast<std::size_t>(nl - bytes.data()) : bytes.size();
    if (!discarding_line_) {
      if (control_line_.size() + (end - at) > kControlLineBytes) {
        reply("error: line longer than " + std::to_string(kControlLineBytes) +
              " bytes: discarded up to its newline");
        std::string().swap(control_line_);
        discarding_line_ = true;
      } else {
        control_line_.append(bytes.begin() + static_cast<std::ptrdiff_t>(at),
                             bytes.begin() + static_cast<std::ptrdiff_t>(end));
      }
    }
    if (!nl) break;
    if (!discarding_line_) reply(instrument_->control(control_line_, *this));
    control_line_.clear();
    discarding_line_ = false;
    at = end + 1;
  }
}

}  // namespace palp::sim
