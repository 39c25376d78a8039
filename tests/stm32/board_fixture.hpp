// SPDX-License-Identifier: Apache-2.0
// The STM32G474 board class (firmware/board/stm32g474/stm_board.hpp) on a host register file, for
// tests/stm32/test_board*.cpp: the hardware's part the board's init polls (ADC calibration ends,
// ADEN raises ADRDY, ISR bits are write-1-to-clear), the USB peripheral's registers and PMA
// answered by the FSDEV model (fsdev_model.hpp) and the flash controller's registers and
// calibration pages by the flash model (flash_model.hpp), a Cpu that records PRIMASK/WFI/
// barriers, and a fixture that builds and inits a board with a recording tick handler.
#pragma once

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <deque>
#include <string>
#include <vector>

#include "flash_model.hpp"
#include "fsdev_model.hpp"
#include "register_file.hpp"
#include "stm_board.hpp"

namespace palp::stm32::board_test {

/// The register file plus what the board's init needs from the ADCs to succeed; LPUART1's RDR
/// and RXNE from a queue of received bytes; the USB and flash address ranges go to their models. RCC_APB1ENR1 lives in the register file and each
/// write of it is copied to the FSDEV model, whose USB registers answer only with USBEN set.
class BoardHardware {
 public:
  std::uint32_t read(std::uint32_t address) {
    if (is_flash(address)) return flash_model.read(address);
    if (is_usb(address)) return usb_model.read(address);
    if (address == lpuart1::Isr::reg.address() && !uart_rx.empty()) {
      return rf.read(address) | lpuart1::Isr::RXNE.mask();
    }
    if (address == lpuart1::Rdr::reg.address() && !uart_rx.empty()) {
      const std::uint8_t byte = uart_rx.front();
      uart_rx.pop_front();
      return byte;
    }
    return rf.read(address);
  }
  std::uint16_t read16(std::uint32_t address) { return usb_model.read16(address); }
  void write16(std::uint32_t address, std::uint16_t value) { usb_model.write16(address, value); }
  void write(std::uint32_t address, std::uint32_t value) {
    if (is_flash(address)) return flash_model.write(address, value);
    if (is_usb(address)) return usb_model.write(address, value);
    if (address == rcc::Apb1enr1::reg.address()) usb_model.write(address, value);
    for (const auto& [cr, isr] : {std::pair{adc::Cr::adc1, adc::Isr::adc1},
                                  std::pair{adc::Cr::adc2, adc::Isr::adc2}}) {
      if (address == isr.address()) {  // write 1 to clear; logged
        const std::uint32_t before = rf.peek(isr);
        rf.write(address, value);
        rf.poke(isr, before & ~value);
        return;
      }
      if (address == cr.address()) {  // calibration ends at once; ADEN raises ADRDY
        rf.write(address, value & ~adc::Cr::ADCAL.mask());
        if (adc::Cr::ADEN.decode(value) == 1) set(isr, adc::Isr::ADRDY.mask());
        return;
      }
    }
    rf.write(address, value);
  }

  /// Sets bits of a register as the hardware would.
  void set(const Register& reg, std::uint32_t bits) { rf.poke(reg, rf.peek(reg) | bits); }
  std::uint32_t peek(const Register& reg) const { return rf.peek(reg); }
  std::uint32_t peek(std::uint32_t address) const { return rf.peek({"", "", address, 0, {}}); }
  void poke(const Register& reg, std::uint32_t value) { rf.poke(reg, value); }
  void poke(std::uint32_t address, std::uint32_t value) {
    rf.poke({"", "", address, 0, {}}, value);
  }
  std::uint32_t field(const Register& reg, const Field& f) const { return f.decode(rf.peek(reg)); }

  /// The writes logged since `from` (an index into the log).
  std::vector<test::Write> writes_since(std::size_t from) const {
    return {rf.log().begin() + static_cast<std::ptrdiff_t>(from), rf.log().end()};
  }
  std::size_t log_size() const { return rf.log().size(); }
  /// How many writes of `value` to `address` since `from`.
  std::size_t count_writes(std::uint32_t address, std::uint32_t value, std::size_t from = 0) const {
    std::size_t n = 0;
    for (const test::Write& w : writes_since(from)) n += w.address == address && w.value == value;
    return n;
  }

