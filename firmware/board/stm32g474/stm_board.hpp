// SPDX-License-Identifier: Apache-2.0
// The STM32G474 probe controller as the app's Board (firmware/app/include/palp/app/board.hpp): the
// drivers of this directory (clock.hpp at reset, pins.hpp, timers.hpp, adc.hpp, link_uart.hpp,
// usb_fsdev.hpp with firmware/usb's Device, calibration_flash.hpp) wired to the seam. A template
// over the register access (regs/register.hpp) and the core's operations
// (board/cortex_m/cpu.hpp), so tests/stm32 runs it on a host register file and device models:
// StmBoardT<Mmio, CortexM> is the target's (StmBoard, stm_board.cpp; its interrupt entry is
// board_irqs.cpp). What each member does, and why (NOTES.md "Board class"):
//
//   init         pins (README §3), the LPUART1 host link, the TIM2 encoder, ADC1 injected + ADC2
//                scan with DMA (armed, waiting for TIM1), the µs clock (TIM5), NVIC priorities
//                (tick 0x40 above both links' 0x80), the serial from the device UID, the USB
//                device (FSDEV init, that serial as string 3, D+ pull-up on). The tick starts
//                with start_tick().
//   two links    LPUART1 (ST-LINK VCP) and USB (bulk or HID; the USB_LP interrupt, IRQ 20, runs
//                Device::service()). Both receive into the core; link_read takes the link in
//                use first and the other only when the first has nothing, and the link that
//                last delivered bytes is "in use": link_write sends there, and identity()'s
//                max_stream_rate_Hz is its figure (USB bulk: the core's maximum; HID 2000 Hz;
//                LPUART1 3840 Hz). Until any link has delivered a byte: LPUART1.
//   tick         20 or 40 kHz only: TIM1's PWM period is the tick; ADC1's injected sequence
//                (current, supply) converts on TRGO2 at the counter's top, and its end-of-
//                sequence interrupt (ADC1_2, IRQ 18) runs on_tick_irq() -> handler.run(ctx).
//   rate change  MOE is cleared first (every gate off: the coil current decays through the
//                bridge's diodes, no leg is driven), TIM1 is re-initialised at the new rate with
//                both legs at 50 % (0 V), MOE last; until the next tick the coil sees 0 V. No
//                output state mixes the two rates' periods.
//   missed ticks TIM5 counts µs; the tick falls due on the grid start + k periods (the PWM and
//                TIM5 share the 170 MHz clock, so the grid does not drift). An interrupt at
//                grid time t counts the ticks due up to t (a half-period tolerance for latency);
//                due ticks beyond one per interrupt were missed and are reported once.
//   watchdog     the IWDG (75 ms nominal, timers.hpp) starts at the first start_tick (boot:
//                the app starts the tick before its main loop). The tick refreshes it only
//                while the main loop has passed idle() within kMainLoopWindow_us: a stalled
//                tick or a stalled main loop each let it reset the board.
//   status LED   PA5 (LD2): off until the tick starts; on while it runs; blinking at 2 Hz while
//                nFAULT is asserted or an init step failed (init_status()).
//   calibration  the flash journal in bank 2 (calibration_flash.hpp). write_calibration starts a
//                commit and returns; idle() advances it one flash step per main-loop pass and
//                does not sleep until it is done (a page erase takes ~22 ms: waiting for it
//                would stall the link and the watchdog's main-loop rule). A block written while
//                a commit runs waits in RAM and is committed next.
//   bootloader   facts §1.4 pattern 1: a 64-bit request in .bss (>= 0x2000_4000, after the
//                16 KiB stack), AIRCR.SYSRESETREQ; startup.cpp's reset handler jumps to the ROM.
#pragma once

#include <algorithm>
#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <string_view>

