// SPDX-License-Identifier: Apache-2.0
#include "palp/sim/simulation.hpp"

#include <cmath>
#include <cstring>

namespace palp::sim {

Simulation::Simulation(const fw::DeviceIdentity& identity, std::unique_ptr<PlantLink> plant,
                       SimulationOptions options)
    : controller_(identity), plant_(std::move(plant)), options_(options) {}

double Simulation::virtual_s() const {
  return s_at_rate_ + static_cast<double>(controller_.ticks() - ticks_at_rate_) /
                          controller_.control_rate_Hz();
}

void Simulation::host_bytes(const std::uint8_t* data, std::size_t size, std::uint64_t wall_us) {
  last_wall_us_ = wall_us;
  host_wall_us_ = wall_us;
  if (hold_.active || hold_.releasing) {
    hold_.pending.insert(hold_.pending.end(), data, data + size);
    if (hold_.active) {
      // the host reacted: its bytes land reaction_latency after the event, in virtual time
      hold_.active = false;
      hold_.releasing = true;
      hold_.release_tick =
          controller_.ticks() + static_cast<std::uint64_t>(std::llround(
                                    options_.reaction_latency_ms * 1e-3 * controller_.control_rate_Hz()));
    }
    return;
  }
  deliver(data, size, wall_us);
}

std::uint64_t Simulation::host_reaction(std::uint64_t wall_us) {
  last_wall_us_ = wall_us;
  if (hold_.active) {
    hold_.active = false;
    hold_.releasing = true;
    hold_.release_tick =
        controller_.ticks() + static_cast<std::uint64_t>(std::llround(
                                  options_.reaction_latency_ms * 1e-3 * controller_.control_rate_Hz()));
  }
  return hold_.releasing ? hold_.release_tick : controller_.ticks();
}

void Simulation::deliver(const std::uint8_t* data, std::size_t size, std::uint64_t wall_us) {
  const std::uint32_t rate = controller_.control_rate_Hz();
  controller_.receive(data, size, wall_us);
  if (controller_.control_rate_Hz() != rate) {  // SetParams: the ticks so far at the old rate
    s_at_rate_ += static_cast<double>(controller_.ticks() - ticks_at_rate_) / rate;
    ticks_at_rate_ = controller_.ticks();
  }
  collect_device_output();
}

std::uint32_t Simulation::run(std::uint32_t max_ticks, std::uint64_t wall_us) {
  last_wall_us_ = wall_us;
  if (hold_.active) {
    // a host silent for the heartbeat timeout will not react: the core's watchdog would trip
    // on hardware, so held virtual time goes on for it to do so
    const bool host_silent = wall_us > host_wall_us_ && wall_us - host_wall_us_ >
                             std::uint64_t{controller_.params().heartbeat_timeout_ms} * 1000u;
    if (static_cast<double>(wall_us - hold_.since_wall_us) < options_.hold_timeout_ms * 1e3 &&
        !host_silent)
      return 0;
    hold_.active = false;  // the host did not react in time: go on
    ++counters_.hold_timeouts;
  }
  std::uint32_t ran = 0;
  while (ran < max_ticks && !hold_.active) {
    if (hold_.releasing && controller_.ticks() >= hold_.release_tick) {
      hold_.releasing = false;
      std::vector<std::uint8_t> bytes;
      bytes.swap(hold_.pending);
      if (!bytes.empty()) deliver(bytes.data(), bytes.size(), wall_us);
    }
    tick_once(wall_us);
    ++ran;
    if ((controller_.ticks() & 7u) == 0 || ran == max_ticks) {
      controller_.service();
      collect_device_output();
    }
  }
  return ran;
}

void Simulation::tick_once(std::uint64_t wall_us) {
  fw::TickInputs in;
  in.i_sense_A = plant_->current_sense_A();
  in.encoder_timer = static_cast<std::uint16_t>(plant_->encoder_counts());
  in.pressure_codes = plant_->pressure_codes();
  in.watchdog_now_us = wall_us;
  in.supply_V = plant_->supply_V();
  in.driver_fault = plant_->driver_fault();
  fw::TickOutputs out;
  controller_.tick(in, out);
  contact_line_ = out.contact_line;
  plant_->step(1.0 / controller_.control_rate_Hz(), out.v_coil_V);
}

namespace {

// Byte `index` of the frame that the COBS bytes in[0, n) decode to, without decoding the rest;
// -1 when they end or stop being valid COBS before it (then the whole frame is rejected too).
int cobs_byte_at(const std::uint8_t* in, std::size_t n, std::size_t index) {
  std::size_t i = 0, o = 0;
  while (i < n) {
    const std::uint8_t code = in[i++];
    if (code == 0) return -1;
    const std::size_t run = static_cast<std::size_t>(code) - 1;
    if (run > n - i) return -1;
    if (index < o + run) return in[i + (index - o)];
    i += run;
    o += run;
    if (code != 0xFF && i < n) {  // the implied zero after a short block
      if (index == o) return 0;
      ++o;
    }
  }
  return -1;
}

constexpr std::size_t kIdOffset = 2;  // the message id's place in the header (frame.hpp)

}  // namespace

void Simulation::collect_device_output() {
  std::uint8_t buf[4096];
  std::size_t n;
  while ((n = controller_.transmit(buf, sizeof buf)) > 0) {
    const std::uint8_t* p = buf;
    const std::uint8_t* const end = buf + n;
    while (p < end) {
      const auto* zero = static_cast<const std::uint8_t*>(std::memchr(p, 0, end - p));
      const std::uint8_t* stop = zero ? zero + 1 : end;
      frame_.insert(frame_.end(), p, stop);
      p = stop;
      if (zero) frame_done();
    }
  }
}

void Simulation::frame_done() {
  // one whole frame (ending with its delimiter): fault injection, holds
  ++counters_.frames_out;
  const bool drop = options_.drop_every != 0 && counters_.frames_out % options_.drop_every == 0;
  if (!drop && options_.corrupt_every != 0 &&
      counters_.frames_out % options_.corrupt_every == 0 && frame_.size() > 2) {
    std::uint8_t& b = frame_[frame_.size() / 2];
    b = static_cast<std::uint8_t>(b ^ 0x04);
    if (b == 0) b = 0x08;  // never create a delimiter (0x04 -> 0x08: still a changed byte)
    ++counters_.frames_corrupted;
  }
  if (drop) {
    ++counters_.frames_dropped;
  } else {
    // a contact event holds virtual time until the host reacts; the id alone rules out every
    // other frame, the full frame checks decide for a contact event's id
    if (cobs_byte_at(frame_.data(), frame_.size() - 1, kIdOffset) ==
        static_cast<int>(proto::MessageId::EventContact)) {
      proto::FrameReader peek;
      peek.feed(
          frame_.data(), frame_.size(),
          [&](const proto::Frame& f) {
            if (f.header.id == static_cast<std::uint8_t>(proto::MessageId::EventContact)) {
              hold_.active = true;
              hold_.since_wall_us = last_wall_us_;
              ++counters_.holds;
            }
          },
          [](proto::Reject) {});
    }
    out_.insert(out_.end(), frame_.begin(), frame_.end());
  }
  frame_.clear();
}

std::vector<std::uint8_t> Simulation::take_device_bytes() {
  std::vector<std::uint8_t> out;
  out.swap(out_);
  return out;
}

}  // namespace palp::sim
