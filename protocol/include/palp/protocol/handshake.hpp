// SPDX-License-Identifier: Apache-2.0
// The handshake verdict (SPEC.md §8): what a host and a device that exchanged Hello/DeviceInfo
// may do together. Portable: the firmware judges the host's Hello with the same function.
#pragma once

#include <iterator>

#include "palp/protocol/messages.hpp"
#include "palp/protocol/schema.hpp"

namespace palp::proto {

struct ProtocolVersion {
  u8 major = 0;
  u8 minor = 0;
  u32 schema_hash = 0;
  constexpr bool operator==(const ProtocolVersion&) const = default;
};

/// This build's protocol version and schema hash.
inline constexpr ProtocolVersion kThisProtocol{kProtocolMajor, kProtocolMinor, kSchemaHash};

enum class Compatibility : u8 {
  compatible,                ///< everything the host knows, the device knows
  compatible_missing_features,  ///< same major; the device's minor is older: some host features are absent
  incompatible,              ///< only identify, version and enter-bootloader may be used
};

/// Why a verdict is incompatible (none when it is not).
enum class IncompatibleBecause : u8 {
  none,
  major_differs,        ///< different major versions
  unstable_minor,       ///< major 0 (no compatibility promise) and the minors differ
  schema_differs,       ///< same major.minor but different schema hashes: an unreleased build
};

struct Verdict {
  Compatibility compatibility = Compatibility::incompatible;
  IncompatibleBecause because = IncompatibleBecause::none;
};

/// Judges a host against a device. Rules, in the order they are applied:
///  1. different majors: incompatible (major_differs);
///  2. same minor: equal hashes compatible, different hashes incompatible (schema_differs);
///  3. major 0 (no compatibility promise) and different minors: incompatible (unstable_minor);
///  4. host minor newer than the device's: compatible_missing_features;
///  5. device minor newer than the host's: compatible (the host uses a subset).
constexpr Verdict judge(const ProtocolVersion& host, const ProtocolVersion& device) {
  if (host.major != device.major)
    return {Compatibility::incompatible, IncompatibleBecause::major_differs};
  if (host.minor == device.minor) {
    if (host.schema_hash != device.schema_hash)
      return {Compatibility::incompatible, IncompatibleBecause::schema_differs};
    return {Compatibility::compatible, IncompatibleBecause::none};
  }
  if (host.major == 0) return {Compatibility::incompatible, IncompatibleBecause::unstable_minor};
  if (host.minor > device.minor)
    return {Compatibility::compatible_missing_features, IncompatibleBecause::none};
  return {Compatibility::compatible, IncompatibleBecause::none};
}

/// Calls f(message, field) for every feature of this build that a peer speaking `peer_minor`
/// (same major) lacks: f(m, nullptr) for a whole message added after peer_minor, f(m, &field)
/// for a trailing field added after peer_minor to a message the peer has.
template <class F>
constexpr void for_each_feature_newer_than(const MessageInfo* begin, const MessageInfo* end,
                                           u8 peer_minor, F&& f) {
  for (const MessageInfo* it = begin; it != end; ++it) {
    const MessageInfo& m = *it;
    if (m.since > peer_minor) {
      f(m, static_cast<const FieldInfo*>(nullptr));
      continue;
    }
    for (std::size_t k = 0; k < m.field_count; ++k)
      if (m.fields[k].since > peer_minor) f(m, &m.fields[k]);
  }
}
/// The same over this build's catalogue.
template <class F>
constexpr void for_each_feature_newer_than(u8 peer_minor, F&& f) {
  for_each_feature_newer_than(std::begin(kMessages), std::end(kMessages), peer_minor, f);
}

}  // namespace palp::proto
