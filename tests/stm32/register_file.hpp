// SPDX-License-Identifier: Apache-2.0
// A host register file for the STM32G474 drivers: an Access (regs/register.hpp) over a map of
// 32-bit words that logs every write and plays the hardware's part for the flags the clock init
// polls: PLLON -> PLLRDY, SW -> SWS, HSI48ON -> HSI48RDY (each unless the test turns it off).
#pragma once

#include <cstdint>
#include <map>
#include <vector>

#include "regs/all.hpp"

namespace palp::stm32::test {

struct Write {
  std::uint32_t address;
  std::uint32_t value;
};

class RegisterFile {
 public:
  /// The reset values of the registers the clock init reads (RM0440 via facts §3.1, §3.3).
  RegisterFile() {
    words_[rcc::Cr::reg.address()] = rcc::Cr::HSION.mask() | rcc::Cr::HSIRDY.mask();
    words_[rcc::Cfgr::reg.address()] = rcc::Cfgr::SW.encode(rcc::Cfgr::kSwHsi16) |
                                       rcc::Cfgr::SWS.encode(rcc::Cfgr::kSwHsi16);
    words_[pwr::Cr1::reg.address()] = pwr::Cr1::VOS.encode(pwr::Cr1::kVosRange1);
    words_[pwr::Cr5::reg.address()] = pwr::Cr5::R1MODE.mask();
    words_[crs::Cr::reg.address()] = crs::Cr::TRIM.encode(64);
    words_[crs::Cfgr::reg.address()] = 0x2022'BB7F;  // facts §3.3: RELOAD, FELIM, SYNCSRC = SOF
  }

  std::uint32_t read(std::uint32_t address) {
    ++reads_;
    const auto it = words_.find(address);
    return it == words_.end() ? 0 : it->second;
  }

  void write(std::uint32_t address, std::uint32_t value) {
    log_.push_back({address, value});
    words_[address] = value;
    if (!react_) {
      return;
    }
    if (address == rcc::Cr::reg.address()) {
      set(rcc::Cr::reg, rcc::Cr::PLLRDY, rcc::Cr::PLLON.decode(value));
    } else if (address == rcc::Cfgr::reg.address()) {
      set(rcc::Cfgr::reg, rcc::Cfgr::SWS, rcc::Cfgr::SW.decode(value));
    } else if (address == rcc::Crrcr::reg.address()) {
      set(rcc::Crrcr::reg, rcc::Crrcr::HSI48RDY, rcc::Crrcr::HSI48ON.decode(value));
    }
  }

  /// The register's current word, without counting a read.
  std::uint32_t peek(const Register& reg) const {
    const auto it = words_.find(reg.address());
    return it == words_.end() ? 0 : it->second;
  }
  /// Sets a register's word as the hardware would (no write logged, no reaction).
  void poke(const Register& reg, std::uint32_t value) { words_[reg.address()] = value; }
  const std::vector<Write>& log() const { return log_; }
  std::uint64_t reads() const { return reads_; }
  /// Off: no ready flag ever rises (a board whose PLL or HSI48 does not start).
  void set_hardware_reacts(bool react) { react_ = react; }

 private:
  void set(const Register& reg, const Field& field, std::uint32_t value) {
    std::uint32_t& word = words_[reg.address()];
    word = (word & ~field.mask()) | field.encode(value);
  }

  std::map<std::uint32_t, std::uint32_t> words_;
  std::vector<Write> log_;
  std::uint64_t reads_ = 0;
  bool react_ = true;
};

static_assert(RegisterAccess<RegisterFile>);

}  // namespace palp::stm32::test
