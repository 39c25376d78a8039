// SPDX-License-Identifier: Apache-2.0
// Sensor and actuator faults (firmware/core/include/palp/fw/sensor_monitor.hpp): each check's
// exact trip tick and detail on synthetic readings, the normal runs it must leave alone, and the
// controller's reaction end to end: the latch with its reason and detail, 0 V in the tick that
// trips, EventFault at that tick's time, fault_latched in every streamed sample from that tick on,
// and FaultClear refused while the cause is still there.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>

#include "palp/fw/controller.hpp"
#include "palp/fw/sensor_monitor.hpp"
#include "palp/protocol/stream.hpp"

namespace palp::fw::sensor_faults_test {  // named: the unity build shares anonymous namespaces
namespace {

using namespace palp::proto;
constexpr float kDt = 50e-6f;  // 20 kHz

// --- the monitor on synthetic readings ---------------------------------------------------------

/// Readings of a coil floating mid-stroke at 0.5 A on a healthy 24 V bridge.
SensorReadings healthy() {
  SensorReadings r;
  r.i_sense_A = 0.5f;
  r.i_measured_A = 0.5f;
  r.encoder_counts = 20000;
  r.v_applied_V = 2.9f;
  r.supply_V = 24.0f;
  r.dt_s = kDt;
  return r;
}

/// Runs ticks of readings from make(tick) until one is found; returns the tick (-1: none).
int first_finding(SensorMonitor& m, int ticks, const std::function<SensorReadings(int)>& make,
                  SensorFinding& found) {
  for (int k = 0; k < ticks; ++k) {
    found = m.update(make(k));
    if (found.reason != FaultReason::none) return k;
  }
  return -1;
}

SensorMonitor monitor() {
  SensorMonitor m;
  m.configure(24.0f, 0);
  return m;
}

/// A live current-sense reading: it never repeats exactly (ADC noise).
float live(int k) { return 0.5f + 0.0025f * static_cast<float>(k % 3); }

TEST(SensorMonitor, DriverFaultLineTripsAtTheFirstTickWithTheMeasuredCurrentInTenthMilliamps) {
  SensorMonitor m = monitor();
  SensorFinding f;
  const int tick = first_finding(m, 100, [](int k) {
    SensorReadings r = healthy();
    r.i_sense_A = r.i_measured_A = live(k);
    r.driver_fault = k >= 40;
    return r;
  }, f);
  EXPECT_EQ(tick, 40);
  EXPECT_EQ(f.reason, FaultReason::driver_fault);
  EXPECT_EQ(f.detail, 5025);  // live(40) = 0.5025 A
  EXPECT_TRUE(m.cause_present(FaultReason::driver_fault));
  SensorReadings r = healthy();
  r.i_sense_A = live(101);
  (void)m.update(r);
  EXPECT_FALSE(m.cause_present(FaultReason::driver_fault));
}

TEST(SensorMonitor, SupplyBelow75PercentFor1msTripsOnThe20thTickAt20kHzWithMillivolts) {
  SensorMonitor m = monitor();
  SensorFinding f;
  const int tick = first_finding(m, 200, [](int k) {
    SensorReadings r = healthy();
    r.i_sense_A = live(k);
    r.supply_V = k >= 50 ? 17.95f : 24.0f;  // 18 V is the threshold of 24 V
    return r;
  }, f);
  EXPECT_EQ(tick, 69);  // ticks 50..69: 20 ticks = 1 ms
  EXPECT_EQ(f.reason, FaultReason::supply_undervoltage);
  EXPECT_EQ(f.detail, 17950);
}

TEST(SensorMonitor, ASupplyDipShorterThan1msOrAt18VExactlyDoesNotTrip) {
  SensorMonitor m = monitor();
  SensorFinding f;
  EXPECT_EQ(first_finding(m, 2000, [](int k) {
    SensorReadings r = healthy();
    r.i_sense_A = live(k);
    r.supply_V = (k % 100) < 19 ? 12.0f : 24.0f;  // 19 ticks low, then back
    if (k > 1000) r.supply_V = 18.0f;
    return r;
  }, f), -1);
}

TEST(SensorMonitor, SupplyThresholdFollowsParamsSupplyV) {
  SensorMonitor m;
  m.configure(12.0f, 0);  // a 12 V bridge: 9 V is the threshold
  SensorFinding f;
  EXPECT_EQ(first_finding(m, 400, [](int k) {
    SensorReadings r = healthy();
    r.i_sense_A = live(k);
    r.supply_V = 9.5f;
    return r;
  }, f), -1);
  EXPECT_EQ(first_finding(m, 400, [](int k) {
    SensorReadings r = healthy();
    r.i_sense_A = live(k);
    r.supply_V = 8.9f;
    return r;
  }, f), 19);
}

TEST(SensorMonitor, CurrentSenseAtEitherRailTripsAtTheFirstTickWithTheRawReading) {
  for (const float rail : {4.99756f, -5.0f}) {
    SensorMonitor m = monitor();
    SensorFinding f;
    const int tick = first_finding(m, 100, [rail](int k) {
      SensorReadings r = healthy();
      r.i_sense_A = k >= 30 ? rail : live(k);
      return r;
    }, f);
    EXPECT_EQ(tick, 30) << rail;
    EXPECT_EQ(f.reason, FaultReason::current_sense_error);
    EXPECT_EQ(f.detail, rail > 0 ? 49976 : -50000);
  }
  // one code inside the rail is a reading (the loop never drives 4.99 A: the clamp is <= 4 A)
  SensorMonitor m = monitor();
  SensorFinding f;
  EXPECT_EQ(first_finding(m, 100, [](int k) {
    SensorReadings r = healthy();
    r.i_sense_A = 4.99512f + 1e-6f * static_cast<float>(k % 2);
    return r;
  }, f), -1);
}

TEST(SensorMonitor, AFrozenCurrentReadingTripsOnceItLasted1msAndTheVoltageSwung2V) {
  SensorMonitor m = monitor();
  SensorFinding f;
  // frozen from tick 10; the voltage steps by 2.5 V at tick 50: the reading has been identical
  // for 1 ms at tick 30, the voltage spans 2 V from tick 50 on
  const int tick = first_finding(m, 200, [](int k) {
    SensorReadings r = healthy();
    r.i_sense_A = k >= 10 ? 0.4987f : live(k);
    r.v_applied_V = k >= 50 ? 5.4f : 2.9f;
    return r;
  }, f);
  EXPECT_EQ(tick, 50);
  EXPECT_EQ(f.reason, FaultReason::current_sense_error);
  EXPECT_EQ(f.detail, 4987);
  EXPECT_TRUE(m.cause_present(FaultReason::current_sense_error));  // still frozen
  SensorReadings r = healthy();
  r.i_sense_A = 0.0021f;  // it reads again
  (void)m.update(r);
  EXPECT_FALSE(m.cause_present(FaultReason::current_sense_error));
}

TEST(SensorMonitor, AFrozenReadingIsFoundNoSoonerThan1msAfterItFroze) {
  SensorMonitor m = monitor();
  SensorFinding f;
  const int tick = first_finding(m, 200, [](int k) {
    SensorReadings r = healthy();
    r.i_sense_A = k >= 10 ? 0.4987f : live(k);
    r.v_applied_V = k >= 11 ? -24.0f : 2.9f;  // the loop swings at once
    return r;
  }, f);
  EXPECT_EQ(tick, 30);  // identical at ticks 11..30: 20 repeats = 1 ms
}

TEST(SensorMonitor, AConstantReadingAtAConstantVoltageIsNotAFault) {
  SensorMonitor m = monitor();
  SensorFinding f;
  EXPECT_EQ(first_finding(m, 20000, [](int) { return healthy(); }, f), -1);  // 1 s
}

TEST(SensorMonitor, AnEncoderJumpBeyond5MetresPerSecondTripsInThatTickWithTheJump) {
  SensorMonitor m = monitor();
  SensorFinding f;
  const int tick = first_finding(m, 100, [](int k) {
    SensorReadings r = healthy();
    r.i_sense_A = live(k);
    r.encoder_step_counts = k == 60 ? -251 : (k < 60 ? 250 : 0);  // 250 counts = 5 m/s: allowed
    return r;
  }, f);
  EXPECT_EQ(tick, 60);
  EXPECT_EQ(f.reason, FaultReason::encoder_error);
  EXPECT_EQ(f.detail, -251);
  EXPECT_FALSE(m.cause_present(FaultReason::encoder_error));  // a jump is over once it happened
}

TEST(SensorMonitor, TheJumpLimitHalvesAt40kHz) {
  SensorMonitor m = monitor();
  SensorFinding f;
  const int tick = first_finding(m, 100, [](int k) {
    SensorReadings r = healthy();
    r.dt_s = 25e-6f;
    r.i_sense_A = live(k);
    r.encoder_step_counts = k == 7 ? 126 : 125;
    return r;
  }, f);
  EXPECT_EQ(tick, 7);
  EXPECT_EQ(f.detail, 126);
}

/// An encoder frozen at `counts` from tick 0 while the current goes from `from_A` to `to_A` at
/// tick 100 (the reading last changed at tick 0).
int stuck_encoder_trip(std::int32_t counts, float from_A, float to_A, SensorFinding& f) {
  SensorMonitor m = monitor();
  return first_finding(m, 2000, [=](int k) {
    SensorReadings r = healthy();
    r.encoder_counts = counts;
    r.encoder_step_counts = k == 0 ? 3 : 0;
    // a live reading: 0.1 mA of wiggle, away from the start after the change
    const float wiggle = (to_A > from_A ? 1e-4f : -1e-4f) * static_cast<float>(k % 2);
    r.i_sense_A = r.i_measured_A = k >= 100 ? to_A + wiggle : from_A - wiggle;
    return r;
  }, f);
}

TEST(SensorMonitor, AnEncoderStillFor10msWhileTheCurrentMovedHalfAnAmpTripsMidStroke) {
  SensorFinding f;
  EXPECT_EQ(stuck_encoder_trip(20000, 0.5f, 1.0f, f), 299);  // ticks 100..299: 200 = 10 ms
  EXPECT_EQ(f.reason, FaultReason::encoder_error);
  EXPECT_EQ(f.detail, 0);
  EXPECT_EQ(stuck_encoder_trip(20000, 0.5f, 0.0f, f), 299);
  EXPECT_EQ(stuck_encoder_trip(20000, 0.5f, 0.95f, f), -1);  // 0.45 A: may be a stiff contact
}

TEST(SensorMonitor, AtTheRearStopOnlyACurrentThatLiftsTheCoilOffInAnyOrientationCounts) {
  SensorFinding f;
  EXPECT_EQ(stuck_encoder_trip(0, 0.0f, 1.4f, f), -1);   // may still rest on the rear stop
  EXPECT_EQ(stuck_encoder_trip(999, 0.0f, 1.4f, f), -1);
  EXPECT_EQ(stuck_encoder_trip(0, 0.0f, 1.5f, f), 299);
  EXPECT_EQ(stuck_encoder_trip(1000, 0.0f, 1.0f, f), 299);  // 1 mm out: mid-stroke rules
}

TEST(SensorMonitor, AtTheFrontStopOnlyACurrentTheSpringsOvercomeCounts) {
  SensorFinding f;
  EXPECT_EQ(stuck_encoder_trip(34000, 3.0f, 1.0f, f), -1);  // still pressed on the front stop
  EXPECT_EQ(stuck_encoder_trip(34000, 1.0f, 0.3f, f), -1);
  EXPECT_EQ(stuck_encoder_trip(34000, 1.0f, 0.25f, f), 299);
}

TEST(SensorMonitor, TheStopsMoveWithTheCalibratedStrokeOrigin) {
  // homed where the encoder read 20000: a coil resting there is on the rear stop, not mid-stroke
  for (const std::int32_t origin : {20000, 0}) {
    SensorMonitor m;
    m.configure(24.0f, origin);
    SensorFinding f;
    const int tick = first_finding(m, 2000, [](int k) {
      SensorReadings r = healthy();
      r.encoder_counts = 20000;
      r.i_sense_A = r.i_measured_A = (k >= 100 ? 1.4f : 0.0f) + 1e-4f * static_cast<float>(k % 2);
      return r;
    }, f);
    EXPECT_EQ(tick, origin == 20000 ? -1 : 299) << origin;
  }
}

TEST(SensorMonitor, ACoilReleasedFromTheFrontStopThatMovesWithin10msIsNotAFault) {
  // the current falls from 1 A to 0 in 0.5 ms; the springs pull the coil off the stop, the first
  // count changes 2 ms later
  SensorMonitor m = monitor();
  SensorFinding f;
  EXPECT_EQ(first_finding(m, 2000, [](int k) {
    SensorReadings r = healthy();
    const float t_ms = static_cast<float>(k) * 0.05f;
    r.encoder_counts = k < 140 ? 34000 : 34000 - (k - 140);
    r.encoder_step_counts = k == 0 || k >= 140 ? -1 : 0;
    r.i_sense_A = r.i_measured_A = t_ms < 5.0f ? 1.0f : std::fmax(0.0f, 1.0f - (t_ms - 5.0f) * 2.0f);
    return r;
  }, f), -1);
}

// --- the controller's reaction -----------------------------------------------------------------

/// The controller against an exact RL coil and a free-air coil on its springs (the plant's
/// numbers: 161 g, 43.9 N/m with the neutral point 46 mm behind the rear stop, K_f 3 N/A, probe
/// pointing down, inelastic stops at 0 and 34 mm), with the host's requests in between.
class Rig {
 public:
  Rig() : c_(DeviceIdentity{}) { send(Hello{kProtocolMajor, kProtocolMinor, kSchemaHash, "test"}); }

