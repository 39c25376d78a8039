// SPDX-License-Identifier: Apache-2.0
// The protocol's enums and message structs, expanded from catalogue.hpp.
//
// Every message is a plain struct with its fields as members (initialised to the catalogue's
// defaults) and a compile-time description: kId, kName, kDirection, kSince, kReply, kFields,
// and visit(), which hands each field with its FieldInfo to a visitor. The codec, the schema
// hash, the range checks and the text printer are all written once over visit().
//
// Freestanding: no heap, no exceptions, no RTTI.
#pragma once

#include <array>
#include <cstddef>
#include <iterator>

#include "palp/protocol/catalogue.hpp"
#include "palp/protocol/wire_types.hpp"

namespace palp::proto {

inline constexpr u8 kProtocolMajor = PALP_PROTOCOL_MAJOR;
inline constexpr u8 kProtocolMinor = PALP_PROTOCOL_MINOR;
/// EnterBootloader.magic: the bytes 42 4f 4f 54, 'BOOT' little-endian (SPEC.md §6.2); any other
/// value is refused with bad_magic.
inline constexpr u32 kBootloaderMagic = 0x544F4F42u;

/// "No limit" marker of the catalogue's lo/hi columns.
struct NoLimit {};
inline constexpr NoLimit NOLIM{};

// ---- enums ---------------------------------------------------------------------------------
#define PALP_X_ENUM_VALUE(name, value, doc) name = value,
#define PALP_X_ENUM_DECL(Name, type, doc) \
  enum class Name : type { PALP_ENUM_##Name(PALP_X_ENUM_VALUE) };
PALP_ENUMS(PALP_X_ENUM_DECL)
#undef PALP_X_ENUM_DECL
#undef PALP_X_ENUM_VALUE

struct EnumValueInfo {
  const char* name;
  u32 value;
  const char* doc;
};

template <class E>
struct EnumInfo;  // name, type, doc, values: specialised for every catalogue enum

#define PALP_X_ENUM_VALUE_INFO(name, value, doc) EnumValueInfo{#name, value, doc},
#define PALP_X_ENUM_INFO(Name, utype, edoc)                                      \
  template <>                                                                    \
  struct EnumInfo<Name> {                                                        \
    static constexpr const char* name = #Name;                                   \
    static constexpr const char* type = #utype;                                  \
    static constexpr const char* doc = edoc;                                     \
    static constexpr EnumValueInfo values[] = {PALP_ENUM_##Name(PALP_X_ENUM_VALUE_INFO)}; \
  };
PALP_ENUMS(PALP_X_ENUM_INFO)
#undef PALP_X_ENUM_INFO
#undef PALP_X_ENUM_VALUE_INFO

/// The catalogue name of an enum value, or nullptr for a value this build does not know
/// (a newer peer may send values added in a later minor version).
template <class E>
constexpr const char* enum_name(E value) {
  for (const auto& v : EnumInfo<E>::values)
    if (v.value == static_cast<u32>(value)) return v.name;
  return nullptr;
}

/// Calls f(EnumInfo<E>{}) for every catalogue enum, in catalogue order.
template <class F>
constexpr void for_each_enum(F&& f) {
#define PALP_X_ENUM_EACH(Name, type, doc) f(EnumInfo<Name>{});
  PALP_ENUMS(PALP_X_ENUM_EACH)
#undef PALP_X_ENUM_EACH
}

// ---- message ids -----------------------------------------------------------------------------
enum class Direction : u8 { H2D, D2H };

enum class MessageId : u8 {
  None = 0,
#define PALP_X_ID(Name, id, dir, since, reply, doc) Name = id,
  PALP_MESSAGES(PALP_X_ID)
#undef PALP_X_ID
};

/// Ids 0x01-0x0F are frozen across major versions (SPEC.md §6.1).
constexpr bool is_frozen_id(u8 id) { return id >= 0x01 && id <= 0x0F; }

// ---- field descriptions ----------------------------------------------------------------------
struct FieldInfo {
  const char* name;
  char kind;         // 'S' scalar, 'E' enum, 'A' fixed array, 'V' bounded array, 'T' text
  const char* type;  // element type as spelled in the catalogue
  u16 count;         // elements (A), capacity (V), bytes (T), 1 otherwise
  u8 since;          // minor version that added the field
  const char* default_text;
  const char* lo_text;
  const char* hi_text;
  const char* unit;
  const char* doc;
};

namespace detail {
template <class T, std::size_t N, class V>
constexpr Arr<T, N> filled(V value) {
  Arr<T, N> a{};
  for (auto& x : a) x = static_cast<T>(value);
  return a;
}
}  // namespace detail

#define PALP_MEMBER_TYPE_S(type, n) type
#define PALP_MEMBER_TYPE_E(type, n) type
#define PALP_MEMBER_TYPE_A(type, n) ::palp::proto::Arr<type, n>
#define PALP_MEMBER_TYPE_V(type, n) ::palp::proto::Vec<type, n>
#define PALP_MEMBER_TYPE_T(type, n) ::palp::proto::Str<n>
#define PALP_MEMBER_INIT_S(type, n, def) static_cast<type>(def)
#define PALP_MEMBER_INIT_E(type, n, def) def
#define PALP_MEMBER_INIT_A(type, n, def) ::palp::proto::detail::filled<type, n>(def)
#define PALP_MEMBER_INIT_V(type, n, def) \
  {}
#define PALP_MEMBER_INIT_T(type, n, def) \
  {}

#define PALP_X_MEMBER(kind, type, n, name, since, def, lo, hi, unit, doc) \
  PALP_MEMBER_TYPE_##kind(type, n) name = PALP_MEMBER_INIT_##kind(type, n, def);
#define PALP_X_FIELD_INFO(kind, type, n, name, since, def, lo, hi, unit, doc) \
  FieldInfo{#name, (#kind)[0], #type, n, since, #def, #lo, #hi, unit, doc},
#define PALP_X_VISIT(kind, type, n, name, since, def, lo, hi, unit, doc) v(kFields[i++], name);
#define PALP_X_RANGE(kind, type, n, name, since, def, lo, hi, unit, doc) \
  if (!::palp::proto::detail::in_range(name, lo, hi)) return static_cast<int>(i);   \
  ++i;

namespace detail {
constexpr bool below(double v, double lo) { return !(v >= lo); }  // NaN is out of range
template <class T, class L, class H>
constexpr bool scalar_in_range(const T& value, const L& lo, const H& hi) {
  if constexpr (std::is_enum_v<T>) {
    return true;  // unknown enum values are judged by the command handler
  } else {
    // bounds are taken in the field's own type, so an f32 field accepts the f32 nearest its
    // bound (0.0001f is below the double 0.0001)
    const auto bound = [](const auto& b) {
      if constexpr (std::is_floating_point_v<T>) return static_cast<double>(static_cast<T>(b));
      else return static_cast<double>(b);
    };
    const double v = static_cast<double>(value);
    if (v != v) return false;
    if constexpr (!std::is_same_v<L, NoLimit>)
      if (below(v, bound(lo))) return false;
    if constexpr (!std::is_same_v<H, NoLimit>)
      if (!(v <= bound(hi))) return false;
    return true;
  }
}
template <class T, class L, class H>
constexpr bool in_range(const T& value, const L& lo, const H& hi) {
  if constexpr (is_wire_scalar_v<T>) {
    return scalar_in_range(value, lo, hi);
  } else if constexpr (requires { value.bytes; }) {
    return true;  // text
  } else if constexpr (requires { value.items; }) {
    for (u16 k = 0; k < value.size; ++k)
      if (!scalar_in_range(value.items[k], lo, hi)) return false;
    return true;
  } else {
    for (const auto& x : value)
      if (!scalar_in_range(x, lo, hi)) return false;
    return true;
  }
}
}  // namespace detail

/// Whether messages A and B carry the same field list: the same names, kinds, types and sizes in
/// the same order (the catalogue gives SetParams the fields of Params, SetCalibration those of
/// Calibration).
template <class A, class B>
consteval bool same_fields() {
  constexpr auto same_text = [](const char* x, const char* y) {
    for (; *x != 0 && *x == *y; ++x) ++y;
    return *x == *y;
  };
  if (A::kFields.size() != B::kFields.size()) return false;
  for (std::size_t k = 0; k < A::kFields.size(); ++k) {
    const FieldInfo& a = A::kFields[k];
    const FieldInfo& b = B::kFields[k];
    if (!same_text(a.name, b.name) || a.kind != b.kind || !same_text(a.type, b.type) ||
        a.count != b.count)
      return false;
  }
  return true;
}

// ---- message structs -------------------------------------------------------------------------
#define PALP_X_STRUCT(Name, id, dir, since, reply, doc)                                     \
  struct Name {                                                                             \
    static constexpr MessageId kId = MessageId::Name;                                       \
    static constexpr const char* kName = #Name;                                             \
    static constexpr Direction kDirection = Direction::dir;                                 \
    static constexpr u8 kSince = since;                                                     \
    static constexpr MessageId kReply = MessageId::reply;                                   \
    static constexpr const char* kDoc = doc;                                                \
    static constexpr std::array<FieldInfo, 0 PALP_FIELDS_##Name(PALP_X_COUNT)> kFields = {  \
        {PALP_FIELDS_##Name(PALP_X_FIELD_INFO)}};                                           \
    PALP_FIELDS_##Name(PALP_X_MEMBER)                                                       \
                                                                                            \
    template <class V>                                                                      \
    constexpr void visit([[maybe_unused]] V&& v) {                                          \
      [[maybe_unused]] std::size_t i = 0;                                                   \
      PALP_FIELDS_##Name(PALP_X_VISIT)                                                      \
    }                                                                                       \
    template <class V>                                                                      \
    constexpr void visit([[maybe_unused]] V&& v) const {                                    \
      [[maybe_unused]] std::size_t i = 0;                                                   \
      PALP_FIELDS_##Name(PALP_X_VISIT)                                                      \
    }                                                                                       \
    /** Index of the first field outside its catalogue range, or -1 when all are valid. */ \
    constexpr int first_out_of_range() const {                                              \
      [[maybe_unused]] std::size_t i = 0;                                                   \
      PALP_FIELDS_##Name(PALP_X_RANGE) return -1;                                           \
    }                                                                                       \
    /** Copies every field of a message with the same field list (same_fields; use  */     \
    /** fields_as). */                                                                      \
    template <class Other>                                                                  \
      requires(same_fields<Name, Other>())                                                  \
    constexpr void assign_fields([[maybe_unused]] const Other& o) {                         \
      PALP_FIELDS_##Name(PALP_X_ASSIGN)                                                     \
    }                                                                                       \
    constexpr bool operator==(const Name&) const = default;                                 \
  };
#define PALP_X_COUNT(...) +1
#define PALP_X_ASSIGN(kind, type, n, name, since, def, lo, hi, unit, doc) name = o.name;
PALP_MESSAGES(PALP_X_STRUCT)
#undef PALP_X_ASSIGN
#undef PALP_X_COUNT
#undef PALP_X_STRUCT

// ---- fields named at compile time ------------------------------------------------------------
namespace detail {
template <class P>
struct member_of;
template <class C, class T>
struct member_of<T C::*> {
  using type = C;
};
void not_a_catalogue_field();  // never defined: reaching it in field_index_of does not compile
}  // namespace detail

/// The zero-based catalogue index of a message field named by its member pointer: the number
/// Nak.field_index carries (SPEC.md §5.5, the `#` of §10.1), e.g.
/// `field_index_of<&LoadSweep::stop_Hz>()` is 3. Found at compile time by walking the message's
/// visit() for the member's address, so it follows the catalogue when fields are renamed,
/// reordered or inserted: no field number is ever written by hand.
template <auto Member>
consteval u8 field_index_of() {
  using M = typename detail::member_of<decltype(Member)>::type;
  const M m{};
  const void* const target = &(m.*Member);
  int found = -1;
  int k = 0;
  m.visit([&](const FieldInfo&, const auto& field) {
    if (static_cast<const void*>(&field) == target) found = k;
    ++k;
  });
  if (found < 0) detail::not_a_catalogue_field();
  return static_cast<u8>(found);
}

/// `from` as message type To with the same field list, every field copied
/// (`fields_as<Params>(set_params)`); does not compile when the field lists differ.
template <class To, class From>
  requires(same_fields<From, To>())
constexpr To fields_as(const From& from) {
  To to;
  to.assign_fields(from);
  return to;
}

// ---- the catalogue as data -------------------------------------------------------------------
struct MessageInfo {
  MessageId id;
  const char* name;
  Direction direction;
  u8 since;
  MessageId reply;
  const char* doc;
  const FieldInfo* fields;
  std::size_t field_count;
};

inline constexpr MessageInfo kMessages[] = {
#define PALP_X_INFO(Name, id, dir, since, reply, doc)                                      \
  MessageInfo{MessageId::Name, #Name, Direction::dir, since, MessageId::reply, doc, \
              Name::kFields.data(), Name::kFields.size()},
    PALP_MESSAGES(PALP_X_INFO)
#undef PALP_X_INFO
};

/// Index of a message id in kMessages, or -1 when this build does not know it.
constexpr int message_index(u8 id) {
  for (std::size_t k = 0; k < std::size(kMessages); ++k)
    if (static_cast<u8>(kMessages[k].id) == id) return static_cast<int>(k);
  return -1;
}
/// The catalogue entry of a message id, or nullptr when this build does not know it.
constexpr const MessageInfo* find_message(u8 id) {
  const int k = message_index(id);
  return k < 0 ? nullptr : &kMessages[k];
}
/// The catalogue name of a message id, or nullptr when this build does not know it.
constexpr const char* message_name(MessageId id) {
  const int k = message_index(static_cast<u8>(id));
  return k < 0 ? nullptr : kMessages[k].name;
}

/// Calls f(Name{}) with a default-constructed value of every message type, in catalogue order.
template <class F>
constexpr void for_each_message_type(F&& f) {
#define PALP_X_EACH(Name, id, dir, since, reply, doc) f(Name{});
  PALP_MESSAGES(PALP_X_EACH)
#undef PALP_X_EACH
}

}  // namespace palp::proto
