// SPDX-License-Identifier: Apache-2.0
// Payload codec: round trips of every catalogue message, exact bytes, defaults, the
// compatibility rules for longer and shorter payloads, bounded arrays and range checks.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "palp/protocol/codec.hpp"
#include "palp/protocol/examples.hpp"
#include "palp/protocol/frame.hpp"
#include "palp/protocol/text.hpp"

namespace palp::proto {
namespace {

template <class M>
std::vector<u8> payload_of(const M& m) {
  std::vector<u8> out(kMaxPayload);
  const int n = encode_payload(m, out.data(), out.size());
  EXPECT_GE(n, 0) << M::kName;
  out.resize(static_cast<std::size_t>(n < 0 ? 0 : n));
  return out;
}

TEST(Codec, EveryMessageRoundTripsWithEveryFieldSet) {
  int messages = 0;
  for_each_message_type([&](auto prototype) {
    using M = decltype(prototype);
    for (u32 salt : {1u, 2u, 3u, 1000u}) {
      const M original = filled_example<M>(salt);
      const std::vector<u8> bytes = payload_of(original);
      M decoded;
      ASSERT_EQ(decode_payload(bytes.data(), bytes.size(), decoded), Reject::ok) << M::kName;
      EXPECT_EQ(decoded, original) << M::kName << " salt " << salt << "\n"
                                   << format_fields(original) << "decoded:\n"
                                   << format_fields(decoded);
    }
    ++messages;
  });
  EXPECT_EQ(messages, static_cast<int>(std::size(kMessages)));
}

TEST(Codec, EveryMessagePayloadSizeLiesBetweenItsMinimumAndMaximum) {
  for_each_message_type([&](auto prototype) {
    using M = decltype(prototype);
    const std::size_t n = payload_of(filled_example<M>(5)).size();
    EXPECT_GE(n, min_payload_size<M>()) << M::kName;
    EXPECT_LE(n, max_payload_size<M>()) << M::kName;
    EXPECT_LE(max_payload_size<M>(), kMaxPayload) << M::kName << " cannot fit a frame";
  });
}

TEST(Codec, LoadRampEncodesToTheExactLittleEndianBytes) {
  LoadRamp r;
  r.start_A = 0.5f;     // 0x3F000000
  r.stop_A = 3.0f;      // 0x40400000
  r.step_A = 0.01f;     // 0x3C23D70A
  r.dwell_s = 0.025f;   // 0x3CCCCCCD
  r.repetitions = 3;
  r.unload = 1;
  r.displacement_limit_counts = 5000;  // 0x00001388
  EXPECT_EQ(to_hex(payload_of(r)),
            "00 00 00 3f 00 00 40 40 0a d7 23 3c cd cc cc 3c 03 00 01 88 13 00 00");
}

TEST(Codec, TextFieldsAreExactlyTheirLengthAndZeroPadded) {
  Hello h;
  h.host_software = "ab";
  const std::vector<u8> bytes = payload_of(h);
  ASSERT_EQ(bytes.size(), 1u + 1u + 4u + 16u);
  EXPECT_EQ(bytes[6], 'a');
  EXPECT_EQ(bytes[7], 'b');
  for (std::size_t k = 8; k < bytes.size(); ++k) EXPECT_EQ(bytes[k], 0) << k;
}

TEST(Codec, ATextFieldFilledToItsLengthHasNoTerminatorAndRoundTrips) {
  Hello h;
  h.host_software = "0123456789abcdefXYZ";  // 19 characters: kept to 16
  EXPECT_EQ(h.host_software.length(), 16u);
  const std::vector<u8> bytes = payload_of(h);
  Hello back;
  ASSERT_EQ(decode_payload(bytes.data(), bytes.size(), back), Reject::ok);
  EXPECT_EQ(std::string(back.host_software.bytes.data(), 16), "0123456789abcdef");
}

TEST(Codec, DefaultsAreTheCatalogueDefaults) {
  EXPECT_EQ(LoadContactWatch{}.threshold_counts, 200u);  // paper §II-B
  EXPECT_EQ(Params{}.heartbeat_timeout_ms, 500u);
  EXPECT_EQ(Params{}.control_rate_Hz, 20000u);
  EXPECT_FLOAT_EQ(Params{}.supply_V, 24.0f);
  EXPECT_FLOAT_EQ(LoadSweep{}.step_Hz, 0.05f);           // paper §IV-B
  EXPECT_EQ(LoadMultisine{}.line_first, 41);             // 2.05 Hz at 0.05 Hz
  EXPECT_EQ(Nak{}.field_index, 255);
  for (f32 g : Calibration{}.pressure_gain) EXPECT_FLOAT_EQ(g, 1.0f);
  EXPECT_FLOAT_EQ(Calibration{}.spring_k_N_per_m, 43.9f);  // 0.0439 N/mm, paper §II-A
}

TEST(Codec, DecodingResetsFieldsToDefaultsFirst) {
  Params p = filled_example<Params>(3);
  const std::vector<u8> bytes = payload_of(Params{});
  ASSERT_EQ(decode_payload(bytes.data(), bytes.size(), p), Reject::ok);
  EXPECT_EQ(p, Params{});
}

TEST(Codec, ALongerPayloadFromANewerPeerIsAcceptedAndItsExtraBytesIgnored) {
  const LoadHold hold{1.25f, 2.5f};
  std::vector<u8> bytes = payload_of(hold);
  bytes.insert(bytes.end(), {0xAA, 0xBB, 0xCC});  // fields a later minor added
  LoadHold back;
  ASSERT_EQ(decode_payload(bytes.data(), bytes.size(), back), Reject::ok);
  EXPECT_EQ(back, hold);
}

TEST(Codec, EveryCutShortOfTheRequiredFieldsIsShortPayload) {
  for_each_message_type([&](auto prototype) {
    using M = decltype(prototype);
    const std::vector<u8> bytes = payload_of(filled_example<M>(9));
    for (std::size_t cut = 0; cut < bytes.size(); ++cut) {
      M back;
      const Reject r = decode_payload(bytes.data(), cut, back);
      // a cut inside a bounded array's elements may instead look like a smaller count: never ok
      ASSERT_NE(r, Reject::ok) << M::kName << " cut at " << cut << " of " << bytes.size();
      EXPECT_EQ(r, Reject::short_payload) << M::kName << " cut at " << cut;
    }
  });
}

// A message as a later minor version would have it: field `a` from minor 1, `b` and `c` added
// in minor 2. Written by hand with the interface the catalogue generates.
struct Evolving {
  static constexpr u8 kSince = 1;
  static constexpr std::array<FieldInfo, 3> kFields = {{
      {"a", 'S', "u16", 1, 1, "0", "NOLIM", "NOLIM", "", ""},
      {"b", 'S', "u32", 1, 2, "42", "NOLIM", "NOLIM", "", ""},
      {"c", 'V', "u8", 4, 2, "0", "NOLIM", "NOLIM", "", ""},
  }};
  u16 a = 0;
  u32 b = 42;
  Vec<u8, 4> c{};
  template <class V>
  void visit(V&& v) {
    v(kFields[0], a);
    v(kFields[1], b);
    v(kFields[2], c);
  }
  template <class V>
  void visit(V&& v) const {
    v(kFields[0], a);
    v(kFields[1], b);
    v(kFields[2], c);
  }
  bool operator==(const Evolving&) const = default;
};

TEST(Codec, TrailingFieldsAddedInALaterMinorTakeTheirDefaultsWhenAnOlderPeerOmitsThem) {
  const u8 minor1[] = {0x34, 0x12};  // a = 0x1234 only
  Evolving e;
  e.b = 7;
  ASSERT_EQ(decode_payload(minor1, sizeof minor1, e), Reject::ok);
  EXPECT_EQ(e.a, 0x1234);
  EXPECT_EQ(e.b, 42u);
  EXPECT_EQ(e.c.size, 0);
}

TEST(Codec, ATrailingFieldCutInTheMiddleIsShortPayload) {
  const u8 bytes[] = {0x34, 0x12, 0x01, 0x02};  // b needs 4 bytes
  Evolving e;
  EXPECT_EQ(decode_payload(bytes, sizeof bytes, e), Reject::short_payload);
}

TEST(Codec, ATrailingFieldPresentIsDecodedAndLaterOnesDefaulted) {
  const u8 bytes[] = {0x34, 0x12, 0x05, 0x00, 0x00, 0x00};
  Evolving e;
  ASSERT_EQ(decode_payload(bytes, sizeof bytes, e), Reject::ok);
  EXPECT_EQ(e.b, 5u);
  EXPECT_EQ(e.c.size, 0);
}

TEST(Codec, ABoundedArrayCountBeyondItsCapacityIsBadField) {
  const u8 bytes[] = {0x34, 0x12, 0x05, 0x00, 0x00, 0x00, 0x05, 0x00, 1, 2, 3, 4, 5};
  Evolving e;
  EXPECT_EQ(decode_payload(bytes, sizeof bytes, e), Reject::bad_field);
}

TEST(Codec, ABoundedArrayAtItsCapacityDecodes) {
  const u8 bytes[] = {0x34, 0x12, 0x05, 0x00, 0x00, 0x00, 0x04, 0x00, 1, 2, 3, 4};
  Evolving e;
  ASSERT_EQ(decode_payload(bytes, sizeof bytes, e), Reject::ok);
  ASSERT_EQ(e.c.size, 4);
  EXPECT_EQ(e.c.items[3], 4);
}

TEST(Codec, EncodingIntoATooSmallBufferFailsWithoutWritingPastIt) {
  const DeviceInfo info = examples_device_info();
  std::vector<u8> buf(20 + 8, 0xEE);
  EXPECT_EQ(encode_payload(info, buf.data(), 20), -1);
  for (std::size_t k = 20; k < buf.size(); ++k) EXPECT_EQ(buf[k], 0xEE);
}

TEST(Codec, AnUnknownMessageIdIsRejectedWithoutCallingTheVisitor) {
  const u8 payload[] = {1, 2, 3};
  bool called = false;
  EXPECT_EQ(decode_message(0xEE, payload, sizeof payload, [&](const auto&) { called = true; }),
            Reject::unknown_message);
  EXPECT_FALSE(called);
}

TEST(Codec, DecodeMessageHandsTheTypedMessageToTheVisitor) {
  const LoadSine sine{1.0f, 0.1f, 7.5f, 20};
  const std::vector<u8> bytes = payload_of(sine);
  LoadSine seen{};
  int calls = 0;
  ASSERT_EQ(decode_message(static_cast<u8>(MessageId::LoadSine), bytes.data(), bytes.size(),
                           [&](const auto& m) {
                             if constexpr (std::is_same_v<std::decay_t<decltype(m)>, LoadSine>)
                               seen = m;
                             ++calls;
                           }),
            Reject::ok);
  EXPECT_EQ(calls, 1);
  EXPECT_EQ(seen, sine);
}

TEST(Codec, UnknownEnumValuesFromANewerPeerAreKeptNotRejected) {
  Nak n;
  n.error = static_cast<ErrorCode>(999);
  const std::vector<u8> bytes = payload_of(n);
  Nak back;
  ASSERT_EQ(decode_payload(bytes.data(), bytes.size(), back), Reject::ok);
  EXPECT_EQ(static_cast<u16>(back.error), 999);
  EXPECT_EQ(enum_name(back.error), nullptr);
  EXPECT_STREQ(enum_name(ErrorCode::out_of_range), "out_of_range");
}

// ---- range checks --------------------------------------------------------------------------

TEST(Ranges, DefaultsOfEveryHostToDeviceMessageAreInRange) {
  for_each_message_type([&](auto m) {
    using M = decltype(m);
    if constexpr (M::kDirection == Direction::H2D) {
      EXPECT_EQ(m.first_out_of_range(), -1) << M::kName;
    }
  });
}

TEST(Ranges, HeartbeatTimeoutMustLieBetween50MsAnd10S) {
  const int index = field_index_of<&SetParams::heartbeat_timeout_ms>();
  SetParams p;
  p.heartbeat_timeout_ms = 49;
  EXPECT_EQ(p.first_out_of_range(), index);
  p.heartbeat_timeout_ms = 50;
  EXPECT_EQ(p.first_out_of_range(), -1);
  p.heartbeat_timeout_ms = 10000;
  EXPECT_EQ(p.first_out_of_range(), -1);
  p.heartbeat_timeout_ms = 10001;
  EXPECT_EQ(p.first_out_of_range(), index);
}

TEST(Ranges, NaNIsOutOfRange) {
  SetParams p;
  p.current_clamp_A = std::numeric_limits<f32>::quiet_NaN();
  EXPECT_EQ(p.first_out_of_range(), 0);
}

TEST(Ranges, EveryElementOfAnArrayIsChecked) {
  const int index = field_index_of<&SetCalibration::kf_N_per_A>();
  SetCalibration c;
  c.kf_N_per_A.push_back(2.918f);
  c.kf_N_per_A.push_back(25.0f);  // beyond 20 N/A
  EXPECT_EQ(c.first_out_of_range(), index);
  c.kf_N_per_A.items[1] = 3.84f;
  EXPECT_EQ(c.first_out_of_range(), -1);
}

TEST(Ranges, AnOpenUpperBoundAcceptsTheTypesMaximum) {
  LoadMultisine m;
  m.phase_seed = 0xFFFFFFFFu;
  EXPECT_EQ(m.first_out_of_range(), -1);
  m.phase_seed = 0;  // the generator needs a non-zero seed
  EXPECT_EQ(m.first_out_of_range(), field_index_of<&LoadMultisine::phase_seed>());
}

}  // namespace
}  // namespace palp::proto

namespace palp::proto {
namespace {

TEST(Ranges, AnF32ExactlyAtItsBoundIsAccepted) {
  LoadRamp r;
  r.step_A = 0.0001f;
  r.dwell_s = 0.0001f;
  EXPECT_EQ(r.first_out_of_range(), -1);
  LoadSine s;
  s.frequency_Hz = 0.01f;
  EXPECT_EQ(s.first_out_of_range(), -1);
  s.frequency_Hz = 0.0099f;
  EXPECT_EQ(s.first_out_of_range(), 2);
}

TEST(Codec, TextCutToItsLengthNeverSplitsAUtf8Character) {
  const Str<4> fits("ab\xc3\xa9\xc3\xa9");  // "abéé": the first é ends at byte 4
  EXPECT_EQ(fits.length(), 4u);
  EXPECT_EQ(fits.bytes[3], '\xa9');
  const Str<3> cut("ab\xc3\xa9");  // é would be cut after its first byte: left out whole
  EXPECT_EQ(cut.length(), 2u);
  EXPECT_EQ(cut.bytes[2], '\0');
}

}  // namespace
}  // namespace palp::proto
