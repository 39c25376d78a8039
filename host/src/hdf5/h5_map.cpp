// SPDX-License-Identifier: Apache-2.0
// A map directory as one HDF5 file (docs/hdf5-format.md "A map file"): map.json as text, the
// map's settings and analysis typed, a result's group per point.
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "experiments/trace_json.hpp"
#include "hdf5/h5.hpp"
#include "hdf5/h5_map_dynamic.hpp"
#include "hdf5/h5_result.hpp"
#include "palp/error.hpp"
#include "palp/hdf5.hpp"

namespace palp {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

using namespace hdf5_detail;

/// A point's group name: its place on the grid, as its result directory's ("r1_c2").
std::string point_group_name(const MapPoint& p) {
  return "r" + std::to_string(p.row) + "_c" + std::to_string(p.column);
}

/// analyze_map's numbers in lab units (N/mm), as datasets and attributes of `/map/analysis`; the
/// grid holds map.json's own numbers (`doc`), exactly.
void write_map_analysis(hid_t parent, const Where& w, const StiffnessMap& m, const json& doc) {
  const MapAnalysis a = analyze_map(m);
  const Id g = create_group(parent, w);
  const auto n_per_mm = [](double v) { return v * 1e-3; };
  std::vector<double> k(a.k_N_per_m.size(), std::numeric_limits<double>::quiet_NaN());
  for (std::size_t n = 0; n < m.points.size(); ++n) {  // doc's points are m's (map_from_json)
    const MapPoint& p = m.points[n];
    const auto v = doc["points"][n].find("k_fd_N_per_mm");
    if (p.row >= 1 && p.row <= a.rows && p.column >= 1 && p.column <= a.columns && v != doc["points"][n].end() &&
        v->is_number())
      k[static_cast<std::size_t>((p.row - 1) * a.columns + p.column - 1)] = v->get<double>();
  }
  put_grid(g.get(), "k_fd_N_per_mm", k, static_cast<std::size_t>(a.rows), static_cast<std::size_t>(a.columns),
           "N/mm", w);
  // which points were measured: an adaptive map's NaN is "not measured" where this is 0
  const std::vector<std::uint8_t> measured(a.measured.begin(), a.measured.end());
  put_mask_grid(g.get(), "measured", measured, static_cast<std::size_t>(a.rows),
                static_cast<std::size_t>(a.columns), w);
  const auto means = [&](const char* name, const std::vector<double>& v) {
    std::vector<double> out;
    for (double x : v) out.push_back(n_per_mm(x));
    put_column<double>(g.get(), name, out, "N/mm", w);
  };
  means("column_mean_N_per_mm", a.column_mean_N_per_m);
  means("row_mean_N_per_mm", a.row_mean_N_per_m);
  for (const auto& [name, lines] : {std::pair{"soft_columns", &a.soft_columns}, {"stiff_columns", &a.stiff_columns},
                                    {"soft_rows", &a.soft_rows}, {"stiff_rows", &a.stiff_rows}})
    put_column<int>(g.get(), name, *lines, "1", w);
  put_attr(g.get(), "median_N_per_mm", n_per_mm(a.median_N_per_m), w);
  put_attr(g.get(), "contrast", a.contrast, w);
}

/// The touches of map.json's surface as rows x columns grids of `/map/surface` (its own numbers,
/// exactly; NaN where a point was not touched or not mapped): the contact point and the normal
/// in the work object's frame, and the tilt.
void write_map_surface(hid_t parent, const Where& w, const StiffnessMap& m, const json& doc) {
  const Id g = create_group(parent, w);
  const auto rows = static_cast<std::size_t>(m.rows), columns = static_cast<std::size_t>(m.columns);
  const json* points = nullptr;
  if (const auto s = doc.find("surface"); s != doc.end() && s->is_object())
    if (const auto p = s->find("points"); p != s->end() && p->is_array()) points = &*p;
  struct Grid {
    const char* name;
    const char* key;
    int index;  ///< into the key's array; -1: a number
    const char* unit;
  };
  for (const Grid& grid : {Grid{"contact_x_mm", "contact_mm", 0, "mm"}, Grid{"contact_y_mm", "contact_mm", 1, "mm"},
                           Grid{"contact_z_mm", "contact_mm", 2, "mm"}, Grid{"normal_x", "normal", 0, "1"},
                           Grid{"normal_y", "normal", 1, "1"}, Grid{"normal_z", "normal", 2, "1"},
                           Grid{"tilt_deg", "tilt_deg", -1, "deg"}}) {
    std::vector<double> v(rows * columns, std::numeric_limits<double>::quiet_NaN());
    for (std::size_t n = 0; points != nullptr && n < points->size() && n < m.points.size(); ++n) {
      const MapPoint& p = m.points[n];
      const json& q = (*points)[n];
      if (!p.surface.ok || !q.is_object() || p.row < 1 || p.row > m.rows || p.column < 1 || p.column > m.columns)
        continue;
      const auto f = q.find(grid.key);
      if (f == q.end()) continue;
      const auto at = static_cast<std::size_t>(grid.index);
      const json* x = grid.index < 0 ? &*f : f->is_array() && f->size() > at ? &(*f)[at] : nullptr;
      if (x != nullptr && x->is_number())
        v[static_cast<std::size_t>(p.row - 1) * columns + static_cast<std::size_t>(p.column - 1)] = x->get<double>();
    }
    put_grid(g.get(), grid.name, v, rows, columns, grid.unit, w);
  }
}

const LoadedResult* result_of(const LoadedMap& m, const std::string& result_dir) {
  for (const auto& [dir, r] : m.results)
    if (dir == result_dir) return &r;
  return nullptr;
}
const std::string* damage_of(const LoadedMap& m, const std::string& result_dir) {
  for (const auto& [dir, why] : m.damaged)
    if (dir == result_dir) return &why;
  return nullptr;
}

}  // namespace

