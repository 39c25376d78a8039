// SPDX-License-Identifier: Apache-2.0
// The controller end to end at the protocol level: a host's frames in, the device's frames out,
// with an exact RL coil on the other side of the tick. Virtual control time and a separate
// watchdog clock, as on hardware.
#include <gtest/gtest.h>

#include "controller_bench.hpp"

namespace palp::fw {
namespace {

using namespace palp::proto;
using test::Bench;

TEST(Controller, HelloFromThisBuildIsAnsweredWithDeviceInfoAndTheSameSeq) {
  Bench b(Bench::Start::without_hello);
  b.send(Hello{kProtocolMajor, kProtocolMinor, kSchemaHash, "test"}, 77);
  b.pump();
  ASSERT_FALSE(b.got_.empty());
  EXPECT_EQ(b.last_frame().header.seq, 77);
  EXPECT_EQ(b.last_frame().header.flags, kFlagResponse);
  const DeviceInfo d = b.last<DeviceInfo>();
  EXPECT_EQ(d.state, DeviceState::idle);
  EXPECT_EQ(d.schema_hash, kSchemaHash);
  EXPECT_EQ(std::string(d.board.bytes.data()), "test-bench");
  EXPECT_EQ(d.heartbeat_timeout_ms, 500u);
}

TEST(Controller, AfterAnIncompatibleHelloOnlyFrozenRequestsAreServed) {
  Bench b;
  b.send(Hello{kProtocolMajor, kProtocolMinor, kSchemaHash ^ 1u, "other build"});
  b.send(GetStatus{}, 2);
  b.send(GetDeviceInfo{}, 3);
  b.send(EnterBootloader{0x544F4F42u}, 4);
  b.pump();
  EXPECT_EQ(b.all<DeviceInfo>().front().state, DeviceState::incompatible);
  EXPECT_EQ(b.last<Nak>().error, ErrorCode::incompatible_host);
  EXPECT_EQ(b.all<DeviceInfo>().size(), 2u);
  EXPECT_EQ(b.last<Ack>().request_id, static_cast<u8>(MessageId::EnterBootloader));
  EXPECT_TRUE(b.c_.bootloader_requested());
  // a compatible Hello restores the session
  b.send(Hello{kProtocolMajor, kProtocolMinor, kSchemaHash, "this build"}, 5);
  b.send(GetStatus{}, 6);
  b.pump();
  EXPECT_EQ(b.all<Status>().size(), 1u);
}

TEST(Controller, AHostOfAnotherMajorCanStillIdentifyTheDevice) {
  Bench b(Bench::Start::without_hello);
  b.send(GetDeviceInfo{}, 9, kProtocolMajor + 1);
  b.send(Ping{1, 2}, 10, kProtocolMajor + 1);  // not frozen: rejected at frame level, no reply
  b.pump();
  ASSERT_EQ(b.got_.size(), 1u);
  EXPECT_EQ(b.got_[0].name, "DeviceInfo");
  EXPECT_EQ(b.c_.health().rx_unsupported_major, 1u);
}

TEST(Controller, PongCarriesTheExactDeviceTime) {
  Bench b;
  b.run_ticks(2000);  // 100 ms at 20 kHz
  b.send(Ping{42, 123456}, 3);
  b.pump();
  const Pong p = b.last<Pong>();
  EXPECT_EQ(p.nonce, 42u);
  EXPECT_EQ(p.host_time_us, 123456u);
  EXPECT_EQ(p.device_time_us, 100000u);
}

TEST(Controller, BadRequestsAreRefusedWithTheirReasonAndField) {
  Bench b;
  SetParams p;
  p.heartbeat_timeout_ms = 20;
  b.send(p, 4);
  b.pump();
  Nak n = b.last<Nak>();
  EXPECT_EQ(n.error, ErrorCode::out_of_range);
  EXPECT_EQ(n.field_index, 6);
  EXPECT_EQ(b.last_frame().header.seq, 4);

  p.heartbeat_timeout_ms = 500;
  p.control_rate_Hz = 30000;
  b.send(p, 5);
  b.pump();
  EXPECT_EQ(b.last<Nak>().field_index, 7);

  b.send(Pong{}, 6);  // a device-to-host message
  b.pump();
  EXPECT_EQ(b.last<Nak>().error, ErrorCode::wrong_direction);

  std::vector<u8> w(kMaxWireFrame);
  const u8 junk[] = {1, 2};
  w.resize(encode_frame(FrameHeader{kProtocolMajor, kProtocolMinor, 0xEE, 0, 7, 0}, junk, 2,
                        w.data(), w.size()));
  b.c_.receive(w.data(), w.size(), b.wd_us_);
  b.pump();
  EXPECT_EQ(b.last<Nak>().error, ErrorCode::unknown_message);
  EXPECT_EQ(b.last_frame().header.seq, 7);
  EXPECT_EQ(b.c_.health().rx_unknown_message, 1u);
}

TEST(Controller, CrossFieldRefusalsNameTheSpecTablesFieldNumbers) {
  Bench b;
  SetParams p;
  p.travel_min_counts = p.travel_max_counts;  // each in range, but no travel left
  b.send(p, 1);
  b.pump();
  EXPECT_EQ(b.last<Nak>().error, ErrorCode::out_of_range);
  EXPECT_EQ(b.last<Nak>().field_index, 4);  // SPEC.md §10.1 SetParams #4 travel_min_counts

  b.send(EnterBootloader{0x544F4F41u}, 2);
  b.pump();
  EXPECT_EQ(b.last<Nak>().error, ErrorCode::bad_magic);
  EXPECT_EQ(b.last<Nak>().field_index, 0);  // EnterBootloader #0 magic

  SetCalibration c;
  c.kf_position_counts.push_back(0);
  c.kf_position_counts.push_back(10000);
  c.kf_N_per_A.push_back(3.5f);  // one force constant for two positions
  b.send(c, 3);
  b.pump();
  EXPECT_EQ(b.last<Nak>().error, ErrorCode::calibration_invalid);
  EXPECT_EQ(b.last<Nak>().field_index, 2);  // SetCalibration #2 kf_N_per_A
}

/// How many fields of m differ from its message's defaults.
template <class M>
std::size_t fields_unlike_defaults(const M& m) {
  const M defaults{};
  std::size_t differing = 0, k = 0;
  m.visit([&](const FieldInfo&, const auto& value) {
    std::size_t j = 0;
    defaults.visit([&](const FieldInfo&, const auto& default_value) {
      if constexpr (std::is_same_v<decltype(value), decltype(default_value)>)
        if (j == k && !(value == default_value)) ++differing;
      ++j;
    });
    ++k;
  });
  return differing;
}

TEST(Controller, SetParamsWithEveryFieldChangedComesBackExactlyFromGetParams) {
  SetParams p;
  p.current_clamp_A = 2.5f;
  p.i2t_continuous_A = 1.5f;
  p.i2t_limit_A2s = 70.0f;
  p.i2t_tau_s = 90.0f;
  p.travel_min_counts = -2000;
  p.travel_max_counts = 30000;
  p.heartbeat_timeout_ms = 750;
  p.control_rate_Hz = 40000;
  p.supply_V = 12.0f;
  p.contact_output = ContactOutputMode::active_low;
  p.contact_output_hold_ms = 250;
  ASSERT_EQ(fields_unlike_defaults(p), SetParams::kFields.size());

  Bench b;
  b.send(p, 1);
  b.pump();
  // Params and SetParams share their field list, so their payloads are byte for byte the same
  const std::vector<u8> sent = b.payload_of(p);
  ASSERT_EQ(b.last_frame().name, "Params");
  EXPECT_EQ(b.last_frame().payload, sent);
  b.send(GetParams{}, 2);
  b.pump();
  ASSERT_EQ(b.last_frame().name, "Params");
  EXPECT_EQ(b.last_frame().payload, sent);
  EXPECT_EQ(b.c_.control_rate_Hz(), 40000u);
}

TEST(Controller, SetCalibrationWithEveryFieldChangedComesBackExactlyFromGetCalibration) {
  SetCalibration c;
  // layout_version is informative: the device always answers with its own (2, the default)
  for (const i32 x : {0, 9000, 21000, 34000}) c.kf_position_counts.push_back(x);
  for (const f32 k : {3.84f, 3.6f, 3.2f, 2.918f}) c.kf_N_per_A.push_back(k);
  c.current_offset_A = 0.012f;
  c.current_gain = 1.03f;
  c.pressure_offset_Pa = {-15.0f, -5.0f, 0.5f, 5.0f, 15.0f, 25.0f};
  c.pressure_gain = {0.9f, 0.95f, 1.05f, 1.1f, 1.15f, 1.2f};
  c.spring_k_N_per_m = 41.5f;
  c.stroke_origin_counts = -321;
  c.stroke_origin_valid = 1;
  ASSERT_EQ(fields_unlike_defaults(c), SetCalibration::kFields.size() - 1);

  Bench b;
  b.send(c, 1);
  b.pump();
  const std::vector<u8> sent = b.payload_of(c);
  ASSERT_EQ(b.last_frame().name, "Calibration");
  EXPECT_EQ(b.last_frame().payload, sent);
  b.send(GetCalibration{}, 2);
  b.pump();
  ASSERT_EQ(b.last_frame().name, "Calibration");
  EXPECT_EQ(b.last_frame().payload, sent);
}

TEST(Controller, AHoldProgramDrivesTheCoilToItsCurrent) {
  Bench b;
  b.send(LoadHold{1.0f, 0.0f}, 1);
  b.send(ProgramStart{}, 2);
  b.run_ticks(200);  // 10 ms: the loop settles in about 0.5 ms
  EXPECT_NEAR(b.i_A_, 1.0, 0.01);
  b.send(GetStatus{}, 3);
  b.pump();
  const Status s = b.last<Status>();
  EXPECT_EQ(s.state, DeviceState::running);
  EXPECT_FLOAT_EQ(s.i_cmd_A, 1.0f);
  EXPECT_NE(s.status_bits & (1u << static_cast<unsigned>(StatusBit::heartbeat_armed)), 0u);
}

TEST(Controller, AStaleHostHeartbeatTripsAndZeroesTheCoilInThatTick) {
  Bench b;
  b.send(LoadHold{1.0f, 0.0f}, 1);
  b.send(ProgramStart{}, 2);
  b.run_ticks(100);
  b.wd_us_ += 501'000;  // the host went quiet for 501 ms of wall time
  b.run_ticks(1);
  EXPECT_EQ(b.last_out_.v_coil_V, 0.0f);
  EXPECT_EQ(b.last<EventFault>().reason, FaultReason::heartbeat_timeout);
  EXPECT_EQ(b.last<EventProgramFinished>().end, ProgramEnd::fault);
  b.send(ProgramStart{}, 3);
  b.pump();
  EXPECT_EQ(b.last<Nak>().error, ErrorCode::faulted);
  b.send(FaultClear{}, 4);
  b.pump();
  EXPECT_EQ(b.last<Ack>().request_id, static_cast<u8>(MessageId::FaultClear));
  EXPECT_FALSE(b.c_.faulted());
}

TEST(Controller, ControlTimeRacingAheadDoesNotTripTheWatchdog) {
  Bench b;
  b.send(LoadHold{0.5f, 0.0f}, 1);
  b.send(ProgramStart{}, 2);
  b.run_ticks(40000);  // 2 s of control time, no wall time passes
  EXPECT_FALSE(b.c_.faulted());
}

TEST(Controller, StreamsEverySampleInOrderWithExactTimes) {
  Bench b;
  b.send(StreamConfigure{kAllChannels, 2, 40}, 1);
  b.send(StreamStart{}, 2);
  b.run_ticks(4000);  // 200 ms: 2000 samples at 10 kHz
  b.send(StreamStop{}, 3);
  b.run_ticks(1);
  const auto batches = b.all<SampleBatch>();
  std::uint32_t next = 0;
  for (const SampleBatch& s : batches) {
    ASSERT_EQ(s.first_index, next);
    EXPECT_EQ(check_batch(s), BatchProblem::none);
    EXPECT_EQ(s.first_time_us, 100u * s.first_index);
    next += s.sample_count;
  }
  EXPECT_EQ(next, 2000u);
  EXPECT_TRUE(b.all<EventStreamGap>().empty());
}

TEST(Controller, AContactWatchFiresAtExactlyItsThreshold) {
  Bench b;
  b.send(LoadContactWatch{0.5f, 200, 0.0f}, 1);
  b.send(ProgramStart{}, 2);
  b.encoder_per_tick_ = 1;  // the coil moves 1 um per tick
  b.run_ticks(400);
  const EventContact c = b.last<EventContact>();
  EXPECT_EQ(c.encoder_count - c.armed_count, 200);
  EXPECT_EQ(b.last<EventProgramFinished>().end, ProgramEnd::contact);
}

TEST(Controller, ACorruptedFrameIsCountedAndNotAnswered) {
  Bench b;
  std::vector<u8> w(kMaxWireFrame);
  w.resize(encode_message(Ping{1, 2}, 1, 0, w.data(), w.size()));
  w[5] ^= 0x10;
  b.c_.receive(w.data(), w.size(), b.wd_us_);
  b.pump();
  EXPECT_TRUE(b.got_.empty());
  EXPECT_EQ(b.c_.health().rx_bad_crc, 1u);
}
TEST(Controller, DeviceTimeRunsOnContinuouslyAcrossControlRateChangesInBothDirections) {
  Bench b;
  b.run_ticks(2000);  // 100 ms at 20 kHz
  SetParams p = fields_as<SetParams>(b.c_.params());
  p.control_rate_Hz = 40000;
  b.send(p, 1);
  b.run_ticks(2000);  // 50 ms at 40 kHz
  b.send(GetStatus{}, 2);
  b.pump();
  EXPECT_EQ(b.last<Status>().device_time_us, 150'000u);  // was 100'000: 4000 ticks / 40 kHz
  p.control_rate_Hz = 20000;
  b.send(p, 3);
  b.run_ticks(1000);  // 50 ms at 20 kHz
  b.send(GetStatus{}, 4);
  b.pump();
  EXPECT_EQ(b.last<Status>().device_time_us, 200'000u);  // was 250'000: 5000 ticks / 20 kHz
  // a stream started after the changes stamps its samples on the same clock
  b.send(StreamConfigure{}, 5);
  b.send(StreamStart{}, 6);
  b.run_ticks(400);
  b.send(StreamStop{}, 7);
  b.pump();
  const auto batches = b.all<SampleBatch>();
  ASSERT_FALSE(batches.empty());
  EXPECT_GE(batches.front().first_time_us, 200'000u);
  EXPECT_LT(batches.front().first_time_us, 201'000u);
}

}  // namespace
}  // namespace palp::fw
