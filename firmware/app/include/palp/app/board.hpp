// SPDX-License-Identifier: Apache-2.0
// The board seam: what a board gives the firmware app (app.hpp). The app owns every decision
// (through the core's Controller); a board only moves bytes, samples sensors, drives the coil
// and touches registers. Two boards implement it: QEMU's mps2-an386 (firmware/board/qemu, the
// image CI runs) and the STM32G474 probe controller (next issue).
//
// A board is a class the app is instantiated with (`App<MyBoard>`), checked by the concept
// `Board` below. Every member is non-blocking. Contexts:
//   boot        identity(), read_calibration(): before the tick starts;
//   tick ISR    read_inputs(), apply_outputs() and the handler start_tick() registered: the
//               control interrupt, at the control rate, the most urgent interrupt that runs app
//               code (a board may keep a more urgent one of its own, e.g. a clock's);
//   main loop   everything else: the link, the calibration write, the tick's rate and guard,
//               idle(), enter_bootloader();
//   any         now_us().
// Units: SI with the unit in the name (V, A, Hz, us); raw sensor values stay in their own
// units (encoder timer counts, 12-bit ADC codes) because the core calibrates them.
#pragma once

#include <concepts>
#include <cstddef>
#include <cstdint>

#include "palp/fw/controller.hpp"

namespace palp::app {

/// The function the board's tick interrupt calls, with its argument (the app).
struct TickHandler {
  void (*run)(void* ctx) = nullptr;
  void* ctx = nullptr;
};

/// What idle() asks before it sleeps: true while the main loop has work (checked with
/// interrupts masked, so work an interrupt makes just before the sleep is never slept over).
using HasWork = bool (*)(void* ctx);

template <class B>
concept Board = requires(B& b, const B& cb, fw::TickInputs& in, const fw::TickOutputs& out,
                         std::uint8_t* bytes, const std::uint8_t* const_bytes, std::size_t size,
                         std::uint32_t rate_Hz, TickHandler handler, HasWork has_work,
                         void* ctx) {
  // --- boot --------------------------------------------------------------------------------
  /// Who the device is: board name, serial, git hash, max_stream_rate_Hz the link carries.
  /// Read at boot, and again after link_read() delivered bytes: a board with two links (the
  /// STM32's LPUART1 and USB) reports the stream rate of the link in use, which changes when
  /// the other link's host starts talking; the app hands a changed rate to the core
  /// (Controller::set_identity) before it handles those bytes. Everything else must not change.
  { cb.identity() } -> std::convertible_to<fw::DeviceIdentity>;
  /// Copies the stored calibration block (at most `size` bytes) into `bytes`; returns the
  /// bytes copied. Erased storage reads as 0xFF (the core reports it as blank and keeps its
  /// defaults); 0 means there is no storage at all.
  { b.read_calibration(bytes, size) } -> std::same_as<std::size_t>;

  // --- the control tick ----------------------------------------------------------------------
  /// Starts the tick at rate_Hz (or changes its rate; main loop, with the tick held): from now
  /// on handler.run(handler.ctx) runs in the tick interrupt every 1/rate_Hz. False when the
  /// board cannot make that rate (the tick then keeps its previous rate).
  { b.start_tick(rate_Hz, handler) } -> std::same_as<bool>;
  /// Tick ISR: this tick's raw sensor readings (all of TickInputs except watchdog_now_us,
  /// which the app takes from now_us()), and in missed_ticks the ticks that fell due since the
  /// previous call but never ran (the interrupt was still pending or held when the next one
  /// came; the core counts them as control overruns).
  { b.read_inputs(in) } -> std::same_as<void>;
  /// Tick ISR: applies the coil voltage (PWM duty = v_coil_V / supply) and the contact line
  /// until the next tick.
  { b.apply_outputs(out) } -> std::same_as<void>;
  /// Main loop: hold_tick() keeps the tick interrupt from running (masks that interrupt only:
  /// the link's keep running) until release_tick(); a tick that falls due meanwhile runs at the
  /// release. The core's TickGuard calls them around its short state changes.
  { b.hold_tick() } -> std::same_as<void>;
  { b.release_tick() } -> std::same_as<void>;

  // --- clocks --------------------------------------------------------------------------------
  /// Any context: a monotonic microsecond clock independent of the tick (the heartbeat
  /// watchdog's), 64 bits, never wraps in practice.
  { b.now_us() } -> std::same_as<std::uint64_t>;

  // --- the link to the host (main loop) ------------------------------------------------------
  /// Moves up to `size` received bytes into `bytes`; returns how many (0: none waiting). The
  /// board never drops a received byte: when its buffer is full it stops taking bytes from the
  /// wire (flow control) until the app reads.
  { b.link_read(bytes, size) } -> std::same_as<std::size_t>;
  /// Takes up to `size` bytes for the host; returns how many it took (0: the link is busy; the
  /// board's transmit interrupt then wakes idle() when it can take more).
  { b.link_write(const_bytes, size) } -> std::same_as<std::size_t>;

  // --- calibration storage, power, reset (main loop) ------------------------------------------
  /// Stores a calibration block (the core's committed_block()); true once stored, or once a
  /// store that the board completes from idle() has started: a flash commit takes tens of ms
  /// (page erase), which a main-loop call must not wait for (the link and a watchdog's
  /// main-loop rule would stall; the STM32 board commits one flash step per idle() and does not
  /// sleep meanwhile). false: it cannot be stored. A board that stores later keeps a block
  /// written meanwhile and stores it next, and read_calibration() returns the newest written.
  { b.write_calibration(const_bytes, size) } -> std::same_as<bool>;
  /// Sleeps until an interrupt unless has_work(ctx) is true (WFI: a polling firmware burns a
  /// host core under QEMU and power on the bench).
  { b.idle(has_work, ctx) } -> std::same_as<void>;
  /// Leaves the firmware for the bootloader (on QEMU: ends the run with a documented exit
  /// code). Does not return.
  { b.enter_bootloader() };
};

}  // namespace palp::app
