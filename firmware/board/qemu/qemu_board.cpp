// SPDX-License-Identifier: Apache-2.0
// The QEMU mps2-an386 board (qemu_board.hpp): registers in cmsdk_uart.hpp, cmsdk_timer.hpp,
// ../cortex_m/nvic.hpp, PRIMASK/WFI in ../cortex_m/cpu.hpp; the vector entries are startup.cpp's
// weak palp_irq_* names, defined here.
#include "qemu_board.hpp"

#include "board.hpp"
#include "cmsdk_timer.hpp"
#include "cmsdk_uart.hpp"
#include "cpu.hpp"
#include "nvic.hpp"

#ifndef PALP_GIT_HASH
#define PALP_GIT_HASH "unknown"
#endif

namespace palp::qemu {

namespace {

namespace uart = board::cmsdk_uart;
namespace timer = board::cmsdk_timer;
namespace nvic = board::nvic;

constexpr std::uintptr_t kLink = uart::kUart0Base;
constexpr std::uintptr_t kTick = timer::kTimer0Base;
constexpr std::uintptr_t kClock = timer::kTimer1Base;
constexpr std::uint32_t kClocksPerUs = timer::kClock_Hz / 1'000'000u;

QemuBoard* g_board = nullptr;  // the one board, for the interrupt handlers

/// Masks every interrupt (PRIMASK) for its lifetime and restores the previous state: the few
/// read-modify-writes that an interrupt could split (board/cortex_m/cpu.hpp).
board::CortexM g_cpu;
using IrqLock = board::InterruptLock<board::CortexM>;

std::uint32_t link_state() { return uart::reg(kLink, uart::kState); }

}  // namespace

QemuBoard::QemuBoard() {
  g_board = this;
  for (auto& b : calibration_) b = 0xFF;  // erased flash

  // the clock: timer 1 over its whole range, no interrupt (writing RELOAD sets VALUE too)
  timer::reg(kClock, timer::kCtrl) = 0;
  timer::reg(kClock, timer::kReload) = 0xFFFFFFFFu;
  clock_last_ = 0xFFFFFFFFu;
  timer::reg(kClock, timer::kCtrl) = timer::kCtrlEnable;

  // the link: UART0, receive interrupt on; the transmit interrupt is armed only while waiting
  uart::reg(kLink, uart::kCtrl) = 0;
  uart::reg(kLink, uart::kBaudDiv) = uart::kMinBaudDiv;
  uart::reg(kLink, uart::kState) = uart::kStateTxOverrun | uart::kStateRxOverrun;
  uart::reg(kLink, uart::kIntStatus) = uart::kIntTx | uart::kIntRx;
  uart::reg(kLink, uart::kCtrl) = uart::kCtrlTxEnable | uart::kCtrlRxEnable | uart::kCtrlRxIrqEnable;

  nvic::set_priority(timer::kTimer0Irq, nvic::kPriorityTick);
  nvic::set_priority(uart::kUart0RxIrq, nvic::kPriorityLink);
  nvic::set_priority(uart::kUart0TxIrq, nvic::kPriorityLink);
  nvic::enable(uart::kUart0RxIrq);
  nvic::enable(uart::kUart0TxIrq);
}

fw::DeviceIdentity QemuBoard::identity() const {
  fw::DeviceIdentity id;
  id.board = kName;
  id.serial = kSerial;
  id.git_hash = PALP_GIT_HASH;
  id.max_stream_rate_Hz = kMaxStreamRate_Hz;
  return id;
}

// ---- calibration storage ------------------------------------------------------------------------

std::size_t QemuBoard::read_calibration(std::uint8_t* bytes, std::size_t size) {
  const std::size_t n = size < calibration_size_ ? size : calibration_size_;
  for (std::size_t k = 0; k < n; ++k) bytes[k] = calibration_[k];
  return n;
}

bool QemuBoard::write_calibration(const std::uint8_t* bytes, std::size_t size) {
  if (size > sizeof calibration_) return false;
  for (std::size_t k = 0; k < size; ++k) calibration_[k] = bytes[k];
  for (std::size_t k = size; k < sizeof calibration_; ++k) calibration_[k] = 0xFF;
  return true;
}

// ---- the control tick ---------------------------------------------------------------------------

bool QemuBoard::start_tick(std::uint32_t rate_Hz, app::TickHandler handler) {
  if (rate_Hz == 0 || timer::kClock_Hz % rate_Hz != 0 || handler.run == nullptr) return false;
  nvic::disable(timer::kTimer0Irq);
  timer::reg(kTick, timer::kCtrl) = 0;
  timer::reg(kTick, timer::kIntStatus) = timer::kIntStatusIrq;
  nvic::clear_pending(timer::kTimer0Irq);
  tick_ = handler;
  tick_period_clocks_ = timer::kClock_Hz / rate_Hz;
  dt_s_ = 1.0f / static_cast<float>(rate_Hz);
  const std::uint32_t reload = timer::reload_for_period(tick_period_clocks_);
  tick_grid_clocks_ = now_clocks() + reload - tick_period_clocks_ / 4;
  ticks_counted_ = 0;
  backlog_ = 0;
  max_backlog_ = static_cast<std::uint64_t>(kMaxBacklog_s * static_cast<float>(rate_Hz));
  timer::reg(kTick, timer::kReload) = reload;
  timer::reg(kTick, timer::kCtrl) = timer::kCtrlEnable | timer::kCtrlIrqEnable;
  if (!tick_held_) nvic::enable(timer::kTimer0Irq);
  return true;
}

void QemuBoard::on_tick_irq() {
  timer::reg(kTick, timer::kIntStatus) = timer::kIntStatusIrq;
  // How many ticks have fallen due since the start? Timer 0 expires on a fixed grid of the clock
  // (both timers count QEMU's one virtual clock; [QT]: the first expiry RELOAD clocks after the
  // start, then one every period), so the count is the clock's, whatever interrupts coalesced
  // meanwhile. The grid is kept a quarter period early, so an interrupt served on time is never
  // counted short by the few clocks the start's register writes took.
  const std::uint64_t now = now_clocks();
  const std::uint64_t due_total =
      now < tick_grid_clocks_ ? 0 : (now - tick_grid_clocks_) / tick_period_clocks_ + 1;
  const std::uint64_t due = due_total - ticks_counted_;
  ticks_counted_ = due_total;
  // Catch up: the due ticks run back to back, at most kCatchUpPerIrq per interrupt (the main
  // loop runs between them); a backlog beyond kMaxBacklog_s is dropped and reported.
  backlog_ += due;
  if (backlog_ > max_backlog_) {
    missed_ticks_ += static_cast<std::uint32_t>(backlog_ - max_backlog_);
    dropped_clocks_ += (backlog_ - max_backlog_) * tick_period_clocks_;
    backlog_ = max_backlog_;
  }
  for (std::uint32_t k = 0; k < kCatchUpPerIrq && backlog_ > 0; ++k) {
    --backlog_;
    tick_.run(tick_.ctx);
  }
}

void QemuBoard::read_inputs(fw::TickInputs& in) {
  const PlantSensors s = plant_.sensors();
  in.i_sense_A = s.i_sense_A;
  in.encoder_timer = s.encoder_timer;
  in.pressure_codes = s.pressure_codes;
  in.supply_V = s.supply_V;
  in.driver_fault = false;
  in.missed_ticks = missed_ticks_;
  missed_ticks_ = 0;
}

void QemuBoard::apply_outputs(const fw::TickOutputs& out) { plant_.step(out.v_coil_V, dt_s_); }

void QemuBoard::hold_tick() {
  tick_held_ = true;
  nvic::disable(timer::kTimer0Irq);
}

void QemuBoard::release_tick() {
  tick_held_ = false;
  if (tick_.run != nullptr) nvic::enable(timer::kTimer0Irq);
}

// ---- the clock ----------------------------------------------------------------------------------

std::uint64_t QemuBoard::now_clocks() {
  const IrqLock lock(g_cpu);  // the main loop and the tick both extend the count
  const std::uint32_t value = timer::reg(kClock, timer::kValue);
  clock_total_ += clock_last_ - value;  // a down-counter over 2^32 clocks: modular difference
  clock_last_ = value;
  return clock_total_;
}

std::uint64_t QemuBoard::now_us() {
  // the clock less the dropped ticks' time (the file comment of qemu_board.hpp: a stall of QEMU
  // is not a silence of the host), read together with the interrupts masked; a drop counted
  // after an earlier read can take back time that read already gave, so the clock holds its
  // last value until it passes it again (monotonic, as the watchdog needs)
  const IrqLock lock(g_cpu);
  const std::uint64_t us = (now_clocks() - dropped_clocks_) / kClocksPerUs;
  if (us > last_us_) last_us_ = us;
  return last_us_;
}

// ---- the link -----------------------------------------------------------------------------------

void QemuBoard::on_rx_irq() {
  uart::reg(kLink, uart::kIntStatus) = uart::kIntRx;
  while ((link_state() & uart::kStateRxFull) != 0) {
    if (rx_.full()) {  // leave the byte in the UART: QEMU holds the next ones back meanwhile
      uart::reg(kLink, uart::kCtrl) &= ~uart::kCtrlRxIrqEnable;
      rx_paused_ = true;
      return;
    }
    rx_.push(static_cast<std::uint8_t>(uart::reg(kLink, uart::kData)));
  }
}

std::size_t QemuBoard::link_read(std::uint8_t* bytes, std::size_t size) {
  std::size_t n = 0;
  while (n < size && rx_.pop(bytes[n])) ++n;
  if (rx_paused_ && !rx_.full()) {
    const IrqLock lock(g_cpu);
    rx_paused_ = false;
    uart::reg(kLink, uart::kCtrl) |= uart::kCtrlRxIrqEnable;
    // a byte that arrived while the interrupt was off raised none: take it through the handler
    if ((link_state() & uart::kStateRxFull) != 0) nvic::set_pending(uart::kUart0RxIrq);
  }
  return n;
}

std::size_t QemuBoard::link_write(const std::uint8_t* bytes, std::size_t size) {
  std::size_t n = 0;
  while (n < size) {
    if ((link_state() & uart::kStateTxFull) != 0) {
      {  // QEMU's chardev is busy: arm the transmit interrupt, then look again
        const IrqLock lock(g_cpu);
        uart::reg(kLink, uart::kCtrl) |= uart::kCtrlTxIrqEnable;
      }
      if ((link_state() & uart::kStateTxFull) != 0) break;
    }
    uart::reg(kLink, uart::kData) = bytes[n++];
  }
  return n;
}

void QemuBoard::on_tx_irq() {
  uart::reg(kLink, uart::kIntStatus) = uart::kIntTx;
  uart::reg(kLink, uart::kCtrl) &= ~uart::kCtrlTxIrqEnable;  // the main loop re-arms it
}

// ---- power and reset ----------------------------------------------------------------------------

void QemuBoard::idle(app::HasWork has_work, void* ctx) {
  // with interrupts masked, so an interrupt between the check and the WFI still wakes it (WFI
  // wakes on a pending interrupt whatever PRIMASK says; it is taken at the cpsie)
  g_cpu.disable_interrupts();
  if (rx_.empty() && !has_work(ctx)) g_cpu.wait_for_interrupt();
  g_cpu.enable_interrupts();
}

void QemuBoard::enter_bootloader() { board::exit(kBootloaderExitCode); }

}  // namespace palp::qemu

extern "C" {
void palp_irq_timer0() { palp::qemu::g_board->on_tick_irq(); }
void palp_irq_uart0_rx() { palp::qemu::g_board->on_rx_irq(); }
void palp_irq_uart0_tx() { palp::qemu::g_board->on_tx_irq(); }
}
