// SPDX-License-Identifier: Apache-2.0
// The tidy CSV of a map or a result directory (tidy_csv.hpp; docs/result-format.md "The tidy CSV").
#include "palp/tidy_csv.hpp"


#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "experiment_common.hpp"
#include "format/field_table.hpp"
#include "palp/error.hpp"
#include "palp/indent.hpp"
#include "palp/map.hpp"
#include "palp/result.hpp"
#include "recording/internal.hpp"
#include "result_dir.hpp"

namespace palp {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

/// One column of a repetition's keys: where indentation_summary_json puts its value.
struct KeyColumn {
  std::string name;   ///< in the header
  std::string key;    ///< in the summary, or in its sub-object `group`
  std::string group;  ///< "", or "k_at_depth_N_per_mm" / "k_at_depth_N_per_mm_se"
  bool reason = true; ///< followed by a <name>_reason column (the key may be null)
};

/// result.json's "analysis" keys of one repetition, in the documented order. Left out: params
/// (in result.json), the model-free descriptors' _se (always null: no fit behind them) and the
/// pooled-only _sd and repetitions.
std::vector<KeyColumn> key_columns(const analysis::IndentationParams& p) {
  std::vector<KeyColumn> c;
  const auto add = [&c](const std::string& key, bool reason = true) { c.push_back({key, key, "", reason}); };
  const auto add_se = [&add](const std::string& key) {
    add(key);
    add(key + "_se");
  };
  add_se("contact_point_mm");
  add("model_by_aic");
  add_se("k_linear_N_per_mm");
  add("r2_linear");
  add("aic_linear");
  for (const std::string m : {"hertz", "sneddon"}) {
    add_se("E_star_" + m + "_Pa");
    add_se("E_" + m + "_Pa");
    add("r2_" + m);
    add("aic_" + m);
  }
  add_se("delta0_mm");
  add_se("k_tangent_N_per_mm");
  add("k_fd_N_per_mm");
  add("k_ls_window_N_per_mm");
  add("k_fd_paper_N_per_mm");
  for (const double d : p.tangent_depths_m) {
    const std::string depth = experiment::depth_key(d);
    std::string tag = depth;
    std::replace(tag.begin(), tag.end(), '.', 'p');  // a MATLAB variable name: "0p5_mm"
    c.push_back({"k_at_depth_" + tag + "_N_per_mm", depth, "k_at_depth_N_per_mm", true});
    c.push_back({"k_at_depth_" + tag + "_N_per_mm_se", depth, "k_at_depth_N_per_mm_se", true});
  }
  for (const char* k : {"F0_N", "has_baseline", "n_loading", "n_unloading"}) add(k, false);
  return c;
}

/// RFC 4180: quoted when it holds a comma, a quote or a line break; quotes doubled.
std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\r\n") == std::string::npos) return s;
  std::string q = "\"";
  for (const char ch : s) {
    if (ch == '"') q += '"';
    q += ch;
  }
  return q + '"';
}

std::string number_text(double v) { return recording_detail::shortest(v); }

struct Cell {
  std::string value, reason;
};

/// A key's value as text, or empty with the reason (the summary's <key>_reason when it is null).
Cell cell_of(const json& object, const std::string& key) {
  const auto it = object.find(key);
  if (it == object.end()) return {"", "not in this result's analysis"};
  if (it->is_null()) {
    const auto r = object.find(key + "_reason");
    return {"", r != object.end() && r->is_string() ? r->get<std::string>() : "not computed"};
  }
  if (it->is_boolean()) return {it->get<bool>() ? "true" : "false", ""};
  if (it->is_number_integer()) return {it->dump(), ""};
  if (it->is_number_float()) {
    const double v = it->get<double>();
    if (!std::isfinite(v)) return {"", "not a finite number: " + number_text(v)};
    return {number_text(v), ""};
  }
  if (it->is_string()) return {it->get<std::string>(), ""};
  return {"", "not a single value"};
}

