// SPDX-License-Identifier: Apache-2.0
#include "palp/protocol/examples.hpp"

namespace palp::proto {

DeviceInfo examples_device_info() {
  DeviceInfo info;
  info.protocol_major = kProtocolMajor;
  info.protocol_minor = kProtocolMinor;
  info.schema_hash = kSchemaHash;
  info.fw_major = 0;
  info.fw_minor = 1;
  info.fw_patch = 0;
  info.git_hash = "3f9c2a1";
  info.board = "palp-sim";
  info.serial = "SIM-0001";
  info.capabilities = (1u << static_cast<u8>(Capability::pressure)) |
                      (1u << static_cast<u8>(Capability::contact_output)) |
                      (1u << static_cast<u8>(Capability::simulated));
  info.max_current_A = 4.0f;
  return info;
}

LoadRamp example_ramp_2d() {
  LoadRamp r;
  r.start_A = 0.5f;
  r.stop_A = 3.0f;
  r.step_A = 0.01f;
  r.dwell_s = 0.025f;
  r.repetitions = 3;
  r.unload = 1;
  r.displacement_limit_counts = 5000;
  return r;
}

SampleBatch example_batch(u32 first_index, u64 first_time_us, u16 n) {
  SampleBatch b;
  b.first_index = first_index;
  b.first_time_us = first_time_us;
  b.period_ns = 100'000;  // 10 kHz
  b.channels = kAllChannels;
  b.sample_count = n;
  Writer w(b.data.items.data(), b.data.items.size());
  for (u16 k = 0; k < n; ++k) {
    RawSample s;
    s.i_cmd = static_cast<i16>(2500 + 50 * k);   // 0.5 A + 10 mA per sample
    s.i_meas = static_cast<i16>(2497 + 50 * k);
    s.encoder = 12'000 + 3 * k;                  // um
    for (u8 c = 0; c < 6; ++c) s.pressure[c] = static_cast<i16>(-20 + 7 * c + k);
    s.status = (1u << static_cast<u8>(StatusBit::program_running)) |
               (1u << static_cast<u8>(StatusBit::heartbeat_armed));
    s.v_cmd = static_cast<i16>(2900 + 58 * k);   // mV
    pack_sample(w, s, b.channels);
  }
  b.data.size = static_cast<u16>(w.size());
  return b;
}

}  // namespace palp::proto
