// SPDX-License-Identifier: Apache-2.0
// Example messages with known contents: the source of the golden vectors and of the round-trip
// tests. Every message type appears at least once with every field set to a distinct,
// non-default value ("<Name>.filled"); the messages a lab sees most also appear with realistic
// values taken from the paper's procedures.
#pragma once

#include <string>
#include <vector>

#include "palp/protocol/handshake.hpp"
#include "palp/protocol/messages.hpp"
#include "palp/protocol/stream.hpp"

namespace palp::proto {

namespace detail {
template <class T>
void fill_value(T& v, u32 seed) {
  if constexpr (std::is_enum_v<T>) {
    constexpr auto& vals = EnumInfo<T>::values;
    constexpr std::size_t n = sizeof(vals) / sizeof(vals[0]);
    v = static_cast<T>(vals[(seed % (n > 1 ? n - 1 : 1)) + (n > 1 ? 1 : 0)].value);
  } else if constexpr (std::is_same_v<T, f32>) {
    v = static_cast<f32>(seed % 1000) * 0.25f + 0.5f;  // exact in binary
    if (seed % 3 == 0) v = -v;
  } else if constexpr (std::is_integral_v<T>) {
    const u64 x = static_cast<u64>(seed) * 0x9E3779B97F4A7C15ull;
    v = static_cast<T>(x >> 17);
  } else if constexpr (requires { v.bytes; }) {
    v = {};
    const std::size_t len = (seed % 2 == 0) ? v.bytes.size() : v.bytes.size() / 2;  // full: no terminator
    for (std::size_t k = 0; k < len; ++k) v.bytes[k] = static_cast<char>('a' + (seed + k) % 26);
  } else if constexpr (requires { v.items; }) {
    v.size = static_cast<u16>(std::min<std::size_t>(v.items.size(), 2 + seed % 5));
    for (u16 k = 0; k < v.size; ++k) fill_value(v.items[k], seed * 31 + k + 1);
  } else {
    u32 k = 0;
    for (auto& x : v) fill_value(x, seed * 31 + ++k);
  }
}
}  // namespace detail

/// M with every field set to a distinct value derived from salt (not necessarily in range).
template <class M>
M filled_example(u32 salt = 1) {
  M m{};
  u32 index = 0;
  m.visit([&](const FieldInfo&, auto& field) { detail::fill_value(field, salt * 97 + ++index); });
  return m;
}

/// The DeviceInfo of a palp-sim speaking this build's protocol.
DeviceInfo examples_device_info();

/// The paper's 2D indentation ramp (§V-A): 0.5 -> 3 A by 0.01 A every 25 ms, symmetric unload,
/// 3 repetitions, turning round early after 5000 counts (5 mm).
LoadRamp example_ramp_2d();

/// A SampleBatch of `n` samples with all channels, values from a slow ramp into contact.
SampleBatch example_batch(u32 first_index, u64 first_time_us, u16 n);

/// Calls f(label, message, seq, flags) for every golden example, in a fixed order.
template <class F>
void for_each_golden(F&& f) {
  u16 seq = 0;
  for_each_message_type([&](auto m) {
    using M = decltype(m);
    const u8 flags = M::kDirection == Direction::D2H && M::kId != MessageId::SampleBatch &&
                             static_cast<u8>(M::kId) < 0x40
                         ? kFlagResponse
                         : 0;
    ++seq;
    f(std::string(M::kName) + ".filled", filled_example<M>(seq), seq, flags);
  });

  Hello hello;
  hello.host_major = kProtocolMajor;
  hello.host_minor = kProtocolMinor;
  hello.host_schema_hash = kSchemaHash;
  hello.host_software = "palpctl 0.1.0";
  f("Hello.palpctl", hello, 1, 0);

  f("DeviceInfo.palp_sim", examples_device_info(), 1, kFlagResponse);

  f("LoadRamp.paper_2d", example_ramp_2d(), 7, 0);

  LoadSweep sweep;  // paper §IV-B: 1.0 A + 0.1 A, 2-20 Hz in 0.05 Hz steps
  f("LoadSweep.paper", sweep, 8, 0);

  LoadMultisine multisine;  // 20 s period, lines 4k+1 from 2 to 20 Hz
  f("LoadMultisine.default", multisine, 9, 0);

  LoadContactWatch watch;  // paper §II-B: 200 counts
  f("LoadContactWatch.default", watch, 10, 0);

  Nak nak;
  nak.request_id = static_cast<u8>(MessageId::SetParams);
  nak.error = ErrorCode::out_of_range;
  nak.field_index = field_index_of<&SetParams::heartbeat_timeout_ms>();  // 20 ms: below 50 ms
  f("Nak.heartbeat_too_short", nak, 11, kFlagResponse);

  f("SampleBatch.three_samples", example_batch(4096, 1'234'567'890'123ull, 3), 12, 0);

  EventContact contact;
  contact.time_us = 5'000'000;
  contact.encoder_count = 12'200;
  contact.armed_count = 12'000;
  contact.sample_index = 50'000;
  f("EventContact.threshold_200", contact, 13, 0);

  Nak before_hello;  // SPEC §6.2: the answer to LoadHold (seq 2) from a host that skipped Hello
  before_hello.request_id = static_cast<u8>(MessageId::LoadHold);
  before_hello.error = ErrorCode::hello_required;
  f("Nak.hello_required", before_hello, 2, kFlagResponse);
}

}  // namespace palp::proto
