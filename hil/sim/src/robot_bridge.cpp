// SPDX-License-Identifier: Apache-2.0
#include "palp/sim/robot_bridge.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace palp::sim {

namespace {

using rb::CommandCode;
using rb::Result;
using rb::u16;

constexpr double kRadPerMdeg = std::numbers::pi / 180000.0;

template <class B>
constexpr bool inside(u16 address, u16 count) {
  return address >= B::kAddress && address + count <= B::kAddress + B::kLength;
}

rb::i32 to_i32(double v) {
  const double r = std::round(v);
  if (!(r > std::numeric_limits<rb::i32>::min())) return std::numeric_limits<rb::i32>::min();
  if (!(r < std::numeric_limits<rb::i32>::max())) return std::numeric_limits<rb::i32>::max();
  return static_cast<rb::i32>(r);
}

plant::Transform pose_of(const rb::Command& c) {
  return plant::pose_from_xyzabc(c.x_um * 1e-6, c.y_um * 1e-6, c.z_um * 1e-6, c.a_mdeg * kRadPerMdeg,
                                 c.b_mdeg * kRadPerMdeg, c.c_mdeg * kRadPerMdeg);
}

bool is_motion(CommandCode k) {
  return k == CommandCode::move_lin || k == CommandCode::move_lin_rel ||
         k == CommandCode::move_ptp || k == CommandCode::guarded_approach;
}

constexpr u16 kWatchdogAddress = rb::address_of<rb::HostControl>("watchdog_ms");
constexpr u16 kStopAddress = rb::address_of<rb::HostControl>("stop_request");

}  // namespace

RobotBridge::RobotBridge(plant::RobotArm& arm, RobotBridgeOptions options)
    : arm_(arm), options_(options), rng_(options.seed) {
  written_control_[kWatchdogAddress - rb::HostControl::kAddress] = rb::kDefaultWatchdogMs;
  control_.watchdog_ms = rb::kDefaultWatchdogMs;
  publish(true);
}

// ---- Modbus access --------------------------------------------------------------------------

ModbusException RobotBridge::read(u16 address, u16 count, u16* out) const {
  if (count < 1 || count > rb::kMaxReadRegisters) return ModbusException::illegal_data_value;
  auto copy = [&](const u16* block, u16 block_address) {
    std::copy_n(block + (address - block_address), count, out);
    return ModbusException::none;
  };
  if (inside<rb::Identification>(address, count)) {
    std::array<u16, rb::Identification::kLength> id{};
    rb::encode(rb::this_identification(), std::span<u16, rb::Identification::kLength>(id));
    return copy(id.data(), rb::Identification::kAddress);
  }
  if (inside<rb::StatusBlock>(address, count)) return copy(status_regs_.data(), rb::StatusBlock::kAddress);
  if (inside<rb::HostControl>(address, count))
    return copy(written_control_.data(), rb::HostControl::kAddress);
  if (inside<rb::Command>(address, count)) return copy(written_command_.data(), rb::Command::kAddress);
  return ModbusException::illegal_data_address;
}

ModbusException RobotBridge::check_write(u16 address, std::span<const u16> regs, bool single) const {
  const auto count = static_cast<u16>(std::min<std::size_t>(regs.size(), 0xFFFF));
  if (!single && (count < 1 || count > rb::kMaxWriteRegisters)) return ModbusException::illegal_data_value;
  if (single && count != 1) return ModbusException::illegal_data_value;
  const bool control = inside<rb::HostControl>(address, count);
  const bool command = !single && address == rb::Command::kAddress && count == rb::Command::kLength;
  if (!control && !command) return ModbusException::illegal_data_address;
  if (control && address <= kWatchdogAddress && kWatchdogAddress < address + count) {
    const u16 wd = regs[kWatchdogAddress - address];
    if (wd < rb::kMinWatchdogMs || wd > rb::kMaxWatchdogMs) return ModbusException::illegal_data_value;
  }
  return ModbusException::none;
}

ModbusException RobotBridge::write(u16 address, std::span<const u16> regs, bool single,
                                   double apply_at_s) {
  const ModbusException e = check_write(address, regs, single);
  if (e != ModbusException::none) return e;
  if (address == rb::Command::kAddress)
    std::copy(regs.begin(), regs.end(), written_command_.begin());
  else
    std::copy(regs.begin(), regs.end(), written_control_.begin() + (address - rb::HostControl::kAddress));
  pending_.push_back({address, std::vector<u16>(regs.begin(), regs.end()), apply_at_s});
  return ModbusException::none;
}