#include "adc.hpp"
#include "bootloader_request.hpp"
#include "calibration_flash.hpp"
#include "cpu.hpp"
#include "link_uart.hpp"
#include "nvic.hpp"
#include "palp/app/board.hpp"
#include "palp/fw/calibration.hpp"
#include "palp/protocol/board_id.hpp"
#include "palp/protocol/usb.hpp"
#include "palp/usb/descriptors.hpp"
#include "palp/usb/device.hpp"
#include "pins.hpp"
#include "regs/gpio.hpp"
#include "regs/tim.hpp"
#include "scb.hpp"
#include "timers.hpp"
#include "usb_fsdev.hpp"
#include "vectors_list.hpp"

namespace palp::stm32 {

// ---- the analog transfers (README §5): where the board's gain and offset live -------------------
namespace sense {

inline constexpr float kAdcCodes = 4096.0f;  // 12-bit conversions (CFGR.RES 00)
inline constexpr float kVdda_V = 3.3f;       // the NUCLEO's VDDA = VREF+
/// INA240A1 (20 V/V) across the 16.5 mΩ shunt: 0.33 V/A, biased to mid-rail (REF1 = VS, REF2 =
/// GND: 1.65 V = code 2048 at 0 A). The nominal transfer only: the core's calibration
/// (current_offset_A, current_gain) absorbs the amplifier's offset, the bias and VDDA != 3.3 V.
inline constexpr float kCurrentSense_V_per_A = 20.0f * 0.0165f;
inline constexpr float kCurrentZeroCode = 2048.0f;
/// The 100 k / 8.2 k supply divider: 0.07579 (no calibration field; ±0.4 V at 24 V, README §5).
inline constexpr float kSupplyDivider = 8.2f / (100.0f + 8.2f);

/// TickInputs::i_sense_A for an ADC1 JDR1 code: (code - 2048) x 5 A / 2048.
constexpr float current_A(std::uint16_t code) {
  return (static_cast<float>(code) - kCurrentZeroCode) * (kVdda_V / kAdcCodes) /
         kCurrentSense_V_per_A;
}
/// TickInputs::supply_V for an ADC1 JDR2 code: code x 3.3 V / 4096 / 0.07579.
constexpr float supply_V(std::uint16_t code) {
  return static_cast<float>(code) * (kVdda_V / kAdcCodes) / kSupplyDivider;
}

}  // namespace sense

/// The IRQ number of a vector-table entry by its SVD name (vectors_list.hpp, the one list).
constexpr std::uint32_t irq_number(std::string_view name) {
  for (const vectors::Irq& irq : vectors::kIrqs) {
    if (name == irq.name) return irq.number;
  }
  return 0xFFFF'FFFFu;
}

/// What differs between the target and a host test besides the register access.
struct BoardPlatform {
  /// The six halfwords ADC2's DMA writes (adc.cpp's buffer on the target) and the address the
  /// DMA is given for them.
  const volatile std::uint16_t* pressure_codes = nullptr;
  std::uint32_t pressure_codes_address = 0;
  /// The two words of the bootloader request (bootloader_request.hpp).
  std::uint32_t bootloader_request_address = 0;
  /// DeviceInfo's git hash (`git describe`, as the QEMU board's PALP_GIT_HASH).
  const char* git_hash = "unknown";
};

/// Which host link the app's bytes go to (StmBoardT: the one that last delivered bytes).
enum class HostLinkId : std::uint8_t { lpuart1, usb };

/// The stream rates the board advertises per link (DeviceInfo.max_stream_rate_Hz, SPEC §9.1), at
/// the densest sample (all 11 channels, link_uart::kSampleBytes = 24 B):
/// - LPUART1: link_uart::kStreamRateHz = 3840 Hz (921 600 baud);
/// - USB bulk: full-speed bulk carries 1 216 000 B/s (palp/protocol/usb.hpp), 50 666 samples/s,
///   beyond anything the core produces: the core's own maximum (Streamer::kMaxRate_Hz);
/// - USB HID: one 64-byte report per ms = 64 000 B/s, 2666 samples/s raw; a report is
///   zero-padded after a frame's end (firmware/usb/README.md), so 2000 Hz (48 000 B/s) leaves a
///   quarter of the reports for padding and replies.
namespace stream_rate {
inline constexpr std::uint32_t kLpuart1Hz = link_uart::kStreamRateHz;
inline constexpr std::uint32_t kUsbBulkHz =
    std::min(fw::Streamer::kMaxRate_Hz, proto::usb::kBulkBytesPerS / link_uart::kSampleBytes);
inline constexpr std::uint32_t kUsbHidHz = 2000;
static_assert(kUsbHidHz * link_uart::kSampleBytes <= proto::usb::kHidBytesPerS * 3 / 4);
}  // namespace stream_rate

template <HalfwordAccess Io, class Cpu>
class StmBoardT {
 public:
  /// The board's name in DeviceInfo: the protocol's one spelling (board_id.hpp).
  static constexpr const char* kName = proto::board_name(proto::BoardId::stm32g474);
  /// The interrupts (vectors_list.hpp names; facts §2: ADC1_2 = 18; facts §5.1: USB_LP = 20
  /// serves every non-isochronous endpoint, bus reset and suspend; USB_HP (19) only iso and
  /// double-buffered ones, which this device has none of).
  static constexpr std::uint32_t kTickIrq = irq_number("ADC1_2");
  static constexpr std::uint32_t kLinkIrq = irq_number("LPUART");
  static constexpr std::uint32_t kUsbIrq = irq_number("USB_LP");
  static_assert(kTickIrq == 18 && kLinkIrq == 91 && kUsbIrq == 20);
  /// The device UID: 96 bits at 0x1FFF_7590 (facts §1.1, CMSIS UID_BASE), three words.
  static constexpr std::uint32_t kUidBase = 0x1FFF'7590u;
  /// The main loop must have passed idle() this recently for the tick to refresh the IWDG:
  /// 50 ms, below the IWDG's shortest timeout (68.2 ms with the assumed LSI band, timers.hpp),
  /// so a stalled main loop resets the board within 50 + 83 ms.
  static constexpr std::uint64_t kMainLoopWindow_us = 50'000;
  /// Status LED blink half-period while faulted: 250 ms (2 Hz).
  static constexpr std::uint64_t kBlinkHalfPeriod_us = 250'000;
  /// What the µs clock counts at: TIM5 = 170 MHz / 170.
  static constexpr std::uint32_t kClockPrescaler = timers::kTimerClockHz / 1'000'000u;
  static_assert(kClockPrescaler * 1'000'000u == timers::kTimerClockHz);

