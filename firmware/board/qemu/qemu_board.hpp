// SPDX-License-Identifier: Apache-2.0
// The QEMU mps2-an386 board behind the app's seam (firmware/app/include/palp/app/board.hpp):
//
//   link         CMSDK UART0 (a QEMU chardev, e.g. a TCP socket): received bytes by interrupt
//                into a fixed ring; when the ring is full the board stops reading the UART, so
//                QEMU keeps the host's next bytes in its chardev (nothing is ever dropped).
//                Transmit from the main loop, one byte per write while the UART takes it; when
//                QEMU's chardev is busy the transmit interrupt wakes the main loop.
//   tick         CMSDK timer 0, periodic at the control rate (25 MHz / rate clocks), its
//                interrupt masked alone by hold_tick(). Without -icount QEMU runs the timer on
//                host time and the CPU when the host schedules it: a timer interrupt still
//                pending when the next expiry comes would lose a tick. The tick handler counts
//                the ticks due from the clock (the timer expires on a fixed grid of it) and runs
//                those not run yet back to back (catch-up, at most kCatchUpPerIrq per
//                interrupt), so device time keeps up with host time; a backlog beyond
//                kMaxBacklog_s is dropped and reported in TickInputs::missed_ticks (the core
//                counts them as control overruns).
//   clock        CMSDK timer 1 free-running over its whole 32-bit range at 25 MHz, extended to
//                64 bits in software (read at least every tick, far within its 171.8 s wrap).
//                now_us() (the heartbeat watchdog's clock) leaves out the time of the ticks
//                dropped from the backlog: QEMU's timers follow host time even while the host
//                does not schedule QEMU, and a stall of the emulated MCU is not a silence of the
//                host (whose bytes wait in the chardev meanwhile). A host that is really gone is
//                timed as on hardware: QEMU runs on, no tick is dropped, the clock is host time.
//   sensors      a plant on the target (FloatPlant): sensors() before the core's tick, step()
//                with the voltage the core returned after it.
//   calibration  a RAM block standing in for flash: commit writes it, boot reads it. It starts
//                erased (0xFF) at every QEMU start: nothing survives QEMU's exit.
//   bootloader   no bootloader under QEMU: the request ends the run with exit code
//                kBootloaderExitCode (semihosting).
#pragma once

#include <cstddef>
#include <cstdint>

#include "palp/app/board.hpp"
#include "palp/fw/calibration.hpp"
#include "palp/fw/spsc_queue.hpp"
#include "palp/protocol/board_id.hpp"
#include "float_plant.hpp"

namespace palp::qemu {

class QemuBoard {
 public:
  static constexpr const char* kName = proto::board_name(proto::BoardId::qemu_mps2_an386);
  static constexpr const char* kSerial = "QEMU-AN386-0001";
  /// QEMU's exit status when the host asks for the bootloader.
  static constexpr int kBootloaderExitCode = 42;
  /// The stream rate the emulated UART carries with margin, all 11 channels (firmware/README.md:
  /// measured about 215 KB/s; 1 kHz is 25 KB/s), and whose 1024-sample stream backlog covers a
  /// 1 s stall of the reading host or of QEMU on a loaded machine.
  static constexpr std::uint32_t kMaxStreamRate_Hz = 1000;
  /// Received bytes buffered between the UART interrupt and the main loop.
  static constexpr std::size_t kRxRing = 1024;
  /// Catch-up: late ticks run per tick interrupt at most, and the longest backlog kept.
  static constexpr std::uint32_t kCatchUpPerIrq = 4;
  static constexpr float kMaxBacklog_s = 0.1f;

  /// Sets up the UART, the clock and the NVIC; the tick starts with start_tick().
  QemuBoard();

  fw::DeviceIdentity identity() const;
  std::size_t read_calibration(std::uint8_t* bytes, std::size_t size);
  bool write_calibration(const std::uint8_t* bytes, std::size_t size);

  bool start_tick(std::uint32_t rate_Hz, app::TickHandler handler);
  void read_inputs(fw::TickInputs& in);
  void apply_outputs(const fw::TickOutputs& out);
  void hold_tick();
  void release_tick();

  std::uint64_t now_us();

  std::size_t link_read(std::uint8_t* bytes, std::size_t size);
  std::size_t link_write(const std::uint8_t* bytes, std::size_t size);

  void idle(app::HasWork has_work, void* ctx);
  [[noreturn]] void enter_bootloader();

  // --- interrupt handlers (qemu_board.cpp's vector entries call them) ---------------------------
  void on_tick_irq();
  void on_rx_irq();
  void on_tx_irq();

 private:
  std::uint64_t now_clocks();

  app::TickHandler tick_{};
  std::uint32_t tick_period_clocks_ = 0;
  std::uint64_t tick_grid_clocks_ = 0;  // the first expiry at this rate, a quarter period early
  std::uint64_t ticks_counted_ = 0;     // ticks due on the grid so far (run, backlog or dropped)
  bool tick_held_ = false;                // between hold_tick() and release_tick()
  std::uint64_t backlog_ = 0;       // ticks due and not run yet
  std::uint64_t max_backlog_ = 0;   // kMaxBacklog_s in ticks at the current rate
  std::uint32_t missed_ticks_ = 0;  // dropped from the backlog, not yet reported
  std::uint64_t dropped_clocks_ = 0;  // the dropped ticks' time, left out of now_us()
  std::uint64_t last_us_ = 0;         // now_us()'s last value (it never runs backwards)
  float dt_s_ = 0.0f;

  std::uint64_t clock_total_ = 0;     // clocks since boot, at clock_last_
  std::uint32_t clock_last_ = 0;      // timer 1's VALUE at the last read

  fw::SpscQueue<std::uint8_t, kRxRing> rx_;
  volatile bool rx_paused_ = false;   // the ring was full: the RX interrupt is off

  FloatPlant plant_;
  std::uint8_t calibration_[fw::kCalibrationMaxBlockSize];
  std::size_t calibration_size_ = fw::kCalibrationMaxBlockSize;
};

static_assert(app::Board<QemuBoard>);

}  // namespace palp::qemu
