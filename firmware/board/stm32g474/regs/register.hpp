// SPDX-License-Identifier: Apache-2.0
// The register-access seam of the STM32G474 board: every register the board touches is a
// constexpr Register (peripheral, SVD register name, absolute base, offset, bit fields), and the
// drivers read and write through an Access object so the same init code runs on the target
// (Mmio: volatile 32-bit loads/stores at base + offset) and on the host (a register file).
// tests/stm32 checks every definition against ST's SVD (svd/STM32G474.svd.xz).
#pragma once

#include <cstdint>
#include <span>

namespace palp::stm32 {

/// One bit field: its SVD name, the lowest bit and the number of bits.
struct Field {
  const char* name;
  std::uint8_t position;
  std::uint8_t width;

  constexpr std::uint32_t mask() const {
    return (width >= 32 ? 0xFFFF'FFFFu : ((1u << width) - 1u)) << position;
  }
  /// `value` placed in this field (bits of `value` beyond the width are dropped).
  constexpr std::uint32_t encode(std::uint32_t value) const { return (value << position) & mask(); }
  /// This field's value in the register word `word`.
  constexpr std::uint32_t decode(std::uint32_t word) const { return (word & mask()) >> position; }
};

/// One register: `peripheral` and `name` spelled as in the SVD (so the cross-check can find it).
struct Register {
  const char* peripheral;
  const char* name;
  std::uint32_t base;
  std::uint32_t offset;
  std::span<const Field> fields;

  constexpr std::uint32_t address() const { return base + offset; }
};

/// The target's Access: the register at `address` as a volatile 32-bit word.
struct Mmio {
  std::uint32_t read(std::uint32_t address) const {
    return *reinterpret_cast<volatile std::uint32_t*>(static_cast<std::uintptr_t>(address));
  }
  void write(std::uint32_t address, std::uint32_t value) const {
    *reinterpret_cast<volatile std::uint32_t*>(static_cast<std::uintptr_t>(address)) = value;
  }
  /// 16-bit loads/stores, for memories that take nothing wider (the USB PMA, facts §5.1).
  std::uint16_t read16(std::uint32_t address) const {
    return *reinterpret_cast<volatile std::uint16_t*>(static_cast<std::uintptr_t>(address));
  }
  void write16(std::uint32_t address, std::uint16_t value) const {
    *reinterpret_cast<volatile std::uint16_t*>(static_cast<std::uintptr_t>(address)) = value;
  }
};

/// An Access is anything with read(address) and write(address, value) on 32-bit words.
template <class A>
concept RegisterAccess = requires(A& io, std::uint32_t address, std::uint32_t value) {
  { io.read(address) } -> std::same_as<std::uint32_t>;
  io.write(address, value);
};

/// A RegisterAccess that also does 16-bit accesses: the USB packet memory (PMA) is 16 bits wide
/// and takes only half-word loads and stores (facts §5.1, §5.3 item 10), so the USB driver needs
/// them; every other driver keeps to the 32-bit words.
template <class A>
concept HalfwordAccess = RegisterAccess<A> &&
    requires(A& io, std::uint32_t address, std::uint16_t value) {
      { io.read16(address) } -> std::same_as<std::uint16_t>;
      io.write16(address, value);
    };

template <RegisterAccess A>
std::uint32_t read(A& io, const Register& reg) {
  return io.read(reg.address());
}

template <RegisterAccess A>
std::uint32_t read_field(A& io, const Register& reg, const Field& field) {
  return field.decode(io.read(reg.address()));
}

/// Read-modify-write of one field, the other bits kept.
template <RegisterAccess A>
void write_field(A& io, const Register& reg, const Field& field, std::uint32_t value) {
  const std::uint32_t word = io.read(reg.address());
  io.write(reg.address(), (word & ~field.mask()) | field.encode(value));
}

}  // namespace palp::stm32