LoadedMap load_map_results(const fs::path& dir) {
  LoadedMap out;
  out.dir = dir;
  out.document = detail::read_json_file(dir / "map.json");
  out.map = map_from_json(out.document, (dir / "map.json").string());
  for (const MapPoint& p : out.map.points) {
    if (!p.indented || p.result_dir.empty()) continue;
    for (const std::string& d : {p.result_dir, p.dynamic_dir}) {  // dynamic: its identification too
      if (d.empty()) continue;
      try {
        out.results.emplace_back(d, load_result(dir / d));
      } catch (const Error& e) {  // a damaged point: named, and the others read
        out.damaged.emplace_back(d, e.what());
      }
    }
  }
  return out;
}

void write_map_hdf5(const fs::path& path, const LoadedMap& m, Overwrite overwrite) {
  const json doc = m.document.is_object() ? m.document : map_to_json(m.map);
  const StiffnessMap map = map_from_json(doc, path.string() + ": map.json");  // what is written, checked
  for (const MapPoint& p : map.points)
    for (const std::string& d : {p.result_dir, p.dynamic_dir})  // dynamic: its identification too
      if (p.indented && !d.empty() && !result_of(m, d) && !damage_of(m, d))
        throw ConfigError(path.string() + ": point " + d +
                          " was measured but neither its result nor why it is missing is given");
  write_palp_file(path, overwrite, kHdf5ContentMap, [&](hid_t root) {
    const Where w{path.string(), "/map"};
    const Id g = create_group(root, w);
    put_attr(g.get(), "map_json", doc.dump(), w);
    put_json_scalars(g.get(), "", doc, {}, w);  // quick look: plan, rows, columns, complete, ...
    const Id s = create_group(g.get(), w.at("settings"));
    if (const auto settings = doc.find("settings"); settings != doc.end() && settings->is_object())
      put_json_scalars(s.get(), "", *settings, {"analysis"}, w.at("settings"));
    write_map_analysis(g.get(), w.at("analysis"), map, doc);
    write_map_surface(g.get(), w.at("surface"), map, doc);
    write_map_dynamic_grids(g.get(), w.at("dynamic"), map);
    const Where wp = w.at("points");
    const Id points = create_group(g.get(), wp);
    for (std::size_t k = 0; k < map.points.size(); ++k) {
      const MapPoint& p = map.points[k];
      const Where wq = wp.at(point_group_name(p));
      const LoadedResult* r = p.indented && !p.result_dir.empty() ? result_of(m, p.result_dir) : nullptr;
      if (r != nullptr) write_result_group(points.get(), wq, *r);
      const Id q = r != nullptr ? open_group(points.get(), point_group_name(p).c_str(), wp) : create_group(points.get(), wq);
      put_attr(q.get(), "row", static_cast<std::int64_t>(p.row), wq);  // typed alike whatever JSON made them
      put_attr(q.get(), "column", static_cast<std::int64_t>(p.column), wq);
      put_attr(q.get(), "indented", static_cast<std::int64_t>(p.indented ? 1 : 0), wq);
      put_json_scalars(q.get(), "", doc["points"][k], {}, wq);  // k_fd_N_per_mm, reason, result_dir, ...
      if (const std::string* why = r != nullptr || p.result_dir.empty() ? nullptr : damage_of(m, p.result_dir))
        put_attr(q.get(), "damaged", std::string_view(*why), wq);
      // dynamic: the point's identification as its own group beside it ("r1_c1_dynamic")
      if (p.indented && !p.dynamic_dir.empty()) {
        const Where wd = wp.at(dynamic_group_name(p));
        if (const LoadedResult* id = result_of(m, p.dynamic_dir)) {
          write_result_group(points.get(), wd, *id);
        } else {
          const Id lost = create_group(points.get(), wd);
          put_attr(lost.get(), "damaged", std::string_view(*damage_of(m, p.dynamic_dir)), wd);
        }
      }
    }
  });
}

