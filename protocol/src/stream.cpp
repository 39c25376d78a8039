// SPDX-License-Identifier: Apache-2.0
#include "palp/protocol/stream.hpp"

#include <type_traits>

namespace palp::proto {

namespace {
constexpr bool has(u16 mask, Channel c) { return (mask & (1u << static_cast<u8>(c))) != 0; }
}  // namespace

u8* detail::pack_channels(u8* p, const RawSample& s, u16 mask) {
  auto put = [&p](auto value) {
    using U = std::make_unsigned_t<decltype(value)>;
    const auto bits = static_cast<U>(value);
    for (std::size_t k = 0; k < sizeof(U); ++k) *p++ = static_cast<u8>(bits >> (8 * k));
  };
  if (has(mask, Channel::i_cmd)) put(s.i_cmd);
  if (has(mask, Channel::i_meas)) put(s.i_meas);
  if (has(mask, Channel::encoder)) put(s.encoder);
  for (u8 k = 0; k < 6; ++k)
    if (has(mask, static_cast<Channel>(static_cast<u8>(Channel::p1) + k))) put(s.pressure[k]);
  if (has(mask, Channel::status)) put(s.status);
  if (has(mask, Channel::v_cmd)) put(s.v_cmd);
  return p;
}

void pack_sample(Writer& w, const RawSample& s, u16 mask) {
  u8* p = w.claim(bytes_per_sample(mask));  // one bounds check for the whole sample
  if (p != nullptr) pack_sample_at(p, s, mask);
}

bool unpack_sample(Reader& r, RawSample& s, u16 mask) {
  s = RawSample{};
  bool ok = true;
  if (has(mask, Channel::i_cmd)) ok = ok && r.scalar(s.i_cmd);
  if (has(mask, Channel::i_meas)) ok = ok && r.scalar(s.i_meas);
  if (has(mask, Channel::encoder)) ok = ok && r.scalar(s.encoder);
  for (u8 k = 0; k < 6; ++k)
    if (has(mask, static_cast<Channel>(static_cast<u8>(Channel::p1) + k)))
      ok = ok && r.scalar(s.pressure[k]);
  if (has(mask, Channel::status)) ok = ok && r.scalar(s.status);
  if (has(mask, Channel::v_cmd)) ok = ok && r.scalar(s.v_cmd);
  return ok;
}

}  // namespace palp::proto