bool RobotBridge::is_reaction(u16 address, std::span<const u16> regs) const {
  if (address == rb::Command::kAddress && !regs.empty())
    return regs[0] != 0 && regs[0] != written_command_[0] && regs[0] != status_.ack_seq;
  if (address <= kStopAddress && kStopAddress < address + regs.size())
    return regs[kStopAddress - address] != written_control_[kStopAddress - rb::HostControl::kAddress];
  return false;
}

void RobotBridge::set_external_force(const double f[3], bool valid) {
  for (int i = 0; i < 3; ++i) force_[i] = f[i];
  force_valid_ = valid;
}

void RobotBridge::connection_closed() { closed_pending_ = true; }

// ---- time -----------------------------------------------------------------------------------

void RobotBridge::advance(double dt_s, std::uint64_t wall_us) {
  arm_.step(dt_s);
  time_s_ += dt_s;
  const double period = options_.cycle_ms * 1e-3;
  while (time_s_ + 1e-12 >= next_cycle_s_) {
    cycle(wall_us);
    next_cycle_s_ += period;
  }
}

void RobotBridge::apply_due_writes() {
  std::vector<PendingWrite> later;
  for (PendingWrite& w : pending_) {
    if (w.apply_at_s > time_s_ + 1e-12) {
      later.push_back(std::move(w));
      continue;
    }
    if (w.address == rb::Command::kAddress) {
      std::copy(w.regs.begin(), w.regs.end(), command_.begin());
    } else {
      std::array<u16, rb::HostControl::kLength> c{};
      rb::encode(control_, std::span<u16, rb::HostControl::kLength>(c));
      std::copy(w.regs.begin(), w.regs.end(), c.begin() + (w.address - rb::HostControl::kAddress));
      rb::decode(std::span<const u16>(c), control_);
    }
  }
  pending_.swap(later);
}

void RobotBridge::cycle(std::uint64_t wall_us) {
  ++counters_.cycles;
  if (!wall_started_) {
    wall_started_ = true;
    heartbeat_wall_us_ = wall_us;
  }
  // 1. the host control block as written so far
  apply_due_writes();
  if (!heartbeat_seen_ || control_.host_heartbeat != last_heartbeat_) {
    if (heartbeat_seen_) heartbeat_wall_us_ = wall_us;
    heartbeat_seen_ = true;
    last_heartbeat_ = control_.host_heartbeat;
  }
  const bool stale =
      wall_us - heartbeat_wall_us_ > static_cast<std::uint64_t>(control_.watchdog_ms) * 1000u;
  publish_force();  // the force of this cycle, for the force guard (step 5)
  // 2. a stop
  if (control_.stop_request != stop_acted_) take_stop();
  // 3. a stale heartbeat or a closed connection ends a motion with `watchdog`
  if ((stale || closed_pending_) && motion_.active && !motion_.ending) {
    latch();
    watchdog_tripped_ = true;
    ++counters_.watchdogs;
    end_motion(Result::watchdog);
  }
  closed_pending_ = false;
  // a robot error
  if (fault_pending_) {
    fault_pending_ = false;
    faulted_ = true;
    if (motion_.active && !motion_.ending) end_motion(Result::robot_fault);
  }
  // 4. a new command
  const u16 seq = command_[0];
  if (seq != 0 && seq != status_.ack_seq) take_command(wall_us, stale);
  // 5. the motion in progress
  advance_motion();
  // 6. publish
  publish(stale);
}

void RobotBridge::take_stop() {
  stop_acted_ = control_.stop_request;
  ++counters_.stops;
  latch();
  if (motion_.active) {
    if (!motion_.ending) {
      const bool guard = motion_.code == CommandCode::guarded_approach &&
                         (motion_.cmd.guard_sources & rb::bit(rb::GuardSource::host_stop)) != 0;
      if (!arm_.moving()) {
        // the motion reached its end before the stop (rule 8): it keeps its result
        advance_motion();
      } else if (guard) {
        ++counters_.guards;
        end_motion(Result::guard_fired, rb::bit(rb::GuardSource::host_stop));
      } else {
        end_motion(Result::stopped);
      }
    }
    if (!motion_.active) status_.stop_seen = stop_acted_;
    // else stop_seen is set when the arm is stationary (finish)
  } else {
    status_.stop_seen = stop_acted_;
  }
}

