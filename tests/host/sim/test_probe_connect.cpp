// SPDX-License-Identifier: Apache-2.0
// The probe client against palp-sim: the handshake and its verdicts, device info, requests and
// the errors a person reads when something is refused or missing. Over a real socket where the
// socket or the pace matters (connecting, nothing listening, a wait in real time); the rest
// against palp-sim linked in (palp/sim_inproc.hpp).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "palp/probe.hpp"
#include "palp/protocol/schema.hpp"
#include "palp/protocol/verdict_text.hpp"
#include "palp/sim_inproc.hpp"
#include "sim_process.hpp"

namespace {

using namespace std::chrono_literals;
using palp::sim::InprocSimulator;
using palp::sim::test::SimProcess;
using testing::HasSubstr;

TEST(ProbeConnect, HandshakeWithTheSimulatorIsCompatibleAndNamesTheDevice) {
  SimProcess sim({}, false);
  ASSERT_TRUE(sim.ok()) << sim.banner();
  palp::Probe probe(sim.uri());
  EXPECT_EQ(probe.info().serial, "SIM-0001");
  EXPECT_EQ(probe.info().board, "palp-sim");
  EXPECT_TRUE(probe.info().has(palp::proto::Capability::simulated));
  EXPECT_EQ(probe.info().protocol_major, palp::proto::kProtocolMajor);
  EXPECT_EQ(probe.info().control_rate_Hz, 20000);
  EXPECT_FALSE(probe.handshake().missing_features);
  EXPECT_TRUE(probe.handshake().missing.empty());
}

std::string version_error(const std::string& announce) {
  InprocSimulator sim;
  if (sim.control("announce " + announce) != "ok") return "announce refused";
  try {
    palp::Probe probe(sim.transport());
  } catch (const palp::VersionError& e) {
    return e.what();
  }
  return "connected";
}

TEST(ProbeConnect, AnotherMajorVersionIsRefusedNamingBothVersionsAndTheFix) {
  const std::string other = std::to_string(palp::proto::kProtocolMajor + 1) + ".0";
  const std::string e = version_error(other);
  EXPECT_THAT(e, HasSubstr(palp::proto::version_text(palp::proto::kProtocolMajor,
                                                     palp::proto::kProtocolMinor)));
  EXPECT_THAT(e, HasSubstr(other));
}

TEST(ProbeConnect, SameVersionWithAnotherSchemaHashIsRefusedNamingBothHashes) {
  const std::string v = palp::proto::version_text(palp::proto::kProtocolMajor,
                                                  palp::proto::kProtocolMinor);
  const std::string e = version_error(v + " 0x0badf00d");
  EXPECT_THAT(e, HasSubstr("0x0badf00d"));
  EXPECT_THAT(e, HasSubstr(palp::proto::hash_text(palp::proto::kSchemaHash)));
}

TEST(ProbeConnect, ANewerMinorOnTheDeviceIsCompatibleUnlessTheMajorIsZero) {
  InprocSimulator sim;
  const std::string newer = std::to_string(palp::proto::kProtocolMajor) + "." +
                            std::to_string(palp::proto::kProtocolMinor + 1) + " 0x11111111";
  ASSERT_EQ(sim.control("announce " + newer), "ok");
  if (palp::proto::kProtocolMajor == 0) {
    EXPECT_THROW(palp::Probe probe(sim.transport()), palp::VersionError);
  } else {
    palp::Probe probe(sim.transport());
    EXPECT_FALSE(probe.handshake().missing_features);
    EXPECT_EQ(probe.info().protocol_minor, palp::proto::kProtocolMinor + 1);
  }
}

TEST(ProbeConnect, NothingListeningIsAConnectionErrorThatSaysWhatToDo) {
  SimProcess sim({}, false);
  ASSERT_TRUE(sim.ok());
  const std::string uri = sim.uri();
  sim.stop();
  try {
    palp::ConnectOptions o;
    o.timeout = 500ms;
    palp::Probe probe(uri, o);
    FAIL() << "connected to a stopped simulator";
  } catch (const palp::ConnectionError& e) {
    EXPECT_THAT(e.what(), HasSubstr("cannot reach palp-sim at " + uri));
    EXPECT_THAT(e.what(), HasSubstr("is palp-sim running?"));
  }
}

TEST(ProbeConnect, AnOutOfRangeFieldIsRefusedNamingTheMessageTheCodeAndTheField) {
  InprocSimulator sim;
  palp::Probe probe(sim.transport());
  palp::RampProgram r;
  r.step_A = 0.0f;  // below its range [0.0001, 4]
  try {
    probe.load(r);
    FAIL() << "the device accepted step_A = 0";
  } catch (const palp::DeviceError& e) {
    EXPECT_EQ(std::string(e.what()),
              "LoadRamp refused: out_of_range (A field is outside its range; Nak.field_index "
              "names it.), field step_A");
    EXPECT_EQ(e.request(), "LoadRamp");
    EXPECT_EQ(e.code(), static_cast<std::uint16_t>(palp::proto::ErrorCode::out_of_range));
    EXPECT_EQ(e.field_index(), 2);
  }
}

TEST(ProbeConnect, StatusParamsAndCalibrationRoundTripInSiUnits) {
  InprocSimulator sim;
  palp::Probe probe(sim.transport());
  const palp::Status st = probe.status();
  EXPECT_EQ(st.state, palp::proto::DeviceState::idle);
  EXPECT_DOUBLE_EQ(st.z_m, st.encoder_counts * 1e-6);
  palp::Params p = probe.params();
  EXPECT_FLOAT_EQ(p.current_clamp_A, 3.2f);
  p.heartbeat_timeout_ms = 1000;
  probe.set_params(p);
  EXPECT_EQ(probe.params().heartbeat_timeout_ms, 1000u);
  palp::Calibration c = probe.calibration();
  c.pressure_offset_Pa[2] = 12.5f;
  probe.set_calibration(c);
  EXPECT_FLOAT_EQ(probe.calibration().pressure_offset_Pa[2], 12.5f);
}

// A control-rate change through set_params() is the rate configure_stream() divides from: at
// 40 kHz a 20 kHz stream is every second tick (with the connect-time 20 kHz it was asked as every
// tick, i.e. 40 kHz, and refused stream_too_fast).
TEST(ProbeConnect, AControlRateSetThroughSetParamsIsTheRateTheStreamDecimationComesFrom) {
  SimProcess sim({}, false);
  ASSERT_TRUE(sim.ok());
  palp::Probe probe(sim.uri());
  ASSERT_EQ(probe.info().control_rate_Hz, 20000.0);
  palp::Params p = probe.params();
  p.control_rate_Hz = 40000;
  probe.set_params(p);
  EXPECT_EQ(probe.info().control_rate_Hz, 40000.0);
  const palp::StreamInfo info = probe.configure_stream({.rate_Hz = 20000.0});
  EXPECT_DOUBLE_EQ(info.rate_Hz, 20000.0);
  EXPECT_DOUBLE_EQ(info.period_s, 50e-6);
}

TEST(ProbeConnect, AHoldProgramRunsToItsEndAndAShortWaitTimesOutWithHealth) {
  SimProcess sim({}, false);
  ASSERT_TRUE(sim.ok());
  palp::Probe probe(sim.uri());
  palp::HoldProgram h;
  h.current_A = 0.2f;
  h.duration_s = 0.5f;
  const palp::ProgramResult r = probe.run(h, 10s);
  EXPECT_EQ(r.kind, palp::proto::ProgramKind::hold);
  EXPECT_EQ(r.end, palp::proto::ProgramEnd::completed);

  ASSERT_EQ(sim.control("pace 1"), "ok");  // real time: a 60 s hold cannot end in 50 ms
  h.duration_s = 60.0f;
  probe.load(h);
  probe.start();
  try {
    probe.wait(50ms);
    FAIL() << "a 60 s hold ended within 50 ms";
  } catch (const palp::TimeoutError& e) {
    EXPECT_THAT(e.what(), HasSubstr("waiting for the program to finish on " + sim.uri()));
    EXPECT_EQ(e.waited_for().rfind("the program to finish", 0), 0u);
    ASSERT_TRUE(e.health().has_value());
    EXPECT_GT(e.health()->host_frames_rx, 0u);
  }
  probe.stop();
  EXPECT_EQ(probe.wait(2s).end, palp::proto::ProgramEnd::stopped_by_host);
}

TEST(ProbeConnect, AfterCloseIdentityStaysReadableAndDeviceCallsSayTheProbeIsClosed) {
  InprocSimulator sim;
  palp::Probe probe(sim.transport());
  probe.close();
  probe.close();  // twice is fine
  EXPECT_EQ(probe.info().serial, "SIM-0001");
  EXPECT_EQ(probe.uri(), sim.uri());
  EXPECT_FALSE(probe.handshake().missing_features);
  try {
    probe.status();
    FAIL() << "a closed probe answered";
  } catch (const palp::ConnectionError& e) {
    EXPECT_EQ(std::string(e.what()), "this Probe is closed");
  }
}

}  // namespace
