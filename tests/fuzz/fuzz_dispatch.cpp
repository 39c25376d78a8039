// SPDX-License-Identifier: Apache-2.0
// libFuzzer target for the firmware core's command dispatch: a compatible Hello, then the input
// as host bytes, handed to Controller::receive in chunks with control ticks, service() and
// transmit() between them (as a board's main loop does). The input's first byte picks the chunk
// size and the ticks per chunk, so requests land mid-program and mid-stream. Properties:
//  - nothing crashes, reads out of bounds or overflows (ASan/UBSan watch);
//  - every tick's coil voltage is finite, and 0 V in every tick after the fault latch is set;
//  - the transmit buffer never holds more than Controller::kTxBytes.
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "palp/fw/controller.hpp"
#include "palp/protocol/frame.hpp"

namespace {

using namespace palp;
using namespace palp::proto;

[[noreturn]] void fail() { __builtin_trap(); }

fw::DeviceIdentity identity() {
  fw::DeviceIdentity id;
  id.board = "fuzz";
  id.serial = "FZ-1";
  id.git_hash = "0000000";
  return id;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fw::Controller c(identity());
  std::uint64_t now_us = 0;
  std::uint8_t out_bytes[512];
  double i_A = 0.0;  // a first-order coil: the current follows the voltage
  const auto run_ticks = [&](int n) {
    for (int k = 0; k < n; ++k) {
      const bool faulted_before = c.faulted();
      fw::TickInputs in;
      in.i_sense_A = static_cast<float>(i_A);
      in.encoder_timer = static_cast<std::uint16_t>(c.ticks() * 3);
      in.watchdog_now_us = now_us;
      fw::TickOutputs out;
      c.tick(in, out);
      if (!std::isfinite(out.v_coil_V)) fail();
      if (faulted_before && out.v_coil_V != 0.0f) fail();
      i_A = 0.9 * i_A + 0.1 * out.v_coil_V / 5.8;
      now_us += 50;
    }
    c.service();
    if (c.tx_pending() > fw::Controller::kTxBytes) fail();
    while (c.transmit(out_bytes, sizeof out_bytes) > 0) {
    }
  };

  static std::uint8_t hello[kMaxWireFrame];
  const std::size_t n =
      encode_message(Hello{kProtocolMajor, kProtocolMinor, kSchemaHash, "fuzz"}, 1, 0, hello,
                     sizeof hello);
  c.receive(hello, n, now_us);
  run_ticks(1);
  if (size == 0) return 0;
  const std::size_t chunk = 1 + (data[0] & 0x3F);
  const int ticks = data[0] >> 6;  // 0..3
  for (std::size_t at = 1; at < size; at += chunk) {
    const std::size_t len = size - at < chunk ? size - at : chunk;
    c.receive(data + at, len, now_us);
    run_ticks(ticks * 7 + 1);
  }
  run_ticks(64);
  return 0;
}
