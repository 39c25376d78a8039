// SPDX-License-Identifier: Apache-2.0
#include "palp/protocol/spec_tables.hpp"

#include <cstdio>

#include "palp/protocol/codec.hpp"
#include "palp/protocol/examples.hpp"
#include "palp/protocol/text.hpp"
#include "palp/protocol/verdict_text.hpp"
#include "palp/protocol/schema.hpp"
#include "palp/protocol/stream.hpp"

namespace palp::proto {

namespace {

std::string type_text(const FieldInfo& f) {
  const std::string t = f.type;
  switch (f.kind) {
    case 'A': return t + "[" + std::to_string(f.count) + "]";
    case 'V': return "u16 count + up to " + std::to_string(f.count) + " × " + t;
    case 'T': return "text[" + std::to_string(f.count) + "]";
    case 'E': return t;
    default: return t;
  }
}

std::string range_text(const FieldInfo& f) {
  const std::string lo = f.lo_text, hi = f.hi_text;
  if (lo == "NOLIM" && hi == "NOLIM") return "";
  return (lo == "NOLIM" ? std::string("…") : lo) + " … " + (hi == "NOLIM" ? std::string("…") : hi);
}

std::string default_text(const FieldInfo& f) {
  std::string d = f.default_text;
  const std::size_t colons = d.rfind("::");
  if (colons != std::string::npos) d = d.substr(colons + 2);
  if (f.kind == 'V') return "empty";
  if (f.kind == 'T') return "\"\"";
  return d;
}

template <class M>
std::size_t min_size(const M&) { return min_payload_size<M>(); }
template <class M>
std::size_t max_size(const M&) { return max_payload_size<M>(); }

}  // namespace

std::string spec_message_tables() {
  std::string out;
  for_each_message_type([&](auto m) {
    using M = decltype(m);
    char head[200];
    std::snprintf(head, sizeof head, "#### 0x%02X %s (%s, since %u.%u%s%s)\n\n",
                  static_cast<unsigned>(M::kId), M::kName,
                  M::kDirection == Direction::H2D ? "host → device" : "device → host",
                  kProtocolMajor, M::kSince, M::kReply == MessageId::None ? "" : ", reply ",
                  M::kReply == MessageId::None ? "" : message_name(M::kReply));
    out += head;
    out += M::kDoc;
    out += " Payload " + std::to_string(min_size(m)) + "–" + std::to_string(max_size(m)) +
           " bytes.\n\n";
    if (M::kFields.size() == 0) {
      out += "No fields.\n\n";
      return;
    }
    out += "| # | field | type | unit | range | default | since | meaning |\n";
    out += "|---|---|---|---|---|---|---|---|\n";
    std::size_t index = 0;
    for (const FieldInfo& f : M::kFields) {
      out += "| " + std::to_string(index++) + " | `" + f.name + "` | " + type_text(f) + " | " +
             f.unit + " | " + range_text(f) + " | " + default_text(f) + " | " +
             std::to_string(kProtocolMajor) + "." + std::to_string(f.since) + " | " + f.doc +
             " |\n";
    }
    out += "\n";
  });
  return out;
}

std::string spec_enum_tables() {
  std::string out;
  for_each_enum([&](auto info) {
    using I = decltype(info);
    out += std::string("#### ") + I::name + " (" + I::type + ")\n\n" + I::doc + "\n\n";
    out += "| value | name | meaning |\n|---|---|---|\n";
    for (const auto& v : I::values)
      out += "| " + std::to_string(v.value) + " | `" + v.name + "` | " + v.doc + " |\n";
    out += "\n";
  });
  return out;
}

std::string spec_stream_rates() {
  struct Row {
    const char* channels;
    u16 mask;
  };
  const Row masks[] = {{"all 11", kAllChannels},
                       {"i_meas, encoder", 0x0006},
                       {"i_cmd, i_meas, encoder, status", 0x0207},
                       {"i_meas, encoder, p1–p6", 0x01FE}};
  const double rates[] = {1000, 2000, 5000, 10000};
  std::string out =
      "| channels | bytes/sample | rate (Hz) | samples/batch | batches/s | wire bytes/s |\n"
      "|---|---|---|---|---|---|\n";
  for (const Row& r : masks) {
    for (double rate : rates) {
      // the batch size the SDK chooses by default: 4 ms of samples, at most one full batch
      std::size_t n = static_cast<std::size_t>(rate * 0.004);
      if (n < 1) n = 1;
      if (n > max_batch_samples(r.mask)) n = max_batch_samples(r.mask);
      char row[200];
      std::snprintf(row, sizeof row, "| %s | %zu | %.0f | %zu | %.1f | %u |\n", r.channels,
                    bytes_per_sample(r.mask), rate, n, rate / static_cast<double>(n),
                    stream_wire_bytes_per_s(r.mask, rate, n));
      out += row;
    }
  }
  return out;
}

std::string canonical_schema_text() {
  struct StringSink {
    std::string s;
    void put(char c) { s += c; }
  } sink;
  write_canonical_schema(sink);
  return sink.s;
}

std::string spec_verdict_example() {
  DeviceInfo d = examples_device_info();
  d.protocol_major = static_cast<u8>(kProtocolMajor - 1);  // firmware of the previous major
  d.protocol_minor = 9;
  d.schema_hash = 0x11111111u;
  const ProtocolVersion dv{d.protocol_major, d.protocol_minor, d.schema_hash};
  return "```text\n" +
         describe_verdict(judge(kThisProtocol, dv), kThisProtocol, d,
                          missing_feature_names(d.protocol_minor)) +
         "\n```\n";
}

// The worked example of golden vector `label`: header, a table of every field's bytes (unless
// with_fields is false: the SPEC then explains the payload by hand, and a test checks its bytes),
// CRC and wire bytes.
std::string spec_example(const std::string& label, bool with_fields) {
  std::string out;
  for_each_golden([&](const std::string& name, const auto& m, u16 seq, u8 flags) {
    if (name != label || !out.empty()) return;
    using M = std::decay_t<decltype(m)>;
    std::vector<u8> payload(kMaxPayload);
    payload.resize(static_cast<std::size_t>(encode_payload(m, payload.data(), payload.size())));
    char line[200];
    std::snprintf(line, sizeof line,
                  "Header: major %u, minor %u, id 0x%02X (`%s`), flags 0x%02X, seq %u, "
                  "payload_len %zu.\n",
                  kProtocolMajor, kProtocolMinor, static_cast<unsigned>(M::kId), M::kName, flags,
                  seq, payload.size());
    out = line;
    if (with_fields) out += "\n| bytes | field | value |\n|---|---|---|\n";
    m.visit([&](const FieldInfo& f, const auto& value) {
      if (!with_fields) return;
      std::array<u8, kMaxPayload> bytes;
      Writer w(bytes.data(), bytes.size());
      detail::put(w, value);
      std::string value_text = detail::format_value(value);
      if constexpr (std::is_same_v<std::decay_t<decltype(value)>, u32>) {
        if (std::string(f.name).find("hash") != std::string::npos) {
          char hex[16];
          std::snprintf(hex, sizeof hex, "0x%08x", value);
          value_text = hex;
        }
      }
      out += "| `" + to_hex({bytes.data(), w.size()}) + "` | `" + f.name + "` | " + value_text +
             " |\n";
    });
    std::vector<u8> wire(kMaxWireFrame);
    wire.resize(encode_message(m, seq, flags, wire.data(), wire.size()));
    const std::size_t body = kHeaderSize + payload.size();
    std::vector<u8> raw = {kProtocolMajor, kProtocolMinor, static_cast<u8>(M::kId), flags,
                           static_cast<u8>(seq), static_cast<u8>(seq >> 8),
                           static_cast<u8>(payload.size()), static_cast<u8>(payload.size() >> 8)};
    raw.insert(raw.end(), payload.begin(), payload.end());
    std::snprintf(line, sizeof line, "\nCRC 0x%08x. Wire (%zu bytes):\n\n```\n",
                  crc32(raw.data(), body), wire.size());
    out += line;
    for (std::size_t k = 0; k < wire.size(); k += 32)
      out += to_hex({wire.data() + k, std::min<std::size_t>(32, wire.size() - k)}) + "\n";
    out += "```\n";
  });
  return out;
}

std::string spec_block(const std::string& name) {
  if (name.rfind("example ", 0) == 0) return spec_example(name.substr(8), true);
  if (name.rfind("example-frame ", 0) == 0) return spec_example(name.substr(14), false);
  if (name == "verdict-example") return spec_verdict_example();
  if (name == "version") {
    char text[160];
    std::snprintf(text, sizeof text,
                  "- This document describes **protocol %u.%u** (major %u, minor %u), schema hash "
                  "`0x%08x` (§7.3).\n",
                  kProtocolMajor, kProtocolMinor, kProtocolMajor, kProtocolMinor, kSchemaHash);
    return text;
  }
  if (name == "messages") return spec_message_tables();
  if (name == "enums") return spec_enum_tables();
  if (name == "stream-rates") return spec_stream_rates();
  if (name == "schema") {
    char hash[64];
    std::snprintf(hash, sizeof hash, "Schema hash of this catalogue: `0x%08x`.\n\n", kSchemaHash);
    return hash + std::string("```text\n") + canonical_schema_text() + "```\n";
  }
  return "";
}

std::string refresh_spec(const std::string& spec, std::string& error) {
  std::string out;
  std::size_t pos = 0;
  const std::string begin_tag = "<!-- BEGIN GENERATED ";
  while (true) {
    const std::size_t b = spec.find(begin_tag, pos);
    if (b == std::string::npos) break;
    const std::size_t name_end = spec.find(" -->", b);
    if (name_end == std::string::npos) {
      error = "unterminated BEGIN GENERATED marker";
      return "";
    }
    const std::string name = spec.substr(b + begin_tag.size(), name_end - b - begin_tag.size());
    const std::string end_tag = "<!-- END GENERATED " + name + " -->";
    const std::size_t e = spec.find(end_tag, name_end);
    if (e == std::string::npos) {
      error = "no '" + end_tag + "' after its BEGIN marker";
      return "";
    }
    const std::string block = spec_block(name);
    if (block.empty()) {
      error = "unknown generated block '" + name + "'";
      return "";
    }
    out += spec.substr(pos, name_end + 4 - pos) + "\n" + block;
    pos = e;
  }
  out += spec.substr(pos);
  return out;
}

}  // namespace palp::proto
