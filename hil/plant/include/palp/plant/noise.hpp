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

/// Standard normal deviate N(0, 1) for (seed, stream, tick): splitmix64 hashing and Box-Muller.
double gaussian(std::uint64_t seed, std::uint32_t stream, std::uint64_t tick);

}  // namespace palp::plant
