// SPDX-License-Identifier: Apache-2.0
// palp-sim's control channel: the simulator's own knobs, never part of the device protocol.
// One command per line, words separated by spaces; every command is answered with one line,
// "ok ..." or "error: <what is wrong>". Lab units with the unit in the word (mm, Hz, ms).
//
//   help                              list the commands
//   status                            virtual time, pacing, client, counters
//   mount <x_mm> <y_mm> <z_mm>        place the probe: the tip at the stroke origin, phantom frame
//   phantom <name>|none               load hil/plant/phantoms/<name>.phantom, or free air
//   seed <n>                          noise seed (runs repeat for the same seed)
//   pace realtime|fast|<factor>       pacing: real time, as fast as possible, or factor x real time
//   drop-frames <n>                   drop every n-th device-to-host frame (0: none)
//   corrupt-frames <n>                flip a bit in every n-th device-to-host frame (0: none)
//   announce <major>.<minor> [0x<hash>]   DeviceInfo announces another protocol version/schema
//   announce actual                   back to this build's version and schema
//   reaction-latency <ms>             virtual time from a host's reaction to its effect
//   hold-timeout <ms>                 wall time a contact event waits for the host's reaction
// Sensor and actuator faults (sensor_faults.hpp; the core's reaction: docs/reliability.md §5):
//   fault encoder-stuck               the encoder count freezes where it is
//   fault encoder-glitch <counts>     miscounted edges: the count is offset by <counts> (nonzero,
//                                     |counts| <= 30000) from the next tick on
//   fault adc-stuck                   the current-sense reading freezes where it is
//   fault adc-saturate high|low       the current-sense ADC reads its top (bottom) code
//   fault driver                      the H-bridge driver asserts its fault line, outputs off
//   fault supply-sag <V>              the bridge supply drops to <V> (0 up to the nominal 24 V)
//   fault clear                       every sensor and the power stage work again (the device's
//                                     latch stays until the host clears it)
// With the robot bridge on (--robot-port):
//   robot-reply-delay <ms>            wall time every Modbus reply is held back (0: none)
//   robot-drop                        close the Modbus client's connection now
//   robot-freeze-heartbeat on|off     the bridge's heartbeat register stops (or resumes) counting
//   robot-reject <result-name> <n>    the next n commands are rejected with that Result
//                                     (rejected_busy, rejected_not_ready, ...)
//   robot-fault                       a robot error: the motion ends with robot_fault, faulted
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <variant>

namespace palp::sim {

namespace cmd {
struct Help {};
struct Status {};
struct Mount { double x_mm, y_mm, z_mm; };
struct Phantom { std::string name; };  // "none" for free air
struct Seed { std::uint64_t seed; };
struct Pace { double factor; };  // 0: as fast as possible; 1: real time
struct DropFrames { std::uint32_t every; };
struct CorruptFrames { std::uint32_t every; };
struct Announce { bool actual; std::uint8_t major, minor; std::optional<std::uint32_t> hash; };
struct ReactionLatency { double ms; };
struct HoldTimeout { double ms; };
struct RobotReplyDelay { double ms; };
struct RobotDrop {};
struct RobotFreezeHeartbeat { bool on; };
struct RobotReject { std::uint16_t result; std::uint32_t count; };  // a rejection Result value
struct RobotFault {};
struct Fault {
  enum class Kind : std::uint8_t {
    encoder_stuck, encoder_glitch, adc_stuck, adc_saturate, driver, supply_sag, clear
  } kind;
  std::int32_t counts = 0;  // encoder_glitch
  bool high = true;         // adc_saturate
  double volts = 0;         // supply_sag
};
}  // namespace cmd

using ControlCommand = std::variant<cmd::Help, cmd::Status, cmd::Mount, cmd::Phantom, cmd::Seed,
                                    cmd::Pace, cmd::DropFrames, cmd::CorruptFrames, cmd::Announce,
                                    cmd::ReactionLatency, cmd::HoldTimeout, cmd::RobotReplyDelay,
                                    cmd::RobotDrop, cmd::RobotFreezeHeartbeat, cmd::RobotReject,
                                    cmd::RobotFault, cmd::Fault>;

/// Parses one line. On failure returns nullopt and sets error to a one-line reason that names
/// the command and the offending word.
std::optional<ControlCommand> parse_control(std::string_view line, std::string& error);

/// The help text (the list above), one command per line.
const char* control_help();

}  // namespace palp::sim
