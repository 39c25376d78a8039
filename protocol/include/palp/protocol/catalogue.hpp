// SPDX-License-Identifier: Apache-2.0
// THE message catalogue of the palp wire protocol: defined here once, as X-macros.
//
// Everything else (the C++ structs, their encoders and decoders on the firmware and the host,
// the enum names, the schema hash, the message tables in SPEC.md) is expanded from these lists.
// Change the wire only here. Rules (SPEC.md §8):
//   - a released message id, field order, type, unit or enum value never changes within a major;
//   - a minor version may add messages, enum values and *trailing* fields (with `since` set to
//     the new minor and a default that a decoder fills in when an older peer leaves them out);
//   - after any change, bump PALP_PROTOCOL_MINOR (or MAJOR), regenerate the vectors
//     (`palp-proto vectors protocol/vectors`) and the SPEC's generated blocks
//     (`palp-proto spec --write protocol/SPEC.md`); the tests fail until both match.
//
// Enumerations:   E(name, value, doc)
// Messages:       M(Name, id, direction, since_minor, Reply, doc)
//                 direction: H2D (host to device) or D2H (device to host); Reply: the message a
//                 device answers with, or None (D2H messages and fire-and-forget).
// Fields:         F(kind, type, n, name, since_minor, default, lo, hi, unit, doc)
//                 kind S: scalar of `type`      E: enum `type` (wire: its underlying integer)
//                      A: `n` x `type`, fixed    V: up to `n` x `type`, u16 count first
//                      T: text, exactly `n` bytes, UTF-8, zero-padded
//                 lo/hi: the inclusive valid range (NOLIM: the type's full range); a device
//                 answers a value outside it with Nak{out_of_range, field_index}.
//                 unit: SI or a stated count unit; "" for dimensionless.
#pragma once

#define PALP_PROTOCOL_MAJOR 1
#define PALP_PROTOCOL_MINOR 1

// ---------------------------------------------------------------------------------------------
// Enumerations: PALP_ENUMS lists them (Name, underlying type, doc); PALP_ENUM_<Name> their values.

#define PALP_ENUMS(X)                                                                       \
  X(ErrorCode, u16, "Why a device refused a request (Nak.error).")                          \
  X(FaultReason, u16, "Why the fault latch tripped; the coil current is zero while latched.") \
  X(DeviceState, u8, "The controller's top-level state.")                                   \
  X(ProgramKind, u8, "The on-device waveform programs.")                                    \
  X(ProgramState, u8, "Where the loaded program is in its life.")                           \
  X(ProgramEnd, u8, "How a program ended.")                                                 \
  X(PhaseMode, u8, "How a multisine chooses its line phases.")                              \
  X(GapStage, u8, "The buffering stage where stream samples were lost.")                    \
  X(ContactOutputMode, u8, "How the contact-output line to the robot behaves.")             \
  X(Capability, u8, "Bit numbers of DeviceInfo.capabilities.")                              \
  X(Channel, u8, "Bit numbers of a stream channel mask; samples carry channels in this order.") \
  X(StatusBit, u8, "Bit numbers of the per-sample and Status status word.")

#define PALP_ENUM_ErrorCode(E)                                                         \
  E(ok, 0, "No error.")                                                                \
  E(unknown_message, 1, "The message id is not in the device's catalogue.")            \
  E(bad_payload, 2, "The payload is shorter than the message's required fields or a count exceeds its bound.") \
  E(out_of_range, 3, "A field is outside its range; Nak.field_index names it.")        \
  E(busy, 4, "Refused while a program runs; stop it first.")                           \
  E(faulted, 5, "Refused while the fault latch is set; read the fault and clear it.")  \
  E(no_program, 6, "ProgramStart without a loaded program.")                          \
  E(incompatible_host, 7, "The last Hello named an incompatible protocol; only identify, version and bootloader are served.") \
  E(calibration_invalid, 8, "The calibration block fails its checks (Nak.field_index names the field).") \
  E(flash_failed, 9, "Writing the calibration block to flash failed.")                 \
  E(stream_too_fast, 10, "The stream configuration exceeds what the device can produce.") \
  E(wrong_direction, 11, "A device-to-host message was sent to the device.")           \
  E(bad_magic, 12, "EnterBootloader without the right magic word.")                   \
  E(fault_persists, 13, "FaultClear refused: the cause of the fault is still present.") \
  E(hello_required, 14, "No compatible Hello on this connection yet; only identify, version and bootloader are served. Send Hello first.")