LoadedMap read_map_hdf5(const fs::path& path) {
  const Id f = open_palp_file(path, kHdf5ContentMap);
  const Where root{path.string(), "/"};
  const Id g = open_group(f.get(), "map", root);
  const Where w = root.at("map");
  LoadedMap out;
  out.dir = path;
  out.document = json::parse(get_string_attr(g.get(), "map_json", w), nullptr, false);
  if (out.document.is_discarded() || !out.document.is_object()) fail(w.at("map_json"), "is not a JSON object");
  try {
    out.map = map_from_json(out.document, "map.json");
  } catch (const ConfigError& e) {
    fail(w.at("map_json"), e.what());
  }
  const Id points = open_group(g.get(), "points", w);
  const Where wp = w.at("points");
  for (const MapPoint& p : out.map.points) {
    const std::string name = point_group_name(p);
    if (!p.indented || p.result_dir.empty()) continue;
    const Id q = open_group(points.get(), name.c_str(), wp);
    if (has_attr(q.get(), "damaged"))
      out.damaged.emplace_back(p.result_dir, get_string_attr(q.get(), "damaged", wp.at(name)));
    else
      out.results.emplace_back(p.result_dir, read_result_group(points.get(), name.c_str(), wp, path));
    if (p.dynamic_dir.empty()) continue;  // dynamic: the point's identification group
    const std::string dname = dynamic_group_name(p);
    const Id d = open_group(points.get(), dname.c_str(), wp);
    if (has_attr(d.get(), "damaged"))
      out.damaged.emplace_back(p.dynamic_dir, get_string_attr(d.get(), "damaged", wp.at(dname)));
    else
      out.results.emplace_back(p.dynamic_dir,
                               read_result_group(points.get(), dname.c_str(), wp, path));
  }
  return out;
}

}  // namespace palp
