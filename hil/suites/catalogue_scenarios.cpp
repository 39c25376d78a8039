// SPDX-License-Identifier: Apache-2.0
// Catalogue scenarios: the device speaks the message catalogue this SDK was built from
// (protocol/include/palp/protocol/catalogue.hpp): it serves every request of it that the public
// API sends, and refuses every value outside a field's catalogue range naming that field. What
// each proves is in README.md.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <functional>
#include <limits>
#include <map>
#include <thread>

#include "bench.hpp"
#include "palp/protocol/catalogue.hpp"

namespace palp::hil {
namespace {

using namespace std::chrono_literals;

// ---- every request served ---------------------------------------------------------------------

/// Requests the public API does not send, and where they are proved instead.
const std::map<proto::MessageId, const char*> kNotSentHere = {
    {proto::MessageId::EnterBootloader, "it reboots the device into its ROM bootloader"},
    {proto::MessageId::GetDeviceInfo,
     "the public API does not send it (Hello gets the same reply)"},
    {proto::MessageId::Heartbeat, "the SDK's I/O thread sends it: Heartbeat.* proves it is taken"},
    {proto::MessageId::CommitCalibration, "it writes flash: Calibration.* proves it"},
};

/// True when the call is served: a reply of the right kind, or a Nak other than unknown_message
/// (the device knows the message and judged this instance of it).
void expect_served(const char* name, const std::function<void()>& call) {
  try {
    call();
  } catch (const DeviceError& e) {
    EXPECT_NE(e.code(), static_cast<std::uint16_t>(proto::ErrorCode::unknown_message))
        << name << ": the device does not know it: " << e.what();
  } catch (const Error& e) {
    ADD_FAILURE() << name << ": " << e.what();
  }
}

using Catalogue = Scenario;
TEST_F(Catalogue, EveryRequestOfTheDevicesMinorThatThePublicApiSendsIsServed) {
  Probe& p = probe();
  const auto rate_Hz = stream_rate_at_most(p.info(), 100.0);
  HoldProgram zero;  // 0 A for 10 ms: starts, runs, ends on its own
  zero.current_A = 0.0f;
  zero.duration_s = 0.01f;
  const std::map<proto::MessageId, std::function<void()>> sent = {
      {proto::MessageId::Hello, [&] { ASSERT_FALSE(p.info().serial.empty()); }},  // the fixture's
      {proto::MessageId::Ping,
       [&] {
         for (int k = 0; k < 100 && p.clock().points == 0; ++k) std::this_thread::sleep_for(20ms);
         EXPECT_GT(p.clock().points, 0u) << "no Pong in 2 s";
       }},
      {proto::MessageId::GetStatus, [&] { p.status(); }},
      {proto::MessageId::GetHealth, [&] { p.health(); }},
      {proto::MessageId::GetParams, [&] { p.params(); }},
      {proto::MessageId::SetParams, [&] { p.set_params(saved_params()); }},
      {proto::MessageId::GetCalibration, [&] { p.calibration(); }},
      {proto::MessageId::SetCalibration, [&] { p.set_calibration(p.calibration()); }},
      {proto::MessageId::LoadHold, [&] { p.load(HoldProgram{}); }},
      {proto::MessageId::LoadRamp, [&] { p.load(RampProgram{}); }},
      {proto::MessageId::LoadSine, [&] { p.load(SineProgram{}); }},
      {proto::MessageId::LoadSweep, [&] { p.load(SweepProgram{}); }},
      {proto::MessageId::LoadMultisine, [&] { p.load(MultisineProgram{}); }},
      {proto::MessageId::LoadContactWatch, [&] { p.load(ContactWatchProgram{}); }},
      {proto::MessageId::ProgramStart, [&] { p.load(zero), p.start(), p.wait(5s); }},
      {proto::MessageId::ProgramStop, [&] { p.stop(); }},
      {proto::MessageId::GetProgramStatus, [&] { p.program_status(); }},
      {proto::MessageId::StreamConfigure, [&] { p.configure_stream({.rate_Hz = rate_Hz}); }},
      {proto::MessageId::StreamStart, [&] { p.start_stream(); }},
      {proto::MessageId::StreamStop, [&] { p.stop_stream(); }},
      {proto::MessageId::FaultClear, [&] { p.clear_fault(); }},  // none latched: Ack
  };
  int checked = 0;
  for (const proto::MessageInfo& m : proto::kMessages) {
    if (m.direction != proto::Direction::H2D) continue;
    if (m.since > p.info().protocol_minor) continue;  // the device's minor lacks it
    if (kNotSentHere.count(m.id) != 0) continue;
    const auto call = sent.find(m.id);
    if (call == sent.end()) {
      ADD_FAILURE() << m.name << " is in the catalogue but in neither table of this scenario: "
                    << "add how the public API sends it";
      continue;
    }
    SCOPED_TRACE(m.name);
    expect_served(m.name, call->second);
    ++checked;
  }
  std::printf("[  FIGURES ] %d requests served; not sent here: %zu\n", checked,
              kNotSentHere.size());
}

// ---- every range enforced ---------------------------------------------------------------------

/// The value of a field's catalogue bound ("NOLIM": none).
std::optional<double> bound(const char* text) {
  if (std::string(text) == "NOLIM") return std::nullopt;
  return std::strtod(text, nullptr);
}

/// Sets a scalar (or an array's first element) to v when its type can hold v exactly enough to
/// lie outside the bound it was derived from; false when it cannot (a u8 above 255).
template <class T>
bool assign(T& field, double v) {
  if constexpr (std::is_arithmetic_v<T>) {
    if (v < static_cast<double>(std::numeric_limits<T>::lowest()) ||
        v > static_cast<double>(std::numeric_limits<T>::max()))
      return false;
    field = static_cast<T>(v);
    return true;
  } else if constexpr (requires {
                         field[0];
                         std::size(field);
                       }) {
    return assign(field[0], v);
  } else {
    return false;  // enums, bounded arrays, text: no numeric range of their own here
  }
}

/// For each ranged field of a valid message m: the value just below its range and just above
/// it, each judged out of range by the SDK's catalogue at that field's index, sent with `send`;
/// the device must refuse it with one of `codes`, naming that field.
template <class M>
void expect_ranges_enforced(const M& valid, const std::function<void(const M&)>& send,
                            std::initializer_list<proto::ErrorCode> codes, int& tried) {
  ASSERT_EQ(valid.first_out_of_range(), -1) << M::kName << ": the scenario's valid message";
  for (std::size_t index = 0; index < M::kFields.size(); ++index) {
    const proto::FieldInfo& f = M::kFields[index];
    for (const bool above : {false, true}) {
      const std::optional<double> b = bound(above ? f.hi_text : f.lo_text);
      if (!b) continue;
      const bool integer = f.type[0] == 'u' || f.type[0] == 'i';
      const double step = integer ? 1.0 : std::max(std::fabs(*b) * 1e-3, 1e-3);
      M bad = valid;
      bool set = false;
      std::size_t k = 0;
      bad.visit([&](const proto::FieldInfo&, auto& field) {
        if (k++ == index) set = assign(field, above ? *b + step : *b - step);
      });
      if (!set) continue;  // the type cannot leave the range on this side
      ASSERT_EQ(bad.first_out_of_range(), static_cast<int>(index)) << M::kName << "." << f.name;
      ++tried;
      try {
        send(bad);
        ADD_FAILURE() << M::kName << "." << f.name << " = " << (above ? *b + step : *b - step)
                      << " (range " << f.lo_text << " .. " << f.hi_text << ") was accepted";
      } catch (const DeviceError& e) {
        bool expected = false;
        for (const proto::ErrorCode c : codes)
          expected |= e.code() == static_cast<std::uint16_t>(c);
        EXPECT_TRUE(expected) << M::kName << "." << f.name << ": " << e.what();
        EXPECT_EQ(e.field_index(), index) << M::kName << "." << f.name << ": " << e.what();
      }
    }
  }
}

TEST_F(Catalogue, EveryValueOutsideAFieldsCatalogueRangeIsRefusedNamingThatField) {
  Probe& p = probe();
  int tried = 0;
  const auto out = {proto::ErrorCode::out_of_range};
  expect_ranges_enforced<proto::SetParams>(
      proto::fields_as<proto::SetParams>(saved_params()),
      [&](const proto::SetParams& m) { p.set_params(proto::fields_as<proto::Params>(m)); }, out,
      tried);
  const Calibration cal = p.calibration();
  expect_ranges_enforced<proto::SetCalibration>(
      proto::fields_as<proto::SetCalibration>(cal),
      [&](const proto::SetCalibration& m) { p.set_calibration(proto::fields_as<Calibration>(m)); },
      {proto::ErrorCode::out_of_range, proto::ErrorCode::calibration_invalid}, tried);
  const auto load = [&](const auto& m) { p.load(m); };
  expect_ranges_enforced<HoldProgram>(HoldProgram{}, load, out, tried);
  expect_ranges_enforced<RampProgram>(RampProgram{}, load, out, tried);
  expect_ranges_enforced<SineProgram>(SineProgram{}, load, out, tried);
  expect_ranges_enforced<SweepProgram>(SweepProgram{}, load, out, tried);
  expect_ranges_enforced<MultisineProgram>(MultisineProgram{}, load, out, tried);
  expect_ranges_enforced<ContactWatchProgram>(ContactWatchProgram{}, load, out, tried);
  // nothing was taken: the parameters and the calibration are as they were
  EXPECT_EQ(p.params(), saved_params());
  EXPECT_EQ(p.calibration(), cal);
  EXPECT_EQ(p.fault().reason, proto::FaultReason::none);
  std::printf("[  FIGURES ] %d out-of-range values refused\n", tried);
}

}  // namespace
}  // namespace palp::hil