  test::RegisterFile rf;
  test::FsdevModel usb_model;
  test::FlashModel flash_model;
  /// Bytes LPUART1 has received and not yet given up through RDR (ISR.RXNE while any wait).
  std::deque<std::uint8_t> uart_rx;

 private:
  static bool is_flash(std::uint32_t address) {  // the memory, then FLASH_ACR .. the last register
    return (address >= 0x0800'0000 && address < 0x0808'0000) ||
           (address >= flash::Acr::reg.address() && address < flash::Acr::reg.address() + 0x400);
  }
  static bool is_usb(std::uint32_t address) {  // the registers (facts §5.2), then the PMA (§5.1)
    return address >= usb::kBase && address < usb::kPmaBase + usb::kPmaSize;
  }
};

/// The core's operations, recorded: "mask"/"restore" (PRIMASK save/restore), "cpsid", "cpsie",
/// "wfi", "barrier", "wait_for_reset".
class RecordingCpu {
 public:
  std::uint32_t mask_interrupts() {
    events.emplace_back("mask");
    const std::uint32_t was = primask;
    primask = 1;
    return was;
  }
  void restore_interrupts(std::uint32_t was) {
    events.emplace_back("restore");
    primask = was;
  }
  void disable_interrupts() {
    events.emplace_back("cpsid");
    primask = 1;
  }
  void enable_interrupts() {
    events.emplace_back("cpsie");
    primask = 0;
  }
  void wait_for_interrupt() { events.emplace_back(primask ? "wfi (masked)" : "wfi"); }
  void barrier() { events.emplace_back("barrier"); }
  void wait_for_reset() { events.emplace_back("wait_for_reset"); }

  std::vector<std::string> events;
  std::uint32_t primask = 0;
};

using Board = StmBoardT<BoardHardware, RecordingCpu>;
static_assert(app::Board<Board>, "the register-file board satisfies the app's Board concept");

inline constexpr std::uint32_t kPressureAddress = 0x2000'5000;
inline constexpr std::uint32_t kRequestAddress = 0x2000'6000;

/// The platform every board test builds on: the pressure DMA buffer `pressure` at
/// kPressureAddress, the bootloader request word at kRequestAddress.
inline BoardPlatform test_platform(std::array<std::uint16_t, 6>& pressure,
                                   const char* git_hash = nullptr) {
  BoardPlatform p;
  p.pressure_codes = pressure.data();
  p.pressure_codes_address = kPressureAddress;
  p.bootloader_request_address = kRequestAddress;
  if (git_hash != nullptr) p.git_hash = git_hash;
  return p;
}

/// A board after init(), with a tick handler that runs the app's part: read_inputs, then
/// apply_outputs with `outputs`, recording the inputs of every tick.
class BoardTest : public ::testing::Test {
 protected:
  BoardTest() : link(hw), board(hw, cpu, link, platform()) {
    hw.poke(gpio::IdrC::reg, gpio::IdrC::IDR10.mask());  // nFAULT released (pulled up)
    hw.poke(lpuart1::Isr::reg, lpuart1::Isr::TXE.mask());  // TX FIFO has room
    board.init();
  }

  BoardPlatform platform() { return test_platform(pressure, "abc1234"); }

  static void on_tick(void* self) {
    auto& t = *static_cast<BoardTest*>(self);
    fw::TickInputs in;
    t.board.read_inputs(in);
    t.inputs.push_back(in);
    t.board.apply_outputs(t.outputs);
  }
  app::TickHandler handler() { return {&BoardTest::on_tick, this}; }

  /// TIM5 at `us` µs (the count's low 32 bits), then one ADC1 end-of-sequence interrupt.
  void tick_at(std::uint64_t us) {
    hw.poke(tim5::Cnt::reg, static_cast<std::uint32_t>(us));
    hw.set(adc::Isr::adc1, adc::Isr::JEOC.mask() | adc::Isr::JEOS.mask());
    board.on_tick_irq();
  }

  BoardHardware hw;
  RecordingCpu cpu;
  std::array<std::uint16_t, 6> pressure{};
  Board::Link link;
  Board board;
  fw::TickOutputs outputs;
  std::vector<fw::TickInputs> inputs;
};

}  // namespace palp::stm32::board_test
