// SPDX-License-Identifier: Apache-2.0
// The SDK's figures: stream decode throughput on one core, and command round trips against
// palp-sim over a loopback socket. Figures only: nothing here asserts a time.
//
// Stream decode: the wire bytes of full SampleBatch frames (all 11 channels, 40 samples, 10 kHz
// times) go through proto::FrameReader and detail::StreamAssembler into palp::Sample items the
// way the probe's I/O thread does it (read-sized chunks, every message decoded, the clock
// mapping applied under the session's lock). Counters:
//   samples_per_s          samples delivered per second of one core
//   x_usb_fullspeed_bulk   the same as a multiple of what USB full-speed bulk can carry
//                          (kBulkBytesPerS over the wire bytes per sample, framing included;
//                          samples per CPU second of this thread, like samples_per_s)
//   usb_bulk_samples_per_s that ceiling itself, for the record
// BM_StreamDecodeToQueue adds the hand-off to the application: StreamQueue push and drain.
//
// Round trips: one palp::Probe on a palp-sim child process (--pace fast), timing each request
// with the steady clock; p50_us / p99_us are percentiles of those times (wall time: palp-sim
// runs as another process and shares the cores).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <memory>
#include <mutex>
#include <vector>

#include "palp/probe.hpp"
#include "palp/protocol/frame.hpp"
#include "palp/protocol/stream.hpp"
#include "palp/protocol/usb.hpp"
#include "probe/stream_assembler.hpp"
#include "probe/stream_queue.hpp"
#include "sim_process.hpp"

namespace {

using namespace palp::proto;

constexpr u16 kBatch = 40;          // the largest batch of all 11 channels (960 data bytes)
constexpr u32 kPeriodNs = 100'000;  // 10 kHz
constexpr std::size_t kFrames = 256;
constexpr std::size_t kReadChunk = 4096;  // what one transport read hands the session

/// kFrames consecutive full batches, encoded back to back as they arrive on the wire. Sample
/// values vary like a slow loading ramp with noise, so COBS sees realistic bytes.
std::vector<u8> stream_bytes() {
  static_assert(max_batch_samples(kAllChannels) == kBatch);
  std::vector<u8> wire;
  std::vector<u8> one(kMaxWireFrame);
  u32 state = 12345;
  auto noise = [&state] {
    state = state * 1664525u + 1013904223u;
    return static_cast<int>(state >> 28) - 8;
  };
  for (std::size_t f = 0; f < kFrames; ++f) {
    SampleBatch b;
    b.first_index = static_cast<u32>(f * kBatch);
    b.first_time_us = 5'000'000 + f * kBatch * (kPeriodNs / 1000);
    b.period_ns = kPeriodNs;
    b.channels = kAllChannels;
    b.sample_count = kBatch;
    Writer w(b.data.items.data(), b.data.items.size());
    for (u16 k = 0; k < kBatch; ++k) {
      const int n = static_cast<int>(f * kBatch + k);
      RawSample s;
      s.i_cmd = static_cast<i16>(2500 + n / 20);
      s.i_meas = static_cast<i16>(s.i_cmd + noise());
      s.encoder = 12'000 + n / 7 + noise();
      for (u8 c = 0; c < 6; ++c) s.pressure[c] = static_cast<i16>(-20 + 7 * c + n / 50 + noise());
      s.status = (1u << static_cast<u8>(StatusBit::program_running)) |
                 (1u << static_cast<u8>(StatusBit::heartbeat_armed));
      s.v_cmd = static_cast<i16>(2900 + n / 10 + noise());
      pack_sample(w, s, b.channels);
    }
    b.data.size = static_cast<u16>(w.size());
    const std::size_t len = encode_message(b, static_cast<u16>(f), 0, one.data(), one.size());
    wire.insert(wire.end(), one.begin(), one.begin() + static_cast<long>(len));
  }
  return wire;
}

/// Samples per second USB full-speed bulk carries for this stream (framing included).
double usb_bulk_samples_per_s() {
  const double bytes_per_sample =
      static_cast<double>(batch_wire_bytes(kAllChannels, kBatch)) / kBatch;
  return usb::kBulkBytesPerS / bytes_per_sample;
}

/// This thread's CPU time (what Google Benchmark's CPU column and kIsRate counters use).
double thread_cpu_s() {
  timespec t{};
  ::clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_nsec) * 1e-9;
}