#define PALP_ENUM_FaultReason(E)                                                          \
  E(none, 0, "No fault.")                                                                 \
  E(overcurrent, 1, "Measured current beyond the clamp by more than the margin.")         \
  E(i2t, 2, "The coil's I2t thermal model reached its limit.")                            \
  E(travel_limit, 3, "The encoder left [travel_min_counts, travel_max_counts].")          \
  E(heartbeat_timeout, 4, "No host message within heartbeat_timeout_ms while armed.")     \
  E(supply_undervoltage, 5, "The coil supply fell below its minimum; detail: the supply in mV.") \
  E(encoder_error, 6, "The encoder reported an impossible transition; detail: the counts of a jump, or 0 when it stood still while the coil had to move.") \
  E(control_overrun, 7, "A control tick did not finish within its period.")               \
  E(host_request, 8, "The host asked for a fault (test and emergency stop).")             \
  E(internal, 9, "An internal consistency check failed.")                                \
  E(driver_fault, 10, "The H-bridge driver signalled a fault on its fault line; detail: measured current in 0.1 mA (since 1.1).") \
  E(current_sense_error, 11, "The current-sense reading is at the end of its range or stuck while the coil voltage changed; detail: the raw reading in 0.1 mA (since 1.1).")

#define PALP_ENUM_DeviceState(E)                                  \
  E(idle, 0, "Current zero, no program running.")                 \
  E(running, 1, "A program is running.")                          \
  E(faulted, 2, "The fault latch is set; current is zero.")       \
  E(incompatible, 3, "The host's Hello was incompatible.")

#define PALP_ENUM_ProgramKind(E)                                     \
  E(none, 0, "No program.")                                          \
  E(hold, 1, "Hold a current.")                                      \
  E(ramp, 2, "Staircase ramp: load, symmetric unload, repetitions.") \
  E(sine, 3, "Sine about an offset.")                                \
  E(sweep, 4, "Stepped-sine sweep.")                                 \
  E(multisine, 5, "Periodic multisine.")                             \
  E(contact_watch, 6, "Hold a current and watch the encoder for contact.")

#define PALP_ENUM_ProgramState(E)                         \
  E(idle, 0, "Nothing loaded.")                           \
  E(loaded, 1, "Loaded, waiting for ProgramStart.")       \
  E(running, 2, "Running.")                               \
  E(finished, 3, "Ended; EventProgramFinished was sent.")

#define PALP_ENUM_ProgramEnd(E)                                          \
  E(completed, 0, "Ran to its end.")                                     \
  E(stopped_by_host, 1, "ProgramStop arrived.")                          \
  E(fault, 2, "A fault latched.")                                        \
  E(timeout, 3, "A contact watch expired without contact.")              \
  E(contact, 4, "A contact watch fired.")

#define PALP_ENUM_PhaseMode(E)                                                        \
  E(random_seeded, 0, "Line n (n from 0) at the (n+1)-th xorshift32 output from phase_seed / 2^32 turns (multisine.hpp).") \
  E(schroeder, 1, "Schroeder phases: line n of K (n from 1) at -n (n - 1) / (2 K) turns (multisine.hpp).")                     \
  E(zero, 2, "All phases zero (maximum crest factor; for tests).")

#define PALP_ENUM_GapStage(E)                                                      \
  E(isr_queue, 0, "The control ISR's sample queue was full.")                      \
  E(stream_backlog, 1, "The stream backlog was full (host did not drain).")        \
  E(usb_in, 2, "The USB IN endpoint was not drained by the host.")                 \
  E(transport, 3, "Frames lost between device and host (seen by the host).")

#define PALP_ENUM_ContactOutputMode(E)                          \
  E(disabled, 0, "The line is not driven.")                     \
  E(active_high, 1, "High while contact is latched.")           \
  E(active_low, 2, "Low while contact is latched.")

#define PALP_ENUM_Capability(E)                                            \
  E(usb_bulk, 0, "Vendor interface with bulk endpoints.")                  \
  E(hid, 1, "HID interface carrying the byte stream.")                     \
  E(uart, 2, "UART carrying the byte stream.")                             \
  E(pressure, 3, "Six pressure channels.")                                 \
  E(contact_output, 4, "A contact-output line for the robot.")             \
  E(calibration_flash, 5, "Calibration survives power cycles.")            \
  E(simulated, 6, "This device is palp-sim, not hardware.")

#define PALP_ENUM_Channel(E)                                                       \
  E(i_cmd, 0, "Commanded coil current, i16, 0.0002 A per LSB.")                   \
  E(i_meas, 1, "Measured coil current, i16, 0.0002 A per LSB.")                   \
  E(encoder, 2, "Encoder count, i32, 1 count = 1 um, +z into the specimen.")      \
  E(p1, 3, "Pressure channel 1, i16, 0.05 Pa per LSB.")                           \
  E(p2, 4, "Pressure channel 2, i16, 0.05 Pa per LSB.")                           \
  E(p3, 5, "Pressure channel 3, i16, 0.05 Pa per LSB.")                           \
  E(p4, 6, "Pressure channel 4, i16, 0.05 Pa per LSB.")                           \
  E(p5, 7, "Pressure channel 5, i16, 0.05 Pa per LSB.")                           \
  E(p6, 8, "Pressure channel 6, i16, 0.05 Pa per LSB.")                           \
  E(status, 9, "Status word, u16, StatusBit bits.")                               \
  E(v_cmd, 10, "Commanded coil voltage, i16, 0.001 V per LSB.")

