// SPDX-License-Identifier: Apache-2.0
// Sensor transfer functions shared by the plant and by anyone who decodes its codes.
// ADC widths (bits) are 2..16, as PlantConfig requires.
#pragma once

#include <cstdint>

namespace palp::plant {

/// Pressure sensor + ADC (ELVH-L05D, ratiometric, +-full_scale_Pa): code/2^bits = 0.5 + 0.4 p/FS,
/// rounded to nearest and clamped to [0, 2^bits - 1].
std::uint16_t pressure_code_from_Pa(double pressure_Pa, double full_scale_Pa = 1245.42,
                                    int bits = 12);
/// Inverse of pressure_code_from_Pa (code centre), Pa.
double pressure_Pa_from_code(std::uint16_t code, double full_scale_Pa = 1245.42, int bits = 12);

/// Current-sense ADC (assumed bipolar chain): 0 A at mid-scale 2^(bits-1), +-full_scale_A at the
/// ends: code = 2^(bits-1) + i/FS * 2^(bits-1), rounded and clamped.
std::uint16_t current_code_from_A(double current_A, double full_scale_A = 5.0, int bits = 12);
/// Inverse of current_code_from_A, A.
double current_A_from_code(std::uint16_t code, double full_scale_A = 5.0, int bits = 12);

}  // namespace palp::plant
