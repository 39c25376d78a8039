// SPDX-License-Identifier: Apache-2.0
// The protocol's refusals as the controller makes them (SPEC.md §6.2, §6.3, §9.1): the Hello
// gate, which refusal wins when several apply, the Nak fields, the last stream batch after the
// StreamStop Ack, the Health snapshot's own request, and each fault reason's EventFault.detail.
#include <gtest/gtest.h>

#include <limits>

#include "controller_bench.hpp"

namespace palp::fw {
namespace {

using namespace palp::proto;
using test::Bench;

/// The device's bytes since the last call, raw.
std::string wire_out(Bench& b) {
  b.c_.service();
  std::vector<u8> out;
  u8 buf[4096];
  std::size_t n;
  while ((n = b.c_.transmit(buf, sizeof buf)) > 0) out.insert(out.end(), buf, buf + n);
  return to_hex(out);
}

/// Calls f(message) with a default-constructed message of every host-to-device type.
template <class F>
void for_each_request(F&& f) {
  for_each_message_type([&](auto m) {
    if constexpr (decltype(m)::kDirection == Direction::H2D) f(m);
  });
}

TEST(HelloGate, ALoadHoldBeforeHelloGetsTheHelloRequiredNakOfSpec12_6ByteForByteAndLoadsNothing) {
  Bench b(Bench::Start::without_hello);
  b.send(LoadHold{0.3f, 0.0f}, 2);
  // protocol/vectors/messages.txt, Nak.hello_required (SPEC.md §12.6)
  EXPECT_EQ(wire_out(b), "06 01 01 06 01 02 02 08 03 20 0e 02 ff 01 01 01 05 f3 93 bd 42 00");
  b.send(ProgramStart{}, 3);
  b.run_ticks(200);
  EXPECT_EQ(b.last<Nak>().error, ErrorCode::hello_required);
  EXPECT_EQ(b.last_out_.v_coil_V, 0.0f);  // the raw client of issue 17 drove 0.3 A here
  b.send(Hello{kProtocolMajor, kProtocolMinor, kSchemaHash, "late"}, 4);
  b.send(GetProgramStatus{}, 5);
  b.pump();
  EXPECT_EQ(b.last<ProgramStatus>().state, ProgramState::idle);
}

TEST(HelloGate, BeforeHelloEveryRequestButTheFrozenOnesIsRefusedWithHelloRequired) {
  Bench b(Bench::Start::without_hello);
  int refused = 0;
  for_each_request([&](auto m) {
    using M = decltype(m);
    if constexpr (std::is_same_v<M, Hello>) return;  // it would open the session: below
    b.clear();
    if constexpr (std::is_same_v<M, EnterBootloader>) m.magic = 0x544F4F42u;
    b.send(m, 40);
    b.pump();
    ASSERT_EQ(b.got_.size(), 1u) << M::kName;
    if (is_frozen_id(static_cast<u8>(M::kId))) {
      EXPECT_NE(b.got_[0].name, "Nak") << M::kName << " is frozen and must be served";
      return;
    }
    const Nak n = b.last<Nak>();
    EXPECT_EQ(n.request_id, static_cast<u8>(M::kId)) << M::kName;
    EXPECT_EQ(n.error, ErrorCode::hello_required) << M::kName;
    EXPECT_EQ(n.field_index, 255) << M::kName;
    EXPECT_EQ(n.detail, 0) << M::kName;
    ++refused;
  });
  EXPECT_EQ(refused, 22);  // every request of protocol 1.1 but Hello, GetDeviceInfo, EnterBootloader
  EXPECT_TRUE(b.c_.bootloader_requested());  // EnterBootloader was served
  EXPECT_FALSE(b.c_.session_open());
}

TEST(HelloGate, AfterACompatibleHelloNoRequestIsRefusedForTheSession) {
  Bench b;
  for_each_request([&](auto m) {
    using M = decltype(m);
    if constexpr (std::is_same_v<M, EnterBootloader>) m.magic = 0x544F4F42u;
    if constexpr (std::is_same_v<M, Hello>) m = Hello{kProtocolMajor, kProtocolMinor, kSchemaHash, "again"};
    b.clear();
    b.send(m, 41);
    b.pump();
    for (const auto& n : b.all<Nak>()) {
      EXPECT_NE(n.error, ErrorCode::hello_required) << M::kName;
      EXPECT_NE(n.error, ErrorCode::incompatible_host) << M::kName;
    }
    EXPECT_FALSE(b.got_.empty()) << M::kName;
  });
}

TEST(HelloGate, AnIncompatibleHelloClosesTheSessionAndAnEndedSessionNeedsANewHello) {
  Bench b;
  b.send(Hello{kProtocolMajor, static_cast<u8>(kProtocolMinor), kSchemaHash ^ 1u, "other build"}, 1);
  b.send(LoadHold{0.3f, 0.0f}, 2);
  b.pump();
  EXPECT_EQ(b.all<DeviceInfo>().back().state, DeviceState::incompatible);
  EXPECT_EQ(b.last<Nak>().error, ErrorCode::incompatible_host);

  b.send(Hello{kProtocolMajor, kProtocolMinor, kSchemaHash, "this build"}, 3);
  b.send(LoadHold{0.3f, 0.0f}, 4);
  b.pump();
  EXPECT_EQ(b.last<Ack>().request_id, static_cast<u8>(MessageId::LoadHold));

  b.c_.end_session();  // palp-sim: a new client connected
  b.send(GetStatus{}, 5);
  b.send(GetDeviceInfo{}, 6);
  b.pump();
  EXPECT_EQ(b.last<Nak>().error, ErrorCode::hello_required);
  EXPECT_EQ(b.last<DeviceInfo>().state, DeviceState::idle);  // identify still works
}

TEST(HelloGate, ASecondCompatibleHelloKeepsTheRunningProgramAndStream) {
  Bench b;
  b.send(LoadHold{0.3f, 0.0f}, 1);
  b.send(ProgramStart{}, 2);
  b.send(StreamStart{}, 3);
  b.run_ticks(400);
  b.send(Hello{kProtocolMajor, kProtocolMinor, kSchemaHash, "again"}, 4);
  b.send(GetStatus{}, 5);
  b.pump();
  EXPECT_EQ(b.last<DeviceInfo>().state, DeviceState::running);
  const Status s = b.last<Status>();
  EXPECT_EQ(s.program_state, ProgramState::running);
  EXPECT_EQ(s.streaming, 1);
}

// A peer outside a session cannot keep the coil energised: its requests do not feed the watchdog.
TEST(HelloGate, RequestsOutsideAnOpenSessionDoNotFeedTheWatchdog) {
  for (const bool incompatible : {false, true}) {
    Bench b;
    b.send(LoadHold{0.3f, 0.0f}, 1);
    b.send(ProgramStart{}, 2);
    b.run_ticks(100);
    if (incompatible) b.send(Hello{static_cast<u8>(kProtocolMajor), kProtocolMinor, kSchemaHash ^ 1u, "x"}, 3);
    else b.c_.end_session();
    for (int k = 0; k < 10; ++k) {  // 1 s of watchdog time, a request every 100 ms
      b.wd_us_ += 100'000;
      b.send(GetDeviceInfo{}, static_cast<u16>(10 + k));
      b.send(Ping{1, 2}, static_cast<u16>(30 + k));
      b.run_ticks(20);
    }
    EXPECT_TRUE(b.c_.faulted()) << (incompatible ? "incompatible Hello" : "no Hello");
    EXPECT_EQ(b.c_.fault(), FaultReason::heartbeat_timeout);
    EXPECT_EQ(b.last_out_.v_coil_V, 0.0f);
  }
  // the same traffic inside a session feeds it
  Bench b;
  b.send(LoadHold{0.3f, 0.0f}, 1);
  b.send(ProgramStart{}, 2);
  for (int k = 0; k < 10; ++k) {
    b.wd_us_ += 100'000;
    b.send(Ping{1, 2}, static_cast<u16>(30 + k));
    b.run_ticks(20);
  }
  EXPECT_FALSE(b.c_.faulted());
}

// SPEC.md §6.3 "Which refusal wins".
TEST(RefusalPrecedence, PayloadAndDirectionChecksComeBeforeTheHelloGate) {
  Bench b(Bench::Start::without_hello);
  std::vector<u8> w(kMaxWireFrame);
  const u8 junk[] = {1, 2};
  w.resize(encode_frame(FrameHeader{kProtocolMajor, kProtocolMinor, 0xEE, 0, 7, 0}, junk, 2,
                        w.data(), w.size()));
  b.c_.receive(w.data(), w.size(), b.wd_us_);
  b.pump();
  EXPECT_EQ(b.last<Nak>().error, ErrorCode::unknown_message);

  const u8 short_payload[] = {1};  // LoadHold needs 8 bytes
  w.assign(kMaxWireFrame, 0);
  w.resize(encode_frame(FrameHeader{kProtocolMajor, kProtocolMinor, 0x20, 0, 8, 0}, short_payload,
                        1, w.data(), w.size()));
  b.c_.receive(w.data(), w.size(), b.wd_us_);
  b.pump();
  EXPECT_EQ(b.last<Nak>().error, ErrorCode::bad_payload);

  b.send(Pong{}, 9);
  b.pump();
  EXPECT_EQ(b.last<Nak>().error, ErrorCode::wrong_direction);
}

TEST(RefusalPrecedence, TheHelloGateWinsOverOutOfRangeAndFaulted) {
  Bench b;
  b.send(LoadHold{0.3f, 0.0f}, 1);
  b.send(ProgramStart{}, 2);
  b.run_ticks(100);
  b.wd_us_ += 2'000'000;  // no host for 2 s: heartbeat_timeout latches
  b.run_ticks(10);
  ASSERT_TRUE(b.c_.faulted());

  SetParams bad;
  bad.heartbeat_timeout_ms = 20;  // out_of_range
  b.c_.end_session();
  b.send(bad, 3);
  b.send(ProgramStart{}, 4);  // faulted
  b.pump();
  auto naks = b.all<Nak>();
  ASSERT_EQ(naks.size(), 2u);
  EXPECT_EQ(naks[0].error, ErrorCode::hello_required);
  EXPECT_EQ(naks[1].error, ErrorCode::hello_required);

  b.send(Hello{kProtocolMajor, kProtocolMinor, kSchemaHash ^ 1u, "other build"}, 5);
  b.send(bad, 6);
  b.pump();
  EXPECT_EQ(b.last<Nak>().error, ErrorCode::incompatible_host);
}

TEST(RefusalPrecedence, WithinARequestTheOrderIsTheSpecsPerMessageOrder) {
  Bench b;
  // ProgramStart: faulted before no_program
  b.send(LoadHold{0.3f, 0.0f}, 1);
  b.send(ProgramStart{}, 2);
  b.run_ticks(100);
  b.send(ProgramStop{}, 3);
  b.run_ticks(10);
  b.send(LoadHold{0.3f, 0.0f}, 4);
  b.send(ProgramStart{}, 5);
  b.wd_us_ += 2'000'000;
  b.run_ticks(10);
  ASSERT_TRUE(b.c_.faulted());
  SetParams rate;
  rate.control_rate_Hz = 40000;
  b.send(rate, 6);  // accepted while faulted; the loaded program is now timed for another rate
  b.send(ProgramStart{}, 7);
  b.pump();
  EXPECT_EQ(b.last<Params>().control_rate_Hz, 40000u);
  EXPECT_EQ(b.last<Nak>().error, ErrorCode::faulted);
  EXPECT_EQ(b.last<Nak>().detail, static_cast<i32>(FaultReason::heartbeat_timeout));

  Bench r;  // a hold runs
  r.send(LoadHold{0.3f, 0.0f}, 1);
  r.send(ProgramStart{}, 2);
  r.run_ticks(10);
  SetParams bad;
  bad.heartbeat_timeout_ms = 20;
  r.send(bad, 3);                  // SetParams: out_of_range before busy
  r.send(LoadHold{9.0f, 0.0f}, 4);  // Load*: busy before out_of_range
  r.send(EnterBootloader{1}, 5);   // EnterBootloader: bad_magic before busy
  r.send(StreamStart{}, 6);
  r.send(StreamConfigure{kAllChannels, 1, 40}, 7);  // StreamConfigure: busy before stream_too_fast
  r.pump();
  const auto naks = r.all<Nak>();
  ASSERT_EQ(naks.size(), 4u);
  EXPECT_EQ(naks[0].error, ErrorCode::out_of_range);
  EXPECT_EQ(naks[1].error, ErrorCode::busy);
  EXPECT_EQ(naks[1].detail, static_cast<i32>(ProgramKind::hold));
  EXPECT_EQ(naks[2].error, ErrorCode::bad_magic);
  EXPECT_EQ(naks[3].error, ErrorCode::busy);
  EXPECT_EQ(naks[3].detail, static_cast<i32>(ProgramKind::hold));
}

TEST(NakFields, BusyNamesTheRunningProgramOrNoneWhenOnlyTheStreamRuns) {
  Bench b;
  b.send(LoadHold{0.3f, 0.0f}, 1);  // loaded, not running
  b.send(StreamStart{}, 2);
  b.send(StreamConfigure{}, 3);
  b.send(SetParams{}, 4);
  b.pump();
  const auto naks = b.all<Nak>();
  ASSERT_EQ(naks.size(), 2u);
  for (const Nak& n : naks) {
    EXPECT_EQ(n.error, ErrorCode::busy);
    EXPECT_EQ(n.detail, static_cast<i32>(ProgramKind::none));
  }
}

TEST(RefusalPrecedence, FaultedRefusesOnlyProgramStart) {
  Bench b;
  b.send(LoadHold{0.3f, 0.0f}, 1);
  b.send(ProgramStart{}, 2);
  b.run_ticks(10);
  b.wd_us_ += 2'000'000;
  b.run_ticks(10);
  ASSERT_TRUE(b.c_.faulted());
  b.send(GetCalibration{}, 3);
  b.pump();
  const SetCalibration same = fields_as<SetCalibration>(b.last<Calibration>());
  b.clear();
  b.send(SetParams{}, 3);
  b.send(LoadHold{0.2f, 0.0f}, 4);
  b.send(same, 5);
  b.send(StreamConfigure{}, 6);
  b.send(StreamStart{}, 7);
  b.send(StreamStop{}, 8);
  b.send(ProgramStart{}, 9);
  b.pump();
  const auto naks = b.all<Nak>();
  ASSERT_EQ(naks.size(), 1u);
  EXPECT_EQ(naks[0].request_id, static_cast<u8>(MessageId::ProgramStart));
  EXPECT_EQ(naks[0].error, ErrorCode::faulted);
}

TEST(RefusalPrecedence, StreamConfigureOutOfRangeComesBeforeStreamTooFast) {
  Bench b;
  b.send(StreamConfigure{kAllChannels, 1, 960}, 1);  // too fast, and 960 x 24 bytes do not fit
  b.pump();
  EXPECT_EQ(b.last<Nak>().error, ErrorCode::out_of_range);
  EXPECT_EQ(b.last<Nak>().field_index, 2);  // batch_samples
}

TEST(NakFields, BadPayloadNamesNoFieldAndStreamTooFastNamesDecimation) {
  Bench b;
  std::vector<u8> w(kMaxWireFrame);
  const u8 short_payload[] = {1};
  w.resize(encode_frame(FrameHeader{kProtocolMajor, kProtocolMinor, 0x20, 0, 8, 0}, short_payload,
                        1, w.data(), w.size()));
  b.c_.receive(w.data(), w.size(), b.wd_us_);
  SetParams p;
  p.control_rate_Hz = 40000;
  b.send(p, 8);
  b.send(StreamConfigure{kAllChannels, 1, 40}, 9);  // 40 kHz > 20 kHz
  b.pump();
  const auto naks = b.all<Nak>();
  ASSERT_EQ(naks.size(), 2u);
  EXPECT_EQ(naks[0].error, ErrorCode::bad_payload);
  EXPECT_EQ(naks[0].field_index, 255);
  EXPECT_EQ(naks[0].detail, 0);
  EXPECT_EQ(naks[1].error, ErrorCode::stream_too_fast);
  EXPECT_EQ(naks[1].field_index, 1);  // StreamConfigure #1 decimation
  EXPECT_EQ(naks[1].detail, 20000);   // the device's max_stream_rate_Hz (SPEC.md §9.1)
}

TEST(NakFields, NoProgramSaysWhetherNothingIsLoadedOrTheRateChanged) {
  Bench b;
  b.send(ProgramStart{}, 1);
  b.send(LoadHold{0.3f, 0.0f}, 2);
  SetParams rate;
  rate.control_rate_Hz = 40000;
  b.send(rate, 3);
  b.send(ProgramStart{}, 4);
  b.pump();
  const auto naks = b.all<Nak>();
  ASSERT_EQ(naks.size(), 2u);
  EXPECT_EQ(naks[0].error, ErrorCode::no_program);
  EXPECT_EQ(naks[0].detail, 0);
  EXPECT_EQ(naks[1].error, ErrorCode::no_program);
  EXPECT_EQ(naks[1].detail, 1);
}

TEST(StreamStop, TheLastBatchArrivesAfterTheAckWithEverySampleTakenBeforeTheStop) {
  Bench b;
  b.send(StreamConfigure{1, 2, 40}, 1);  // i_cmd at 10 kHz, 40 samples a batch
  b.send(StreamStart{}, 2);
  b.run_ticks(100);                     // 50 samples: one full batch sent, 10 waiting
  b.clear();
  b.send(StreamStop{}, 3);
  b.pump();
  b.run_ticks(100);                     // nothing more after the stop
  ASSERT_EQ(b.got_.size(), 2u);
  EXPECT_EQ(b.got_[0].name, "Ack");
  EXPECT_EQ(b.got_[0].header.seq, 3);
  EXPECT_EQ(b.got_[1].name, "SampleBatch");
  const SampleBatch last = b.last<SampleBatch>();
  EXPECT_EQ(last.first_index, 40u);
  EXPECT_EQ(last.sample_count, 10u);
}

TEST(HealthSnapshot, CountsNeitherItsOwnRequestNorItsReply) {
  Bench b(Bench::Start::without_hello);
  b.send(Hello{kProtocolMajor, kProtocolMinor, kSchemaHash, "h"}, 1);
  b.send(GetHealth{}, 2);
  b.send(GetHealth{}, 3);
  b.pump();
  const auto h = b.all<Health>();
  ASSERT_EQ(h.size(), 2u);
  EXPECT_EQ(h[0].frames_rx, 1u);  // the Hello
  EXPECT_EQ(h[0].frames_tx, 1u);  // its DeviceInfo
  EXPECT_EQ(h[1].frames_rx, 2u);  // and the first GetHealth
  EXPECT_EQ(h[1].frames_tx, 2u);  // and its Health

  // a frame whose message does not decode counts under its reason, not in frames_rx
  std::vector<u8> w(kMaxWireFrame);
  w.resize(encode_frame(FrameHeader{kProtocolMajor, kProtocolMinor, 0xEE, 0, 4, 0}, nullptr, 0,
                        w.data(), w.size()));
  b.c_.receive(w.data(), w.size(), b.wd_us_);
  b.send(GetHealth{}, 5);
  b.pump();
  EXPECT_EQ(b.last<Health>().frames_rx, 3u);  // Hello and two GetHealth
  EXPECT_EQ(b.last<Health>().rx_unknown_message, 1u);
}

// SPEC.md §10.2 FaultReason: the detail each reason the core latches carries in EventFault.
TEST(EventFaultDetail, HeartbeatTimeoutCarriesTheMillisecondsLate) {
  Bench b;
  b.send(LoadHold{0.3f, 0.0f}, 1);
  b.send(ProgramStart{}, 2);
  b.run_ticks(10);
  b.wd_us_ += 1'250'000;  // 1.25 s without a request, timeout 0.5 s
  b.run_ticks(10);
  const EventFault f = b.last<EventFault>();
  EXPECT_EQ(f.reason, FaultReason::heartbeat_timeout);
  EXPECT_EQ(f.detail, 750);
}

TEST(EventFaultDetail, TravelLimitCarriesTheEncoderCount) {
  Bench b;
  b.encoder_per_tick_ = 10;  // 10 counts a tick toward +z: past 35000 at tick 3501
  b.run_ticks(3600);
  const EventFault f = b.last<EventFault>();
  EXPECT_EQ(f.reason, FaultReason::travel_limit);
  EXPECT_EQ(f.detail, 35010);
}

TEST(EventFaultDetail, InternalCarries2ForANonFiniteMeasuredCurrent) {
  Bench b;
  b.i_A_ = std::numeric_limits<double>::quiet_NaN();
  b.run_ticks(2);
  const EventFault f = b.last<EventFault>();
  EXPECT_EQ(f.reason, FaultReason::internal);
  EXPECT_EQ(f.detail, 2);
}

}  // namespace
}  // namespace palp::fw