#define PALP_ENUM_StatusBit(E)                                                  \
  E(program_running, 0, "A program is running.")                                \
  E(fault_latched, 1, "The fault latch is set.")                                \
  E(contact_latched, 2, "The contact watch has fired and not been re-armed.")   \
  E(voltage_saturated, 3, "The current loop's output is at the supply limit.")  \
  E(current_clamped, 4, "The set-point was clamped to current_clamp_A.")        \
  E(heartbeat_armed, 5, "The host heartbeat watchdog is armed.")                \
  E(i2t_warning, 6, "The I2t model is above 80 % of its limit.")                \
  E(after_gap, 7, "Samples were lost right before this one.")

// ---------------------------------------------------------------------------------------------
// Messages. Ids 0x01-0x0F are frozen across every major version (SPEC.md §6.1): their id and
// fields never change, so an incompatible device can always be identified and reflashed.

#define PALP_MESSAGES(M)                                                                        \
  M(Hello, 0x01, H2D, 0, DeviceInfo, "Opens a session: the host's protocol version and schema hash.") \
  M(DeviceInfo, 0x02, D2H, 0, None, "Who the device is and what it speaks.")                   \
  M(GetDeviceInfo, 0x03, H2D, 0, DeviceInfo, "Identify and version, without opening a session.") \
  M(EnterBootloader, 0x04, H2D, 0, Ack, "Reboot into the ROM bootloader for reflashing.")      \
  M(Ack, 0x05, D2H, 0, None, "The request with this sequence number was carried out.")         \
  M(Nak, 0x06, D2H, 0, None, "The request with this sequence number was refused.")             \
  M(Ping, 0x10, H2D, 0, Pong, "Round-trip and time sync.")                                     \
  M(Pong, 0x11, D2H, 0, None, "Answer to Ping with the device time.")                          \
  M(Heartbeat, 0x12, H2D, 0, Ack, "Keeps the host watchdog fed; so does every other valid request (rejected frames do not).")       \
  M(GetStatus, 0x13, H2D, 0, Status, "Read the status.")                                       \
  M(Status, 0x14, D2H, 0, None, "State, fault, program, live values.")                         \
  M(GetHealth, 0x15, H2D, 0, Health, "Read the health counters.")                              \
  M(Health, 0x16, D2H, 0, None, "Counters of every buffering stage, since boot.")             \
  M(GetParams, 0x18, H2D, 0, Params, "Read the parameters.")                                   \
  M(Params, 0x19, D2H, 0, None, "The parameters in force.")                                    \
  M(SetParams, 0x1A, H2D, 0, Params, "Replace all parameters (read, modify, write).")          \
  M(GetCalibration, 0x1C, H2D, 0, Calibration, "Read the calibration in RAM.")                 \
  M(Calibration, 0x1D, D2H, 0, None, "The calibration in RAM.")                                \
  M(SetCalibration, 0x1E, H2D, 0, Calibration, "Replace the calibration in RAM (not flash).")  \
  M(CommitCalibration, 0x1F, H2D, 0, Ack, "Write the calibration in RAM to flash.")            \
  M(LoadHold, 0x20, H2D, 0, Ack, "Load a hold program.")                                       \
  M(LoadRamp, 0x21, H2D, 0, Ack, "Load a staircase ramp.")                                     \
  M(LoadSine, 0x22, H2D, 0, Ack, "Load a sine.")                                               \
  M(LoadSweep, 0x23, H2D, 0, Ack, "Load a stepped-sine sweep.")                                \
  M(LoadMultisine, 0x24, H2D, 0, Ack, "Load a periodic multisine.")                            \
  M(LoadContactWatch, 0x25, H2D, 0, Ack, "Load a contact watch.")                              \
  M(ProgramStart, 0x28, H2D, 0, Ack, "Start the loaded program.")                              \
  M(ProgramStop, 0x29, H2D, 0, Ack, "Stop the running program; the set-point goes to 0 A at once.")        \
  M(GetProgramStatus, 0x2A, H2D, 0, ProgramStatus, "Read the program status.")                 \
  M(ProgramStatus, 0x2B, D2H, 0, None, "Where the program is.")                                \
  M(StreamConfigure, 0x30, H2D, 0, StreamConfig, "Choose channels, decimation and batch size.") \
  M(StreamConfig, 0x31, D2H, 0, None, "The stream configuration in force.")                    \
  M(StreamStart, 0x32, H2D, 0, Ack, "Start streaming; the sample index restarts at 0.")        \
  M(StreamStop, 0x33, H2D, 0, Ack, "Stop streaming.")                                          \
  M(SampleBatch, 0x38, D2H, 0, None, "Consecutive samples of the stream.")                     \
  M(EventFault, 0x40, D2H, 0, None, "The fault latch tripped.")                                \
  M(EventContact, 0x41, D2H, 0, None, "The contact watch fired.")                              \
  M(EventProgramFinished, 0x42, D2H, 0, None, "A program ended.")                              \
  M(EventStreamGap, 0x43, D2H, 0, None, "Stream samples were lost on the device.")             \
  M(FaultClear, 0x48, H2D, 0, Ack, "Release the fault latch if its cause is gone.")