  template <class M>
  void send(const M& m) {
    std::vector<u8> w(kMaxWireFrame);
    w.resize(encode_message(m, seq_++, 0, w.data(), w.size()));
    c_.receive(w.data(), w.size(), kWatchdogUs);
    pump();
  }

  /// One tick; `fault` may change the board's readings.
  void tick() {
    TickInputs in;
    in.i_sense_A = static_cast<float>(i_A_);
    true_counts_ = static_cast<std::int32_t>(std::lround(s_m_ * 1e6));
    in.encoder_timer = static_cast<std::uint16_t>(true_counts_);
    in.watchdog_now_us = kWatchdogUs;
    if (fault) fault(in);
    sensed_ = in;
    TickOutputs out;
    c_.tick(in, out);
    v_ = out.v_coil_V;
    const double dt = 1.0 / c_.control_rate_Hz();
    const double a = std::exp(-5.8 * dt / 2.07e-3);
    i_A_ = i_A_ * a + v_ / 5.8 * (1 - a);
    const double f_N = 3.0 * i_A_ - 43.9 * (s_m_ + 0.046) + 0.161 * 9.80665 - 1.38 * speed_;
    speed_ += f_N / 0.161 * dt;
    s_m_ += speed_ * dt;
    if (s_m_ < 0.0 || s_m_ > 0.034) {
      s_m_ = std::fmin(std::fmax(s_m_, 0.0), 0.034);
      speed_ = 0.0;
    }
    if ((c_.ticks() & 7u) == 0) pump();
  }
  void run(int n) {
    for (int k = 0; k < n; ++k) tick();
    pump();
  }
  /// Runs until the controller faults (at most n ticks); returns the tick that tripped (-1: none).
  std::int64_t run_until_fault(int n) {
    for (int k = 0; k < n; ++k) {
      const std::uint64_t now = c_.ticks();
      tick();
      if (c_.faulted()) {
        pump();
        return static_cast<std::int64_t>(now);
      }
    }
    pump();
    return -1;
  }

