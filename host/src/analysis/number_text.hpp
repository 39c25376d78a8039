// SPDX-License-Identifier: Apache-2.0
// A number in error messages and notes: six significant digits, as std::ostream prints it
// (private to the analysis).
#pragma once

#include <sstream>
#include <string>

namespace palp::analysis::detail {

inline std::string number_text(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

}  // namespace palp::analysis::detail