  using Link = link_uart::Link<Io, link_uart::kRxRingBytes>;
  using UsbHardware = fsdev::UsbFsdev<Io>;
  using UsbDevice = ::palp::usb::Device<UsbHardware>;
  using Calibration = CalibrationFlash<Io>;
  /// A block write_calibration takes while a commit runs waits here (the core's block size).
  static constexpr std::size_t kPendingCalibrationBytes = std::tuple_size_v<fw::CalibrationBlock>;

  /// Which init step failed first (ok: none). The LED blinks while not ok.
  enum class InitStatus : std::uint8_t { ok, clock_failed, adc_failed, watchdog_failed };

  StmBoardT(Io& io, Cpu& cpu, Link& link, const BoardPlatform& platform)
      : io_(io), cpu_(cpu), link_(link), platform_(platform), usb_hw_(io), usb_(usb_hw_),
        calibration_(io) {}

  /// Boot: every peripheral but the tick's (see the file comment). `clock_ok`: the reset
  /// handler's clock init succeeded (startup.hpp).
  void init(bool clock_ok = true) {
    if (!clock_ok) fail(InitStatus::clock_failed);
    pins::init(io_, pins::kPins);
    link_uart::init(io_);
    timers::init_encoder(io_);
    if (adc::init(io_, platform_.pressure_codes_address) != adc::Status::ok) {
      fail(InitStatus::adc_failed);
    }
    start_clock();
    read_serial();
    // USB (facts §5.3 item 1; PA11/PA12 analog in pins::kPins, facts §5.1): the serial string
    // first, so the host never sees another; the pull-up last.
    usb_hw_.init();
    (void)::palp::usb::set_serial_number(serial_);  // 24 hex digits: within its 24 characters
    set_priority(kTickIrq, board::nvic::kPriorityTick);
    set_priority(kLinkIrq, board::nvic::kPriorityLink);
    set_priority(kUsbIrq, board::nvic::kPriorityLink);
    io_.write(board::nvic::bit_word(board::nvic::kIser0, kLinkIrq), board::nvic::bit_of(kLinkIrq));
    io_.write(board::nvic::bit_word(board::nvic::kIser0, kUsbIrq), board::nvic::bit_of(kUsbIrq));
    usb_.start();
  }

