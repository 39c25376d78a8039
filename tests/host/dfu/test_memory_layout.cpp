// SPDX-License-Identifier: Apache-2.0
// The DfuSe memory-layout string (usb-dfu-facts.md §5.8): the G474 ROM's and the F4 example
// parse to the documented segments; a range is mapped to its pages or refused.
#include <gtest/gtest.h>

#include "dfu_fixture.hpp"

namespace palp::dfutest {
namespace {

using dfu::DfuseError;
using dfu::parse_memory_layout;

TEST(DfuMemoryLayout, G474StringIs256PagesOf2KiBReadableErasableWritable) {
  const dfu::MemoryLayout l = parse_memory_layout("@Internal Flash  /0x08000000/256*02Kg");
  EXPECT_EQ(l.name, "Internal Flash");
  ASSERT_EQ(l.segments.size(), 1u);
  EXPECT_EQ(l.segments[0].start, 0x08000000u);
  EXPECT_EQ(l.segments[0].page_size, 2048u);
  EXPECT_EQ(l.segments[0].pages, 256u);
  EXPECT_TRUE(l.segments[0].readable && l.segments[0].erasable && l.segments[0].writable);
  EXPECT_EQ(l.segments[0].end(), 0x08080000u);
}

TEST(DfuMemoryLayout, F4StringGivesThreeRunsOfSectorsBackToBack) {
  const dfu::MemoryLayout l =
      parse_memory_layout("@Internal Flash  /0x08000000/04*016Kg,01*064Kg,07*128Kg");
  ASSERT_EQ(l.segments.size(), 3u);
  EXPECT_EQ(l.segments[1].start, 0x08010000u);
  EXPECT_EQ(l.segments[1].page_size, 64u * 1024);
  EXPECT_EQ(l.segments[2].start, 0x08020000u);
  EXPECT_EQ(l.segments[2].end(), 0x08100000u);
}

TEST(DfuMemoryLayout, TypeLetterAndSpaceMultiplierFollowTheFormat) {
  const dfu::MemoryLayout l = parse_memory_layout("@Option Bytes   /0x1FFF7800/01*048 e");
  ASSERT_EQ(l.segments.size(), 1u);
  EXPECT_EQ(l.segments[0].page_size, 48u);  // ' ' = bytes
  EXPECT_TRUE(l.segments[0].readable);
  EXPECT_FALSE(l.segments[0].erasable);
  EXPECT_TRUE(l.segments[0].writable);
}

TEST(DfuMemoryLayout, SecondStartAddressBeginsANewRun) {
  const dfu::MemoryLayout l = parse_memory_layout("@X/0x08000000/2*1Ka/0x20000000/1*4Kg");
  ASSERT_EQ(l.segments.size(), 2u);
  EXPECT_EQ(l.segments[1].start, 0x20000000u);
  EXPECT_FALSE(l.segments[0].writable);
}

TEST(DfuMemoryLayout, MalformedStringsAreRefusedSayingWhere) {
  EXPECT_EQ(error_of([] { parse_memory_layout("Internal Flash /0x08000000/256*02Kg"); }).what(),
            std::string("the device's memory-layout string \"Internal Flash /0x08000000/256*02Kg\" "
                        "cannot be read: expected '@' first at character 1; is this an STM32 ROM "
                        "bootloader (0483:df11)? dfu-util -l lists it"));
  EXPECT_EQ(error_of([] { parse_memory_layout("@F/0x08000000/256*02Xg"); }).kind(),
            DfuseError::Kind::bad_layout);
  EXPECT_EQ(error_of([] { parse_memory_layout("@F/0x08000000/256*02Kz"); }).kind(),
            DfuseError::Kind::bad_layout);
  EXPECT_EQ(error_of([] { parse_memory_layout("@F/0x08000000/0*02Kg"); }).kind(),
            DfuseError::Kind::bad_layout);
  EXPECT_EQ(error_of([] { parse_memory_layout("@F/0xFFFFF800/2*02Kg"); }).kind(),
            DfuseError::Kind::bad_layout);
}

TEST(DfuMemoryLayout, PagesOfARangeAreTheTouchedPagesOnly) {
  const dfu::MemoryLayout l = parse_memory_layout("@Internal Flash  /0x08000000/256*02Kg");
  const auto p = l.pages(0x08000700, 0x200, true, true);  // crosses 0x08000800
  ASSERT_EQ(p.size(), 2u);
  EXPECT_EQ(p[0].first, 0x08000000u);
  EXPECT_EQ(p[1].first, 0x08000800u);
  EXPECT_EQ(p[1].second, 2048u);
  EXPECT_TRUE(l.pages(0x08000000, 0, true, true).empty());
}

TEST(DfuMemoryLayout, RangePastTheEndIsRefusedNamingTheFirstBadAddress) {
  const dfu::MemoryLayout l = parse_memory_layout("@Internal Flash  /0x08000000/256*02Kg");
  const DfuseError e = error_of([&] { l.pages(0x0807F800, 4096, true, true); });
  EXPECT_EQ(e.kind(), DfuseError::Kind::refused_address);
  EXPECT_EQ(e.address(), 0x08080000u);
  EXPECT_EQ(std::string(e.what()),
            "0x0807F800..0x080807FF (4096 bytes) refused before anything was sent: 0x08080000 is "
            "outside every segment in the device's memory layout \"Internal Flash\"; check the "
            "image's address and size");
}

TEST(DfuMemoryLayout, WriteToAReadOnlySegmentIsRefused) {
  const dfu::MemoryLayout l = parse_memory_layout("@X/0x08000000/2*1Ka");
  EXPECT_EQ(error_of([&] { l.pages(0x08000000, 16, false, true); }).kind(),
            DfuseError::Kind::refused_address);
  EXPECT_EQ(error_of([&] { l.pages(0x08000000, 16, true, false); }).kind(),
            DfuseError::Kind::refused_address);
  EXPECT_EQ(l.pages(0x08000000, 16, false, false).size(), 1u);
}

}  // namespace
}  // namespace palp::dfutest
