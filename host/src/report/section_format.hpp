// SPDX-License-Identifier: Apache-2.0
// Numbers for people in the report's tables and labels (the figures' section builders): a
// number to a few significant digits, and a result.json value (a number, or null with its
// `<key>_reason`) as a table cell.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace palp::report {

/// `v` to `significant` digits, without an exponent between 1e-4 and 1e6 ("0.4512", "125800",
/// "1.3e-07"); "—" when not finite.
std::string format_number(double v, int significant = 4);
/// `v` times `scale` (a unit change: 1e-3 for Pa -> kPa) formatted, from a JSON object's key:
/// a number formatted, null "—", absent "" (the table's cell).
std::string format_cell(const nlohmann::json& object, const std::string& key, double scale = 1.0,
                        int significant = 4);
/// The reason beside a null value (`<key>_reason`), or "".
std::string reason_of(const nlohmann::json& object, const std::string& key);

}  // namespace palp::report