template <class Deliver>
void stream_decode(benchmark::State& state, Deliver&& deliver) {
  const std::vector<u8> wire = stream_bytes();
  const palp::ClockMapping map{0.25, 1e-6, 1e-4, 8};
  std::mutex mu;  // the session takes its lock around the assembler
  std::int64_t samples = 0;
  const double cpu0 = thread_cpu_s();
  for (auto _ : state) {
    FrameReader reader;
    palp::detail::StreamAssembler assembler;
    assembler.restart();
    for (std::size_t off = 0; off < wire.size(); off += kReadChunk) {
      std::vector<palp::StreamItem> items;  // one per read, as in Session::on_bytes
      reader.feed_messages(
          wire.data() + off, std::min(kReadChunk, wire.size() - off),
          [&](const FrameHeader&, const auto& m) {
            if constexpr (std::is_same_v<std::decay_t<decltype(m)>, SampleBatch>) {
              std::lock_guard lock(mu);
              assembler.batch(m, [&](double d) { return map.to_host_s(d); }, items);
            }
          },
          [](Reject) {});
      for (const palp::StreamItem& item : items)
        samples += std::holds_alternative<palp::Sample>(item) ? 1 : 0;
      deliver(items);
    }
  }
  const double cpu_s = thread_cpu_s() - cpu0;
  const double bulk = usb_bulk_samples_per_s();
  state.SetBytesProcessed(static_cast<std::int64_t>(wire.size()) * state.iterations());
  state.counters["samples_per_s"] =
      benchmark::Counter(static_cast<double>(samples), benchmark::Counter::kIsRate);
  if (cpu_s > 0)
    state.counters["x_usb_fullspeed_bulk"] = static_cast<double>(samples) / cpu_s / bulk;
  state.counters["usb_bulk_samples_per_s"] = bulk;
  if (samples != static_cast<std::int64_t>(kFrames * kBatch) * state.iterations())
    state.SkipWithError("the assembler did not deliver every sample");
}

void BM_StreamDecode(benchmark::State& state) {
  stream_decode(state, [](std::vector<palp::StreamItem>& items) {
    benchmark::DoNotOptimize(items.data());
  });
}

void BM_StreamDecodeToQueue(benchmark::State& state) {
  palp::detail::StreamQueue queue(1u << 20);
  std::vector<palp::StreamItem> out;
  stream_decode(state, [&](std::vector<palp::StreamItem>& items) {
    queue.push(items);
    out.clear();
    queue.drain(out, SIZE_MAX);
    benchmark::DoNotOptimize(out.data());
  });
}

// ---- round trips against palp-sim --------------------------------------------------------------

struct SimProbe {
  palp::sim::test::SimProcess sim{{}, false};
  std::unique_ptr<palp::Probe> probe;
  SimProbe() {
    if (sim.ok()) probe = std::make_unique<palp::Probe>(sim.uri());
  }
};

/// One simulator and one connection for every round-trip benchmark of this run.
palp::Probe* sim_probe(benchmark::State& state) {
  static SimProbe p;
  if (!p.probe) state.SkipWithError(("palp-sim did not start: " + p.sim.banner()).c_str());
  return p.probe.get();
}

template <class Request>
void round_trip(benchmark::State& state, Request&& request) {
  palp::Probe* probe = sim_probe(state);
  if (!probe) return;
  std::vector<double> us;
  us.reserve(1 << 16);
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    request(*probe);
    us.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0)
                     .count());
  }
  if (us.empty()) return;
  std::sort(us.begin(), us.end());
  auto pct = [&us](double p) {  // nearest rank
    const std::size_t r = static_cast<std::size_t>(p / 100.0 * static_cast<double>(us.size()));
    return us[std::min(us.size() - 1, r)];
  };
  state.counters["p50_us"] = pct(50);
  state.counters["p99_us"] = pct(99);
  state.counters["max_us"] = us.back();
}

void BM_RoundTripStatus(benchmark::State& state) {
  round_trip(state, [](palp::Probe& p) { benchmark::DoNotOptimize(p.status()); });
}

void BM_RoundTripLoadHold(benchmark::State& state) {
  palp::HoldProgram h;
  h.current_A = 0.2f;
  h.duration_s = 0.5f;
  round_trip(state, [&h](palp::Probe& p) { p.load(h); });
}

BENCHMARK(BM_StreamDecode)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_StreamDecodeToQueue)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_RoundTripStatus)->UseRealTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_RoundTripLoadHold)->UseRealTime()->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