// --- frozen messages -------------------------------------------------------------------------
#define PALP_FIELDS_Hello(F)                                                                  \
  F(S, u8, 1, host_major, 0, 0, NOLIM, NOLIM, "", "Host's protocol major version.")           \
  F(S, u8, 1, host_minor, 0, 0, NOLIM, NOLIM, "", "Host's protocol minor version.")           \
  F(S, u32, 1, host_schema_hash, 0, 0, NOLIM, NOLIM, "", "Host's schema hash (SPEC.md §7).")  \
  F(T, char, 16, host_software, 0, 0, NOLIM, NOLIM, "", "Host software name and version, for the device's log.")

#define PALP_FIELDS_DeviceInfo(F)                                                              \
  F(S, u8, 1, protocol_major, 0, 0, NOLIM, NOLIM, "", "Device's protocol major version.")      \
  F(S, u8, 1, protocol_minor, 0, 0, NOLIM, NOLIM, "", "Device's protocol minor version.")      \
  F(S, u32, 1, schema_hash, 0, 0, NOLIM, NOLIM, "", "Device's schema hash (SPEC.md §7).")      \
  F(S, u8, 1, fw_major, 0, 0, NOLIM, NOLIM, "", "Firmware semantic version, major.")           \
  F(S, u8, 1, fw_minor, 0, 0, NOLIM, NOLIM, "", "Firmware semantic version, minor.")           \
  F(S, u8, 1, fw_patch, 0, 0, NOLIM, NOLIM, "", "Firmware semantic version, patch.")           \
  F(T, char, 16, git_hash, 0, 0, NOLIM, NOLIM, "", "Firmware source revision (abbreviated git hash, '-dirty' if modified).") \
  F(T, char, 16, board, 0, 0, NOLIM, NOLIM, "", "Board id: 'stm32g474', 'qemu-mps2', 'palp-sim'.") \
  F(T, char, 24, serial, 0, 0, NOLIM, NOLIM, "", "Unique serial number (the USB iSerial).")   \
  F(S, u32, 1, capabilities, 0, 0, NOLIM, NOLIM, "", "Capability bits.")                       \
  F(S, f32, 1, max_current_A, 0, 0, NOLIM, NOLIM, "A", "Largest current_clamp_A accepted.")    \
  F(S, u32, 1, control_rate_Hz, 0, 20000, NOLIM, NOLIM, "Hz", "Control tick rate in force.")   \
  F(S, u32, 1, max_stream_rate_Hz, 0, 10000, NOLIM, NOLIM, "Hz", "Highest sample rate the device streams.") \
  F(S, u32, 1, heartbeat_timeout_ms, 0, 500, NOLIM, NOLIM, "ms", "Host heartbeat timeout in force.") \
  F(S, u16, 1, max_payload, 0, 1024, NOLIM, NOLIM, "bytes", "Largest payload the device accepts.") \
  F(E, DeviceState, 1, state, 0, DeviceState::idle, NOLIM, NOLIM, "", "State after this request (incompatible after an incompatible Hello).")

#define PALP_FIELDS_GetDeviceInfo(F)

#define PALP_FIELDS_EnterBootloader(F) \
  F(S, u32, 1, magic, 0, 0, NOLIM, NOLIM, "", "Must be 0x544F4F42 ('BOOT' little-endian).")

#define PALP_FIELDS_Ack(F) \
  F(S, u8, 1, request_id, 0, 0, NOLIM, NOLIM, "", "Message id of the request carried out.")

#define PALP_FIELDS_Nak(F)                                                                   \
  F(S, u8, 1, request_id, 0, 0, NOLIM, NOLIM, "", "Message id of the refused request.")     \
  F(E, ErrorCode, 1, error, 0, ErrorCode::ok, NOLIM, NOLIM, "", "Why.")                      \
  F(S, u8, 1, field_index, 0, 255, NOLIM, NOLIM, "", "Zero-based index of the offending field, 255 if none.") \
  F(S, i32, 1, detail, 0, 0, NOLIM, NOLIM, "", "For faulted and fault_persists: the latched FaultReason; for busy: the running ProgramKind (none when only the stream runs); for no_program: 1 when the loaded program was timed for another control rate; for stream_too_fast: the device's max_stream_rate_Hz; otherwise 0 (SPEC.md 6.3).")

// --- session, time, status -------------------------------------------------------------------
#define PALP_FIELDS_Ping(F)                                                           \
  F(S, u32, 1, nonce, 0, 0, NOLIM, NOLIM, "", "Echoed back.")                         \
  F(S, u64, 1, host_time_us, 0, 0, NOLIM, NOLIM, "us", "Host clock at sending, echoed back.")

