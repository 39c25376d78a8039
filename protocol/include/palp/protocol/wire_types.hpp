// SPDX-License-Identifier: Apache-2.0
// Wire types of the palp protocol: the scalar aliases the catalogue names, fixed strings,
// fixed arrays and bounded arrays, and the little-endian reader/writer every codec uses.
//
// Freestanding: no heap, no exceptions, no RTTI; builds for the host and for Cortex-M4.
#pragma once

#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>

namespace palp::proto {

using u8 = std::uint8_t;
using u16 = std::uint16_t;
using u32 = std::uint32_t;
using u64 = std::uint64_t;
using i8 = std::int8_t;
using i16 = std::int16_t;
using i32 = std::int32_t;
using i64 = std::int64_t;
using f32 = float;

static_assert(sizeof(f32) == 4, "f32 must be IEEE-754 binary32");

/// A fixed-size text field: exactly N bytes on the wire, UTF-8, padded with zero bytes.
/// A string of N bytes has no terminator on the wire.
template <std::size_t N>
struct Str {
  std::array<char, N> bytes{};

  constexpr Str() = default;
  constexpr Str(const char* text) { assign(text); }  // NOLINT: implicit from literals is the point

  /// Copies text, cut to N bytes; a UTF-8 character that would be cut is left out whole.
  constexpr void assign(const char* text) {
    bytes = {};
    if (text == nullptr) return;
    std::size_t n = 0;
    for (; n < N && text[n] != '\0'; ++n) bytes[n] = text[n];
    // drop a trailing UTF-8 sequence whose lead byte promises more bytes than were kept
    std::size_t lead = n;
    while (lead > 0 && n - lead < 4 && (static_cast<unsigned char>(bytes[lead - 1]) & 0xC0) == 0x80)
      --lead;
    if (lead == 0) return;
    const auto b = static_cast<unsigned char>(bytes[lead - 1]);
    const std::size_t need = b < 0x80 ? 1 : (b >= 0xF0 ? 4 : (b >= 0xE0 ? 3 : (b >= 0xC0 ? 2 : 1)));
    if (lead - 1 + need > n)
      for (std::size_t k = lead - 1; k < n; ++k) bytes[k] = '\0';
  }
  /// Number of bytes before the first zero (at most N).
  constexpr std::size_t length() const {
    std::size_t n = 0;
    while (n < N && bytes[n] != '\0') ++n;
    return n;
  }
  constexpr bool operator==(const Str&) const = default;
};

/// A bounded array: a u16 element count on the wire, then that many elements. At most N.
template <class T, std::size_t N>
struct Vec {
  u16 size = 0;
  std::array<T, N> items{};

  static constexpr std::size_t capacity = N;
  constexpr bool push_back(const T& value) {
    if (size >= N) return false;
    items[size++] = value;
    return true;
  }
  constexpr const T* begin() const { return items.data(); }
  constexpr const T* end() const { return items.data() + size; }
  constexpr bool operator==(const Vec& other) const {
    if (size != other.size) return false;
    for (std::size_t k = 0; k < size; ++k)
      if (!(items[k] == other.items[k])) return false;
    return true;
  }
};

/// A fixed-length array: exactly N elements on the wire, no count.
template <class T, std::size_t N>
using Arr = std::array<T, N>;

template <class T>
inline constexpr bool is_wire_scalar_v =
    (std::is_integral_v<T> && !std::is_same_v<T, bool>) || std::is_same_v<T, f32> ||
    std::is_enum_v<T>;

/// Writes little-endian values into a caller-owned buffer; never writes past its end.
/// After an overflow ok() is false and the contents are unspecified.
class Writer {
 public:
  constexpr Writer(u8* data, std::size_t capacity) : data_(data), capacity_(capacity) {}

  template <class T>
  constexpr void scalar(T value) {
    static_assert(is_wire_scalar_v<T>);
    if constexpr (std::is_enum_v<T>) {
      scalar(static_cast<std::underlying_type_t<T>>(value));
    } else if constexpr (std::is_same_v<T, f32>) {
      scalar(std::bit_cast<u32>(value));
    } else {
      using U = std::make_unsigned_t<T>;
      const U bits = static_cast<U>(value);
      if (!reserve(sizeof(T))) return;
      for (std::size_t k = 0; k < sizeof(T); ++k)
        data_[size_ + k] = static_cast<u8>(bits >> (8 * k));
      size_ += sizeof(T);
    }
  }
  void bytes(const void* src, std::size_t n) {
    if (!reserve(n)) return;
    std::memcpy(data_ + size_, src, n);
    size_ += n;
  }
  /// Room for n more bytes, for the caller to fill: where they start, or nullptr (and the writer
  /// has failed) when they do not fit.
  constexpr u8* claim(std::size_t n) {
    if (!reserve(n)) return nullptr;
    u8* p = data_ + size_;
    size_ += n;
    return p;
  }
  constexpr std::size_t size() const { return size_; }
  constexpr bool ok() const { return ok_; }

 private:
  constexpr bool reserve(std::size_t n) {
    if (!ok_ || capacity_ - size_ < n) {
      ok_ = false;
      return false;
    }
    return true;
  }
  u8* data_;
  std::size_t capacity_;
  std::size_t size_ = 0;
  bool ok_ = true;
};

/// Reads little-endian values from a byte range; a read past the end fails and reads nothing.
class Reader {
 public:
  constexpr Reader(const u8* data, std::size_t size) : data_(data), size_(size) {}

  template <class T>
  constexpr bool scalar(T& out) {
    static_assert(is_wire_scalar_v<T>);
    if constexpr (std::is_enum_v<T>) {
      std::underlying_type_t<T> raw{};
      if (!scalar(raw)) return false;
      out = static_cast<T>(raw);
      return true;
    } else if constexpr (std::is_same_v<T, f32>) {
      u32 bits = 0;
      if (!scalar(bits)) return false;
      out = std::bit_cast<f32>(bits);
      return true;
    } else {
      using U = std::make_unsigned_t<T>;
      if (remaining() < sizeof(T)) return false;
      U bits = 0;
      for (std::size_t k = 0; k < sizeof(T); ++k)
        bits = static_cast<U>(bits | (static_cast<U>(data_[pos_ + k]) << (8 * k)));
      pos_ += sizeof(T);
      out = static_cast<T>(bits);
      return true;
    }
  }
  bool bytes(void* dst, std::size_t n) {
    if (remaining() < n) return false;
    std::memcpy(dst, data_ + pos_, n);
    pos_ += n;
    return true;
  }
  constexpr std::size_t remaining() const { return size_ - pos_; }
  constexpr std::size_t position() const { return pos_; }

 private:
  const u8* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
};

}  // namespace palp::proto
