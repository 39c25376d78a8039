// SPDX-License-Identifier: Apache-2.0
// Protocol throughput on one core: encode and decode of the stream's largest frame (a full
// 40-sample SampleBatch) and of a small command (LoadRamp), plus CRC-32 and COBS alone.
// bytes_per_second counts wire bytes; items_per_second counts messages.
#include <benchmark/benchmark.h>

#include <vector>

#include "palp/protocol/examples.hpp"
#include "palp/protocol/frame.hpp"

namespace {

using namespace palp::proto;

template <class M>
void encode_bench(benchmark::State& state, const M& m) {
  std::vector<u8> out(kMaxWireFrame);
  std::size_t bytes = 0;
  u16 seq = 0;
  for (auto _ : state) {
    const std::size_t n = encode_message(m, ++seq, 0, out.data(), out.size());
    benchmark::DoNotOptimize(out.data());
    bytes += n;
  }
  state.SetBytesProcessed(static_cast<int64_t>(bytes));
  state.SetItemsProcessed(state.iterations());
}

template <class M>
void decode_bench(benchmark::State& state, const M& m, bool unpack_samples) {
  // 256 frames back to back, fed through the reader and decoded like a host does
  std::vector<u8> stream;
  std::vector<u8> one(kMaxWireFrame);
  for (u16 k = 0; k < 256; ++k) {
    const std::size_t n = encode_message(m, k, 0, one.data(), one.size());
    stream.insert(stream.end(), one.begin(), one.begin() + static_cast<long>(n));
  }
  std::size_t messages = 0;
  int64_t samples = 0;
  for (auto _ : state) {
    FrameReader reader;
    reader.feed(
        stream.data(), stream.size(),
        [&](const Frame& f) {
          decode_message(f.header.id, f.payload, f.header.payload_len, [&](const auto& msg) {
            ++messages;
            if constexpr (std::is_same_v<std::decay_t<decltype(msg)>, SampleBatch>) {
              if (unpack_samples) {
                Reader r(msg.data.items.data(), msg.data.size);
                RawSample s;
                for (u16 k = 0; k < msg.sample_count; ++k) {
                  unpack_sample(r, s, msg.channels);
                  benchmark::DoNotOptimize(s);
                }
                samples += msg.sample_count;
              }
            }
          });
        },
        [](Reject) {});
  }
  state.SetBytesProcessed(static_cast<int64_t>(stream.size()) * state.iterations());
  state.SetItemsProcessed(static_cast<int64_t>(messages));
  if (samples > 0)
    state.counters["samples_per_second"] =
        benchmark::Counter(static_cast<double>(samples), benchmark::Counter::kIsRate);
}

void BM_EncodeSampleBatch40(benchmark::State& state) {
  encode_bench(state, example_batch(0, 0, 40));
}
void BM_DecodeSampleBatch40(benchmark::State& state) {
  decode_bench(state, example_batch(0, 0, 40), false);
}
void BM_DecodeAndUnpackSampleBatch40(benchmark::State& state) {
  decode_bench(state, example_batch(0, 0, 40), true);
}
void BM_EncodeLoadRamp(benchmark::State& state) { encode_bench(state, example_ramp_2d()); }
void BM_DecodeLoadRamp(benchmark::State& state) { decode_bench(state, example_ramp_2d(), false); }

void BM_Crc32_1KiB(benchmark::State& state) {
  std::vector<u8> data(1024);
  for (std::size_t k = 0; k < data.size(); ++k) data[k] = static_cast<u8>(k * 7);
  for (auto _ : state) benchmark::DoNotOptimize(crc32(data.data(), data.size()));
  state.SetBytesProcessed(static_cast<int64_t>(data.size()) * state.iterations());
}

void BM_CobsEncode_1KiB(benchmark::State& state) {
  std::vector<u8> data(1024);
  for (std::size_t k = 0; k < data.size(); ++k) data[k] = static_cast<u8>(k * 7);
  std::vector<u8> out(cobs_max_encoded(data.size()));
  for (auto _ : state) {
    benchmark::DoNotOptimize(cobs_encode(data.data(), data.size(), out.data(), out.size()));
  }
  state.SetBytesProcessed(static_cast<int64_t>(data.size()) * state.iterations());
}

BENCHMARK(BM_EncodeSampleBatch40);
BENCHMARK(BM_DecodeSampleBatch40);
BENCHMARK(BM_DecodeAndUnpackSampleBatch40);
BENCHMARK(BM_EncodeLoadRamp);
BENCHMARK(BM_DecodeLoadRamp);
BENCHMARK(BM_Crc32_1KiB);
BENCHMARK(BM_CobsEncode_1KiB);

}  // namespace

BENCHMARK_MAIN();