  // ---- boot ------------------------------------------------------------------------------------
  fw::DeviceIdentity identity() const {
    fw::DeviceIdentity id;
    id.board = kName;
    id.serial = serial_;
    id.git_hash = platform_.git_hash;
    id.max_stream_rate_Hz = link_stream_rate_Hz();
    return id;
  }
  /// The stored block (the newest valid journal slot) or 0xFF fill (calibration_flash.hpp). At
  /// boot nothing runs; otherwise a running commit and the block waiting behind it are finished
  /// first, so what is read is the newest block written.
  std::size_t read_calibration(std::uint8_t* bytes, std::size_t size) {
    finish_calibration();
    return calibration_.read(bytes, size);
  }

  // ---- the control tick ------------------------------------------------------------------------
  bool start_tick(std::uint32_t rate_Hz, app::TickHandler handler) {
    if ((rate_Hz != timers::kPwm20kHz && rate_Hz != timers::kPwm40kHz) || handler.run == nullptr) {
      return false;  // nothing written: the tick keeps its rate
    }
    mask_tick();
    if (tick_running_) {  // a rate change: every gate off while TIM1 is reprogrammed
      write_field(io_, tim1::Bdtr::reg, tim1::Bdtr::MOE, 0);
    }
    (void)timers::init_bridge_pwm(io_, rate_Hz);  // cannot fail at 20/40 kHz (static_asserts)
    // A conversion finished at the old rate is not this rate's tick.
    io_.write(adc::Isr::adc1.address(), adc::Isr::JEOC.mask() | adc::Isr::JEOS.mask());
    io_.write(board::nvic::bit_word(board::nvic::kIcpr0, kTickIrq), board::nvic::bit_of(kTickIrq));
    tick_ = handler;
    period_us_ = 1'000'000u / rate_Hz;
    grid_start_us_ = clock_us();
    ticks_counted_ = 0;
    if (!tick_running_) {
      tick_running_ = true;
      main_alive_at_us_ = grid_start_us_;
      main_passes_seen_ = main_passes_.load(std::memory_order_relaxed);
      io_.write(gpio::BsrrC::reg.address(), gpio::BsrrC::BS11.mask());  // DRV8323 ENABLE on
      if (timers::start_watchdog(io_) != timers::Status::ok) fail(InitStatus::watchdog_failed);
      watchdog_running_ = true;
    }
    if (hold_depth_ == 0) unmask_tick();
    return true;
  }

