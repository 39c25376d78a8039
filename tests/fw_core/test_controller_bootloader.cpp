// SPDX-License-Identifier: Apache-2.0
// EnterBootloader in every session state (SPEC.md §6.1, §6.2): a frozen request, so any host —
// one that never said Hello, one the device judged incompatible, one whose frames carry another
// major — can put the controller into its ROM bootloader and reflash it (issue 21). Its own
// refusals stay: bad_magic, and busy while a program runs (the watchdog ends that program when no
// session feeds it, so an incompatible host waits at most heartbeat_timeout_ms).
#include <gtest/gtest.h>

#include "controller_bench.hpp"

namespace palp::fw {
namespace {

using namespace palp::proto;
using test::Bench;

constexpr u8 kOtherMajor = static_cast<u8>(kProtocolMajor + 1);

/// Sends EnterBootloader with the magic in a frame of `major`; true when the device acked it and
/// set its bootloader request.
bool enter(Bench& b, u8 major = kProtocolMajor, u16 seq = 50) {
  b.clear();
  b.send(EnterBootloader{kBootloaderMagic}, seq, major);
  b.pump();
  const auto acks = b.all<Ack>();
  return acks.size() == 1 && acks[0].request_id == static_cast<u8>(MessageId::EnterBootloader) &&
         b.all<Nak>().empty() && b.c_.bootloader_requested();
}

TEST(BootloaderInEveryState, AcceptedBeforeAnyHello) {
  Bench b(Bench::Start::without_hello);
  EXPECT_TRUE(enter(b));
  EXPECT_FALSE(b.c_.session_open());  // it opens no session
}

TEST(BootloaderInEveryState, AcceptedFromAHostOfAnotherMajorThatNeverSaidHello) {
  Bench b(Bench::Start::without_hello);
  EXPECT_TRUE(enter(b, kOtherMajor));
}

TEST(BootloaderInEveryState, AcceptedAfterTheDeviceJudgedTheHostIncompatible) {
  Bench b(Bench::Start::without_hello);
  b.send(Hello{kOtherMajor, 0, 0x11111111u, "palp-sdk 9.0.0"}, 1, kOtherMajor);
  b.send(GetStatus{}, 2);
  b.pump();
  ASSERT_EQ(b.last<DeviceInfo>().state, DeviceState::incompatible);
  ASSERT_EQ(b.last<Nak>().error, ErrorCode::incompatible_host);  // the session is closed
  EXPECT_TRUE(enter(b, kOtherMajor));
}

TEST(BootloaderInEveryState, AcceptedAfterASameMajorHelloWithAnotherSchemaHash) {
  Bench b;
  b.send(Hello{kProtocolMajor, kProtocolMinor, kSchemaHash ^ 1u, "an unreleased build"}, 1);
  b.pump();
  ASSERT_EQ(b.last<DeviceInfo>().state, DeviceState::incompatible);
  EXPECT_TRUE(enter(b));
}

TEST(BootloaderInEveryState, AcceptedInAnOpenSessionWhileStreamingAndAfterTheSessionEnded) {
  Bench b;
  b.send(StreamStart{}, 1);
  b.run_ticks(50);
  ASSERT_TRUE(b.c_.session_open());
  EXPECT_TRUE(enter(b));
  Bench ended;
  ended.c_.end_session();  // palp-sim: the client went
  EXPECT_TRUE(enter(ended));
}

TEST(BootloaderInEveryState, AcceptedWhileTheFaultLatchIsSet) {
  Bench b;
  b.send(LoadHold{0.3f, 0.0f}, 1);
  b.send(ProgramStart{}, 2);
  b.run_ticks(50);
  b.wd_us_ += 2'000'000;  // no host for 2 s: heartbeat_timeout
  b.run_ticks(5);
  ASSERT_TRUE(b.c_.faulted());
  EXPECT_TRUE(enter(b));
}

TEST(BootloaderInEveryState, ARunningProgramRefusesItBusyForEveryHostUntilTheWatchdogEndsIt) {
  Bench b;
  b.send(LoadHold{0.3f, 0.0f}, 1);
  b.send(ProgramStart{}, 2);
  b.run_ticks(50);
  b.send(Hello{kOtherMajor, 0, 0x11111111u, "palp-sdk 9.0.0"}, 3, kOtherMajor);  // session closed
  b.clear();
  b.send(EnterBootloader{kBootloaderMagic}, 4, kOtherMajor);
  b.pump();
  EXPECT_EQ(b.last<Nak>().error, ErrorCode::busy);
  EXPECT_EQ(b.last<Nak>().detail, static_cast<i32>(ProgramKind::hold));
  EXPECT_FALSE(b.c_.bootloader_requested());
  b.wd_us_ += 600'000;  // the incompatible host does not feed the watchdog: 0.5 s ends the hold
  b.run_ticks(5);
  ASSERT_TRUE(b.c_.faulted());
  EXPECT_TRUE(enter(b, kOtherMajor, 5));
}

TEST(BootloaderInEveryState, AWrongMagicIsRefusedInEveryStateAndRequestsNothing) {
  Bench none(Bench::Start::without_hello);
  Bench open;
  for (Bench* b : {&none, &open}) {
    b->clear();
    b->send(EnterBootloader{kBootloaderMagic ^ 1u}, 7);
    b->pump();
    EXPECT_EQ(b->last<Nak>().error, ErrorCode::bad_magic);
    EXPECT_EQ(b->last<Nak>().field_index, 0);
    EXPECT_FALSE(b->c_.bootloader_requested());
  }
}

}  // namespace
}  // namespace palp::fw