#define PALP_FIELDS_Pong(F)                                                            \
  F(S, u32, 1, nonce, 0, 0, NOLIM, NOLIM, "", "Ping.nonce.")                           \
  F(S, u64, 1, host_time_us, 0, 0, NOLIM, NOLIM, "us", "Ping.host_time_us.")           \
  F(S, u64, 1, device_time_us, 0, 0, NOLIM, NOLIM, "us", "Device clock when the Ping was handled.")

#define PALP_FIELDS_Heartbeat(F)
#define PALP_FIELDS_GetStatus(F)

#define PALP_FIELDS_Status(F)                                                                     \
  F(S, u64, 1, device_time_us, 0, 0, NOLIM, NOLIM, "us", "Device clock.")                         \
  F(E, DeviceState, 1, state, 0, DeviceState::idle, NOLIM, NOLIM, "", "Top-level state.")         \
  F(E, FaultReason, 1, fault, 0, FaultReason::none, NOLIM, NOLIM, "", "Latched fault, none if clear.") \
  F(E, ProgramKind, 1, program_kind, 0, ProgramKind::none, NOLIM, NOLIM, "", "Loaded program.")   \
  F(E, ProgramState, 1, program_state, 0, ProgramState::idle, NOLIM, NOLIM, "", "Its state.")     \
  F(S, f32, 1, i_cmd_A, 0, 0, NOLIM, NOLIM, "A", "Commanded coil current.")                      \
  F(S, f32, 1, i_A, 0, 0, NOLIM, NOLIM, "A", "Measured coil current.")                           \
  F(S, i32, 1, encoder_count, 0, 0, NOLIM, NOLIM, "counts", "Encoder, 1 count = 1 um, +z into the specimen.") \
  F(S, f32, 1, i2t_fraction, 0, 0, NOLIM, NOLIM, "", "I2t model state as a fraction of its trip level.") \
  F(S, u8, 1, streaming, 0, 0, NOLIM, NOLIM, "", "1 while the stream runs.")                     \
  F(S, u16, 1, status_bits, 0, 0, NOLIM, NOLIM, "", "StatusBit bits.")

#define PALP_FIELDS_GetHealth(F)

#define PALP_FIELDS_Health(F)                                                                     \
  F(S, u64, 1, device_time_us, 0, 0, NOLIM, NOLIM, "us", "Device clock.")                         \
  F(S, u32, 1, frames_rx, 0, 0, NOLIM, NOLIM, "frames", "Valid frames received.")                 \
  F(S, u32, 1, frames_tx, 0, 0, NOLIM, NOLIM, "frames", "Frames sent.")                           \
  F(S, u32, 1, rx_bad_cobs, 0, 0, NOLIM, NOLIM, "frames", "Rejected: invalid COBS.")              \
  F(S, u32, 1, rx_bad_crc, 0, 0, NOLIM, NOLIM, "frames", "Rejected: CRC mismatch.")               \
  F(S, u32, 1, rx_oversize, 0, 0, NOLIM, NOLIM, "frames", "Rejected: longer than the largest frame.") \
  F(S, u32, 1, rx_truncated, 0, 0, NOLIM, NOLIM, "frames", "Rejected: shorter than header and CRC.") \
  F(S, u32, 1, rx_length_mismatch, 0, 0, NOLIM, NOLIM, "frames", "Rejected: payload length field disagrees.") \
  F(S, u32, 1, rx_unsupported_major, 0, 0, NOLIM, NOLIM, "frames", "Rejected: another major version.") \
  F(S, u32, 1, rx_unknown_message, 0, 0, NOLIM, NOLIM, "frames", "Rejected: unknown message id.")  \
  F(S, u32, 1, rx_short_payload, 0, 0, NOLIM, NOLIM, "frames", "Rejected: payload shorter than required.") \
  F(S, u32, 1, rx_bad_field, 0, 0, NOLIM, NOLIM, "frames", "Rejected: a count beyond its bound.")  \
  F(S, u32, 1, isr_queue_overflows, 0, 0, NOLIM, NOLIM, "samples", "Samples lost at the control ISR's queue.") \
  F(S, u32, 1, stream_backlog_depth, 0, 0, NOLIM, NOLIM, "samples", "Samples waiting in the stream backlog now.") \
  F(S, u32, 1, stream_backlog_max, 0, 0, NOLIM, NOLIM, "samples", "Deepest the backlog has been.") \
  F(S, u32, 1, stream_samples_lost, 0, 0, NOLIM, NOLIM, "samples", "Samples lost because the backlog was full.") \
  F(S, u32, 1, usb_in_not_drained, 0, 0, NOLIM, NOLIM, "frames", "Frames dropped because the host did not read the IN endpoint.") \
  F(S, u32, 1, tx_frames_dropped, 0, 0, NOLIM, NOLIM, "frames", "Other frames the device could not send.") \
  F(S, u32, 1, control_overruns, 0, 0, NOLIM, NOLIM, "ticks", "Control ticks that overran their period.") \
  F(S, u32, 1, stream_gaps, 0, 0, NOLIM, NOLIM, "events", "EventStreamGap events emitted.")