  void pump() {
    c_.service();
    u8 buf[4096];
    std::size_t n;
    while ((n = c_.transmit(buf, sizeof buf)) > 0) {
      host_.feed_messages(buf, n, [&](const FrameHeader&, const auto& m) {
        using M = std::decay_t<decltype(m)>;
        if constexpr (std::is_same_v<M, EventFault>) faults_.push_back(m);
        if constexpr (std::is_same_v<M, Nak>) naks_.push_back(m);
        if constexpr (std::is_same_v<M, Ack>) acks_.push_back(m);
        if constexpr (std::is_same_v<M, Status>) status_ = m;
        if constexpr (std::is_same_v<M, SampleBatch>) {
          Reader r(m.data.items.data(), m.data.size);
          for (u16 k = 0; k < m.sample_count; ++k) {
            RawSample s;
            if (!unpack_sample(r, s, m.channels)) break;
            samples_.push_back({m.first_time_us + k * m.period_ns / 1000u, s});
          }
        }
      }, [](Reject r) { ADD_FAILURE() << "bad device frame " << static_cast<int>(r); });
    }
  }

  /// A 0.6 A hold started, with the full stream on: the coil floats at about 31 mm.
  void hold_and_stream(float current_A = 0.6f) {
    send(StreamConfigure{kAllChannels, 2, 40});
    send(StreamStart{});
    send(LoadHold{current_A, 0.0f});
    send(ProgramStart{});
    run(8000);  // 0.4 s: settled
  }

