// SPDX-License-Identifier: Apache-2.0
// palp-sim's control channel: the sensor and actuator fault commands (`fault ...`) parse to their
// values in lab units; every bad line is refused naming the fault and the word.
#include <gtest/gtest.h>

#include "palp/sim/control.hpp"

namespace palp::sim {
namespace {

cmd::Fault fault_of(const char* line) {
  std::string error;
  const auto c = parse_control(line, error);
  EXPECT_TRUE(c && std::holds_alternative<cmd::Fault>(*c)) << line << ": " << error;
  return c && std::holds_alternative<cmd::Fault>(*c) ? std::get<cmd::Fault>(*c) : cmd::Fault{};
}

std::string refusal(const char* line) {
  std::string error;
  EXPECT_FALSE(parse_control(line, error).has_value()) << line;
  return error;
}

using K = cmd::Fault::Kind;

TEST(ControlFaults, EveryFaultParsesWithItsArgument) {
  EXPECT_EQ(fault_of("fault encoder-stuck").kind, K::encoder_stuck);
  EXPECT_EQ(fault_of("fault adc-stuck").kind, K::adc_stuck);
  EXPECT_EQ(fault_of("fault driver").kind, K::driver);
  EXPECT_EQ(fault_of(" fault  clear ").kind, K::clear);
  const cmd::Fault g = fault_of("fault encoder-glitch -1500");
  EXPECT_EQ(g.kind, K::encoder_glitch);
  EXPECT_EQ(g.counts, -1500);
  EXPECT_TRUE(fault_of("fault adc-saturate high").high);
  EXPECT_FALSE(fault_of("fault adc-saturate low").high);
  const cmd::Fault s = fault_of("fault supply-sag 17.5");
  EXPECT_EQ(s.kind, K::supply_sag);
  EXPECT_DOUBLE_EQ(s.volts, 17.5);
  EXPECT_DOUBLE_EQ(fault_of("fault supply-sag 0").volts, 0.0);
}

TEST(ControlFaults, BadFaultLinesNameTheFaultAndTheWord) {
  EXPECT_EQ(refusal("fault"),
            "fault: expected encoder-stuck, encoder-glitch <counts>, adc-stuck, adc-saturate "
            "high|low, driver, supply-sag <V> or clear");
  EXPECT_EQ(refusal("fault brakes"),
            "fault: unknown fault 'brakes'; expected encoder-stuck, encoder-glitch <counts>, "
            "adc-stuck, adc-saturate high|low, driver, supply-sag <V> or clear");
  EXPECT_EQ(refusal("fault driver now"), "fault driver: expected no arguments");
  EXPECT_EQ(refusal("fault encoder-glitch"), "fault encoder-glitch: expected <counts>");
  EXPECT_EQ(refusal("fault encoder-glitch 0"),
            "fault encoder-glitch: '0' is not a whole number of counts, nonzero, -30000 to 30000");
  EXPECT_EQ(refusal("fault encoder-glitch 30001"),
            "fault encoder-glitch: '30001' is not a whole number of counts, nonzero, -30000 to "
            "30000");
  EXPECT_EQ(refusal("fault encoder-glitch 2.5"),
            "fault encoder-glitch: '2.5' is not a whole number of counts, nonzero, -30000 to "
            "30000");
  EXPECT_EQ(refusal("fault adc-saturate"), "fault adc-saturate: expected high or low");
  EXPECT_EQ(refusal("fault adc-saturate max"), "fault adc-saturate: expected high or low");
  EXPECT_EQ(refusal("fault supply-sag -1"), "fault supply-sag: '-1' is not a voltage in V >= 0");
  EXPECT_EQ(refusal("fault supply-sag nan"), "fault supply-sag: 'nan' is not a voltage in V >= 0");
  EXPECT_EQ(refusal("fault supply-sag 12 V"), "fault supply-sag: expected <V>");
}

TEST(ControlFaults, HelpListsTheFaultCommands) {
  const std::string help = control_help();
  for (const char* c : {"fault encoder-stuck", "fault encoder-glitch <counts>", "fault adc-stuck",
                        "fault adc-saturate high|low", "fault driver", "fault supply-sag <V>",
                        "fault clear"})
    EXPECT_NE(help.find(c), std::string::npos) << c;
}

}  // namespace
}  // namespace palp::sim
