// SPDX-License-Identifier: Apache-2.0
// The catalogue's integrity and its schema hash.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "palp/protocol/codec.hpp"
#include "palp/protocol/schema.hpp"
#include "palp/protocol/spec_tables.hpp"

namespace palp::proto {
namespace {

TEST(Schema, HashIsTheCrc32OfTheCanonicalText) {
  const std::string text = canonical_schema_text();
  EXPECT_EQ(crc32(reinterpret_cast<const u8*>(text.data()), text.size()), kSchemaHash);
}

TEST(Schema, CanonicalTextOpensWithTheVersionAndSpellsFieldsAsSpecified) {
  const std::string text = canonical_schema_text();
  EXPECT_EQ(text.rfind("palp-protocol 1.1\nenum ErrorCode u16\n value 0 ok\n", 0), 0u);
  EXPECT_NE(text.find("message 0x25 LoadContactWatch h2d since 0 reply Ack\n"
                      " field Sf32 hold_current_A since 0 default 0.5 range -4 4 unit \"A\"\n"
                      " field Su32 threshold_counts since 0 default 200 range 1 100000 unit "
                      "\"counts\"\n"),
            std::string::npos);
  EXPECT_NE(text.find(" field Vi32[16] kf_position_counts since 0 default 0 range NOLIM NOLIM "
                      "unit \"counts\"\n"),
            std::string::npos);
  EXPECT_NE(text.find(" field Tchar[24] serial since 0"), std::string::npos);
  EXPECT_EQ(text.back(), '\n');
}

TEST(Catalogue, MessageIdsAndNamesAreUnique) {
  std::set<int> ids;
  std::set<std::string> names;
  for (const MessageInfo& m : kMessages) {
    EXPECT_TRUE(ids.insert(static_cast<int>(m.id)).second) << m.name;
    EXPECT_TRUE(names.insert(m.name).second) << m.name;
    EXPECT_NE(static_cast<int>(m.id), 0) << m.name;
  }
}

TEST(Catalogue, FrozenIdsAreExactlyIdentifyVersionBootloaderAndTheirReplies) {
  std::set<std::string> frozen;
  for (const MessageInfo& m : kMessages)
    if (is_frozen_id(static_cast<u8>(m.id))) frozen.insert(m.name);
  EXPECT_EQ(frozen, (std::set<std::string>{"Hello", "DeviceInfo", "GetDeviceInfo",
                                           "EnterBootloader", "Ack", "Nak"}));
}

TEST(Catalogue, EveryRequestIsAnsweredByADeviceMessageAndNoDeviceMessageExpectsAReply) {
  for (const MessageInfo& m : kMessages) {
    if (m.direction == Direction::H2D) {
      const MessageInfo* reply = find_message(static_cast<u8>(m.reply));
      ASSERT_NE(reply, nullptr) << m.name;
      EXPECT_EQ(reply->direction, Direction::D2H) << m.name;
    } else {
      EXPECT_EQ(m.reply, MessageId::None) << m.name;
    }
  }
}

TEST(Catalogue, NoFieldIsNewerThanTheProtocolOrOlderThanItsMessage) {
  for (const MessageInfo& m : kMessages) {
    EXPECT_LE(m.since, kProtocolMinor) << m.name;
    for (std::size_t k = 0; k < m.field_count; ++k) {
      EXPECT_LE(m.fields[k].since, kProtocolMinor) << m.name << "." << m.fields[k].name;
      EXPECT_GE(m.fields[k].since, m.since) << m.name << "." << m.fields[k].name;
    }
  }
}

TEST(Catalogue, EnumValuesAreUniqueWithinEachEnum) {
  for_each_enum([](auto info) {
    using I = decltype(info);
    std::set<u32> values;
    for (const auto& v : I::values) EXPECT_TRUE(values.insert(v.value).second) << I::name;
  });
}

TEST(Catalogue, UnitsInFieldNamesMatchTheirUnitColumn) {
  // DESIGN.md: the unit is in the name. A field ending in _A has unit "A", and so on.
  const std::pair<const char*, const char*> suffixes[] = {
      {"_A", "A"}, {"_s", "s"}, {"_Hz", "Hz"}, {"_us", "us"}, {"_ns", "ns"}, {"_ms", "ms"},
      {"_V", "V"}, {"_Pa", "Pa"}, {"_counts", "counts"}, {"_A2s", "A^2*s"},
      {"_N_per_A", "N/A"}, {"_N_per_m", "N/m"}, {"_bytes_per_s", "bytes/s"}};
  int checked = 0;
  for (const MessageInfo& m : kMessages) {
    for (std::size_t k = 0; k < m.field_count; ++k) {
      const std::string name = m.fields[k].name;
      std::string best_suffix, best_unit;  // the longest matching suffix decides
      for (const auto& [suffix, unit] : suffixes) {
        const std::string s = suffix;
        if (name.size() > s.size() && name.compare(name.size() - s.size(), s.size(), s) == 0 &&
            s.size() > best_suffix.size()) {
          best_suffix = s;
          best_unit = unit;
        }
      }
      if (best_suffix.empty()) continue;
      EXPECT_EQ(std::string(m.fields[k].unit), best_unit) << m.name << "." << name;
      ++checked;
    }
  }
  EXPECT_GT(checked, 50);
}

}  // namespace
}  // namespace palp::proto
