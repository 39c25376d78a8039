// SPDX-License-Identifier: Apache-2.0
#include "report/section_format.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace palp::report {

std::string format_number(double v, int significant) {
  if (!std::isfinite(v)) return "—";
  char buf[64];
  const double a = std::abs(v);
  if (a != 0.0 && (a < 1e-4 || a >= 1e6)) {
    std::snprintf(buf, sizeof buf, "%.*g", significant, v);
    return buf;
  }
  // fixed notation with `significant` digits (trailing zeros removed)
  const int magnitude = a == 0.0 ? 0 : static_cast<int>(std::floor(std::log10(a)));
  const int decimals = std::max(0, significant - 1 - magnitude);
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  std::string s = buf;
  if (s.find('.') != std::string::npos) {
    while (!s.empty() && s.back() == '0') s.pop_back();
    if (!s.empty() && s.back() == '.') s.pop_back();
  }
  if (s == "-0") s = "0";
  return s;
}

std::string format_cell(const nlohmann::json& object, const std::string& key, double scale,
                        int significant) {
  if (!object.is_object() || !object.contains(key)) return "";
  const auto& v = object[key];
  if (v.is_number()) return format_number(v.get<double>() * scale, significant);
  if (v.is_boolean()) return v.get<bool>() ? "yes" : "no";
  if (v.is_string()) return v.get<std::string>();
  return "—";
}

std::string reason_of(const nlohmann::json& object, const std::string& key) {
  const std::string k = key + "_reason";
  if (object.is_object() && object.contains(k) && object[k].is_string())
    return object[k].get<std::string>();
  return "";
}

}  // namespace palp::report