  /// The ADC1_2 interrupt (board_irqs.cpp): the injected codes, the flags cleared, the grid's
  /// missed ticks counted, then the app's tick.
  void on_tick_irq() {
    const adc::InjectedCodes codes = adc::take_injected(io_);
    current_code_ = codes.current;
    supply_code_ = codes.supply;
    if (tick_.run == nullptr) return;
    tick_now_us_ = clock_us();
    const std::uint64_t due = (tick_now_us_ - grid_start_us_) / period_us_ + 1;
    if (due > ticks_counted_ + 1) {
      missed_ticks_ += static_cast<std::uint32_t>(due - ticks_counted_ - 1);
    }
    ticks_counted_ = std::max(due, ticks_counted_ + 1);
    tick_.run(tick_.ctx);
  }

  void read_inputs(fw::TickInputs& in) {
    in.i_sense_A = sense::current_A(current_code_);
    supply_V_ = sense::supply_V(supply_code_);
    in.supply_V = supply_V_;
    in.encoder_timer = timers::encoder_count16(io_);
    for (std::size_t k = 0; k < in.pressure_codes.size(); ++k) {
      in.pressure_codes[k] = platform_.pressure_codes[k];
    }
    driver_fault_ = read_field(io_, gpio::IdrC::reg, gpio::IdrC::IDR10) == 0;  // nFAULT low
    in.driver_fault = driver_fault_;
    in.missed_ticks = missed_ticks_;
    missed_ticks_ = 0;
  }

  void apply_outputs(const fw::TickOutputs& out) {
    timers::set_coil_voltage(io_, out.v_coil_V, supply_V_);
    io_.write(gpio::BsrrC::reg.address(),
              out.contact_line ? gpio::BsrrC::BS6.mask() : gpio::BsrrC::BR6.mask());
    adc::start_pressure_scan(io_);
    refresh_watchdog_if_main_loop_alive();
    update_led();
  }

  void hold_tick() {
    ++hold_depth_;
    mask_tick();
  }
  void release_tick() {
    if (hold_depth_ > 0) --hold_depth_;
    if (hold_depth_ == 0 && tick_running_) unmask_tick();
  }

  // ---- clocks ----------------------------------------------------------------------------------
  /// TIM5's count extended to 64 bits (read at least every tick: far within its 71.6-minute
  /// wrap), with interrupts masked: the main loop and the tick both extend it.
  std::uint64_t now_us() { return clock_us(); }

  // ---- the links -------------------------------------------------------------------------------
  /// The link in use first; the other only when that one has nothing (so two hosts' bytes do
  /// not interleave while one is talking). The link that delivers bytes becomes the one in use.
  std::size_t link_read(std::uint8_t* bytes, std::size_t size) {
    std::size_t n = read_from(active_, bytes, size);
    if (n == 0) {
      const HostLinkId other = active_ == HostLinkId::usb ? HostLinkId::lpuart1 : HostLinkId::usb;
      n = read_from(other, bytes, size);
      if (n > 0) active_ = other;
    }
    return n;
  }
  /// To the link in use. LPUART1: a full FIFO arms its TX interrupt (it wakes idle()); USB: the
  /// USB interrupt is pended so service() starts the IN pipe (its IN-complete interrupt wakes
  /// idle() when the ring has room again).
  std::size_t link_write(const std::uint8_t* bytes, std::size_t size) {
    if (active_ == HostLinkId::usb) {
      const std::size_t n = usb_.write(bytes, size);
      if (n > 0) pend_usb();
      return n;
    }
    const std::size_t n = link_.write_bytes(bytes, size);
    if (n < size) {  // the FIFO is full: its interrupt wakes idle() when it has room
      const board::InterruptLock<Cpu> lock(cpu_);
      link_.arm_tx_wakeup();
    }
    return n;
  }

  /// The USB_LP interrupt (board_irqs.cpp): every pending USB event, the stream moved.
  void on_usb_irq() { usb_.service(); }

