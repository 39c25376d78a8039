// SPDX-License-Identifier: Apache-2.0
// The handshake verdict in words: what a person reads when a host and a device do not match.
#pragma once

#include <string>
#include <vector>

#include "palp/protocol/handshake.hpp"

namespace palp::proto {

/// "Message" or "Message.field" for every feature of this build that a same-major peer speaking
/// peer_minor lacks (handshake.hpp, for_each_feature_newer_than).
std::vector<std::string> missing_feature_names(u8 peer_minor);
std::vector<std::string> missing_feature_names(const MessageInfo* begin, const MessageInfo* end,
                                               u8 peer_minor);

/// One paragraph for a verdict of `host` against the device described by `device`:
/// compatible; compatible without the named features; or incompatible, naming the firmware
/// version, both protocol versions and schema hashes, and the command that fixes it.
std::string describe_verdict(const Verdict& verdict, const ProtocolVersion& host,
                             const DeviceInfo& device,
                             const std::vector<std::string>& missing_features);

/// "0.1" and "0x1234abcd" spellings used in every message.
std::string version_text(u8 major, u8 minor);
std::string hash_text(u32 hash);

}  // namespace palp::proto
