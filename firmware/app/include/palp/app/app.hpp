// SPDX-License-Identifier: Apache-2.0
// The probe-controller firmware as a program: the core's Controller wired to a board (board.hpp).
//
//   boot       the board's identity, the stored calibration (blank or bad: the core's defaults,
//              never a silent replacement), then the tick at the default control rate;
//   tick ISR   board.read_inputs -> watchdog clock -> controller.tick -> board.apply_outputs;
//   main loop  link bytes -> (the board's stream rate for the link in use) -> controller.receive
//              (which holds the tick through the board's hold_tick/release_tick while a command
//              changes its state), a rate change -> the tick timer, controller.service every
//              few ticks, controller.transmit -> link, a calibration commit -> board storage,
//              a bootloader request -> the board once its Ack is on the wire; nothing to do ->
//              board.idle.
//
// One App per image (the board's interrupt reaches it through start_tick's handler). No heap:
// construct it as a static object.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>

#include "palp/app/board.hpp"
#include "palp/fw/controller.hpp"

namespace palp::app {

template <Board B>
class App {
 public:
  /// The main loop runs controller.service() once this many ticks have passed since the last
  /// run (or at once after received bytes): 8 ticks = 0.4 ms at 20 kHz, 40 samples at most
  /// per batch at the highest sample rate.
  static constexpr std::uint32_t kServiceTicks = 8;
  /// Bytes moved per pass on the link (each way).
  static constexpr std::size_t kChunk = 256;

  explicit App(B& board) : board_(board), controller_(board.identity()) {}

  /// Boot and run the main loop; returns only through enter_bootloader().
  [[noreturn]] void run() {
    boot();
    for (;;) step();
  }

  /// Boot: the calibration block from storage, then the tick.
  void boot() {
    static std::uint8_t block[fw::kCalibrationMaxBlockSize];
    const std::size_t n = board_.read_calibration(block, sizeof block);
    if (n > 0) calibration_status_ = controller_.load_calibration_block(block, n);
    commits_seen_ = controller_.commits();
    controller_.set_tick_guard(fw::TickGuard{&App::hold_entry, &App::release_entry, this});
    rate_Hz_ = controller_.control_rate_Hz();
    board_.start_tick(rate_Hz_, TickHandler{&App::tick_entry, this});
  }

  /// One pass of the main loop (run() repeats it; tests/app calls it over a fake board).
  void step() {
    const std::size_t received = board_.link_read(rx_, sizeof rx_);
    if (received > 0) {
      follow_link_stream_rate();
      receive(received);
    }
    const std::uint32_t ticks = ticks_.load(std::memory_order_relaxed);
    if (received > 0 || ticks - serviced_at_ >= kServiceTicks) {
      serviced_at_ = ticks;
      controller_.service();
    }
    flush();
    if (controller_.commits() != commits_seen_) {
      commits_seen_ = controller_.commits();
      const fw::CalibrationBlock& b = controller_.committed_block();
      board_.write_calibration(b.data(), b.size());
    }
    if (controller_.bootloader_requested() && !tx_waiting())
      board_.enter_bootloader();
    board_.idle(&App::has_work, this);
  }

  const fw::Controller& controller() const { return controller_; }
  /// The stored block's status at boot (blank: the defaults are in use).
  fw::CalibrationStatus calibration_status() const { return calibration_status_; }

 private:
  static void tick_entry(void* self) { static_cast<App*>(self)->tick(); }

  void tick() {
    fw::TickInputs in;
    board_.read_inputs(in);
    in.watchdog_now_us = board_.now_us();
    fw::TickOutputs out;
    controller_.tick(in, out);
    board_.apply_outputs(out);
    ticks_.store(ticks_.load(std::memory_order_relaxed) + 1u, std::memory_order_relaxed);
  }

  // Commands act on the tick's state: the core holds the board's tick guard around every
  // change (TickGuard, set at boot). A new control rate reprograms the timer after the request
  // (the ticks between run at the new rate's dt with the old period: at most the main loop's
  // pass, a few ticks).
  void receive(std::size_t n) {
    controller_.receive(rx_, n, board_.now_us());
    const std::uint32_t rate = controller_.control_rate_Hz();
    if (rate == rate_Hz_) return;
    board_.hold_tick();
    if (board_.start_tick(rate, TickHandler{&App::tick_entry, this})) rate_Hz_ = rate;
    board_.release_tick();
  }

  // A board with two links advertises the stream rate of the one in use, which received bytes
  // may have just changed (board.hpp identity()): the core takes it before handling them, so
  // the DeviceInfo and StreamConfigure that answer them use that link's limit.
  void follow_link_stream_rate() {
    const fw::DeviceIdentity id = board_.identity();
    if (id.max_stream_rate_Hz != controller_.identity().max_stream_rate_Hz)
      controller_.set_identity(id);
  }

  static void hold_entry(void* self) { static_cast<App*>(self)->board_.hold_tick(); }
  static void release_entry(void* self) { static_cast<App*>(self)->board_.release_tick(); }

  // Transmit at most one chunk per pass, so the main loop comes back to service() between
  // chunks (writing a chunk can take longer than a tick). What the link does not take stays
  // staged; link_busy_ says the board's transmit interrupt will wake the loop.
  void flush() {
    if (tx_sent_ == tx_size_) {
      tx_sent_ = 0;
      tx_size_ = controller_.transmit(tx_, sizeof tx_);
      if (tx_size_ == 0) return;
    }
    const std::size_t w = board_.link_write(tx_ + tx_sent_, tx_size_ - tx_sent_);
    tx_sent_ += w;
    link_busy_ = tx_sent_ < tx_size_;
  }

  bool tx_waiting() const { return tx_sent_ < tx_size_ || controller_.tx_pending() > 0; }

  static bool has_work(void* self) {
    const App& a = *static_cast<const App*>(self);
    const std::uint32_t ticks = a.ticks_.load(std::memory_order_relaxed);
    return ticks - a.serviced_at_ >= kServiceTicks || (!a.link_busy_ && a.tx_waiting());
  }

  B& board_;
  fw::Controller controller_;
  fw::CalibrationStatus calibration_status_ = fw::CalibrationStatus::blank;
  std::uint32_t commits_seen_ = 0;
  std::uint32_t rate_Hz_ = 0;
  std::atomic<std::uint32_t> ticks_{0};  // written by the tick, read by the main loop
  std::uint32_t serviced_at_ = 0;
  std::uint8_t rx_[kChunk] = {};
  std::uint8_t tx_[kChunk] = {};
  std::size_t tx_size_ = 0, tx_sent_ = 0;
  bool link_busy_ = false;
};

}  // namespace palp::app
