// SPDX-License-Identifier: Apache-2.0
// The test bench of the controller tests: a Controller, a host that frames requests and reads
// every device frame back, and an exact RL coil on the other side of the tick. Virtual control
// time and a separate watchdog clock (wd_us_), as on hardware.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "palp/fw/controller.hpp"
#include "palp/protocol/text.hpp"

namespace palp::fw::test {

using namespace palp::proto;

struct Received {
  FrameHeader header;
  std::string name;
  std::vector<u8> payload;
};

class Bench {
 public:
  /// A controller with a host session open (a compatible Hello, its reply discarded), or none.
  enum class Start { with_session, without_hello };
  explicit Bench(Start start = Start::with_session, const DeviceIdentity& id = identity())
      : c_(id) {
    if (start == Start::without_hello) return;
    send(Hello{kProtocolMajor, kProtocolMinor, kSchemaHash, "bench"}, 0);
    pump();
    clear();
  }

  static DeviceIdentity identity() {
    DeviceIdentity id;
    id.board = "test-bench";
    id.serial = "TB-1";
    id.git_hash = "abc1234";
    return id;
  }

  template <class M>
  void send(const M& m, u16 seq = 1, u8 major = kProtocolMajor) {
    std::vector<u8> w(kMaxWireFrame);
    w.resize(encode_message(m, seq, 0, w.data(), w.size(), major));
    c_.receive(w.data(), w.size(), wd_us_);
  }

  // One control tick against an exact RL coil (5.8 ohm, 2.07 mH), then the main loop.
  void run_ticks(int n) {
    for (int k = 0; k < n; ++k) {
      TickInputs in;
      in.i_sense_A = static_cast<float>(i_A_);
      in.encoder_timer = static_cast<std::uint16_t>(encoder_ + encoder_per_tick_ * static_cast<int>(c_.ticks()));
      in.watchdog_now_us = wd_us_;
      TickOutputs out;
      c_.tick(in, out);
      const double dt = 1.0 / c_.control_rate_Hz();
      const double a = std::exp(-5.8 * dt / 2.07e-3);
      i_A_ = i_A_ * a + out.v_coil_V / 5.8 * (1 - a);
      last_out_ = out;
      if (k % 8 == 7) pump();
    }
    pump();
  }

  void pump() {
    c_.service();
    u8 buf[4096];
    std::size_t n;
    while ((n = c_.transmit(buf, sizeof buf)) > 0) {
      host_.feed_messages(
          buf, n,
          [&](const FrameHeader& h, const auto& m) { got_.push_back({h, m.kName, payload_of(m)}); },
          [&](Reject r) { ADD_FAILURE() << "device sent a bad frame: " << reject_name(r); });
    }
  }

  template <class M>
  std::vector<M> all() {
    std::vector<M> out;
    for (const Received& r : got_) {
      if (r.name != M::kName) continue;
      M m;
      EXPECT_EQ(decode_payload(r.payload.data(), r.payload.size(), m), Reject::ok);
      out.push_back(m);
    }
    return out;
  }
  template <class M>
  M last() {
    auto v = all<M>();
    EXPECT_FALSE(v.empty()) << "no " << M::kName << " received";
    return v.empty() ? M{} : v.back();
  }
  template <class M>
  static std::vector<u8> payload_of(const M& m) {
    std::vector<u8> p(kMaxPayload);
    p.resize(static_cast<std::size_t>(encode_payload(m, p.data(), p.size())));
    return p;
  }
  const Received& last_frame() const { return got_.back(); }
  void clear() { got_.clear(); }

  Controller c_;
  double i_A_ = 0.0;
  int encoder_ = 0;
  int encoder_per_tick_ = 0;
  std::uint64_t wd_us_ = 1'000'000;
  TickOutputs last_out_{};
  FrameReader host_;
  std::vector<Received> got_;
};

}  // namespace palp::fw::test