// --- parameters and calibration --------------------------------------------------------------
#define PALP_FIELDS_GetParams(F)

#define PALP_FIELDS_Params(F)                                                                     \
  F(S, f32, 1, current_clamp_A, 0, 3.2, 0, 4.0, "A", "The commanded current never exceeds this magnitude.") \
  F(S, f32, 1, i2t_continuous_A, 0, 2.0, 0, 4.0, "A", "Current the coil carries indefinitely (I2t model; an assumption, see firmware/core).") \
  F(S, f32, 1, i2t_limit_A2s, 0, 60, 0.1, 10000, "A^2*s", "I2t model trip level above the continuous rating.") \
  F(S, f32, 1, i2t_tau_s, 0, 120, 1, 10000, "s", "I2t model cooling time constant.")             \
  F(S, i32, 1, travel_min_counts, 0, -1000, NOLIM, NOLIM, "counts", "Lowest allowed encoder count (toward -z); default: 1 mm behind the rear end stop, the stroke origin.") \
  F(S, i32, 1, travel_max_counts, 0, 35000, NOLIM, NOLIM, "counts", "Highest allowed encoder count (toward +z); default: 1 mm beyond the front end stop of the 34 mm stroke.") \
  F(S, u32, 1, heartbeat_timeout_ms, 0, 500, 50, 10000, "ms", "Host watchdog timeout, armed while current is non-zero or a program runs.") \
  F(S, u32, 1, control_rate_Hz, 0, 20000, 20000, 40000, "Hz", "Control tick rate; a device accepts 20000 and 40000 and answers other values with out_of_range.") \
  F(S, f32, 1, supply_V, 0, 24, 6, 48, "V", "Coil supply voltage (the current loop's saturation).") \
  F(E, ContactOutputMode, 1, contact_output, 0, ContactOutputMode::disabled, NOLIM, NOLIM, "", "Contact-output line to the robot.") \
  F(S, u16, 1, contact_output_hold_ms, 0, 100, 0, 10000, "ms", "Minimum time the contact line stays asserted.")

#define PALP_FIELDS_SetParams(F) PALP_FIELDS_Params(F)
#define PALP_FIELDS_GetCalibration(F)

#define PALP_FIELDS_Calibration(F)                                                                \
  F(S, u16, 1, layout_version, 0, 2, NOLIM, NOLIM, "", "Calibration block layout version on the device.") \
  F(V, i32, 16, kf_position_counts, 0, 0, NOLIM, NOLIM, "counts", "Force-constant table: stroke positions from the stroke origin, increasing.") \
  F(V, f32, 16, kf_N_per_A, 0, 0, 0, 20, "N/A", "Force-constant table: K_f at each position; same count.") \
  F(S, f32, 1, current_offset_A, 0, 0, -0.5, 0.5, "A", "Current-sense offset, subtracted.")      \
  F(S, f32, 1, current_gain, 0, 1, 0.5, 2, "", "Current-sense gain, multiplied after the offset.") \
  F(A, f32, 6, pressure_offset_Pa, 0, 0, -2000, 2000, "Pa", "Per-channel pressure offset, subtracted.") \
  F(A, f32, 6, pressure_gain, 0, 1, 0.1, 10, "", "Per-channel pressure gain, multiplied after the offset.") \
  F(S, f32, 1, spring_k_N_per_m, 0, 43.9, 0, 1000, "N/m", "Return-spring stiffness k_v.")     \
  F(S, i32, 1, stroke_origin_counts, 0, 0, NOLIM, NOLIM, "counts", "Encoder count at the stroke origin.") \
  F(S, u8, 1, stroke_origin_valid, 0, 0, 0, 1, "", "1 when the stroke origin was homed.")

#define PALP_FIELDS_SetCalibration(F) PALP_FIELDS_Calibration(F)
#define PALP_FIELDS_CommitCalibration(F)

// --- programs --------------------------------------------------------------------------------
#define PALP_FIELDS_LoadHold(F)                                                         \
  F(S, f32, 1, current_A, 0, 0, -4, 4, "A", "Held current.")                            \
  F(S, f32, 1, duration_s, 0, 0, 0, 1e6, "s", "How long; 0 holds until ProgramStop.")