  static constexpr std::uint64_t kWatchdogUs = 1'000'000;  // the host feeds it: no timeout
  Controller c_;
  std::function<void(TickInputs&)> fault;
  TickInputs sensed_{};
  std::int32_t true_counts_ = 0;
  double i_A_ = 0, s_m_ = 0, speed_ = 0;
  float v_ = 0;
  u16 seq_ = 1;
  FrameReader host_;
  std::vector<EventFault> faults_;
  std::vector<Nak> naks_;
  std::vector<Ack> acks_;
  Status status_{};
  struct Timed {
    u64 t_us;
    RawSample s;
  };
  std::vector<Timed> samples_;
};

constexpr u16 kFaultBit = 1u << static_cast<unsigned>(StatusBit::fault_latched);

/// The reaction every sensor fault shares: one EventFault with this reason and detail at the
/// trip tick's time, 0 V from that tick on, the status, and every sample from that tick on
/// marked fault_latched with 0 A and 0 V commanded (none before it).
void expect_reaction(Rig& r, std::int64_t trip_tick, FaultReason reason, std::int32_t detail) {
  ASSERT_GE(trip_tick, 0) << "no trip";
  ASSERT_EQ(r.faults_.size(), 1u);
  EXPECT_EQ(r.faults_[0].reason, reason);
  EXPECT_EQ(r.faults_[0].detail, detail);
  const u64 trip_us = static_cast<u64>(trip_tick) * 50u;
  EXPECT_EQ(r.faults_[0].time_us, trip_us);
  EXPECT_EQ(r.v_, 0.0f);  // the tick that tripped applied 0 V
  r.run(200);
  EXPECT_EQ(r.v_, 0.0f);
  r.send(GetStatus{});
  EXPECT_EQ(r.status_.state, DeviceState::faulted);
  EXPECT_EQ(r.status_.fault, reason);
  std::size_t before = 0, after = 0;
  for (const Rig::Timed& t : r.samples_) {
    if (t.t_us < trip_us) {
      ++before;
      EXPECT_EQ(t.s.status & kFaultBit, 0u) << t.t_us;
    } else {
      ++after;
      EXPECT_NE(t.s.status & kFaultBit, 0u) << t.t_us;
      EXPECT_EQ(t.s.i_cmd, 0) << t.t_us;
      EXPECT_EQ(t.s.v_cmd, 0) << t.t_us;
    }
  }
  EXPECT_GT(before, 1000u);
  EXPECT_GT(after, 50u);
}

std::int32_t tenth_mA(float i_A) { return static_cast<std::int32_t>(std::lround(i_A * 1e4f)); }

/// FaultClear is refused (fault_persists) while the fault is on, accepted once it is off.
void expect_clear_only_without_cause(Rig& r) {
  r.send(FaultClear{});
  ASSERT_EQ(r.naks_.size(), 1u);
  EXPECT_EQ(r.naks_[0].error, ErrorCode::fault_persists);
  EXPECT_TRUE(r.c_.faulted());
  r.fault = nullptr;
  r.run(2);
  r.send(FaultClear{});
  EXPECT_EQ(r.naks_.size(), 1u);
  EXPECT_FALSE(r.c_.faulted());
}

TEST(SensorFaultReaction, DriverFaultLineTripsInItsFirstTickWithZeroVoltsEventAndMarkedSamples) {
  Rig r;
  r.hold_and_stream();
  ASSERT_GT(r.v_, 1.0f);
  r.fault = [](TickInputs& in) { in.driver_fault = true; };
  const std::int64_t tick = r.run_until_fault(10);
  EXPECT_EQ(tick, 8000);
  const std::int32_t detail = tenth_mA(r.sensed_.i_sense_A);
  EXPECT_NEAR(detail, 6000, 10);  // 0.6 A
  expect_reaction(r, tick, FaultReason::driver_fault, detail);
  expect_clear_only_without_cause(r);
}

TEST(SensorFaultReaction, SupplySagTo17VTripsAfter1msWithTheSupplyInMillivolts) {
  Rig r;
  r.hold_and_stream();
  r.fault = [](TickInputs& in) { in.supply_V = 17.0f; };
  const std::int64_t tick = r.run_until_fault(100);
  EXPECT_EQ(tick, 8019);
  expect_reaction(r, tick, FaultReason::supply_undervoltage, 17000);
  expect_clear_only_without_cause(r);
}

TEST(SensorFaultReaction, CurrentSenseSaturatedTripsInTheFirstTickWithTheRailReading) {
  Rig r;
  r.hold_and_stream();
  r.fault = [](TickInputs& in) { in.i_sense_A = 4.99756f; };  // code 4095 of +-5 A
  const std::int64_t tick = r.run_until_fault(10);
  EXPECT_EQ(tick, 8000);
  expect_reaction(r, tick, FaultReason::current_sense_error, 49976);
  expect_clear_only_without_cause(r);
}

TEST(SensorFaultReaction, CurrentSenseStuckTripsTheTickAfterTheLoopSwingsTheVoltage) {
  Rig r;
  r.hold_and_stream();
  const float frozen = r.sensed_.i_sense_A;
  r.fault = [frozen](TickInputs& in) { in.i_sense_A = frozen; };
  EXPECT_EQ(r.run_until_fault(400), -1);  // 20 ms at a steady voltage: nothing to see
  const std::int64_t stop_tick = static_cast<std::int64_t>(r.c_.ticks());
  r.send(ProgramStop{});  // the set-point drops to 0: the loop swings the voltage at once
  const std::int64_t tick = r.run_until_fault(100);
  EXPECT_EQ(tick, stop_tick + 1);
  expect_reaction(r, tick, FaultReason::current_sense_error, tenth_mA(frozen));
  expect_clear_only_without_cause(r);
}

TEST(SensorFaultReaction, EncoderGlitchOf1000CountsTripsInThatTickWithTheJump) {
  Rig r;
  r.hold_and_stream();
  const std::int32_t before = r.true_counts_;
  r.fault = [](TickInputs& in) { in.encoder_timer = static_cast<std::uint16_t>(in.encoder_timer + 1000); };
  const std::int64_t tick = r.run_until_fault(10);
  EXPECT_EQ(tick, 8000);
  expect_reaction(r, tick, FaultReason::encoder_error, r.true_counts_ + 1000 - before);
}

TEST(SensorFaultReaction, EncoderStuckTrips10msAfterTheCurrentLeftItsValueByHalfAnAmp) {
  Rig r;
  r.hold_and_stream();
  r.run(22000);  // 1.5 s in all: the floating coil has settled mid-stroke
  const std::uint16_t frozen = r.sensed_.encoder_timer;
  ASSERT_GT(r.true_counts_, 2000);
  ASSERT_LT(r.true_counts_, 32000);
  // the reference: the measured current the last time the count changed
  r.fault = [frozen](TickInputs& in) { in.encoder_timer = frozen; };
  EXPECT_EQ(r.run_until_fault(400), -1);  // nothing moves the current: nothing to see
  const float ref = r.sensed_.i_sense_A;   // settled: the current when the count last moved
  r.send(ProgramStop{});
  std::int64_t first = -1, tick = -1;
  for (int k = 0; k < 1000 && tick < 0; ++k) {
    const std::int64_t now = static_cast<std::int64_t>(r.c_.ticks());
    r.tick();
    if (first < 0 && std::fabs(r.sensed_.i_sense_A - ref) >= 0.5f) first = now;
    if (r.c_.faulted()) tick = now;
  }
  r.pump();
  ASSERT_GE(first, 0);
  EXPECT_EQ(tick, first + 199);  // 200 ticks = 10 ms
  expect_reaction(r, tick, FaultReason::encoder_error, 0);
}

TEST(SensorFaultReaction, AHealthyRigRunsHoldsStepsAndStopsWithoutASensorFault) {
  Rig r;
  r.hold_and_stream(0.6f);
  r.send(ProgramStop{});
  r.run(20000);  // back to the rear stop
  r.send(LoadHold{3.0f, 0.0f});  // to the front stop and beyond the rear-stop lift-off
  r.send(ProgramStart{});
  r.run(20000);
  EXPECT_NEAR(r.i_A_, 3.0, 0.01);
  EXPECT_NEAR(r.s_m_, 0.034, 1e-9);  // pressed on the front stop
  r.send(ProgramStop{});  // released from the front stop
  r.run(20000);
  EXPECT_FALSE(r.c_.faulted());
  EXPECT_TRUE(r.faults_.empty());
}

}  // namespace
}  // namespace palp::fw::sensor_faults_test
