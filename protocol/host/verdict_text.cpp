// SPDX-License-Identifier: Apache-2.0
#include "palp/protocol/verdict_text.hpp"

#include <cstdio>
#include <iterator>

namespace palp::proto {

std::string version_text(u8 major, u8 minor) {
  return std::to_string(major) + "." + std::to_string(minor);
}

std::string hash_text(u32 hash) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "0x%08x", hash);
  return buf;
}

std::vector<std::string> missing_feature_names(const MessageInfo* begin, const MessageInfo* end,
                                               u8 peer_minor) {
  std::vector<std::string> out;
  for_each_feature_newer_than(begin, end, peer_minor, [&](const MessageInfo& m, const FieldInfo* f) {
    out.push_back(f == nullptr ? std::string(m.name) : std::string(m.name) + "." + f->name);
  });
  return out;
}

std::vector<std::string> missing_feature_names(u8 peer_minor) {
  return missing_feature_names(std::begin(kMessages), std::end(kMessages), peer_minor);
}

namespace {
std::string text_of(const char* bytes, std::size_t n) {
  std::size_t len = 0;
  while (len < n && bytes[len] != '\0') ++len;
  return len == 0 ? std::string("unknown") : std::string(bytes, len);
}
}  // namespace

std::string describe_verdict(const Verdict& verdict, const ProtocolVersion& host,
                             const DeviceInfo& d, const std::vector<std::string>& missing) {
  const std::string dev_proto = version_text(d.protocol_major, d.protocol_minor);
  const std::string host_proto = version_text(host.major, host.minor);
  const std::string firmware = std::to_string(d.fw_major) + "." + std::to_string(d.fw_minor) +
                               "." + std::to_string(d.fw_patch) + ", git " +
                               text_of(d.git_hash.bytes.data(), d.git_hash.bytes.size());
  const std::string device = "device " + text_of(d.serial.bytes.data(), d.serial.bytes.size()) +
                             " (board " + text_of(d.board.bytes.data(), d.board.bytes.size()) +
                             ", firmware " + firmware + ")";
  const std::string sides = device + " speaks protocol " + dev_proto + " with schema " +
                            hash_text(d.schema_hash) + "; this SDK speaks protocol " + host_proto +
                            " with schema " + hash_text(host.schema_hash);
  switch (verdict.compatibility) {
    case Compatibility::compatible:
      return "compatible: " + sides + ".";
    case Compatibility::compatible_missing_features: {
      std::string list;
      for (const std::string& f : missing) list += (list.empty() ? "" : ", ") + f;
      return "compatible with missing features: " + sides + ". The firmware lacks: " +
             (list.empty() ? std::string("(none listed)") : list) +
             ". Flash firmware that speaks protocol " + host_proto + " to use them.";
    }
    case Compatibility::incompatible:
      break;
  }
  std::string why;
  switch (verdict.because) {
    case IncompatibleBecause::major_differs: why = "the major versions differ"; break;
    case IncompatibleBecause::unstable_minor:
      why = "protocol 0.x makes no compatibility promise and the minor versions differ";
      break;
    case IncompatibleBecause::schema_differs:
      why = "the versions match but the schema hashes differ, so one side is an unreleased build";
      break;
    case IncompatibleBecause::none: why = "of an unknown reason"; break;
  }
  const bool device_older = d.protocol_major < host.major ||
                            (d.protocol_major == host.major && d.protocol_minor < host.minor);
  const bool device_newer = d.protocol_major > host.major ||
                            (d.protocol_major == host.major && d.protocol_minor > host.minor);
  std::string fix;
  const std::string flash =
      "put the device in its bootloader (palp EnterBootloader; the controller then enumerates as "
      "the STM32 ROM DFU device) and flash it: dfu-util -a 0 -s 0x08000000:leave -D "
      "palp-firmware-protocol-" + host_proto + ".bin";
  if (device_newer) {
    fix = "Update the palp SDK to a release that speaks protocol " + dev_proto +
          ", or flash firmware that speaks protocol " + host_proto + ": " + flash + ".";
  } else if (device_older) {
    fix = "Flash firmware that speaks protocol " + host_proto + " (schema " +
          hash_text(host.schema_hash) + "): " + flash + ".";
  } else {
    fix = "Flash firmware built from the same palp source as this SDK (schema " +
          hash_text(host.schema_hash) + "): " + flash + ".";
  }
  return "incompatible: " + sides + ": " + why + ". " + fix +
         " Until then the device answers only identify, version and enter-bootloader.";
}

}  // namespace palp::proto
