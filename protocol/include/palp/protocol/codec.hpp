// SPDX-License-Identifier: Apache-2.0
// Payload encoding and decoding, written once over every message's visit().
//
// Encoding: fields in catalogue order, little-endian; A arrays element by element; V arrays a
// u16 count then the elements; T text exactly n bytes. Decoding is the inverse, with the
// compatibility rules of SPEC.md §8: a payload longer than this build knows is accepted (the
// extra bytes are a newer peer's trailing fields); a payload that ends exactly before a field
// added after the message (since > message since) leaves that field and all after it at their
// defaults; ending anywhere else is short_payload; a count beyond its bound is bad_field.
#pragma once

#include <cstddef>
#include <type_traits>

#include "palp/protocol/messages.hpp"
#include "palp/protocol/reject.hpp"

namespace palp::proto {

namespace detail {
template <class T>
void put(Writer& w, const T& value) {
  if constexpr (is_wire_scalar_v<T>) {
    w.scalar(value);
  } else if constexpr (requires { value.bytes; }) {
    w.bytes(value.bytes.data(), value.bytes.size());
  } else if constexpr (requires { value.items; }) {
    w.scalar(value.size);
    const std::size_t n = value.size < value.items.size() ? value.size : value.items.size();
    if constexpr (std::is_same_v<std::remove_cvref_t<decltype(value.items[0])>, u8>) {
      w.bytes(value.items.data(), n);  // bytes are their own encoding: one copy
    } else {
      for (std::size_t k = 0; k < n; ++k) put(w, value.items[k]);
    }
  } else {
    for (const auto& x : value) put(w, x);
  }
}

template <class T>
Reject get(Reader& r, T& value) {
  if constexpr (is_wire_scalar_v<T>) {
    return r.scalar(value) ? Reject::ok : Reject::short_payload;
  } else if constexpr (requires { value.bytes; }) {
    return r.bytes(value.bytes.data(), value.bytes.size()) ? Reject::ok : Reject::short_payload;
  } else if constexpr (requires { value.items; }) {
    u16 n = 0;
    if (!r.scalar(n)) return Reject::short_payload;
    if (n > value.items.size()) return Reject::bad_field;
    value.size = n;
    if constexpr (std::is_same_v<std::remove_cvref_t<decltype(value.items[0])>, u8>) {
      return r.bytes(value.items.data(), n) ? Reject::ok : Reject::short_payload;
    } else {
      for (u16 k = 0; k < n; ++k)
        if (Reject e = get(r, value.items[k]); e != Reject::ok) return e;
      return Reject::ok;
    }
  } else {
    for (auto& x : value)
      if (Reject e = get(r, x); e != Reject::ok) return e;
    return Reject::ok;
  }
}

template <class T>
constexpr std::size_t wire_size_max(const T& value) {
  if constexpr (is_wire_scalar_v<T>) return sizeof(T);
  else if constexpr (requires { value.bytes; }) return value.bytes.size();
  else if constexpr (requires { value.items; }) return 2 + value.items.size() * sizeof(value.items[0]);
  else return value.size() * sizeof(value[0]);
}
template <class T>
constexpr std::size_t wire_size_min(const T& value) {
  if constexpr (requires { value.items; }) return 2;
  else return wire_size_max(value);
}
}  // namespace detail

/// Encodes m's payload into out[0, capacity). Returns the payload size, or -1 if it does not fit.
template <class M>
int encode_payload(const M& m, u8* out, std::size_t capacity) {
  Writer w(out, capacity);
  m.visit([&](const FieldInfo&, const auto& field) { detail::put(w, field); });
  return w.ok() ? static_cast<int>(w.size()) : -1;
}

/// Decodes a payload into out (reset to defaults first). Reject::ok on success.
template <class M>
Reject decode_payload(const u8* data, std::size_t size, M& out) {
  out = M{};
  Reader r(data, size);
  Reject result = Reject::ok;
  bool ended = false;
  out.visit([&](const FieldInfo& info, auto& field) {
    if (result != Reject::ok || ended) return;
    if (r.remaining() == 0 && info.since > M::kSince) {
      ended = true;  // an older peer: this and every later field keep their defaults
      return;
    }
    result = detail::get(r, field);
  });
  return result;
}

/// Smallest payload a decoder accepts for M: every field the message had when it was added.
template <class M>
constexpr std::size_t min_payload_size() {
  std::size_t n = 0;
  const M m{};
  m.visit([&](const FieldInfo& info, const auto& field) {
    if (info.since <= M::kSince) n += detail::wire_size_min(field);
  });
  return n;
}
/// Largest payload this build encodes for M.
template <class M>
constexpr std::size_t max_payload_size() {
  std::size_t n = 0;
  const M m{};
  m.visit([&](const FieldInfo&, const auto& field) { n += detail::wire_size_max(field); });
  return n;
}

/// Decodes the payload of message `id` into a value of its type and calls v(value).
/// Returns unknown_message for an id this build does not know; v is called only on success.
template <class Visitor>
Reject decode_message(u8 id, const u8* payload, std::size_t size, Visitor&& v) {
  switch (id) {
#define PALP_X_CASE(Name, mid, dir, since, reply, doc)                  \
  case mid: {                                                           \
    Name m;                                                             \
    const Reject e = decode_payload(payload, size, m);                  \
    if (e == Reject::ok) v(static_cast<const Name&>(m));                \
    return e;                                                           \
  }
    PALP_MESSAGES(PALP_X_CASE)
#undef PALP_X_CASE
    default:
      return Reject::unknown_message;
  }
}

}  // namespace palp::proto
