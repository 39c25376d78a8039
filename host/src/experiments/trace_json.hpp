// SPDX-License-Identifier: Apache-2.0
// Trace JSON (trace_io.cpp) for the other files that embed a traced surface (map.json).
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "palp/trace.hpp"

namespace palp::detail {

/// j is an object whose "format" is the string `format` (json::value("format", ...) would throw
/// a type_error for a number there, not a ConfigError).
inline bool has_format(const nlohmann::json& j, std::string_view format) {
  if (!j.is_object()) return false;
  const auto f = j.find("format");
  return f != j.end() && f->is_string() && f->get_ref<const std::string&>() == format;
}

nlohmann::json trace_to_json(const TracedSurface& s);
/// ConfigError "where: problem"; finishes the surface (finish_surface).
TracedSurface trace_from_json(const nlohmann::json& j, const std::string& where);
nlohmann::json point_to_json(const TracePoint& p);
TracePoint point_from_json(const nlohmann::json& j, const std::string& where);
/// A temporary file renamed over `file`. ConfigError when it cannot be written.
void write_json_atomically(const std::filesystem::path& file, const nlohmann::json& j);
/// At most format::kMaxJsonFileBytes. ConfigError "file: cannot open: ..." / "file: the file has
/// N bytes, more than the limit ..." / "file: not JSON (...)".
nlohmann::json read_json_file(const std::filesystem::path& file);

}  // namespace palp::detail
