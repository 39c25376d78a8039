// SPDX-License-Identifier: Apache-2.0
// The in-process simulator (palp/sim_inproc.hpp): its transport's time model (virtual time runs
// inside read(), stalls while device bytes wait, holds on a contact event until the host's next
// bytes, the heartbeat watchdog on the wall clock), sim+inproc:// URIs, its control channel, and
// a Probe over an injected transport that loses its link.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <atomic>
#include <thread>

#include "palp/probe.hpp"
#include "palp/protocol/frame.hpp"
#include "palp/protocol/schema.hpp"  // kSchemaHash (include what is used: unity batches move)
#include "palp/protocol/stream.hpp"
#include "palp/sim_inproc.hpp"
#include "sanitized.hpp"

namespace {

using namespace std::chrono_literals;
using palp::sim::InprocSimulator;
using testing::AllOf;
using testing::HasSubstr;
using testing::StartsWith;
namespace proto = palp::proto;

/// The device protocol straight over a transport, as a host without the SDK speaks it.
struct Raw {
  std::unique_ptr<palp::Transport> t;
  proto::FrameReader reader{};

  template <class M>
  void send(const M& m, proto::u16 seq) {
    std::vector<proto::u8> w(proto::kMaxWireFrame);
    w.resize(proto::encode_message(m, seq, 0, w.data(), w.size()));
    t->write(w, 100ms);
  }
  /// Opens the session (Hello, seq 0; its DeviceInfo is skipped by the reads that follow):
  /// the device serves nothing but identify and bootloader before it.
  void hello() { send(proto::Hello{proto::kProtocolMajor, proto::kProtocolMinor, proto::kSchemaHash, "raw"}, 0); }
  /// Reads (up to max_reads reads of 5 ms of virtual time) until seen(message) returns true.
  template <class Seen>
  bool read_until(Seen&& seen, int max_reads = 20000) {
    bool done = false;
    std::array<proto::u8, 4096> buf;
    for (int k = 0; k < max_reads && !done; ++k) {
      const std::size_t n = t->read(buf, 5ms);
      reader.feed_messages(
          buf.data(), n, [&](const proto::FrameHeader&, const auto& m) { done = done || seen(m); },
          [](proto::Reject) {});
    }
    return done;
  }
  /// Reads until the reply of type M to seq arrives.
  template <class M>
  bool reply(M& out) {
    return read_until([&](const auto& m) {
      if constexpr (std::is_same_v<std::decay_t<decltype(m)>, M>) {
        out = m;
        return true;
      }
      return false;
    });
  }
};

TEST(SimInproc, AReadWithNothingToSayRunsExactlyItsTimeoutOfVirtualTime) {
  InprocSimulator sim;
  auto t = sim.transport();
  std::array<std::uint8_t, 256> buf;
  EXPECT_EQ(t->read(buf, 100ms), 0u);  // an idle device says nothing unasked
  EXPECT_DOUBLE_EQ(sim.virtual_s(), 0.1);
  EXPECT_EQ(t->read(buf, 0ms), 0u);  // no timeout: no virtual time
  EXPECT_DOUBLE_EQ(sim.virtual_s(), 0.1);
}

TEST(SimInproc, ADeviceReplyComesAsSoonAsItExistsOneChunkOfVirtualTimeAfterTheRequest) {
  InprocSimulator sim;
  Raw r{sim.transport()};
  r.hello();
  r.send(proto::Ping{7, 0}, 1);
  proto::Pong p;
  ASSERT_TRUE(r.reply(p));
  EXPECT_EQ(p.nonce, 7u);
  EXPECT_DOUBLE_EQ(sim.virtual_s(), 1e-3);  // one palp-sim step of 1 ms, not the read's 5 ms
}

TEST(SimInproc, ATwentySecondHoldEndsFarWithinItsWaitAndTheHeartbeatNeverTrips) {
  InprocSimulator sim;
  palp::Probe probe(sim.transport());
  palp::HoldProgram h;
  h.current_A = 0.2f;
  h.duration_s = 20.0f;
  const double before_s = probe.status().t_device_s;
  const palp::ProgramResult r = probe.run(h, 60s);  // 60 s of wall time at most
  EXPECT_EQ(r.end, proto::ProgramEnd::completed);
  // virtual time runs on while load and start go out: at least 20 s, a little more. How much
  // more depends on how long this thread waits between the reads that pace it (2.4 s seen on a
  // loaded machine): the bound only rules out a hold that ran twice as long
  EXPECT_GE(r.t_device_s - before_s, 20.0);
  EXPECT_LT(r.t_device_s - before_s, 30.0);
  EXPECT_EQ(probe.fault().reason, proto::FaultReason::none);
}

TEST(SimInproc, AHostThatStopsSendingTripsTheHeartbeatWatchdogOnTheWallClock) {
  InprocSimulator sim;
  Raw r{sim.transport()};
  r.hello();
  proto::Ack ack;
  r.send(proto::LoadHold{0.2f, 0.0f}, 1);
  ASSERT_TRUE(r.reply(ack));
  r.send(proto::ProgramStart{}, 2);
  ASSERT_TRUE(r.reply(ack));  // the watchdog is armed (a program runs) and fed
  const double before_s = sim.virtual_s();
  std::this_thread::sleep_for(700ms);  // the default heartbeat timeout is 500 ms
  proto::EventFault f;
  ASSERT_TRUE(r.reply(f));
  EXPECT_EQ(f.reason, proto::FaultReason::heartbeat_timeout);
  // it tripped at the first tick the host let run, not after 500 ms of virtual time
  EXPECT_LE(static_cast<double>(f.time_us) * 1e-6 - before_s, 1e-3);
}

TEST(SimInproc, AContactEventHoldsVirtualTimeUntilTheHostsNextBytes) {
  // the coil floating at 0.5 A reaches the solid's top 25 mm below the mount (test_indent.cpp);
  // a hold timeout far beyond the test's waits, however slow the machine
  InprocSimulator sim({.phantom = "solid_1d", .mount_mm = {27, 0, -25}, .hold_timeout_ms = 60e3});
  Raw r{sim.transport()};
  r.hello();
  proto::Ack ack;
  proto::LoadContactWatch w;
  w.hold_current_A = 0.5f;
  w.threshold_counts = 500;
  r.send(w, 1);
  ASSERT_TRUE(r.reply(ack));
  r.send(proto::ProgramStart{}, 2);
  ASSERT_TRUE(r.reply(ack));
  proto::EventContact contact;
  ASSERT_TRUE(r.reply(contact));
  const double held_s = sim.virtual_s();
  std::array<std::uint8_t, 256> buf;
  EXPECT_EQ(r.t->read(buf, 50ms), 0u);  // waits 50 ms of wall time: virtual time stands
  EXPECT_EQ(sim.virtual_s(), held_s);
  EXPECT_THAT(sim.control("status"), HasSubstr("holding=1"));
  r.send(proto::Heartbeat{}, 3);  // the host reacts
  ASSERT_TRUE(r.reply(ack));
  EXPECT_GE(sim.virtual_s(), held_s + 2e-3);  // its bytes landed reaction_latency later
  EXPECT_THAT(sim.control("status"), HasSubstr("holding=0"));
}

TEST(SimInproc, DeviceBytesTheReaderHasNotTakenStallVirtualTime) {
  InprocSimulator sim;
  Raw r{sim.transport()};
  r.hello();
  r.send(proto::StreamConfigure{proto::kAllChannels, 2, 40}, 1);
  r.send(proto::StreamStart{}, 2);
  std::array<std::uint8_t, 1> one;
  // past the two replies (~40 bytes) into the first SampleBatch (~1000 bytes)
  for (int k = 0; k < 200; ++k) ASSERT_EQ(r.t->read(one, 5ms), 1u);
  const double stalled_s = sim.virtual_s();
  for (int k = 0; k < 500; ++k) ASSERT_EQ(r.t->read(one, 5ms), 1u);
  EXPECT_EQ(sim.virtual_s(), stalled_s);
}

TEST(SimInproc, AUriOpensASimulatorOfItsOwnWithThePhantomAndTheParameters) {
  const std::string uri = "sim+inproc://solid_1d?seed=3&mount_mm=27,0,-25&serial=LAB-7";
  palp::Probe probe(uri);
  EXPECT_EQ(probe.uri(), uri);
  EXPECT_EQ(probe.info().serial, "LAB-7");
  EXPECT_TRUE(probe.info().has(proto::Capability::simulated));
  // the mount holds the floating tip on the solid's top: a contact watch fires
  palp::ContactWatchProgram w;
  w.hold_current_A = 0.5f;
  w.threshold_counts = 500;
  probe.load(w);
  probe.start();
  EXPECT_TRUE(probe.wait_contact(10s).has_value());
}

std::string config_error(const std::string& uri) {
  try {
    palp::Probe probe(uri);
  } catch (const palp::ConfigError& e) {
    return e.what();
  }
  return "no ConfigError";
}

TEST(SimInproc, BadUriParametersAndPhantomsAreConfigErrorsNamingThem) {
  EXPECT_EQ(config_error("sim+inproc://none?speed=2"),
            "transport URI 'sim+inproc://none?speed=2': unknown parameter 'speed' (known: seed, "
            "mount_mm, hold_timeout_ms, reaction_latency_ms, serial, board)");
  EXPECT_EQ(config_error("sim+inproc://none?mount_mm=1,2"),
            "transport URI 'sim+inproc://none?mount_mm=1,2': mount_mm '1,2' is not x,y,z in mm");
  EXPECT_EQ(config_error("sim+inproc://none?seed=-1"),
            "transport URI 'sim+inproc://none?seed=-1': seed '-1' is not a whole number >= 0");
  EXPECT_THAT(config_error("sim+inproc://no_such_phantom"),
              AllOf(StartsWith("the in-process simulator: "), HasSubstr("no_such_phantom")));
}

TEST(SimInproc, PaceIsRefusedAndTheOtherKnobsAnswerAsPalpSims) {
  InprocSimulator sim;
  EXPECT_THAT(sim.control("pace 1"), StartsWith("error: pace: the in-process simulator runs as "
                                                "fast as its reader reads"));
  EXPECT_EQ(sim.control("drop-frames 3"), "ok");
  EXPECT_THAT(sim.control("status"), HasSubstr(" client=0 "));
  auto t = sim.transport();
  EXPECT_THAT(sim.control("status"), HasSubstr(" client=1 "));
  EXPECT_EQ(sim.control("robot-fault"),
            "error: robot-fault: the robot bridge is off (start palp-sim with --robot-port)");
  EXPECT_EQ(sim.robot_uri(), "");
}

TEST(SimInproc, OneTransportAtATimeAndTheNextMeetsTheSameSimulation) {
  InprocSimulator sim;
  auto first = sim.transport();
  EXPECT_THROW(sim.transport(), palp::ConnectionError);
  {
    palp::Probe probe(std::move(first));
    probe.set_calibration([&] {
      palp::Calibration c = probe.calibration();
      c.pressure_offset_Pa[0] = 12.5f;
      return c;
    }());
  }
  palp::Probe again(sim.transport());
  EXPECT_FLOAT_EQ(again.calibration().pressure_offset_Pa[0], 12.5f);
}

/// A transport that loses its link when told to.
class Losable final : public palp::Transport {
 public:
  Losable(std::unique_ptr<palp::Transport> inner, std::atomic<bool>& lost)
      : inner_(std::move(inner)), lost_(lost) {}
  void write(std::span<const std::uint8_t> b, std::chrono::milliseconds t) override {
    if (lost_) throw palp::ConnectionError("test: the link is gone");
    inner_->write(b, t);
  }
  std::size_t read(std::span<std::uint8_t> b, std::chrono::milliseconds t) override {
    if (lost_) throw palp::ConnectionError("test: the link is gone");
    return inner_->read(b, t);
  }
  std::uint32_t max_device_bytes_per_s() const override { return inner_->max_device_bytes_per_s(); }
  const std::string& uri() const override { return inner_->uri(); }

 private:
  std::unique_ptr<palp::Transport> inner_;
  std::atomic<bool>& lost_;
};

TEST(ProbeInjected, ALostLinkIsNeverReopenedEvenWithReconnectOnAndEveryCallSaysSo) {
  InprocSimulator sim;
  std::atomic<bool> lost{false};
  palp::ConnectOptions o;
  o.reconnect = true;
  palp::Probe probe(std::make_unique<Losable>(sim.transport(), lost), o);
  EXPECT_EQ(probe.uri(), "sim+inproc://none");
  EXPECT_EQ(probe.status().state, proto::DeviceState::idle);
  lost = true;
  std::this_thread::sleep_for(100ms);
  for (int k = 0; k < 2; ++k) {
    try {
      probe.status();
      FAIL() << "status() answered over a lost link";
    } catch (const palp::ConnectionError& e) {
      EXPECT_THAT(e.what(), HasSubstr("test: the link is gone"));
      EXPECT_THAT(e.what(), HasSubstr("a transport given to the Probe is never reopened"));
    }
  }
}

TEST(ProbeInjected, ANullTransportIsAConfigError) {
  EXPECT_THROW(palp::Probe(std::unique_ptr<palp::Transport>{}), palp::ConfigError);
}

}  // namespace
