// SPDX-License-Identifier: Apache-2.0
// Counter-based Gaussian noise: the sample for (seed, stream, tick) is a pure function of those
// three numbers, so a run repeats exactly for a given seed whatever the order or number of sensor
// reads, and one sensor's reads never shift another's noise.
#pragma once

#include <cstdint>

namespace palp::plant {

/// Independent noise streams, one per sensor.
enum class NoiseStream : std::uint32_t {
  current_sense = 1,
  encoder = 2,
  pressure_base = 16,  // + channel number 1..6
};

/// The hash of (seed, stream) that every sample of that stream starts from: a plant keeps its
/// streams' keys instead of hashing seed and stream again every tick.
std::uint64_t noise_key(std::uint64_t seed, std::uint32_t stream);

/// Standard normal deviate N(0, 1) of the stream with this key at this tick: one splitmix64 hash
/// of (key, tick) through a 256-layer ziggurat, one multiply for 98.5 % of draws (README.md
/// "Noise"). gaussian_at(noise_key(seed, stream), tick) == gaussian(seed, stream, tick).
double gaussian_at(std::uint64_t key, std::uint64_t tick);

/// Where the ziggurat's tail begins (r = 3.654...): |deviates| beyond it come from Marsaglia's
/// tail method, for the tests that check the tail is sampled.
double ziggurat_tail_start();

/// Standard normal deviate N(0, 1) for (seed, stream, tick).
inline double gaussian(std::uint64_t seed, std::uint32_t stream, std::uint64_t tick) {
  return gaussian_at(noise_key(seed, stream), tick);
}

}  // namespace palp::plant
