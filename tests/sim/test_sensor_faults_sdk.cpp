// SPDX-License-Identifier: Apache-2.0
// Sensor and actuator faults end to end: palp-sim's control channel breaks a sensor or the power
// stage while a hold runs and the full stream records; through the SDK the host sees the
// EventFault (FaultInfo with its device time), the program end by the fault, the status with the
// reason, and a recording in which every sample from the trip on is marked fault_latched with
// 0 A and 0 V commanded (and none before it). The in-process simulator (palp/sim_inproc.hpp) runs
// the same Instrument as palp-sim, so `sim.control(...)` is palp-sim's control channel.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "palp/error.hpp"
#include "palp/probe.hpp"
#include "palp/recording.hpp"
#include "palp/sim_inproc.hpp"

namespace {

using namespace std::chrono_literals;
using palp::proto::FaultReason;
namespace proto = palp::proto;

constexpr std::uint16_t kFaultBit = 1u << static_cast<unsigned>(proto::StatusBit::fault_latched);
constexpr double kTick_s = 50e-6;  // 20 kHz

struct FaultRun {
  palp::sim::InprocSimulator sim;
  palp::Probe probe{sim.transport()};
  std::vector<palp::Sample> samples;

  /// Starts the full stream at 10 kHz and a hold, and records until the hold has run `seconds`.
  explicit FaultRun(double hold_A, double seconds = 0.3) {
    probe.configure_stream({.rate_Hz = 10000.0});
    probe.start_stream();
    probe.load(palp::HoldProgram{static_cast<float>(hold_A), 0.0f});
    probe.start();
    // virtual time runs while the host works: the hold has run `seconds` from its start on
    record_until(sim.virtual_s() + seconds);
  }
  /// Collects stream items until the last sample's device time reaches t_s.
  void record_until(double t_s) {
    std::vector<palp::StreamItem> items;
    for (int k = 0; k < 100000 && (samples.empty() || samples.back().t_device_s < t_s); ++k) {
      items.clear();
      if (probe.drain(items) == 0) std::this_thread::sleep_for(1ms);
      for (const auto& item : items) {
        ASSERT_TRUE(std::holds_alternative<palp::Sample>(item)) << "a gap in the stream";
        samples.push_back(std::get<palp::Sample>(item));
      }
    }
  }
  /// The samples written as a recording and read back.
  palp::Recording recording(const std::string& name) {
    const auto stem = std::filesystem::path(testing::TempDir()) / ("sensor_fault_" + name);
    palp::RecordingWriter w(stem, {.overwrite = palp::Overwrite::yes});
    for (const palp::Sample& s : samples)
      w.append({.sample_index = s.index, .t_s = s.t_device_s, .i_cmd_A = s.i_cmd_A, .i_A = s.i_A,
                .z_mm = s.z_m * 1e3, .p_Pa = s.p_Pa, .status = s.status, .rep = 0});
    w.finish({});
    return palp::read_recording(w.csv_path());
  }
};

struct Expected {
  const char* command;           ///< the control line
  double hold_A = 0.6;
  bool stop_after = false;       ///< the host stops the hold right after the command
  FaultReason reason;
  std::function<void(std::int32_t)> detail;  ///< checks EventFault.detail
  double latest_s;               ///< the trip comes at most this long after the command (or stop)
};

/// Breaks the sensor, then checks every part of the reaction the host sees.
void expect_fault_reaction(const Expected& e, const std::string& name) {
  FaultRun run(e.hold_A, e.hold_A == 0.6 ? 1.0 : 0.3);
  ASSERT_FALSE(run.samples.empty());
  const double before_s = run.sim.virtual_s();
  ASSERT_EQ(run.sim.control(e.command), "ok");
  EXPECT_NE(run.sim.control("status").find(" sensor_faults="), std::string::npos);
  if (e.stop_after) run.probe.stop();
  const double after_s = run.sim.virtual_s();

  // the program ends by the fault; the event carries the device time of the trip
  if (!e.stop_after) {
    try {
      run.probe.wait(5s);
      ADD_FAILURE() << e.command << ": the hold ended without a fault";
    } catch (const palp::FaultError& f) {
      EXPECT_EQ(f.reason(), static_cast<std::uint16_t>(e.reason)) << f.what();
    }
  }
  run.record_until(after_s + 0.2);
  const palp::FaultInfo fault = run.probe.fault();
  EXPECT_EQ(fault.reason, e.reason) << e.command;
  e.detail(fault.detail);
  EXPECT_GE(fault.t_device_s, before_s - 1e-9) << e.command;  // the event came (0: it did not)
  EXPECT_LE(fault.t_device_s, after_s + e.latest_s) << e.command;

  const palp::Status status = run.probe.status();
  EXPECT_EQ(status.state, proto::DeviceState::faulted);
  EXPECT_EQ(status.fault, e.reason);
  EXPECT_NE(status.status_bits & kFaultBit, 0u);

  // the recording: nothing valid from the trip on, nothing marked before it
  const palp::Recording rec = run.recording(name);
  ASSERT_TRUE(rec.status && rec.i_cmd_A);
  std::size_t marked = 0;
  const double trip_s = fault.t_device_s;
  for (std::size_t k = 0; k < rec.size(); ++k) {
    const bool after = rec.t_s[k] >= trip_s - 1e-9;
    EXPECT_EQ(((*rec.status)[k] & kFaultBit) != 0, after) << e.command << " t_s " << rec.t_s[k];
    if (after) {
      ++marked;
      EXPECT_EQ((*rec.i_cmd_A)[k], 0.0) << e.command << " t_s " << rec.t_s[k];
    }
  }
  EXPECT_GE(marked, 1000u);  // 0.1 s and more at 10 kHz
  // 0 V commanded from the first sample at or after the trip (the stream's v_cmd)
  for (const palp::Sample& s : run.samples)
    if (s.t_device_s >= trip_s - 1e-9) {
      EXPECT_EQ(s.v_cmd_V, 0.0) << e.command << " " << s.t_device_s;
    }
}

auto near(std::int32_t value, std::int32_t tolerance) {
  return [=](std::int32_t detail) {
    EXPECT_LE(std::abs(detail - value), tolerance) << "detail " << detail << ", expected " << value;
  };
}

TEST(SensorFaultsSdk, DriverFaultEndsTheHoldInOneTickWithTheEventAndMarkedSamples) {
  expect_fault_reaction({"fault driver", 0.6, false, FaultReason::driver_fault,
                         near(6000, 100) /* 0.6 A in 0.1 mA */, kTick_s},
                        "driver");
}

TEST(SensorFaultsSdk, SupplySagTo12VTripsUndervoltageAfter1ms) {
  expect_fault_reaction({"fault supply-sag 12", 0.6, false, FaultReason::supply_undervoltage,
                         near(12000, 0), 1e-3 + kTick_s},
                        "supply");
}

TEST(SensorFaultsSdk, SaturatedCurrentSenseTripsInOneTickWithTheRailReading) {
  expect_fault_reaction({"fault adc-saturate high", 0.6, false,
                         FaultReason::current_sense_error, near(49976, 0), kTick_s},
                        "adc_saturate");
}

TEST(SensorFaultsSdk, StuckCurrentSenseTripsWhenTheStopSwingsTheVoltage) {
  // frozen at a live reading of about 0.6 A; the stop drops the set-point to 0 A
  expect_fault_reaction({"fault adc-stuck", 0.6, true, FaultReason::current_sense_error,
                         near(6000, 100), 1e-3 + 2 * kTick_s},
                        "adc_stuck");
}

TEST(SensorFaultsSdk, EncoderGlitchOf2000CountsTripsInThatTickWithTheJump) {
  expect_fault_reaction({"fault encoder-glitch 2000", 0.6, false, FaultReason::encoder_error,
                         near(2000, 60) /* plus the coil's own motion in that tick */, kTick_s},
                        "encoder_glitch");
}

TEST(SensorFaultsSdk, StuckEncoderTripsWhenTheStoppedCoilDoesNotMoveFor10ms) {
  // the coil floats mid-stroke at 0.6 A; the stop lets the current fall to 0 A: it must move
  expect_fault_reaction({"fault encoder-stuck", 0.6, true, FaultReason::encoder_error,
                         near(0, 0), 10e-3 + 2e-3},
                        "encoder_stuck");
}

TEST(SensorFaultsSdk, FaultClearIsRefusedWhileTheDriverStillSignalsAndAcceptedAfterwards) {
  FaultRun run(0.6);
  ASSERT_EQ(run.sim.control("fault driver"), "ok");
  EXPECT_THROW(run.probe.wait(5s), palp::FaultError);
  EXPECT_THROW(run.probe.clear_fault(), palp::DeviceError);  // fault_persists
  EXPECT_NE(run.sim.control("status").find(" sensor_faults=driver"), std::string::npos);
  ASSERT_EQ(run.sim.control("fault clear"), "ok");
  EXPECT_NE(run.sim.control("status").find(" sensor_faults=none"), std::string::npos);
  run.record_until(run.sim.virtual_s() + 0.01);
  run.probe.clear_fault();
  EXPECT_EQ(run.probe.status().state, proto::DeviceState::idle);
}

TEST(SensorFaultsSdk, ASupplySagAboveTheNominalSupplyIsRefused) {
  palp::sim::InprocSimulator sim;
  EXPECT_EQ(sim.control("fault supply-sag 30"),
            "error: fault supply-sag: 30 V is above the nominal supply of 24 V");
}

}  // namespace
