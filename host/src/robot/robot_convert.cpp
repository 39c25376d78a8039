// SPDX-License-Identifier: Apache-2.0
// SI arguments <-> register blocks, and the texts of rejections and faults.
#include "robot/robot_convert.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "palp/error.hpp"
#include "palp/protocol/robot_bridge/check.hpp"

namespace palp::detail {
namespace {

constexpr double kMdegPerRad = 180000.0 / std::numbers::pi;

template <class E>
const char* doc_of(E value) {
  for (const auto& v : rb::EnumInfo<E>::values)
    if (v.value == static_cast<rb::u16>(value)) return v.doc;
  return nullptr;
}

/// "Rejected: the target is outside ... limits." -> "the target is outside ... limits"
std::string plain_doc(const char* doc) {
  if (doc == nullptr) return "a value this SDK (register map " + std::to_string(rb::kMapMajor) +
                             "." + std::to_string(rb::kMapMinor) + ") does not know";
  std::string s = doc;
  const std::string prefix = "Rejected: ";
  if (s.rfind(prefix, 0) == 0) s.erase(0, prefix.size());
  if (!s.empty() && s.back() == '.') s.pop_back();
  if (!s.empty() && s[0] >= 'A' && s[0] <= 'Z') s[0] = static_cast<char>(s[0] - 'A' + 'a');
  return s;
}

const rb::RegisterInfo* command_register(std::uint16_t address, std::uint16_t* first = nullptr) {
  std::uint16_t at = rb::Command::kAddress;
  for (const rb::RegisterInfo& r : rb::Command::kRegisters) {
    if (address >= at && address < at + r.count) {
      if (first) *first = at;
      return &r;
    }
    at = static_cast<std::uint16_t>(at + r.count);
  }
  return nullptr;
}

/// si * scale rounded to the nearest integer, as the register's int32.
rb::i32 to_register(double si, double scale, rb::CommandCode code, const char* reg) {
  const double v = std::round(si * scale);
  if (!std::isfinite(v) || v < std::numeric_limits<rb::i32>::min() ||
      v > std::numeric_limits<rb::i32>::max()) {
    const std::uint16_t address = rb::address_of<rb::Command>(reg);
    const rb::RegisterInfo* info = command_register(address);
    throw ConfigError(command_name(code) + ": " + std::to_string(si) + " does not fit register " +
                      reg + " (" + std::to_string(address) + ", int32 in " +
                      (info && *info->unit ? info->unit : "counts") + "); nothing was sent");
  }
  return static_cast<rb::i32>(v);
}

void put_pose(rb::Command& c, const Pose& p) {
  c.x_um = to_register(p.x_m, 1e6, c.code, "x_um");
  c.y_um = to_register(p.y_m, 1e6, c.code, "y_um");
  c.z_um = to_register(p.z_m, 1e6, c.code, "z_um");
  c.a_mdeg = to_register(p.a_rad, kMdegPerRad, c.code, "a_mdeg");
  c.b_mdeg = to_register(p.b_rad, kMdegPerRad, c.code, "b_mdeg");
  c.c_mdeg = to_register(p.c_rad, kMdegPerRad, c.code, "c_mdeg");
}

}  // namespace

rb::Command motion_command(rb::CommandCode code, const Pose& pose, double speed) {
  rb::Command c;
  c.code = code;
  c.speed = to_register(speed, code == rb::CommandCode::move_ptp ? 1000.0 : 1e6, code, "speed");
  put_pose(c, pose);
  return c;
}

rb::Command approach_command(const GuardedApproach& g) {
  rb::Command c;
  c.code = rb::CommandCode::guarded_approach;
  c.axis = g.axis;
  if (g.guard_host_stop) c.guard_sources |= rb::bit(rb::GuardSource::host_stop);
  if (g.digital_input != 0) {
    c.guard_sources |= rb::bit(rb::GuardSource::digital_input);
    c.digital_input = static_cast<rb::u16>(g.digital_input < 0 || g.digital_input > 0xFFFF ? 0xFFFF : g.digital_input);
  }
  if (g.force_threshold_N) {
    c.guard_sources |= rb::bit(rb::GuardSource::force);
    c.force_threshold_mN = to_register(*g.force_threshold_N, 1e3, c.code, "force_threshold_mN");
  }
  c.speed = to_register(g.speed_m_per_s, 1e6, c.code, "speed");
  c.max_travel_um = to_register(g.max_travel_m, 1e6, c.code, "max_travel_um");
  return c;
}

rb::Command tool_command(int id, const Pose& tcp_on_flange) {
  rb::Command c;
  c.code = rb::CommandCode::set_tool;
  c.tool = static_cast<rb::u16>(id < 0 || id > 0xFFFF ? 0xFFFF : id);
  put_pose(c, tcp_on_flange);
  return c;
}

rb::Command plain_command(rb::CommandCode code) {
  rb::Command c;
  c.code = code;
  return c;
}

void check_command_or_throw(const rb::Command& c) {
  const rb::CommandVerdict v = rb::check_command(c);
  if (v.accepted()) return;
  if (v.result != rb::Result::rejected_bad_parameter)
    throw ConfigError(command_name(c.code) + ": " + result_name(v.result) + " — " +
                      plain_doc(doc_of(v.result)) + "; nothing was sent");
  std::array<rb::u16, rb::Command::kLength> regs{};
  rb::encode(c, std::span<rb::u16, rb::Command::kLength>(regs));
  std::uint16_t first = 0;
  const rb::RegisterInfo* info = command_register(v.detail, &first);
  const std::size_t at = static_cast<std::size_t>(first - rb::Command::kAddress);
  const long long value = info && info->count == 2 ? static_cast<long long>(rb::get_i32(&regs[at]))
                                                   : static_cast<long long>(regs[at]);
  const std::string unit = info && *info->unit ? std::string(" ") + info->unit : "";
  throw ConfigError(command_name(c.code) + ": register " + command_register_name(v.detail) + " (" +
                    std::to_string(v.detail) + ") would hold " + std::to_string(value) + unit +
                    ", out of range or not allowed for " + command_name(c.code) +
                    " (robot-bridge.md §6); nothing was sent");
}

std::string command_name(rb::CommandCode code) {
  const char* n = rb::enum_name(code);
  return n ? n : "#" + std::to_string(static_cast<unsigned>(code));
}

std::string result_name(rb::Result r) {
  const char* n = rb::enum_name(r);
  return n ? n : "#" + std::to_string(static_cast<unsigned>(r));
}

std::string command_register_name(std::uint16_t address) {
  const rb::RegisterInfo* info = command_register(address);
  return info ? info->name : "#" + std::to_string(address);
}

std::string rejection_text(rb::CommandCode code, std::uint16_t seq, rb::Result r, std::uint16_t detail) {
  std::string why = plain_doc(doc_of(r));
  if (r == rb::Result::rejected_bad_parameter)
    why = "register " + command_register_name(detail) + " (" + std::to_string(detail) +
          ") is out of range or not zero when unused";
  return "robot bridge rejected " + command_name(code) + " (seq " + std::to_string(seq) +
         "): " + result_name(r) + " — " + why;
}

std::string fault_text(rb::CommandCode code, std::uint16_t seq, rb::Result r) {
  return "robot bridge: " + command_name(code) + " (seq " + std::to_string(seq) + ") ended with " +
         result_name(r) + " — " + plain_doc(doc_of(r));
}

Pose pose_from_registers(rb::i32 x_um, rb::i32 y_um, rb::i32 z_um, rb::i32 a_mdeg, rb::i32 b_mdeg,
                         rb::i32 c_mdeg) {
  return Pose{x_um * 1e-6, y_um * 1e-6, z_um * 1e-6,
              a_mdeg / kMdegPerRad, b_mdeg / kMdegPerRad, c_mdeg / kMdegPerRad};
}

namespace {
std::string map_text(unsigned major, unsigned minor) {
  return std::to_string(major) + "." + std::to_string(minor);
}

std::string decode_problem(const char* block, const rb::RegisterInfo* regs, std::size_t nregs,
                           std::uint16_t base, rb::DecodeResult d,
                           std::span<const std::uint16_t> raw) {
  std::string name = "#" + std::to_string(d.address);
  std::uint16_t at = base;
  for (std::size_t i = 0; i < nregs; ++i) {
    if (at == d.address) name = regs[i].name;
    at = static_cast<std::uint16_t>(at + regs[i].count);
  }
  const std::size_t index = static_cast<std::size_t>(d.address - base);
  const std::string value = index < raw.size() ? std::to_string(raw[index]) : "?";
  if (d.error == rb::DecodeError::bad_enum)
    return std::string(block) + " register " + name + " (" + std::to_string(d.address) +
           ") holds " + value + ", a value this SDK (register map " +
           map_text(rb::kMapMajor, rb::kMapMinor) + ") does not know";
  return std::string(block) + " block: " + rb::error_name(d.error);
}

template <class B>
B decode_or_throw(std::span<const std::uint16_t> regs, const std::string& uri, const char* what) {
  B b;
  if (regs.size() < B::kLength)
    throw ProtocolError("robot bridge " + uri + ": " + what + " block of " +
                        std::to_string(regs.size()) + " registers, expected at least " +
                        std::to_string(B::kLength));
  const rb::DecodeResult d = rb::decode(regs.first(B::kLength), b);
  if (!d.ok())
    throw ProtocolError("robot bridge " + uri + ": " +
                        decode_problem(what, B::kRegisters, std::size(B::kRegisters), B::kAddress,
                                       d, regs));
  return b;
}
}  // namespace

rb::Identification check_identification(std::span<const std::uint16_t> regs, const std::string& uri) {
  rb::Identification id;
  if (regs.size() < rb::Identification::kLength)
    throw ProtocolError("robot bridge " + uri + ": identification block of " +
                        std::to_string(regs.size()) + " registers, expected " +
                        std::to_string(rb::Identification::kLength));
  const rb::DecodeResult d = rb::decode(regs.first(rb::Identification::kLength), id);
  if (d.error == rb::DecodeError::bad_magic) {
    char hex[16];
    std::snprintf(hex, sizeof hex, "0x%08X", static_cast<unsigned>(id.magic));
    throw VersionError(uri + ": not a palp robot bridge (magic " + hex +
                       ", expected 0x50414C50 'PALP')");
  }
  if (d.error == rb::DecodeError::incompatible_version)
    throw VersionError("robot bridge " + uri + " serves register map " +
                       map_text(id.map_major, id.map_minor) + " and this SDK speaks map " +
                       map_text(rb::kMapMajor, rb::kMapMinor) +
                       ": another major version is incompatible; install the bridge "
                       "application for map " + std::to_string(rb::kMapMajor) +
                       ".x on the robot, or use an SDK built for map " +
                       std::to_string(id.map_major) + ".x");
  if (!d.ok()) throw ProtocolError("robot bridge " + uri + ": identification: " + rb::error_name(d.error));
  const auto block_ok = [](std::uint16_t address, std::uint16_t length, std::uint16_t want_address,
                           std::uint16_t want_length) {
    return address == want_address && length >= want_length && length <= rb::kMaxReadRegisters;
  };
  if (!block_ok(id.status_address, id.status_length, rb::StatusBlock::kAddress, rb::StatusBlock::kLength) ||
      !block_ok(id.control_address, id.control_length, rb::HostControl::kAddress, rb::HostControl::kLength) ||
      !block_ok(id.command_address, id.command_length, rb::Command::kAddress, rb::Command::kLength))
    throw ProtocolError("robot bridge " + uri + " (map " + map_text(id.map_major, id.map_minor) +
                        ") gives block addresses/lengths status " + std::to_string(id.status_address) +
                        "/" + std::to_string(id.status_length) + ", control " +
                        std::to_string(id.control_address) + "/" + std::to_string(id.control_length) +
                        ", command " + std::to_string(id.command_address) + "/" +
                        std::to_string(id.command_length) + " that this SDK (map " +
                        map_text(rb::kMapMajor, rb::kMapMinor) + ") cannot use");
  return id;
}

rb::StatusBlock decode_status(std::span<const std::uint16_t> regs, const std::string& uri) {
  return decode_or_throw<rb::StatusBlock>(regs, uri, "status");
}

rb::HostControl decode_control(std::span<const std::uint16_t> regs, const std::string& uri) {
  return decode_or_throw<rb::HostControl>(regs, uri, "host control");
}

RobotStatus status_from_block(const rb::StatusBlock& s) {
  RobotStatus r;
  r.state = s.state;
  r.status_bits = s.status_bits;
  r.heartbeat = s.heartbeat;
  r.ack_seq = s.ack_seq;
  r.done_seq = s.done_seq;
  r.ack_result = s.ack_result;
  r.result = s.result;
  r.guard_fired = s.guard_fired;
  r.stop_seen = s.stop_seen;
  r.tool = s.tool;
  r.robot_time_s = s.robot_time_ms * 1e-3;
  r.pose = pose_from_registers(s.x_um, s.y_um, s.z_um, s.a_mdeg, s.b_mdeg, s.c_mdeg);
  if (r.has(rb::StatusBit::latched_pose_valid))
    r.latched = pose_from_registers(s.latched_x_um, s.latched_y_um, s.latched_z_um,
                                    s.latched_a_mdeg, s.latched_b_mdeg, s.latched_c_mdeg);
  if (r.has(rb::StatusBit::force_valid)) r.force_N = s.force_mN * 1e-3;
  const rb::i32 joints[7] = {s.a1_mdeg, s.a2_mdeg, s.a3_mdeg, s.a4_mdeg, s.a5_mdeg, s.a6_mdeg, s.a7_mdeg};
  for (std::size_t i = 0; i < 7; ++i) r.joints_rad[i] = joints[i] / kMdegPerRad;
  return r;
}

}  // namespace palp::detail