rb::CommandVerdict RobotBridge::verdict(const rb::Command& c, bool stale) const {
  using rb::RobotState;
  if (faulted_ && !motion_.active && c.code != CommandCode::reset_fault)
    return {Result::rejected_faulted, 0};
  const bool motion = is_motion(c.code);
  if ((motion || c.code == CommandCode::set_tool) && motion_.active) return {Result::rejected_busy, 0};
  if (motion && stale) return {Result::rejected_heartbeat_stale, 0};
  if (c.code == CommandCode::move_lin || c.code == CommandCode::move_ptp) {
    if (!arm_.reachable(pose_of(c))) return {Result::rejected_unreachable, 0};
  } else if (c.code == CommandCode::move_lin_rel) {
    if (!arm_.reachable(arm_.tcp() * pose_of(c))) return {Result::rejected_unreachable, 0};
  } else if (c.code == CommandCode::guarded_approach) {
    double d[3];
    direction_of(c, d);
    plant::Transform target = arm_.tcp();
    const double travel = std::abs(c.max_travel_um) * 1e-6;
    for (int i = 0; i < 3; ++i) target.t[i] += d[i] * travel;
    if (!arm_.reachable(target)) return {Result::rejected_unreachable, 0};
  }
  return {};
}

void RobotBridge::take_command(std::uint64_t, bool stale) {
  ++counters_.commands;
  rb::Command c{};
  rb::CommandVerdict v = rb::check_command(std::span<const u16>(command_), c);
  if (reject_left_ > 0) {
    --reject_left_;
    v = {reject_code_, 0};
  } else if (v.accepted()) {
    v = verdict(c, stale);
  }
  status_.ack_seq = command_[0];
  status_.ack_result = v.result;
  status_.reject_detail = v.result == Result::rejected_bad_parameter ? v.detail : 0;
  if (!v.accepted()) {
    ++counters_.rejected;
    return;
  }
  watchdog_tripped_ = false;
  start(c);
}

bool RobotBridge::direction_of(const rb::Command& c, double d[3]) const {
  const plant::Transform tcp = arm_.tcp();
  const double sign = c.max_travel_um < 0 ? -1.0 : 1.0;
  for (int i = 0; i < 3; ++i) d[i] = 0;
  switch (c.axis) {
    case rb::Axis::tool_x:
    case rb::Axis::tool_y:
    case rb::Axis::tool_z: {
      const int col = static_cast<int>(c.axis) - static_cast<int>(rb::Axis::tool_x);
      for (int i = 0; i < 3; ++i) d[i] = sign * tcp.r.m[i][col];
      return true;
    }
    case rb::Axis::base_x:
    case rb::Axis::base_y:
    case rb::Axis::base_z:
      d[static_cast<int>(c.axis) - static_cast<int>(rb::Axis::base_x)] = sign;
      return true;
    default: return false;
  }
}

void RobotBridge::start(const rb::Command& c) {
  switch (c.code) {
    case CommandCode::move_lin:
    case CommandCode::move_lin_rel:
    case CommandCode::move_ptp:
    case CommandCode::guarded_approach: {
      bool ok = false;
      if (c.code == CommandCode::move_lin) ok = arm_.move_lin(pose_of(c), c.speed * 1e-6);
      if (c.code == CommandCode::move_lin_rel) ok = arm_.move_lin_rel(pose_of(c), c.speed * 1e-6);
      if (c.code == CommandCode::move_ptp) ok = arm_.move_ptp(pose_of(c), c.speed);
      if (c.code == CommandCode::guarded_approach) {
        direction_of(c, approach_dir_);
        approach_set_ = true;
        plant::Transform target = arm_.tcp();
        const double travel = std::abs(c.max_travel_um) * 1e-6;
        for (int i = 0; i < 3; ++i) target.t[i] += approach_dir_[i] * travel;
        ok = arm_.move_lin(target, c.speed * 1e-6);
      }
      motion_ = Motion{};
      motion_.active = true;
      motion_.seq = command_[0];
      motion_.code = c.code;
      motion_.cmd = c;
      if (!ok) end_motion(Result::robot_fault);  // checked reachable: not expected
      return;
    }
    case CommandCode::hold: {
      const u16 seq = command_[0];
      if (motion_.active) {
        if (motion_.ending || !arm_.moving()) {
          // already ending (or already at its end): it finishes now with its own result
          advance_motion();
          if (motion_.active) finish(motion_.end_result, motion_.fired);
        } else {
          finish(Result::superseded);
        }
      }
      motion_ = Motion{};
      motion_.active = true;
      motion_.seq = seq;
      motion_.code = c.code;
      motion_.cmd = c;
      end_motion(Result::done);  // brakes; done once stationary
      return;
    }
    case CommandCode::set_tool: {
      plant::Transform tool = pose_of(c);
      arm_.set_tool(tool);
      status_.tool = c.tool;
      tool_set_ = true;
      break;
    }
    case CommandCode::reset_fault: faulted_ = false; break;
    default: break;
  }
  // set_tool, reset_fault: done at once
  motion_ = Motion{};
  motion_.seq = command_[0];
  motion_.active = true;
  finish(Result::done);
}

