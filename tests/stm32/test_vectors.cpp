// SPDX-License-Identifier: Apache-2.0
// The STM32G474 vector table's interrupt list (firmware/board/stm32g474/vectors_list.hpp, from
// which vectors.cpp builds the table) checked against the <interrupt> elements of ST's SVD:
// every number and name equal, none missing, none extra; and the reader's interrupt parsing.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "svd_reader.hpp"
#include "vectors_list.hpp"
#include "vendored_svd.hpp"

namespace palp::stm32 {
namespace {

using Lines = std::vector<std::string>;

std::vector<svd::TableEntry> table() {
  std::vector<svd::TableEntry> entries;
  for (const vectors::Irq& irq : vectors::kIrqs) {
    entries.push_back({irq.number, irq.name});
  }
  return entries;
}

TEST(Stm32Vectors, TheSvdListsInterruptsZeroTo101WithoutReserved85) {
  const svd::Device& device = vendored_svd();
  ASSERT_EQ(device.interrupts.size(), 101u);
  EXPECT_EQ(device.interrupts.front().number, 0u);
  EXPECT_EQ(device.interrupts.front().name, "WWDG");
  EXPECT_EQ(device.interrupts.back().number, 101u);
  EXPECT_EQ(device.interrupts.back().name, "FMAC");
  for (const svd::SvdInterrupt& i : device.interrupts) {
    EXPECT_NE(i.number, 85u) << i.name;
  }
}

TEST(Stm32Vectors, TheTableListEqualsTheSvdInterruptsExactly) {
  EXPECT_EQ(svd::check_interrupts(vendored_svd(), table()), Lines{});
  EXPECT_EQ(std::size(vectors::kIrqs), 101u);
  EXPECT_EQ(vectors::kExternalSlots, 102u);  // IRQ 0..101: the last listed number + 1
}

TEST(Stm32Vectors, AWrongMissingOrExtraEntryIsReportedExactly) {
  auto wrong_name = table();
  wrong_name[25].name = "TIM1_UP";  // IRQ 25 is TIM1_UP_TIM16
  EXPECT_EQ(svd::check_interrupts(vendored_svd(), wrong_name),
            (Lines{"IRQ 25: 'TIM1_UP' in the vector table, 'TIM1_UP_TIM16' in the SVD"}));

  auto shifted = table();
  shifted[27].number = 28;  // TIM1_CC written at TIM2's slot, slot 27 left empty
  EXPECT_EQ(svd::check_interrupts(vendored_svd(), shifted),
            (Lines{"IRQ 28: 'TIM1_CC' in the vector table, 'TIM2' in the SVD",
                   "IRQ 27: none in the vector table, 'TIM1_CC' in the SVD"}));

  auto extra = table();
  extra.push_back({85, "RESERVED85"});
  EXPECT_EQ(svd::check_interrupts(vendored_svd(), extra),
            (Lines{"IRQ 85: 'RESERVED85' in the vector table, none in the SVD"}));
}

TEST(Stm32SvdReader, ReadsInterruptsOnceInNumberOrder) {
  const char* xml = R"(<device><peripherals>
    <peripheral><name>B</name><baseAddress>0x0</baseAddress>
      <interrupt><name>B_IRQ</name><description>b</description><value>7</value></interrupt>
      <interrupt><name>SHARED</name><value>2</value></interrupt></peripheral>
    <peripheral derivedFrom="B"><name>C</name><baseAddress>0x10</baseAddress>
      <interrupt><name>SHARED</name><value>2</value></interrupt></peripheral>
  </peripherals></device>)";
  std::string error;
  const auto device = svd::parse(xml, error);
  ASSERT_TRUE(device.has_value()) << error;
  ASSERT_EQ(device->interrupts.size(), 2u);
  EXPECT_EQ(device->interrupts[0].name, "SHARED");
  EXPECT_EQ(device->interrupts[0].number, 2u);
  EXPECT_EQ(device->interrupts[1].name, "B_IRQ");
  EXPECT_EQ(device->interrupts[1].number, 7u);
}

TEST(Stm32SvdReader, MalformedInterruptsGetASpecificError) {
  std::string error;
  EXPECT_FALSE(svd::parse(R"(<peripheral><name>A</name><baseAddress>0x0</baseAddress>
    <interrupt><name>X</name><value>seven</value></interrupt></peripheral>)", error));
  EXPECT_EQ(error, "A: an <interrupt> without <name> or a numeric <value>");
  EXPECT_FALSE(svd::parse(R"(<peripheral><name>A</name><baseAddress>0x0</baseAddress>
    <interrupt><name>X</name><value>240</value></interrupt></peripheral>)", error));
  EXPECT_EQ(error, "A: interrupt X has number 240, above 239");
  EXPECT_FALSE(svd::parse(R"(<peripheral><name>A</name><baseAddress>0x0</baseAddress>
    <interrupt><name>X</name><value>3</value></interrupt>
    <interrupt><name>Y</name><value>3</value></interrupt></peripheral>)", error));
  EXPECT_EQ(error, "A: interrupt 3 named both X and Y");
  EXPECT_FALSE(svd::parse(R"(<peripheral><name>A</name><baseAddress>0x0</baseAddress>
    <interrupt><name>X</name><value>3</value></peripheral>)", error));
  EXPECT_EQ(error, "<interrupt> without </interrupt>");
}

}  // namespace
}  // namespace palp::stm32
