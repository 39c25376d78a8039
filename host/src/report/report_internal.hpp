// SPDX-License-Identifier: Apache-2.0
// palp_report's internal pieces shared by its files (not installed): the inlined Vega modules,
// the header lines of a result, number text for people.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "palp/result.hpp"

namespace palp::report::detail {

using HeaderLines = std::vector<std::pair<std::string, std::string>>;

/// The page's JavaScript that defines `window.vega` (vega_modules.cpp): Debian's libjs-vega
/// modules, each registered under its module name behind a small AMD shim, merged as vega's own
/// index merges them, with the transforms registered in vega-dataflow's table. Read from
/// $PALP_JS_DIR, else /usr/share/javascript. ConfigError naming a missing file and its package.
std::string vega_modules_js();

/// The header lines of a run from its result.json and its first recording's sidecar: the
/// device, firmware, protocol, calibration, the SDK and the date, and `settings` of the run.
HeaderLines result_header(const LoadedResult& result);

/// The settings of an indentation (result.json's "parameters") as one line for people:
/// "ramp 0.5 → 3 A by 0.01 A every 25 ms, 3 repetitions, limit 5 mm; K_f 2.918 N/A, ...".
std::string indentation_settings_text(const nlohmann::json& parameters);

/// A number with `digits` significant digits ("2.918", "0.0439", "1.26e+05").
std::string num(double v, int digits = 4);
/// A number with `decimals` decimals, with its sign when `sign` ("2.808", "+0.3", "-29.2").
std::string fixed(double v, int decimals, bool sign = false);

}  // namespace palp::report::detail
