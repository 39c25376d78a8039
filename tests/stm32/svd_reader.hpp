// SPDX-License-Identifier: Apache-2.0
// A small, bounded reader of CMSIS-SVD files, enough for the register cross-check: peripherals
// (name, baseAddress, derivedFrom), their registers (name, addressOffset) and the registers' bit
// fields (name with bitOffset/bitWidth, bitRange [msb:lsb], or lsb/msb), and the device's
// interrupts (<interrupt><name>/<value> inside peripherals). Clusters, dim arrays and
// enumerated values are not read. Host test code only.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "regs/register.hpp"

namespace palp::stm32::svd {

struct SvdField {
  std::string name;
  unsigned position = 0;
  unsigned width = 0;
};

struct SvdRegister {
  std::string name;
  std::uint32_t offset = 0;
  std::vector<SvdField> fields;
};

struct SvdPeripheral {
  std::string name;
  std::string derived_from;  ///< empty unless the peripheral has derivedFrom="…"
  std::uint32_t base = 0;
  std::vector<SvdRegister> registers;
};

struct SvdInterrupt {
  std::string name;
  unsigned number = 0;  ///< IRQ number (vector slot 16 + number)
};

struct Device {
  std::vector<SvdPeripheral> peripherals;
  /// Every interrupt once, in increasing number (one listed by several peripherals is kept once;
  /// the same number under two names is a parse error).
  std::vector<SvdInterrupt> interrupts;

  const SvdPeripheral* find(std::string_view name) const;
  /// The registers of `peripheral`, those of the peripheral it derives from if it has none.
  const std::vector<SvdRegister>* registers_of(const SvdPeripheral& peripheral) const;
};

/// Parses SVD text; on malformed input returns nothing and says why in `error`.
std::optional<Device> parse(std::string_view xml, std::string& error);

/// The output of `xz -dc <path>` (at most 64 MiB); empty with `error` set on failure.
std::string read_xz(const std::string& path, std::string& error);

/// Every difference between `reg` and the SVD, one line each, e.g.
/// "RCC.RCC_PLLCFGR: offset 0x10 in regs/, 0x0C in the SVD"; empty when they agree.
std::vector<std::string> check(const Device& device, const Register& reg);

/// Every difference between a vector table's list {number, name} and the SVD's interrupts, one
/// line each, e.g. "IRQ 25: 'TIM1_UP' in the vector table, 'TIM1_UP_TIM16' in the SVD"; empty
/// when they agree.
struct TableEntry {
  unsigned number;
  std::string_view name;
};
std::vector<std::string> check_interrupts(const Device& device,
                                          const std::vector<TableEntry>& table);

}  // namespace palp::stm32::svd
