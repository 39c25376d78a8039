// SPDX-License-Identifier: Apache-2.0
// The probe controller behind a full-speed USB bus, for the SDK's usb:// and hid:// transports
// end to end (tests/usb_e2e: rig_apis.hpp plays libusb and hidapi over it). The device side is
// the firmware as the STM32G474 runs it, minus the silicon:
//
//   the real firmware core  fw::Controller in palp-sim's Simulation (hil/sim) against the
//                           plant in free air, ticked at the control rate in wall time
//   the real USB core       palp::usb::Device (firmware/usb/include/palp/usb/device.hpp)
//   the real FSDEV driver   UsbFsdev (firmware/board/stm32g474/usb_fsdev.hpp) over the
//                           register-level model of the peripheral (tests/stm32/fsdev_model.hpp)
//
// and the host side plays the bus through the model's host side (tests/usb/fsdev_bus.hpp):
// SETUP/OUT/IN tokens to the device address, data toggles, NAK/STALL. Every bus transaction
// runs the device's USB interrupt (Device::service) right after it, as the peripheral's CTR
// interrupt would.
//
// Threads. A device thread is the board's main loop plus its tick timer: each pass moves the
// bytes Device::read() received into the core, runs the control ticks wall time says are due
// (at most 10 ms of them a pass; a longer delay, a descheduled thread, is dropped as a board
// drops ticks it cannot keep up with), hands at most 256 bytes of the core's output to
// Device::write() as the app's main loop does (so a frame reaches the USB ring in pieces) and
// pends the USB interrupt. Host calls (any thread) take the same lock for each transaction and
// wait for the device thread (a condition variable, wall-time deadlines) while the device NAKs.
//
// Loss. The board would lose stream samples when the host leaves its buffers full (the core's
// backlog of 1024 samples, about 50 ms at 20 kHz). The rig keeps up to kBacklogBytes of the
// core's output waiting for the USB ring and, past that, holds the tick instead of dropping
// (ticks_held() counts it: the host, a loaded test machine, did not drain in time). So a test
// that reads a stream checks that the byte path itself loses and reorders nothing; what a board
// would have lost under the same host shows in ticks_held().
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "fsdev_bus.hpp"
#include "host.hpp"
#include "palp/fw/controller.hpp"
#include "palp/sim/simulation.hpp"
#include "palp/usb/device.hpp"

namespace palp::usb_e2e {

using Clock = std::chrono::steady_clock;

struct RigOptions {
  /// The serial number: the descriptors' string 3 and DeviceInfo.serial (the board serves its
  /// UID as 24 hex digits in both).
  std::string serial = "2E0047001151333138333931";
  /// DeviceIdentity::max_stream_rate_Hz: what the board advertises (the core's ceiling).
  std::uint32_t max_stream_rate_Hz = fw::Streamer::kMaxRate_Hz;
};

/// How a host transfer ended (libusb's results, see rig_apis.cpp for the mapping).
enum class Transfer { ok, timeout, stall, overflow, no_answer };

class BoardRig {
 public:
  /// The device's address after enumeration.
  static constexpr std::uint8_t kAddress = 9;
  /// Core output the rig lets wait for the USB ring before it holds the tick (see the file
  /// comment): about the board's own stream buffering, the 1024-sample backlog of 24 bytes.
  static constexpr std::size_t kBacklogBytes = 24 * 1024;

  /// Attaches, enumerates as a host's USB stack does on plug-in (device descriptor, SET_ADDRESS,
  /// configuration, SET_CONFIGURATION), then starts the device thread. Throws std::runtime_error
  /// naming the step that failed.
  explicit BoardRig(const RigOptions& options = {});
  ~BoardRig();
  BoardRig(const BoardRig&) = delete;
  BoardRig& operator=(const BoardRig&) = delete;

  /// The device descriptor read at enumeration (18 bytes).
  const std::vector<std::uint8_t>& device_descriptor() const { return device_descriptor_; }

  // ---- the host's side; any thread; deadlines in wall time ------------------------------------
  /// A control read on ep0 (e.g. GET_DESCRIPTOR): the data stage's bytes; false on STALL or no
  /// answer.
  bool control_in(const usb::SetupPacket& setup, std::vector<std::uint8_t>& data);
  /// An OUT transfer on endpoint `number`: `size` bytes in max-size packets (64), or one
  /// zero-length packet for size 0. `sent` counts the bytes the device took.
  Transfer transfer_out(std::uint8_t number, const std::uint8_t* bytes, std::size_t size,
                        std::size_t& sent, Clock::time_point deadline);
  /// An IN transfer on endpoint `number` into `capacity` bytes: packets until a short one
  /// (zero-length included) or `capacity` is full, or only one packet with `one_packet`
  /// (an interrupt IN report). A packet larger than the room left is an overflow.
  Transfer transfer_in(std::uint8_t number, std::uint8_t* bytes, std::size_t capacity,
                       std::size_t& got, Clock::time_point deadline, bool one_packet = false);

  // ---- faults to inject, observations ---------------------------------------------------------
  /// The host loses the `nth` (1 = the next) IN data packet from now on endpoint `number`: a
  /// transfer the bus damaged, its bytes never delivered (what the sequence checks must see).
  void lose_in_packet(std::uint8_t number, std::uint32_t nth);
  /// What the peripheral model and the driver saw go wrong (toggle mismatches, faults, OUT
  /// overflows, driver refusals); empty when the bus ran as USB says.
  std::vector<std::string> violations();
  /// Control ticks held because the host left more than kBacklogBytes undrained.
  std::uint64_t ticks_held() const { return ticks_held_.load(); }
  /// Control ticks run so far.
  std::uint64_t ticks() const { return ticks_.load(); }
  usb::DeviceCounters device_counters();

 private:
  using Bus = usb::test::FsdevBus;
  using UsbDevice = usb::Device<Bus::Hardware>;

  void enumerate();
  void device_loop();
  void device_pass(std::uint64_t now_us);
  std::uint64_t wall_us() const;
  // Waits (lock held) until the device thread's next pass or the deadline; false at the deadline.
  bool wait_for_device(std::unique_lock<std::mutex>& lock, Clock::time_point deadline);

  RigOptions options_;
  fw::DeviceIdentity identity_{};
  std::mutex mu_;                 // guards everything below but the atomics
  std::condition_variable pass_;  // a device pass ended
  Bus bus_;
  UsbDevice device_{bus_.hardware()};
  usb::test::Host<Bus> host_{bus_, [this] { device_.service(); }};
  std::unique_ptr<sim::Simulation> sim_;
  std::vector<std::uint8_t> device_descriptor_;
  std::vector<std::uint8_t> outbox_;  // core output waiting for room in the USB ring
  Clock::time_point t0_ = Clock::now();
  std::uint64_t anchor_us_ = 0;      // wall time the tick schedule counts from
  std::uint64_t anchor_ticks_ = 0;   // ticks run at anchor_us_
  std::uint32_t rate_Hz_ = 0;        // the control rate the schedule is for
  std::uint64_t passes_ = 0;         // device passes so far (what a NAKed host waits for)
  std::uint8_t lose_number_ = 0;
  std::uint32_t lose_countdown_ = 0;
  std::atomic<std::uint64_t> ticks_{0}, ticks_held_{0};
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace palp::usb_e2e
