#include "palp/sim/server.hpp"

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
  pace_ = factor;
  return "";
}

void Server::resync() {
  virtual_at_sync_ = instrument_->simulation().ticks();
  wall_at_sync_ = Clock::now();
}

void Server::run(const volatile std::sig_atomic_t& stop) {
  while (stop == 0) step();
}

void Server::step() {
  Simulation& sim = instrument_->simulation();
  const bool had_robot_client = robot_client();
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
  // stall while the host has not drained: virtual time waits, nothing is dropped
  const bool any_client = device_.has_client() || robot_client();
  const bool can_run = any_client && device_.tx_pending() + pending_.size() < kStallBytes;
  const auto ev = device_.poll(can_run && !sim.holding() ? 0 : (robot_client() ? 1 : 2));
  if (ev.connected) sim.controller().end_session();  // a new client opens its own session (Hello)
  if (ev.connected || (robot_client() && !had_robot_client && !device_.has_client())) resync();
  const std::vector<std::uint8_t> rx = device_.take_received();
  if (!rx.empty()) sim.host_bytes(rx.data(), rx.size(), wall_us());
  serve_control();
  if (can_run) {
    std::uint32_t chunk = sim.controller().control_rate_Hz() / 1000;  // 1 ms of virtual time
    if (pace_ > 0) {
      // run only as far as wall time allows at this pace
      const double wall_s = std::chrono::duration<double>(Clock::now() - wall_at_sync_).count();
      const double allowed = wall_s * pace_ * sim.controller().control_rate_Hz();
      const double done = static_cast<double>(sim.ticks() - virtual_at_sync_);
      if (done >= allowed) {
        chunk = 0;
        std::this_thread::sleep_for(std::chrono::microseconds(200));
      } else if (allowed - done < chunk) {
        chunk = static_cast<std::uint32_t>(allowed - done);
      }
    }
    if (chunk > 0) sim.run(chunk, wall_us());
  } else if (!any_client) {
    resync();  // no host: virtual time stands still
  }
  // device bytes keep their order: whatever the socket buffer refused goes first next time
  const std::vector<std::uint8_t> out = sim.take_device_bytes();
  pending_.insert(pending_.end(), out.begin(), out.end());
  if (!device_.has_client()) pending_.clear();
  if (!pending_.empty() && device_.send(pending_.data(), pending_.size())) pending_.clear();
}

void Server::reply(const std::string& line) {
  const std::string l = line + "\n";
  control_.send(reinterpret_cast<const std::uint8_t*>(l.data()), l.size());
}

void Server::serve_control() {
  control_.poll(0);
  const std::vector<std::uint8_t> bytes = control_.take_received();
  control_line_.append(bytes.begin(), bytes.end());
  std::size_t eol;
  while ((eol = control_line_.find('\n')) != std::string::npos) {
    const std::string line = control_line_.substr(0, eol);
    control_line_.erase(0, eol + 1);
    reply(instrument_->control(line, *this));
  }
  if (control_line_.size() > 4096) {
    control_line_.clear();
    reply("error: line longer than 4096 bytes");
  }
}

}  // namespace palp::sim