#define PALP_FIELDS_LoadRamp(F)                                                                 \
  F(S, f32, 1, start_A, 0, 0.5, -4, 4, "A", "First step's current.")                            \
  F(S, f32, 1, stop_A, 0, 3, -4, 4, "A", "Top step's current.")                                 \
  F(S, f32, 1, step_A, 0, 0.01, 0.0001, 4, "A", "Increment between steps (toward stop_A).")     \
  F(S, f32, 1, dwell_s, 0, 0.025, 0.0001, 100, "s", "Time on each step.")                       \
  F(S, u16, 1, repetitions, 0, 1, 1, 1000, "", "Load/unload cycles.")                           \
  F(S, u8, 1, unload, 0, 1, 0, 1, "", "1: symmetric unload back to start_A after each load.")   \
  F(S, u32, 1, displacement_limit_counts, 0, 0, 0, 100000, "counts", "Turn round early once the encoder moved this far from the ramp start; 0: no limit.")

#define PALP_FIELDS_LoadSine(F)                                                      \
  F(S, f32, 1, offset_A, 0, 1, -4, 4, "A", "Mean current.")                          \
  F(S, f32, 1, amplitude_A, 0, 0.1, 0, 4, "A", "Peak deviation from the offset.")    \
  F(S, f32, 1, frequency_Hz, 0, 1, 0.01, 2000, "Hz", "Frequency.")                   \
  F(S, u32, 1, cycles, 0, 0, NOLIM, NOLIM, "", "Cycles to run; 0 runs until ProgramStop.")

#define PALP_FIELDS_LoadSweep(F)                                                                  \
  F(S, f32, 1, offset_A, 0, 1, -4, 4, "A", "Mean current.")                                       \
  F(S, f32, 1, amplitude_A, 0, 0.1, 0, 4, "A", "Peak deviation from the offset.")                 \
  F(S, f32, 1, start_Hz, 0, 2, 0.01, 2000, "Hz", "First line.")                                   \
  F(S, f32, 1, stop_Hz, 0, 20, 0.01, 2000, "Hz", "Last line (inclusive when on the step grid).")  \
  F(S, f32, 1, step_Hz, 0, 0.05, 0.001, 1000, "Hz", "Line spacing.")                              \
  F(S, u16, 1, settle_cycles, 0, 3, 0, 10000, "", "Cycles discarded at each line before measuring.") \
  F(S, f32, 1, settle_min_s, 0, 1.2, 0, 100, "s", "Settle at least this long (whole cycles).")    \
  F(S, u16, 1, measure_cycles, 0, 5, 1, 10000, "", "Cycles measured at each line.")

#define PALP_FIELDS_LoadMultisine(F)                                                              \
  F(S, f32, 1, offset_A, 0, 1, -4, 4, "A", "Mean current.")                                       \
  F(S, f32, 1, fundamental_Hz, 0, 0.05, 0.001, 100, "Hz", "1 / period.")                          \
  F(S, u16, 1, line_first, 0, 41, 1, 65535, "", "First excited harmonic of the fundamental.")    \
  F(S, u16, 1, line_last, 0, 397, 1, 65535, "", "Last excited harmonic (inclusive).")            \
  F(S, u16, 1, line_step, 0, 4, 1, 65535, "", "Harmonic spacing of excited lines.")               \
  F(S, f32, 1, line_amplitude_A, 0, 0.01, 0, 4, "A", "Amplitude of each excited line.")          \
  F(E, PhaseMode, 1, phase_mode, 0, PhaseMode::random_seeded, NOLIM, NOLIM, "", "How phases are chosen.") \
  F(S, u32, 1, phase_seed, 0, 1, 1, NOLIM, "", "Seed of the phase generator (non-zero).")        \
  F(S, u16, 1, periods, 0, 3, 0, 65535, "", "Whole periods to run; 0 runs until ProgramStop.")

#define PALP_FIELDS_LoadContactWatch(F)                                                             \
  F(S, f32, 1, hold_current_A, 0, 0.5, -4, 4, "A", "Current held while watching.")                  \
  F(S, u32, 1, threshold_counts, 0, 200, 1, 100000, "counts", "Fires when |count - count at start| reaches this.") \
  F(S, f32, 1, timeout_s, 0, 0, 0, 1e6, "s", "Ends with ProgramEnd.timeout after this long; 0: never.")

#define PALP_FIELDS_ProgramStart(F)
#define PALP_FIELDS_ProgramStop(F)
#define PALP_FIELDS_GetProgramStatus(F)

#define PALP_FIELDS_ProgramStatus(F)                                                             \
  F(E, ProgramKind, 1, kind, 0, ProgramKind::none, NOLIM, NOLIM, "", "Loaded program.")          \
  F(E, ProgramState, 1, state, 0, ProgramState::idle, NOLIM, NOLIM, "", "Its state.")            \
  F(E, ProgramEnd, 1, end, 0, ProgramEnd::completed, NOLIM, NOLIM, "", "How it ended (state finished).") \
  F(S, u64, 1, elapsed_us, 0, 0, NOLIM, NOLIM, "us", "Device time since ProgramStart.")          \
  F(S, u32, 1, step, 0, 0, NOLIM, NOLIM, "", "Current step or line index.")                      \
  F(S, u16, 1, repetition, 0, 0, NOLIM, NOLIM, "", "Current repetition, from 0.")

