// SPDX-License-Identifier: Apache-2.0
// The robot bridge's register map expanded from map.hpp: enums, the block structs, and the one
// encoder and decoder between them and Modbus register arrays (protocol/robot-bridge.md).
// Used by the SDK's Modbus client and by the bridge emulator alike.
//
// 32-bit values are two registers, high word first, two's complement; they are never split
// across two requests because every block is read or written in one request. No floats.
// Freestanding: no heap, no exceptions, no RTTI.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <type_traits>

#include "palp/protocol/robot_bridge/map.hpp"

namespace palp::proto::rb {

using u16 = std::uint16_t;
using u32 = std::uint32_t;
using i32 = std::int32_t;

inline constexpr u16 kMapMajor = PALP_RB_MAP_MAJOR;
inline constexpr u16 kMapMinor = PALP_RB_MAP_MINOR;
inline constexpr u32 kMagic = 0x50414C50u;  // ASCII "PALP"
inline constexpr u16 kDefaultPort = 30005;  // the KLI allows 30000..30010 only
inline constexpr u16 kMaxReadRegisters = 125;   // Modbus FC3 (Read Holding Registers)
inline constexpr u16 kMaxWriteRegisters = 123;  // Modbus FC16 (Write Multiple Registers)
inline constexpr u16 kDefaultWatchdogMs = 500;
inline constexpr u16 kMinWatchdogMs = 100;
inline constexpr u16 kMaxWatchdogMs = 10000;

// ---- int32 <-> two registers ----------------------------------------------------------------
/// The high register of v (two's complement).
constexpr u16 hi_word(u32 v) { return static_cast<u16>(v >> 16); }
constexpr u16 lo_word(u32 v) { return static_cast<u16>(v & 0xFFFFu); }
constexpr u32 to_u32(u16 hi, u16 lo) { return (static_cast<u32>(hi) << 16) | lo; }
constexpr void put_i32(i32 v, u16* out) {
  out[0] = hi_word(static_cast<u32>(v));
  out[1] = lo_word(static_cast<u32>(v));
}
constexpr i32 get_i32(const u16* in) { return static_cast<i32>(to_u32(in[0], in[1])); }  // C++20: modular

// ---- enums ----------------------------------------------------------------------------------
#define PALP_RB_X_ENUM_VALUE(name, value, doc) name = value,
#define PALP_RB_X_ENUM_DECL(Name, doc) enum class Name : u16 { PALP_RB_ENUM_##Name(PALP_RB_X_ENUM_VALUE) };
PALP_RB_ENUMS(PALP_RB_X_ENUM_DECL)
#undef PALP_RB_X_ENUM_DECL
#undef PALP_RB_X_ENUM_VALUE

struct EnumValueInfo {
  const char* name;
  u16 value;
  const char* doc;
};

template <class E>
struct EnumInfo;

#define PALP_RB_X_ENUM_VALUE_INFO(name, value, doc) EnumValueInfo{#name, value, doc},
#define PALP_RB_X_ENUM_INFO(Name, edoc)                                                   \
  template <>                                                                             \
  struct EnumInfo<Name> {                                                                 \
    static constexpr const char* name = #Name;                                            \
    static constexpr const char* doc = edoc;                                              \
    static constexpr EnumValueInfo values[] = {PALP_RB_ENUM_##Name(PALP_RB_X_ENUM_VALUE_INFO)}; \
  };
PALP_RB_ENUMS(PALP_RB_X_ENUM_INFO)
#undef PALP_RB_X_ENUM_INFO
#undef PALP_RB_X_ENUM_VALUE_INFO

/// The map's name of an enum value, or nullptr for a value this build does not know.
template <class E>
constexpr const char* enum_name(E value) {
  for (const auto& v : EnumInfo<E>::values)
    if (v.value == static_cast<u16>(value)) return v.name;
  return nullptr;
}

template <class F>
constexpr void for_each_enum(F&& f) {
#define PALP_RB_X_ENUM_EACH(Name, doc) f(EnumInfo<Name>{});
  PALP_RB_ENUMS(PALP_RB_X_ENUM_EACH)
#undef PALP_RB_X_ENUM_EACH
}

constexpr u16 bit(GuardSource b) { return static_cast<u16>(1u << static_cast<u16>(b)); }
constexpr u16 bit(StatusBit b) { return static_cast<u16>(1u << static_cast<u16>(b)); }

// ---- register types -------------------------------------------------------------------------
enum class RegType : u16 { uint16, int32, uint32, enum16 };

template <class T>
struct RegTraits {  // the enums
  static_assert(std::is_enum_v<T>);
  static constexpr RegType reg_type = RegType::enum16;
  static constexpr u16 count = 1;
};
template <>
struct RegTraits<u16> {
  static constexpr RegType reg_type = RegType::uint16;
  static constexpr u16 count = 1;
};
template <>
struct RegTraits<i32> {
  static constexpr RegType reg_type = RegType::int32;
  static constexpr u16 count = 2;
};
template <>
struct RegTraits<u32> {
  static constexpr RegType reg_type = RegType::uint32;
  static constexpr u16 count = 2;
};

struct RegisterInfo {
  const char* name;
  RegType type;
  const char* enum_name;  // for enum16: the enum's name; else nullptr
  u16 count;              // registers: 1 or 2
  const char* unit;
  const char* doc;
};

constexpr const char* type_name(const RegisterInfo& r) {
  switch (r.type) {
    case RegType::uint16: return "u16";
    case RegType::int32: return "i32";
    case RegType::uint32: return "u32";
    case RegType::enum16: return r.enum_name;
  }
  return "?";
}

template <class T>
constexpr const char* enum_name_of() {
  if constexpr (std::is_enum_v<T>) return EnumInfo<T>::name;
  else return nullptr;
}

template <std::size_t N>
constexpr u16 total_registers(const RegisterInfo (&fields)[N]) {
  u16 n = 0;
  for (const RegisterInfo& f : fields) n = static_cast<u16>(n + f.count);
  return n;
}

// ---- the blocks -----------------------------------------------------------------------------
#define PALP_RB_X_MEMBER(type, name, unit, doc) type name{};
#define PALP_RB_X_REG_INFO(type, name, unit, doc) \
  RegisterInfo{#name, RegTraits<type>::reg_type, enum_name_of<type>(), RegTraits<type>::count, unit, doc},
#define PALP_RB_X_VISIT(type, name, unit, doc) f(s.name);
#define PALP_RB_X_BLOCK(Name, address, access, doc)                                          \
  struct Name {                                                                              \
    PALP_RB_FIELDS_##Name(PALP_RB_X_MEMBER)                                                  \
    static constexpr const char* kName = #Name;                                              \
    static constexpr const char* kAccess = access;                                           \
    static constexpr const char* kDoc = doc;                                                 \
    static constexpr u16 kAddress = address;                                                 \
    static constexpr RegisterInfo kRegisters[] = {PALP_RB_FIELDS_##Name(PALP_RB_X_REG_INFO)}; \
    static constexpr u16 kLength = total_registers(kRegisters);                              \
    template <class S, class F>                                                              \
    static constexpr void visit(S& s, F&& f) {                                               \
      PALP_RB_FIELDS_##Name(PALP_RB_X_VISIT)                                                 \
    }                                                                                        \
    friend constexpr bool operator==(const Name&, const Name&) = default;                    \
  };
PALP_RB_BLOCKS(PALP_RB_X_BLOCK)
#undef PALP_RB_X_BLOCK
#undef PALP_RB_X_VISIT
#undef PALP_RB_X_REG_INFO
#undef PALP_RB_X_MEMBER

/// Calls f(Block{}) for every block, in address order.
template <class F>
constexpr void for_each_block(F&& f) {
#define PALP_RB_X_BLOCK_EACH(Name, address, access, doc) f(Name{});
  PALP_RB_BLOCKS(PALP_RB_X_BLOCK_EACH)
#undef PALP_RB_X_BLOCK_EACH
}

template <class B>
constexpr bool fits_one_request() {
  return B::kLength <= kMaxReadRegisters && (B::kAccess[1] != 'W' || B::kLength <= kMaxWriteRegisters);
}
static_assert(fits_one_request<Identification>() && fits_one_request<StatusBlock>() &&
              fits_one_request<HostControl>() && fits_one_request<Command>());
static_assert(Identification::kLength == 10 && StatusBlock::kLength == 53 &&
              HostControl::kLength == 3 && Command::kLength == 24);
static_assert(Identification::kAddress + Identification::kLength <= StatusBlock::kAddress &&
              StatusBlock::kAddress + StatusBlock::kLength <= HostControl::kAddress &&
              HostControl::kAddress + HostControl::kLength <= Command::kAddress);

/// The address of a block's register by name, or 0xFFFF if the block has none of that name.
template <class B>
constexpr u16 address_of(const char* name) {
  u16 at = B::kAddress;
  for (const RegisterInfo& r : B::kRegisters) {
    const char* a = r.name;
    const char* b = name;
    while (*a != 0 && *a == *b) ++a, ++b;
    if (*a == 0 && *b == 0) return at;
    at = static_cast<u16>(at + r.count);
  }
  return 0xFFFF;
}

/// The identification block this build serves.
constexpr Identification this_identification() {
  return Identification{kMagic,           kMapMajor,         kMapMinor,
                        StatusBlock::kAddress, StatusBlock::kLength, HostControl::kAddress,
                        HostControl::kLength,  Command::kAddress,    Command::kLength};
}

// ---- encode / decode ------------------------------------------------------------------------
enum class DecodeError : u16 {
  ok,
  wrong_length,          // the register array is not the block's length
  bad_magic,             // Identification: magic is not 'PALP' (not a palp bridge)
  incompatible_version,  // Identification: map major is not this build's
  bad_enum,              // an enum register holds a value this build does not know
};

constexpr const char* error_name(DecodeError e) {
  switch (e) {
    case DecodeError::ok: return "ok";
    case DecodeError::wrong_length: return "wrong_length";
    case DecodeError::bad_magic: return "bad_magic";
    case DecodeError::incompatible_version: return "incompatible_version";
    case DecodeError::bad_enum: return "bad_enum";
  }
  return "?";
}

struct DecodeResult {
  DecodeError error = DecodeError::ok;
  u16 address = 0;  // the absolute address of the offending register (0 when ok)
  constexpr bool ok() const { return error == DecodeError::ok; }
  friend constexpr bool operator==(const DecodeResult&, const DecodeResult&) = default;
};

template <class E>
constexpr bool enum_valid(u16 raw) {
  for (const auto& v : EnumInfo<E>::values)
    if (v.value == raw) return true;
  return false;
}

/// Writes b into out[0 .. B::kLength): the registers starting at B::kAddress.
template <class B>
constexpr void encode(const B& b, std::span<u16, B::kLength> out) {
  std::size_t at = 0;
  B::visit(b, [&](const auto& v) {
    using T = std::decay_t<decltype(v)>;
    if constexpr (std::is_same_v<T, u16>) {
      out[at++] = v;
    } else if constexpr (std::is_enum_v<T>) {
      out[at++] = static_cast<u16>(v);
    } else {  // i32, u32
      out[at++] = hi_word(static_cast<u32>(v));
      out[at++] = lo_word(static_cast<u32>(v));
    }
  });
}

/// Reads a block from its registers. Lengths other than B::kLength are wrong_length (a host of
/// a newer minor reads the length from the identification block and passes the first kLength).
/// On an error, out holds what was decoded up to the offending register.
template <class B>
constexpr DecodeResult decode(std::span<const u16> in, B& out) {
  if (in.size() != B::kLength) return {DecodeError::wrong_length, B::kAddress};
  DecodeResult result;
  std::size_t at = 0;
  B::visit(out, [&](auto& v) {
    using T = std::decay_t<decltype(v)>;
    const u16 address = static_cast<u16>(B::kAddress + at);
    if (!result.ok()) return;
    if constexpr (std::is_same_v<T, u16>) {
      v = in[at++];
    } else if constexpr (std::is_enum_v<T>) {
      if (!enum_valid<T>(in[at])) result = {DecodeError::bad_enum, address};
      else v = static_cast<T>(in[at++]);
    } else {
      v = static_cast<T>(to_u32(in[at], in[at + 1]));
      at += 2;
    }
  });
  if constexpr (std::is_same_v<B, Identification>) {
    if (result.ok() && out.magic != kMagic) return {DecodeError::bad_magic, B::kAddress};
    if (result.ok() && out.map_major != kMapMajor)
      return {DecodeError::incompatible_version, address_of<Identification>("map_major")};
  }
  return result;
}

}  // namespace palp::proto::rb
