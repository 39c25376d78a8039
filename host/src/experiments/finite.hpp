// SPDX-License-Identifier: Apache-2.0
// The first check of every settings struct (IndentationSettings, IdentificationSettings,
// KfCalibrationSettings, Rig, Plan): each number is finite, and the first that is not is named.
// A range check alone lets NaN through (every comparison with it is false).
#pragma once

#include <cmath>
#include <cstddef>
#include <initializer_list>
#include <string>
#include <vector>

#include "palp/error.hpp"

namespace palp::experiment {

struct NamedNumber {
  const char* name;
  double value;
};

inline std::string non_finite_text(double v) { return std::isnan(v) ? "nan" : v > 0 ? "inf" : "-inf"; }

/// ConfigError "<who>: <name> is nan, not a finite number" for the first value that is NaN or
/// infinite.
inline void require_finite(const std::string& who, std::initializer_list<NamedNumber> values) {
  for (const NamedNumber& n : values)
    if (!std::isfinite(n.value))
      throw ConfigError(who + ": " + n.name + " is " + non_finite_text(n.value) + ", not a finite number");
}

/// The same for every element of a list: "<who>: <name>[k] is inf, not a finite number".
inline void require_finite(const std::string& who, const char* name, const std::vector<double>& values) {
  for (std::size_t k = 0; k < values.size(); ++k)
    if (!std::isfinite(values[k]))
      throw ConfigError(who + ": " + name + "[" + std::to_string(k) + "] is " + non_finite_text(values[k]) +
                        ", not a finite number");
}

}  // namespace palp::experiment
