// SPDX-License-Identifier: Apache-2.0
// The parameter checks of a committed command (protocol/robot-bridge.md §6): which registers a
// command uses, their ranges, and that every register it does not use is zero. State checks
// (busy, faulted, not ready, heartbeat) and reachability are the bridge's, not these.
// Freestanding: no heap, no exceptions, no RTTI.
#pragma once

#include "palp/protocol/robot_bridge/codec.hpp"

namespace palp::proto::rb {

inline constexpr i32 kMaxLinSpeedUmPerS = 1000000;      // 1 m/s
inline constexpr i32 kMaxApproachSpeedUmPerS = 100000;  // 100 mm/s
inline constexpr i32 kMaxPtpSpeedPermille = 1000;
inline constexpr i32 kMaxApproachTravelUm = 500000;     // 0.5 m
inline constexpr i32 kMaxForceThresholdMN = 1000000;    // 1 kN
inline constexpr i32 kMaxAngleMdeg = 180000;
inline constexpr u16 kMaxDigitalInput = 16;
inline constexpr u16 kMaxTool = 15;

struct CommandVerdict {
  Result result = Result::accepted;  // accepted, or the rejection to put in ack_result
  u16 detail = 0;                    // rejected_bad_parameter: the offending register's address
  constexpr bool accepted() const { return result == Result::accepted; }
  friend constexpr bool operator==(const CommandVerdict&, const CommandVerdict&) = default;
};

namespace detail {
constexpr CommandVerdict bad(const char* reg) {
  return {Result::rejected_bad_parameter, address_of<Command>(reg)};
}
constexpr bool in(i32 v, i32 lo, i32 hi) { return v >= lo && v <= hi; }
constexpr u16 kKnownGuards = bit(GuardSource::host_stop) | bit(GuardSource::digital_input) | bit(GuardSource::force);
}  // namespace detail

/// The verdict on a decoded command's parameters.
constexpr CommandVerdict check_command(const Command& c) {
  using detail::bad;
  using detail::in;
  const CommandCode k = c.code;
  const bool approach = k == CommandCode::guarded_approach;
  const bool pose = k == CommandCode::move_lin || k == CommandCode::move_lin_rel ||
                    k == CommandCode::move_ptp || k == CommandCode::set_tool;
  const bool lin = k == CommandCode::move_lin || k == CommandCode::move_lin_rel;
  if (k == CommandCode::none || enum_name(k) == nullptr) return {Result::rejected_unknown_command, 0};

  // guarded_approach's own registers
  const bool di = (c.guard_sources & bit(GuardSource::digital_input)) != 0;
  const bool force = (c.guard_sources & bit(GuardSource::force)) != 0;
  if (approach ? (c.guard_sources == 0 || (c.guard_sources & ~detail::kKnownGuards) != 0) : c.guard_sources != 0)
    return bad("guard_sources");
  if (approach ? c.axis == Axis::none || enum_name(c.axis) == nullptr : c.axis != Axis::none)
    return bad("axis");
  if (approach && di ? !(c.digital_input >= 1 && c.digital_input <= kMaxDigitalInput) : c.digital_input != 0)
    return bad("digital_input");
  if (k == CommandCode::set_tool ? !(c.tool >= 1 && c.tool <= kMaxTool) : c.tool != 0) return bad("tool");

  i32 max_speed = 0;
  if (lin) max_speed = kMaxLinSpeedUmPerS;
  if (approach) max_speed = kMaxApproachSpeedUmPerS;
  if (k == CommandCode::move_ptp) max_speed = kMaxPtpSpeedPermille;
  if (max_speed != 0 ? !in(c.speed, 1, max_speed) : c.speed != 0) return bad("speed");
  if (approach && force ? !in(c.force_threshold_mN, 1, kMaxForceThresholdMN) : c.force_threshold_mN != 0)
    return bad("force_threshold_mN");
  if (approach ? c.max_travel_um == 0 || !in(c.max_travel_um, -kMaxApproachTravelUm, kMaxApproachTravelUm)
               : c.max_travel_um != 0)
    return bad("max_travel_um");

  if (!pose) {
    if (c.x_um != 0) return bad("x_um");
    if (c.y_um != 0) return bad("y_um");
    if (c.z_um != 0) return bad("z_um");
  }
  const i32 angle_limit = pose ? kMaxAngleMdeg : 0;
  if (!in(c.a_mdeg, -angle_limit, angle_limit)) return bad("a_mdeg");
  if (!in(c.b_mdeg, -angle_limit, angle_limit)) return bad("b_mdeg");
  if (!in(c.c_mdeg, -angle_limit, angle_limit)) return bad("c_mdeg");
  return {};
}

/// The verdict on a command block's raw registers: a code this build does not know is
/// rejected_unknown_command, another bad enum register is rejected_bad_parameter at its address.
constexpr CommandVerdict check_command(std::span<const u16> regs, Command& out) {
  const DecodeResult d = decode(regs, out);
  if (d.error == DecodeError::bad_enum && d.address == address_of<Command>("code"))
    return {Result::rejected_unknown_command, 0};
  if (!d.ok()) return {Result::rejected_bad_parameter, d.address};
  return check_command(out);
}

}  // namespace palp::proto::rb
