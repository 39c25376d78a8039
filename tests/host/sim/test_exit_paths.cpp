// SPDX-License-Identifier: Apache-2.0
// Every SDK exit path leaves the device safe (issue 17, item 2), against palp-sim linked in with a
// link that loses exactly the replies a test chooses (lossy_link.hpp): a closed Probe drops the
// contact hold a float left; a lost reply to a read-only or stopping request is resent with the
// same seq and answered; a lost reply to any other request is a TimeoutError after one copy; an
// indentation whose ProgramStart reply is lost throws and leaves no program and 0 A.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>

#include "lossy_link.hpp"
#include "palp/indent.hpp"
#include "palp/probe.hpp"
#include "palp/sim_inproc.hpp"

namespace {

using palp::proto::MessageId;
using palp::sim::InprocSimulator;
using palp::test::LossyLink;
using namespace std::chrono_literals;

palp::ConnectOptions quick() {
  palp::ConnectOptions o;
  o.timeout = 400ms;  // a lost reply costs a quarter of it before the copy goes out
  return o;
}

/// Floats the coil with a contact watch that fires and keeps holding its current.
void float_coil(palp::Probe& probe) {
  palp::ContactWatchProgram w;
  w.hold_current_A = 0.5f;
  w.threshold_counts = 500;
  probe.load(w);
  probe.start();
  ASSERT_TRUE(probe.wait_contact(10s));
  const palp::Status held = probe.status();
  ASSERT_NE(held.program_state, palp::proto::ProgramState::running);  // the watch ended ...
  ASSERT_FLOAT_EQ(static_cast<float>(held.i_cmd_A), 0.5f);            // ... holding its current
}

TEST(ExitPaths, ClosingAProbeDropsTheContactHoldAFloatLeftTo0A) {
  InprocSimulator sim({.phantom = "solid_1d", .mount_mm = {27, 0, -25}});
  {
    palp::Probe probe(sim.transport());
    float_coil(probe);
  }  // the destructor: close()
  palp::Probe again(sim.transport());
  const palp::Status st = again.status();
  EXPECT_EQ(st.i_cmd_A, 0.0);
  EXPECT_NE(st.program_state, palp::proto::ProgramState::running);
  EXPECT_EQ(st.fault, palp::proto::FaultReason::none);
}

TEST(ExitPaths, MakeSafeReturnsAStatusWithNoProgramAnd0A) {
  InprocSimulator sim({.phantom = "solid_1d", .mount_mm = {27, 0, -25}});
  palp::Probe probe(sim.transport());
  float_coil(probe);
  const palp::Status st = probe.make_safe();
  EXPECT_EQ(st.i_cmd_A, 0.0);
  EXPECT_NE(st.program_state, palp::proto::ProgramState::running);
  EXPECT_FALSE(st.streaming);
}

TEST(ExitPaths, ALostStatusReplyIsResentWithTheSameSeqAndAnswered) {
  InprocSimulator sim;
  auto log = std::make_shared<LossyLink::Log>();
  int status_replies = 0;
  std::atomic<bool> connected{false};  // the Probe's own status at connecting is not the one lost
  log->lose = [&](MessageId id, std::uint16_t) {
    return connected && id == MessageId::GetStatus && status_replies++ == 0;
  };
  palp::Probe probe(std::make_unique<LossyLink>(sim.transport(), log), quick());
  {
    std::lock_guard lock(log->mu);
    log->sent.clear();
  }
  connected = true;
  const palp::Status st = probe.status();  // the first reply is lost: TimeoutError without resend
  EXPECT_EQ(st.state, palp::proto::DeviceState::idle);
  EXPECT_EQ(probe.health().requests_resent, 1u);
  std::lock_guard lock(log->mu);
  EXPECT_EQ(log->lost, 1);
  std::vector<std::uint16_t> seqs;
  for (const auto& s : log->sent)
    if (s.id == MessageId::GetStatus) seqs.push_back(s.seq);
  ASSERT_EQ(seqs.size(), 2u);
  EXPECT_EQ(seqs[0], seqs[1]);  // the copy carries the lost request's seq
}

TEST(ExitPaths, ALostHelloReplyIsResentWithTheSameSeqAndTheProbeConnects) {
  InprocSimulator sim;
  auto log = std::make_shared<LossyLink::Log>();
  int hellos_lost = 0;
  log->lose = [&](MessageId id, std::uint16_t) { return id == MessageId::Hello && hellos_lost++ == 0; };
  palp::Probe probe(std::make_unique<LossyLink>(sim.transport(), log), quick());
  EXPECT_EQ(probe.status().state, palp::proto::DeviceState::idle);
  std::lock_guard lock(log->mu);
  EXPECT_EQ(log->lost, 1);
  std::vector<std::uint16_t> seqs;
  for (const auto& s : log->sent)
    if (s.id == MessageId::Hello) seqs.push_back(s.seq);
  ASSERT_EQ(seqs.size(), 2u);  // without the resend: TimeoutError "the DeviceInfo reply to Hello"
  EXPECT_EQ(seqs[0], seqs[1]);
}

TEST(ExitPaths, AHelloWhoseEveryReplyIsLostIsATimeoutNamingTheReplyAfterFourCopies) {
  InprocSimulator sim;
  auto log = std::make_shared<LossyLink::Log>();
  log->lose = [](MessageId id, std::uint16_t) { return id == MessageId::Hello; };
  try {
    palp::Probe probe(std::make_unique<LossyLink>(sim.transport(), log), quick());
    ADD_FAILURE() << "connected although every Hello reply was lost";
  } catch (const palp::TimeoutError& e) {
    EXPECT_NE(std::string(e.what()).find("the DeviceInfo reply to Hello from "), std::string::npos)
        << e.what();
  }
  std::lock_guard lock(log->mu);
  int hellos = 0;
  for (const auto& s : log->sent) hellos += s.id == MessageId::Hello;
  EXPECT_EQ(hellos, 4);  // kSendAttempts copies within the one timeout
}

TEST(ExitPaths, ALostProgramStartReplyIsATimeoutAfterOneCopy) {
  InprocSimulator sim({.phantom = "solid_1d", .mount_mm = {27, 0, -25}});
  auto log = std::make_shared<LossyLink::Log>();
  log->lose = [](MessageId id, std::uint16_t) { return id == MessageId::ProgramStart; };
  palp::Probe probe(std::make_unique<LossyLink>(sim.transport(), log), quick());
  palp::HoldProgram h;
  h.current_A = 0.2f;
  h.duration_s = 30;
  probe.load(h);
  EXPECT_THROW(probe.start(), palp::TimeoutError);
  {
    std::lock_guard lock(log->mu);
    int starts = 0;
    for (const auto& s : log->sent) starts += s.id == MessageId::ProgramStart;
    EXPECT_EQ(starts, 1);  // a repeated ProgramStart would be refused busy: never resent
  }
  probe.close();  // ProgramStop: the hold the lost start began ends
  palp::Probe again(sim.transport());
  EXPECT_EQ(again.status().i_cmd_A, 0.0);
}

TEST(ExitPaths, AProgramWhoseFinishedEventIsLostEndsByItsStatusNotATimeout) {
  InprocSimulator sim;
  auto log = std::make_shared<LossyLink::Log>();
  log->lose_unasked = [](MessageId id) { return id == MessageId::EventProgramFinished; };
  palp::Probe probe(std::make_unique<LossyLink>(sim.transport(), log), quick());
  palp::HoldProgram h;
  h.current_A = 0.2f;
  h.duration_s = 0.5f;
  const palp::ProgramResult r = probe.run(h, 20s);  // the status is asked every 250 ms
  EXPECT_EQ(r.kind, palp::proto::ProgramKind::hold);
  EXPECT_EQ(r.end, palp::proto::ProgramEnd::completed);
  std::lock_guard lock(log->mu);
  EXPECT_EQ(log->lost, 1);  // the event did come, and was lost
}

TEST(ExitPaths, AnIndentationWhoseFloatStartReplyIsLostThrowsAndLeavesNoProgramAnd0A) {
  InprocSimulator sim({.phantom = "solid_1d", .mount_mm = {27, 0, -25}});
  auto log = std::make_shared<LossyLink::Log>();
  // the float's ProgramStart (the one after its LoadContactWatch) loses its Ack: the watch runs
  log->lose = [&log](MessageId id, std::uint16_t seq) {
    if (id != MessageId::ProgramStart) return false;
    for (std::size_t k = log->sent.size(); k-- > 0;)
      if (log->sent[k].seq != seq && log->sent[k].id != MessageId::Heartbeat &&
          log->sent[k].id != MessageId::Ping && log->sent[k].id != MessageId::GetHealth)
        return log->sent[k].id == MessageId::LoadContactWatch;
    return false;
  };
  palp::Probe probe(std::make_unique<LossyLink>(sim.transport(), log), quick());
  palp::IndentationSettings s = palp::IndentationSettings::preset(palp::IndentationPreset::two_d);
  s.repetitions = 1;
  s.stream_rate_Hz = 200;
  EXPECT_THROW(palp::indent(probe, s), palp::TimeoutError);
  {
    std::lock_guard lock(log->mu);
    EXPECT_EQ(log->lost, 1);
    log->lose = nullptr;
  }
  const palp::Status st = probe.status();  // the Probe stays open: indent() itself made it safe
  EXPECT_EQ(st.i_cmd_A, 0.0);
  EXPECT_NE(st.program_state, palp::proto::ProgramState::running);
  EXPECT_EQ(st.fault, palp::proto::FaultReason::none);
}

}  // namespace