/// Where a row belongs.
struct Place {
  std::optional<int> row, column;
  const TracePoint* surface = nullptr;  ///< its position, when the touch succeeded
};

/// The repetitions of one result directory, each analysed alone, or why there are none.
struct PointResult {
  std::vector<std::pair<int, json>> reps;  ///< the recording's rep number, the summary
  std::string reason;
  analysis::IndentationParams params;
};

PointResult analyse_result(const fs::path& dir) {
  const IndentationRun run = indentation_run_of(load_result(dir));
  PointResult out;
  out.params = run.settings.analysis;
  if (!run.repetitions) {
    out.reason = run.analysis_reason.empty() ? "not analysed" : run.analysis_reason;
    return out;
  }
  // the repetitions are the recording's runs of equal rep (analyze_repetitions splits so)
  const Eigen::VectorXi rep = curve_of(run.recording).rep;
  std::vector<int> labels;
  for (Eigen::Index k = 0; k < rep.size(); ++k)
    if (k == 0 || rep[k] != rep[k - 1]) labels.push_back(rep[k]);
  const auto& per_rep = run.repetitions->per_rep;
  for (std::size_t k = 0; k < per_rep.size(); ++k)
    out.reps.emplace_back(k < labels.size() ? labels[k] : static_cast<int>(k),
                          indentation_summary_json(per_rep[k], nullptr, run.settings.analysis));
  return out;
}

class Table {
 public:
  explicit Table(const analysis::IndentationParams& p) : keys_(key_columns(p)) {
    text_ = std::string(kTidyCsvHeadColumns);
    for (const KeyColumn& k : keys_) {
      text_ += ',' + k.name;
      if (k.reason) text_ += ',' + k.name + "_reason";
    }
    text_ += '\n';
  }

  /// One row: a repetition's summary, or (summary null) a point without one and why.
  void add(const Place& where, std::optional<int> rep, const json* summary, const std::string& point_reason) {
    const auto opt = [](std::optional<int> v) { return v ? std::to_string(*v) : std::string(); };
    const auto mm = [&](double m) {
      const double v = m * format::kMm;
      return where.surface != nullptr && where.surface->ok && std::isfinite(v) ? number_text(v) : std::string();
    };
    std::string line = opt(where.row) + ',' + opt(where.column) + ',' + opt(rep);
    if (where.surface != nullptr)
      line += ',' + mm(where.surface->x_m) + ',' + mm(where.surface->y_m) + ',' + mm(where.surface->z_m);
    else
      line += ",,,";
    line += ',' + csv_field(point_reason);
    for (const KeyColumn& k : keys_) {
      Cell c;
      if (summary != nullptr) {
        const json* object = summary;
        if (!k.group.empty()) {
          const auto g = summary->find(k.group);
          object = g != summary->end() && g->is_object() ? &*g : nullptr;
        }
        c = object != nullptr ? cell_of(*object, k.key) : Cell{"", "not in this result's analysis"};
      }
      line += ',' + csv_field(c.value);
      if (k.reason) line += ',' + csv_field(c.reason);
    }
    text_ += line + '\n';
    ++rows_;
  }

  void add_point(const Place& where, const PointResult& r) {
    if (r.reps.empty()) add(where, std::nullopt, nullptr, r.reason);
    for (const auto& [rep, summary] : r.reps) add(where, rep, &summary, "");
  }

  std::size_t rows() const { return rows_; }
  const std::string& text() const { return text_; }

 private:
  std::vector<KeyColumn> keys_;
  std::string text_;
  std::size_t rows_ = 0;
};

