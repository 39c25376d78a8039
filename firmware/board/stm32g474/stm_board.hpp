// The STM32G474 probe controller as the app's Board (firmware/app/include/palp/app/board.hpp): the
// drivers of this directory (clock.hpp at reset, pins.hpp, timers.hpp, adc.hpp, link_uart.hpp)
// wired to the seam. A template over the register access (regs/register.hpp) and the core's
// operations (board/cortex_m/cpu.hpp), so tests/stm32 runs it on a host register file:
// StmBoardT<Mmio, CortexM> is the target's (StmBoard, stm_board.cpp; its interrupt entry is
// board_irqs.cpp). What each member does, and why (NOTES.md "Board class"):
//
//   init         pins (README §3), the LPUART1 host link, the TIM2 encoder, ADC1 injected + ADC2
//                scan with DMA (armed, waiting for TIM1), the µs clock (TIM5), NVIC priorities
//                (tick 0x40 above link 0x80), the serial from the device UID. The tick starts
//                with start_tick().
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
//   calibration  a RAM stand-in (RamCalibrationStore) behind contract 3's two calls; the flash
//                journal (calibration_flash.hpp, flashcal) replaces it when the lead wires it.
//   bootloader   facts §1.4 pattern 1: a 64-bit request in .bss (>= 0x2000_4000, after the
//                16 KiB stack), AIRCR.SYSRESETREQ; startup.cpp's reset handler jumps to the ROM.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <string_view>

#include "adc.hpp"
#include "bootloader_request.hpp"
#include "cpu.hpp"
#include "link_uart.hpp"
#include "nvic.hpp"
#include "palp/app/board.hpp"
#include "palp/fw/calibration.hpp"
#include "pins.hpp"
#include "regs/gpio.hpp"
#include "regs/tim.hpp"
#include "scb.hpp"
#include "timers.hpp"
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

/// Contract 3 (/work/team19.md) behind a RAM block: read() copies the stored block (erased = 0xFF),
/// write() replaces it. Nothing survives a reset: a STAND-IN until the lead wires
/// CalibrationFlash (calibration_flash.hpp, the flash journal) in with the same two calls.
class RamCalibrationStore {
 public:
  RamCalibrationStore() { std::fill(std::begin(bytes_), std::end(bytes_), std::uint8_t{0xFF}); }
  std::size_t read(std::uint8_t* bytes, std::size_t size) {
    const std::size_t n = std::min(size, sizeof bytes_);
    std::copy(bytes_, bytes_ + n, bytes);
    return n;
  }
  bool write(const std::uint8_t* bytes, std::size_t size) {
    if (size > sizeof bytes_) return false;
    std::copy(bytes, bytes + size, bytes_);
    std::fill(bytes_ + size, std::end(bytes_), std::uint8_t{0xFF});
    return true;
  }

 private:
  std::uint8_t bytes_[fw::kCalibrationMaxBlockSize];
};

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

template <RegisterAccess Io, class Cpu>
class StmBoardT {
 public:
  static constexpr const char* kName = "nucleo-g474re";
  /// The interrupts (vectors_list.hpp names; facts §2: ADC1_2 = 18).
  static constexpr std::uint32_t kTickIrq = irq_number("ADC1_2");
  static constexpr std::uint32_t kLinkIrq = irq_number("LPUART");
  static_assert(kTickIrq == 18 && kLinkIrq == 91);
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

  /// Which init step failed first (ok: none). The LED blinks while not ok.
  enum class InitStatus : std::uint8_t { ok, clock_failed, adc_failed, watchdog_failed };

  StmBoardT(Io& io, Cpu& cpu, Link& link, const BoardPlatform& platform)
      : io_(io), cpu_(cpu), link_(link), platform_(platform) {}

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
    set_priority(kTickIrq, board::nvic::kPriorityTick);
    set_priority(kLinkIrq, board::nvic::kPriorityLink);
    io_.write(board::nvic::bit_word(board::nvic::kIser0, kLinkIrq), board::nvic::bit_of(kLinkIrq));
    read_serial();
  }

  // ---- boot ------------------------------------------------------------------------------------
  fw::DeviceIdentity identity() const {
    fw::DeviceIdentity id;
    id.board = kName;
    id.serial = serial_;
    id.git_hash = platform_.git_hash;
    id.max_stream_rate_Hz = link_uart::kStreamRateHz;
    return id;
  }
  std::size_t read_calibration(std::uint8_t* bytes, std::size_t size) {
    return calibration_.read(bytes, size);
  }
  bool write_calibration(const std::uint8_t* bytes, std::size_t size) {
    return calibration_.write(bytes, size);
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

  // ---- the link --------------------------------------------------------------------------------
  std::size_t link_read(std::uint8_t* bytes, std::size_t size) {
    return link_.read_bytes(bytes, size);
  }
  std::size_t link_write(const std::uint8_t* bytes, std::size_t size) {
    const std::size_t n = link_.write_bytes(bytes, size);
    if (n < size) {  // the FIFO is full: its interrupt wakes idle() when it has room
      const board::InterruptLock<Cpu> lock(cpu_);
      link_.arm_tx_wakeup();
    }
    return n;
  }

  // ---- power and reset -------------------------------------------------------------------------
  void idle(app::HasWork has_work, void* ctx) {
    main_passes_.store(main_passes_.load(std::memory_order_relaxed) + 1, std::memory_order_relaxed);
    // With interrupts masked, so an interrupt between the check and the WFI still wakes it.
    cpu_.disable_interrupts();
    if (link_.rx_pending() == 0 && !has_work(ctx)) cpu_.wait_for_interrupt();
    cpu_.enable_interrupts();
  }

  /// Facts §1.4 pattern 1: gates off, the request words, then a system reset; the reset handler
  /// (startup.cpp) sees the request first thing and enters the ROM bootloader.
  void enter_bootloader() {
    cpu_.disable_interrupts();
    io_.write(gpio::BsrrC::reg.address(), gpio::BsrrC::BR11.mask());  // DRV8323 ENABLE off
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

 private:
  void fail(InitStatus s) {
    if (init_status_ == InitStatus::ok) init_status_ = s;
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
  RamCalibrationStore calibration_;
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
/// and makes it the board the ADC1_2 interrupt (board_irqs.cpp) reaches. One per image.
class StmBoard : public StmBoardT<Mmio, board::CortexM> {
 public:
  StmBoard();
  StmBoard(const StmBoard&) = delete;
  StmBoard& operator=(const StmBoard&) = delete;
};

/// The board the ADC1_2 interrupt runs the tick on (board_irqs.cpp; StmBoard's constructor sets
/// it, which also links that interrupt handler in from the library).
void set_tick_irq_board(StmBoard* board);

static_assert(app::Board<StmBoard>);

}  // namespace palp::stm32
#endif
