// Trace JSON (trace_io.cpp) for the other files that embed a traced surface (map.json).
#pragma once

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "palp/trace.hpp"

namespace palp::detail {

nlohmann::json trace_to_json(const TracedSurface& s);
/// ConfigError "where: problem"; finishes the surface (finish_surface).
TracedSurface trace_from_json(const nlohmann::json& j, const std::string& where);
nlohmann::json point_to_json(const TracePoint& p);
TracePoint point_from_json(const nlohmann::json& j, const std::string& where);
/// A temporary file renamed over `file`. ConfigError when it cannot be written.
void write_json_atomically(const std::filesystem::path& file, const nlohmann::json& j);
/// ConfigError "file: cannot be read" / "file: not JSON (...)".
nlohmann::json read_json_file(const std::filesystem::path& file);

}  // namespace palp::detail