  // ---- calibration storage (main loop) ---------------------------------------------------------
  /// Starts a journal commit of the block and returns (true: it will be stored unless the flash
  /// fails: calibration_commit() then says why). While a commit runs the block waits in RAM
  /// (one: a newer one replaces it) and is committed when the running one ends. False: the
  /// commit could not start (size 0 or beyond the journal, option bytes not dual-bank), or a
  /// commit runs and the block is larger than the RAM copy.
  bool write_calibration(const std::uint8_t* bytes, std::size_t size) {
    if (commit_state_ == fw::CommitState::erasing || commit_state_ == fw::CommitState::programming) {
      if (size == 0 || size > kPendingCalibrationBytes) return false;
      std::copy(bytes, bytes + size, pending_calibration_);
      pending_calibration_size_ = size;
      return true;
    }
    return begin_commit(bytes, size);
  }
  /// The last commit's state (done / failed / running) and its error (calibration_flash.hpp).
  fw::CommitState calibration_commit() const { return commit_state_; }
  bool calibration_busy() const {
    return commit_state_ == fw::CommitState::erasing ||
           commit_state_ == fw::CommitState::programming || pending_calibration_size_ > 0;
  }
  std::uint32_t calibration_failures() const { return calibration_failures_; }
  Calibration& calibration_store() { return calibration_; }

  // ---- power and reset -------------------------------------------------------------------------
  /// One main-loop pass: counted (the watchdog rule), a running calibration commit advanced by
  /// one flash step, then WFI unless a link holds received bytes, a commit runs or the app has
  /// work (the flash raises no interrupt here: the loop keeps polling it, ~30 ms per commit).
  void idle(app::HasWork has_work, void* ctx) {
    main_passes_.store(main_passes_.load(std::memory_order_relaxed) + 1, std::memory_order_relaxed);
    advance_calibration();
    // With interrupts masked, so an interrupt between the check and the WFI still wakes it.
    cpu_.disable_interrupts();
    if (link_.rx_pending() == 0 && usb_.rx_waiting() == 0 && !calibration_busy() &&
        !has_work(ctx))
      cpu_.wait_for_interrupt();
    cpu_.enable_interrupts();
  }

  /// Facts §1.4 pattern 1: gates off, the request words, then a system reset; the reset handler
  /// (startup.cpp) sees the request first thing and enters the ROM bootloader.
  /// A calibration commit still running (or waiting) is finished first, bounded by the store's
  /// poll limit: an update right after a calibration keeps it.
  void enter_bootloader() {
    cpu_.disable_interrupts();
    io_.write(gpio::BsrrC::reg.address(), gpio::BsrrC::BR11.mask());  // DRV8323 ENABLE off
    finish_calibration();
    io_.write(platform_.bootloader_request_address, bootloader::kRequestWord0);
    io_.write(platform_.bootloader_request_address + 4u, bootloader::kRequestWord1);
    cpu_.barrier();
    io_.write(static_cast<std::uint32_t>(board::scb::kAircr),
              board::scb::kAircrVectKey | board::scb::kAircrSysResetReq);
    cpu_.wait_for_reset();
  }

  // ---- for the target's startup reporting and tests --------------------------------------------
  InitStatus init_status() const { return init_status_; }
  bool watchdog_running() const { return watchdog_running_; }
  Link& link() { return link_; }
  UsbDevice& usb_device() { return usb_; }
  HostLinkId active_link() const { return active_; }

 private:
  void fail(InitStatus s) {
    if (init_status_ == InitStatus::ok) init_status_ = s;
  }

  std::size_t read_from(HostLinkId link, std::uint8_t* bytes, std::size_t size) {
    if (link == HostLinkId::lpuart1) return link_.read_bytes(bytes, size);
    const std::size_t n = usb_.read(bytes, size);
    if (n > 0) pend_usb();  // service() re-arms an OUT endpoint paused for ring room
    return n;
  }
  /// NVIC ISPR: the USB interrupt runs service() as soon as the main loop's priority allows.
  void pend_usb() {
    io_.write(board::nvic::bit_word(board::nvic::kIspr0, kUsbIrq), board::nvic::bit_of(kUsbIrq));
  }
  std::uint32_t link_stream_rate_Hz() const {
    if (active_ == HostLinkId::lpuart1) return stream_rate::kLpuart1Hz;
    return usb_.sending_pipe() == ::palp::usb::StreamPipe::hid ? stream_rate::kUsbHidHz
                                                       : stream_rate::kUsbBulkHz;
  }

