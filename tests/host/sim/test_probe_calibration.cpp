// SPDX-License-Identifier: Apache-2.0
// The calibration helpers against palp-sim linked in (palp/sim_inproc.hpp), each with a known
// answer: an offset put into the
// calibration on purpose is found and taken out again; homing finds the rear end stop the
// simulated coil is parked against; all of it in RAM, kept in zeroing() for the sidecar.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "palp/probe.hpp"
#include "palp/recording.hpp"
#include "palp/sim_inproc.hpp"

namespace {

using namespace std::chrono_literals;
using palp::sim::InprocSimulator;
using testing::HasSubstr;

TEST(ProbeCalibration, PressureZeroTakesOutAKnownOffsetOnEveryChannel) {
  InprocSimulator sim;
  palp::Probe probe(sim.transport());
  palp::Calibration c = probe.calibration();
  for (std::size_t k = 0; k < 6; ++k) c.pressure_offset_Pa[k] = -10.0f * static_cast<float>(k + 1);
  probe.set_calibration(c);  // channel k now reads +10 (k+1) Pa with nothing pressing on it
  const std::vector<double> offsets = probe.zero_pressure(0.5);
  ASSERT_EQ(offsets.size(), 6u);
  for (std::size_t k = 0; k < 6; ++k) EXPECT_NEAR(offsets[k], 0.0, 0.5) << "channel " << k + 1;
  ASSERT_EQ(probe.zeroing().size(), 1u);
  EXPECT_EQ(probe.zeroing()[0].what, "pressure_zero");
  EXPECT_FALSE(probe.zeroing()[0].committed);
  EXPECT_NEAR(probe.calibration().pressure_offset_Pa[5], 0.0f, 0.5f);
}

TEST(ProbeCalibration, CurrentOffsetZeroFindsAKnownSenseOffsetFromTheLoopsVoltage) {
  InprocSimulator sim;
  palp::Probe probe(sim.transport());
  palp::Calibration c = probe.calibration();
  c.current_offset_A = 0.02f;  // the loop now drives a real +20 mA to read zero
  probe.set_calibration(c);
  const double offset = probe.zero_current_offset(0.5);
  EXPECT_NEAR(offset, 0.0, 0.001);
  EXPECT_EQ(probe.zeroing().back().what, "current_offset");
}

TEST(ProbeCalibration, HomingSetsTheStrokeOriginAtTheRearEndStop) {
  InprocSimulator sim;
  palp::Probe probe(sim.transport());
  const std::int32_t parked = probe.status().encoder_counts;  // a new plant parks at the stop
  const std::int32_t origin = probe.home(-0.3, 0.5);
  EXPECT_NEAR(origin, parked, 2);
  const palp::Calibration c = probe.calibration();
  EXPECT_EQ(c.stroke_origin_valid, 1);
  EXPECT_EQ(c.stroke_origin_counts, origin);
  EXPECT_EQ(probe.zeroing().back().what, "home");
  EXPECT_EQ(probe.status().i_cmd_A, 0.0) << "homing leaves the coil without current";
}

TEST(ProbeCalibration, HelpersRefuseWhileTheApplicationStreams) {
  InprocSimulator sim;
  palp::Probe probe(sim.transport());
  probe.configure_stream({.rate_Hz = 1000.0});
  probe.start_stream();
  try {
    probe.zero_pressure();
    FAIL() << "zeroing stole the application's stream";
  } catch (const palp::ConfigError& e) {
    EXPECT_EQ(std::string(e.what()),
              "zero_pressure: stop the stream first (the helper streams on its own)");
  }
  EXPECT_THROW(probe.home(0.3), palp::ConfigError);
}

TEST(ProbeRecording, AStreamWrittenAsARecordingReadsBackBitExact) {
  InprocSimulator sim;
  palp::Probe probe(sim.transport());
  probe.configure_stream({.rate_Hz = 2000.0});
  probe.start_stream();
  palp::RampProgram r;
  r.start_A = 0.1f;
  r.stop_A = 0.3f;
  r.step_A = 0.05f;
  r.dwell_s = 0.02f;
  r.repetitions = 2;
  probe.run(r, 10s);
  probe.stop_stream();
  std::vector<palp::StreamItem> items;
  probe.drain(items);
  const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                    ("palp-rec-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::vector<palp::RecordingRow> rows;
  {
    palp::RecordingWriter w(dir / "run.csv");
    for (const auto& item : items) {
      const auto* s = std::get_if<palp::Sample>(&item);
      ASSERT_NE(s, nullptr) << "no gaps expected";
      palp::RecordingRow row;
      row.sample_index = s->index;
      row.t_s = s->t_device_s;
      row.i_cmd_A = s->i_cmd_A;
      row.i_A = s->i_A;
      row.z_mm = s->z_m * 1e3;
      row.p_Pa = s->p_Pa;
      row.status = s->status;
      rows.push_back(row);
      w.append(row);
    }
    palp::Sidecar sc;
    sc.device = {{"serial", probe.info().serial}};
    sc.stroke_origin_z_mm_reason = "not homed";
    w.finish(sc);
  }
  const palp::Recording rec = palp::read_recording(dir / "run.csv");
  ASSERT_EQ(rec.size(), rows.size());
  ASSERT_GT(rows.size(), 100u);
  for (std::size_t k = 0; k < rows.size(); ++k) {
    ASSERT_EQ(rec.t_s[k], rows[k].t_s) << k;  // bit-exact, not near
    ASSERT_EQ(rec.i_A[k], rows[k].i_A) << k;
    ASSERT_EQ(rec.z_mm[k], rows[k].z_mm) << k;
    ASSERT_EQ((*rec.i_cmd_A)[k], rows[k].i_cmd_A) << k;
    ASSERT_EQ((*rec.p_Pa[3])[k], rows[k].p_Pa[3]) << k;
    ASSERT_EQ((*rec.sample_index)[k], rows[k].sample_index) << k;
  }
  ASSERT_TRUE(rec.sidecar.has_value());
  EXPECT_EQ(rec.sidecar->device["serial"], "SIM-0001");
  EXPECT_FALSE(rec.sidecar->stroke_origin_z_mm.has_value());
  std::filesystem::remove_all(dir);
}

}  // namespace