void RobotBridge::end_motion(Result r, u16 fired) {
  motion_.ending = true;
  motion_.end_result = r;
  motion_.fired = fired;
  arm_.stop();
  advance_motion();
}

void RobotBridge::advance_motion() {
  if (!motion_.active) return;
  if (motion_.ending) {
    if (!arm_.moving()) finish(motion_.end_result, motion_.fired);
    return;
  }
  if (motion_.code == CommandCode::guarded_approach) {
    u16 fired = 0;
    const rb::Command& c = motion_.cmd;
    if ((c.guard_sources & rb::bit(rb::GuardSource::digital_input)) != 0 &&
        (inputs_ & (1u << (c.digital_input - 1))) != 0)
      fired |= rb::bit(rb::GuardSource::digital_input);
    if ((c.guard_sources & rb::bit(rb::GuardSource::force)) != 0 && force_valid_ &&
        status_.force_mN >= c.force_threshold_mN)
      fired |= rb::bit(rb::GuardSource::force);
    if (fired != 0) {
      ++counters_.guards;
      latch();
      end_motion(Result::guard_fired, fired);
      return;
    }
  }
  if (!arm_.moving())
    finish(motion_.code == CommandCode::guarded_approach ? Result::max_travel : Result::done);
}

void RobotBridge::finish(Result r, u16 fired) {
  status_.result = r;
  status_.guard_fired = fired;
  status_.done_seq = motion_.seq;
  motion_ = Motion{};
  status_.stop_seen = stop_acted_;
}

void RobotBridge::latch() {
  rb::i32 p[6];
  pose_registers(arm_.tcp(), p);
  status_.latched_x_um = p[0], status_.latched_y_um = p[1], status_.latched_z_um = p[2];
  status_.latched_a_mdeg = p[3], status_.latched_b_mdeg = p[4], status_.latched_c_mdeg = p[5];
  latched_valid_ = true;
}

void RobotBridge::pose_registers(const plant::Transform& t, rb::i32* out) const {
  double a, b, c;
  rb::abc_from_rotation(t.r, a, b, c);
  for (int i = 0; i < 3; ++i) out[i] = to_i32(t.t[i] * 1e6);
  out[3] = to_i32(a / kRadPerMdeg);
  out[4] = to_i32(b / kRadPerMdeg);
  out[5] = to_i32(c / kRadPerMdeg);
  // A and C of +-180 deg are one angle: report +180000, so rounding noise never flips the sign
  if (out[3] == -180000) out[3] = 180000;
  if (out[5] == -180000) out[5] = 180000;
}

void RobotBridge::publish(bool stale) {
  using rb::StatusBit;
  if (!heartbeat_frozen_) ++status_.heartbeat;
  status_.state = motion_.active ? rb::RobotState::moving
                  : faulted_     ? rb::RobotState::faulted
                                 : rb::RobotState::idle;
  u16 bits = rb::bit(StatusBit::drives_enabled) | rb::bit(StatusBit::automatic_mode);
  if (!stale) bits |= rb::bit(StatusBit::host_heartbeat_ok);
  if (watchdog_tripped_) bits |= rb::bit(StatusBit::watchdog_tripped);
  if (latched_valid_) bits |= rb::bit(StatusBit::latched_pose_valid);
  if (force_valid_) bits |= rb::bit(StatusBit::force_valid);
  if (tool_set_) bits |= rb::bit(StatusBit::tool_set);
  status_.status_bits = bits;
  status_.robot_time_ms = static_cast<rb::u32>(static_cast<std::uint64_t>(std::llround(time_s_ * 1e3)));
  rb::i32 p[6];
  pose_registers(arm_.tcp(), p);
  status_.x_um = p[0], status_.y_um = p[1], status_.z_um = p[2];
  status_.a_mdeg = p[3], status_.b_mdeg = p[4], status_.c_mdeg = p[5];
  rb::encode(status_, std::span<u16, rb::StatusBlock::kLength>(status_regs_));
}

void RobotBridge::publish_force() {
  double d[3];
  if (approach_set_) {
    for (int i = 0; i < 3; ++i) d[i] = approach_dir_[i];
  } else {
    const plant::Transform tcp = arm_.tcp();
    for (int i = 0; i < 3; ++i) d[i] = tcp.r.m[i][2];
  }
  if (!force_valid_) {
    status_.force_mN = 0;
    return;
  }
  const double against = -(force_[0] * d[0] + force_[1] * d[1] + force_[2] * d[2]);
  std::normal_distribution<double> noise(0.0, options_.force_noise_N);
  const double n = options_.force_noise_N > 0 ? noise(rng_) : 0.0;
  status_.force_mN = to_i32((against + n) * 1e3);
}

}  // namespace palp::sim