  /// One step of the calibration commit (at most one flash operation started, never a wait on
  /// BSY); when it ends, the block that waited starts.
  void advance_calibration() {
    if (commit_state_ != fw::CommitState::erasing && commit_state_ != fw::CommitState::programming) {
      if (pending_calibration_size_ == 0) return;
      const std::size_t size = pending_calibration_size_;
      pending_calibration_size_ = 0;
      (void)begin_commit(pending_calibration_, size);
      return;
    }
    commit_state_ = calibration_.poll();
    if (commit_state_ == fw::CommitState::failed) ++calibration_failures_;
  }

  /// Polls the commit (and the one waiting) to the end: a wait of ~30 ms per commit, for
  /// read_calibration and enter_bootloader only; bounded by the store's poll limit.
  void finish_calibration() {
    for (std::uint32_t n = 0; calibration_busy() && n < Calibration::kPollLimit; ++n) {
      advance_calibration();
    }
  }

  bool begin_commit(const std::uint8_t* bytes, std::size_t size) {
    const bool started = calibration_.begin_write(bytes, size);  // the erase starts
    commit_state_ = started ? fw::CommitState::erasing : fw::CommitState::failed;
    if (!started) ++calibration_failures_;
    return started;
  }

  void set_priority(std::uint32_t irq, std::uint8_t priority) {
    const std::uint32_t word = board::nvic::priority_word(irq);
    const std::uint32_t shift = board::nvic::priority_shift(irq);
    io_.write(word, (io_.read(word) & ~(0xFFu << shift)) | (std::uint32_t{priority} << shift));
  }
  void mask_tick() {
    io_.write(board::nvic::bit_word(board::nvic::kIcer0, kTickIrq), board::nvic::bit_of(kTickIrq));
    cpu_.barrier();  // masked before the next instruction [GUG] 4.2.9
  }
  void unmask_tick() {
    io_.write(board::nvic::bit_word(board::nvic::kIser0, kTickIrq), board::nvic::bit_of(kTickIrq));
  }