// --- streaming -------------------------------------------------------------------------------
#define PALP_FIELDS_StreamConfigure(F)                                                            \
  F(S, u16, 1, channels, 0, 0x07FF, 1, 0x07FF, "", "Channel bits to stream.")                     \
  F(S, u16, 1, decimation, 0, 2, 1, 65535, "ticks", "Control ticks per sample (rate = control_rate_Hz / decimation).") \
  F(S, u16, 1, batch_samples, 0, 40, 1, 960, "samples", "Samples per SampleBatch; more than fit 960 data bytes is out_of_range.")

#define PALP_FIELDS_StreamConfig(F)                                                               \
  F(S, u16, 1, channels, 0, 0, NOLIM, NOLIM, "", "Channel bits streamed.")                        \
  F(S, u16, 1, decimation, 0, 1, NOLIM, NOLIM, "ticks", "Control ticks per sample.")              \
  F(S, u16, 1, batch_samples, 0, 1, NOLIM, NOLIM, "samples", "Samples per batch.")                \
  F(S, u32, 1, period_ns, 0, 0, NOLIM, NOLIM, "ns", "Sample period.")                             \
  F(S, u16, 1, bytes_per_sample, 0, 0, NOLIM, NOLIM, "bytes", "Sample size for these channels.")  \
  F(S, u32, 1, wire_bytes_per_s, 0, 0, NOLIM, NOLIM, "bytes/s", "Encoded stream bytes per second (SPEC.md §9).")

#define PALP_FIELDS_StreamStart(F)
#define PALP_FIELDS_StreamStop(F)

#define PALP_FIELDS_SampleBatch(F)                                                                \
  F(S, u32, 1, first_index, 0, 0, NOLIM, NOLIM, "", "Stream index of the first sample (wraps).")  \
  F(S, u64, 1, first_time_us, 0, 0, NOLIM, NOLIM, "us", "Device time of the first sample.")      \
  F(S, u32, 1, period_ns, 0, 0, NOLIM, NOLIM, "ns", "Sample period.")                             \
  F(S, u16, 1, channels, 0, 0, NOLIM, NOLIM, "", "Channel bits present in each sample.")          \
  F(S, u16, 1, sample_count, 0, 0, NOLIM, NOLIM, "samples", "Samples in data.")                   \
  F(V, u8, 960, data, 0, 0, NOLIM, NOLIM, "bytes", "sample_count samples, each the channels in bit order (SPEC.md §9).")

// --- events and faults -----------------------------------------------------------------------
#define PALP_FIELDS_EventFault(F)                                                                 \
  F(S, u64, 1, time_us, 0, 0, NOLIM, NOLIM, "us", "Device time of the trip.")                     \
  F(E, FaultReason, 1, reason, 0, FaultReason::none, NOLIM, NOLIM, "", "Why.")                    \
  F(S, i32, 1, detail, 0, 0, NOLIM, NOLIM, "", "Reason-specific (SPEC.md 6.2, Faults): the encoder count, the current in 0.1 mA, milliseconds late, or which check failed.")

#define PALP_FIELDS_EventContact(F)                                                               \
  F(S, u64, 1, time_us, 0, 0, NOLIM, NOLIM, "us", "Device time of the tick that fired.")          \
  F(S, i32, 1, encoder_count, 0, 0, NOLIM, NOLIM, "counts", "Encoder count that fired.")          \
  F(S, i32, 1, armed_count, 0, 0, NOLIM, NOLIM, "counts", "Encoder count when the watch started.") \
  F(S, u32, 1, sample_index, 0, 0, NOLIM, NOLIM, "", "Stream index of the first sample taken at or after the tick that fired (0 when not streaming).")

#define PALP_FIELDS_EventProgramFinished(F)                                                       \
  F(S, u64, 1, time_us, 0, 0, NOLIM, NOLIM, "us", "Device time of the end.")                      \
  F(E, ProgramKind, 1, kind, 0, ProgramKind::none, NOLIM, NOLIM, "", "The program.")              \
  F(E, ProgramEnd, 1, end, 0, ProgramEnd::completed, NOLIM, NOLIM, "", "How it ended.")           \
  F(S, u16, 1, repetitions_done, 0, 0, NOLIM, NOLIM, "", "Whole repetitions or periods completed.")

#define PALP_FIELDS_EventStreamGap(F)                                                             \
  F(S, u64, 1, time_us, 0, 0, NOLIM, NOLIM, "us", "Device time of the first lost sample.")       \
  F(S, u32, 1, first_missing_index, 0, 0, NOLIM, NOLIM, "", "Stream index of the first lost sample.") \
  F(S, u32, 1, missing_count, 0, 0, NOLIM, NOLIM, "samples", "Consecutive samples lost.")         \
  F(E, GapStage, 1, stage, 0, GapStage::isr_queue, NOLIM, NOLIM, "", "Where they were lost.")

#define PALP_FIELDS_FaultClear(F)
