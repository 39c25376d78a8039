// The QEMU mps2-an386 board behind the app's seam (firmware/app/include/palp/app/board.hpp):
//
//   link         CMSDK UART0 (a QEMU chardev, e.g. a TCP socket): received bytes by interrupt
//                into a fixed ring; when the ring is full the board stops reading the UART, so
//                QEMU keeps the host's next bytes in its chardev (nothing is ever dropped).
//                Transmit from the main loop, one byte per write while the UART takes it; when
//                QEMU's chardev is busy the transmit interrupt wakes the main loop.
//   tick         CMSDK timer 0, periodic at the control rate (25 MHz / rate clocks), its
//                interrupt masked alone by hold_tick(); a tick that was due while the previous
//                one was still pending or held is counted in missed_ticks().
//   clock        CMSDK timer 1 free-running over its whole 32-bit range at 25 MHz, extended to
//                64 bits in software (read at least every tick, far within its 171.8 s wrap).
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
#include "placeholder_plant.hpp"

namespace palp::qemu {

class QemuBoard {
 public:
  static constexpr const char* kName = "qemu-mps2-an386";
  static constexpr const char* kSerial = "QEMU-AN386-0001";
  /// QEMU's exit status when the host asks for the bootloader.
  static constexpr int kBootloaderExitCode = 42;
  /// Received bytes buffered between the UART interrupt and the main loop.
  static constexpr std::size_t kRxRing = 1024;

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
  std::uint32_t missed_ticks() const { return missed_ticks_; }

  std::uint64_t now_us();

  std::size_t link_read(std::uint8_t* bytes, std::size_t size);
  std::size_t link_write(const std::uint8_t* bytes, std::size_t size);

  void idle(app::HasWork has_work, void* ctx);
  [[noreturn]] void enter_bootloader();

  /// The plant the sensors come from (for figures; the app never reads it).
  const FloatPlant& plant() const { return plant_; }

  // --- interrupt handlers (qemu_board.cpp's vector entries call them) ---------------------------
  void on_tick_irq();
  void on_rx_irq();
  void on_tx_irq();

 private:
  std::uint64_t now_clocks();

  app::TickHandler tick_{};
  std::uint32_t tick_period_clocks_ = 0;
  std::uint64_t first_due_clocks_ = 0;  // when tick 0 of the current rate fell due
  std::int64_t last_due_index_ = -1;    // the grid index of the last tick that ran
  std::uint32_t missed_ticks_ = 0;
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