std::string map_csv(const fs::path& dir, TidyCsvExport& summary) {
  const StiffnessMap m = load_map(dir);
  Table table(m.settings.analysis);
  const std::size_t total = static_cast<std::size_t>(m.rows) * static_cast<std::size_t>(m.columns);
  // the grid row-major, whatever order map.json's points are in (an adaptive map's: the planner's)
  for (std::size_t k = 0; k < total; ++k) {
    Place where{static_cast<int>(k) / m.columns + 1, static_cast<int>(k) % m.columns + 1, nullptr};
    const auto at = std::find_if(m.points.begin(), m.points.end(), [&](const MapPoint& p) {
      return p.row == where.row && p.column == where.column;
    });
    if (at == m.points.end()) {
      const std::string why = m.adaptive && m.complete
                                  ? "not measured: the adaptive map did not choose this point"
                                  : "not mapped: the map stopped before this point";
      table.add(where, std::nullopt, nullptr,
                why + (m.stopped_because.empty() ? std::string() : " (" + m.stopped_because + ")"));
      continue;
    }
    const MapPoint& p = *at;
    where = {p.row, p.column, &p.surface};
    if (!p.indented || p.result_dir.empty()) {
      table.add(where, std::nullopt, nullptr, p.reason.empty() ? "not indented" : p.reason);
      continue;
    }
    PointResult r;
    try {
      r = analyse_result(dir / p.result_dir);
    } catch (const Error& e) {  // a damaged point: say so in its row and go on
      r.reason = e.what();
      summary.damaged.push_back(r.reason);
    }
    table.add_point(where, r);
  }
  summary.points = total;
  summary.rows = table.rows();
  return table.text();
}

std::string result_csv(const fs::path& dir, TidyCsvExport& summary) {
  const PointResult r = analyse_result(dir);  // the only point: its errors stop the export
  Table table(r.params);
  table.add_point(Place{}, r);
  summary.points = 1;
  summary.rows = table.rows();
  return table.text();
}

}  // namespace

std::vector<std::string> tidy_csv_columns(const analysis::IndentationParams& params) {
  std::vector<std::string> names;
  const std::string head(kTidyCsvHeadColumns);
  for (std::size_t b = 0;;) {
    const std::size_t e = head.find(',', b);
    names.push_back(head.substr(b, e == std::string::npos ? std::string::npos : e - b));
    if (e == std::string::npos) break;
    b = e + 1;
  }
  for (const KeyColumn& k : key_columns(params)) {
    names.push_back(k.name);
    if (k.reason) names.push_back(k.name + "_reason");
  }
  return names;
}

std::string tidy_csv(const fs::path& input, TidyCsvExport* summary) {
  std::error_code ec;
  const std::string kinds = "a map directory (with map.json) or a result directory (with result.json)";
  if (!fs::exists(input, ec)) throw ConfigError(input.string() + ": no such directory; give " + kinds);
  if (!fs::is_directory(input, ec)) throw ConfigError(input.string() + " is not a directory; give " + kinds);
  TidyCsvExport s;
  std::string text;
  if (fs::exists(input / "map.json", ec))
    text = map_csv(input, s);
  else if (fs::exists(input / kResultFile, ec))
    text = result_csv(input, s);
  else
    throw ConfigError(input.string() + " is neither a map directory (no map.json) nor a result directory (no " +
                      std::string(kResultFile) + ")");
  if (summary != nullptr) *summary = s;
  return text;
}

const OwnFileKind& tidy_csv_kind() {
  static const OwnFileKind kind{kTidyCsvHeadColumns, "is not a file palp wrote (not a regular file)",
                                "was not written by palp (its first line does not begin \"" +
                                    std::string(kTidyCsvHeadColumns) + "\")"};
  return kind;
}

void check_tidy_csv_replaceable(const fs::path& file, Overwrite overwrite) {
  check_own_file_replaceable(file, overwrite, tidy_csv_kind());
}

TidyCsvExport export_tidy_csv(const fs::path& input, const fs::path& file, Overwrite overwrite) {
  TidyCsvExport summary;
  write_own_file(file, overwrite, tidy_csv_kind(), [&] { return tidy_csv(input, &summary); });
  return summary;
}

}  // namespace palp