  /// TIM5 free-running at 1 MHz over its 32 bits (facts §2 TIM5EN, §4.3 32-bit, PSC/UG §4.2).
  void start_clock() {
    write_field(io_, rcc::Apb1enr1::reg, rcc::Apb1enr1::TIM5EN, 1);
    (void)read(io_, rcc::Apb1enr1::reg);  // the bus delay after a clock enable (facts §3.2)
    io_.write(tim5::Cr1::reg.address(), 0);
    io_.write(tim5::Psc::reg.address(), kClockPrescaler - 1);
    io_.write(tim5::Arr::reg.address(), 0xFFFF'FFFFu);
    io_.write(tim5::Egr::reg.address(), tim5::Egr::UG.mask());  // loads PSC, CNT = 0
    clock_last_ = 0;
    io_.write(tim5::Cr1::reg.address(), tim5::Cr1::CEN.mask());
  }
  std::uint64_t clock_us() {
    const board::InterruptLock<Cpu> lock(cpu_);
    const std::uint32_t count = read(io_, tim5::Cnt::reg);
    clock_total_us_ += static_cast<std::uint32_t>(count - clock_last_);  // modulo 2^32
    clock_last_ = count;
    return clock_total_us_;
  }

  void refresh_watchdog_if_main_loop_alive() {
    const std::uint32_t passes = main_passes_.load(std::memory_order_relaxed);
    if (passes != main_passes_seen_) {
      main_passes_seen_ = passes;
      main_alive_at_us_ = tick_now_us_;
    }
    if (watchdog_running_ && tick_now_us_ - main_alive_at_us_ <= kMainLoopWindow_us) {
      timers::refresh_watchdog(io_);
    }
  }

  void update_led() {
    const bool faulted = driver_fault_ || init_status_ != InitStatus::ok;
    const bool on = !faulted || (tick_now_us_ / kBlinkHalfPeriod_us) % 2 == 0;
    if (on == led_on_) return;
    led_on_ = on;
    io_.write(gpio::BsrrA::reg.address(), on ? gpio::BsrrA::BS5.mask() : gpio::BsrrA::BR5.mask());
  }

  /// The serial: the 96-bit UID as 24 upper-case hex digits, lowest address word first.
  void read_serial() {
    constexpr char kHex[] = "0123456789ABCDEF";
    for (std::uint32_t w = 0; w < 3; ++w) {
      const std::uint32_t word = io_.read(kUidBase + 4u * w);
      for (std::uint32_t d = 0; d < 8; ++d) {
        serial_[8 * w + d] = kHex[(word >> (28u - 4u * d)) & 0xFu];
      }
    }
    serial_[24] = '\0';
  }

  Io& io_;
  Cpu& cpu_;
  Link& link_;
  BoardPlatform platform_;
  UsbHardware usb_hw_;
  UsbDevice usb_;
  HostLinkId active_ = HostLinkId::lpuart1;  // main loop only
  Calibration calibration_;
  fw::CommitState commit_state_ = fw::CommitState::idle;
  std::uint8_t pending_calibration_[kPendingCalibrationBytes] = {};
  std::size_t pending_calibration_size_ = 0;
  std::uint32_t calibration_failures_ = 0;
  char serial_[25] = "000000000000000000000000";
  InitStatus init_status_ = InitStatus::ok;

  // the tick (main loop writes with the tick masked; the tick reads)
  app::TickHandler tick_{};
  bool tick_running_ = false;
  std::uint32_t hold_depth_ = 0;
  std::uint32_t period_us_ = 50;
  std::uint64_t grid_start_us_ = 0;
  std::uint64_t ticks_counted_ = 0;  // grid ticks accounted for since the grid start
  std::uint32_t missed_ticks_ = 0;   // not yet reported
  std::uint64_t tick_now_us_ = 0;    // the clock at this tick's interrupt
  std::uint16_t current_code_ = 2048, supply_code_ = 0;
  float supply_V_ = 0.0f;
  bool driver_fault_ = false;

  // the µs clock
  std::uint64_t clock_total_us_ = 0;
  std::uint32_t clock_last_ = 0;

  // the watchdog: the main loop counts its passes, the tick notes when they last moved
  bool watchdog_running_ = false;
  std::atomic<std::uint32_t> main_passes_{0};
  std::uint32_t main_passes_seen_ = 0;
  std::uint64_t main_alive_at_us_ = 0;
  bool led_on_ = false;
};

}  // namespace palp::stm32

#if defined(__arm__)
namespace palp::stm32 {

/// The target's board: memory-mapped registers, the Cortex-M core, link_uart's HostLink and
/// adc.cpp's pressure buffer. Its constructor runs init() (the reset handler has set the clocks)
/// and makes it the board the ADC1_2 and USB_LP interrupts (board_irqs.cpp) reach. One per image.
class StmBoard : public StmBoardT<Mmio, board::CortexM> {
 public:
  StmBoard();
  StmBoard(const StmBoard&) = delete;
  StmBoard& operator=(const StmBoard&) = delete;
};

/// The board the ADC1_2 interrupt runs the tick on and the USB_LP interrupt services USB on
/// (board_irqs.cpp; StmBoard's constructor sets it, which also links those handlers in from the
/// library).
void set_irq_board(StmBoard* board);

static_assert(app::Board<StmBoard>);

}  // namespace palp::stm32
#endif
