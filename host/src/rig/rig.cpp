// rig.json: reading, writing (atomically) and the JSON form of palp::Rig.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <system_error>

#include "json_fields.hpp"
#include "palp/error.hpp"
#include "palp/rig.hpp"

namespace palp {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

const std::vector<std::string> kRigKeys = {
    "format_version", "robot_uri", "probe_uri", "tool_id", "tool_tcp_mm_deg", "safe_height_mm",
    "approach_speed_mm_per_s", "travel_speed_mm_per_s", "contact_input", "contact_threshold_mm",
    "watch_current_A", "max_approach_mm", "tip_radius_mm", "work_object"};

Pose pose_from_mm_deg(const std::vector<double>& v) {
  Pose p;
  p.x_m = v[0] * rig_detail::kMm;
  p.y_m = v[1] * rig_detail::kMm;
  p.z_m = v[2] * rig_detail::kMm;
  p.a_rad = v[3] * kDeg;
  p.b_rad = v[4] * kDeg;
  p.c_rad = v[5] * kDeg;
  return p;
}

nlohmann::json pose_to_mm_deg(const Pose& p) {
  return nlohmann::json::array({p.x_m / rig_detail::kMm, p.y_m / rig_detail::kMm, p.z_m / rig_detail::kMm, p.a_rad / kDeg,
                                p.b_rad / kDeg, p.c_rad / kDeg});
}

Pose read_pose(const rig_detail::Fields& f, const std::string& key) {
  const std::vector<double> v = f.numbers(key, 6);
  for (int k = 3; k < 6; ++k) {
    if (std::abs(v[static_cast<std::size_t>(k)]) > 360.0) {
      f.fail(key, "angles must be within +-360 deg");
    }
  }
  for (int k = 0; k < 3; ++k) {
    if (std::abs(v[static_cast<std::size_t>(k)]) > 1e5) f.fail(key, "positions must be within +-100 m");
  }
  return pose_from_mm_deg(v);
}

}  // namespace

Rig parse_rig(std::string_view text, std::string_view source) {
  const rig_detail::Fields f(text, std::string(source), kRigKeys);
  f.require({"format_version", "robot_uri", "probe_uri", "tool_tcp_mm_deg", "safe_height_mm"});
  f.integer("format_version", 1, 1);
  Rig r;
  r.robot_uri = f.text("robot_uri");
  r.probe_uri = f.text("probe_uri");
  if (f.has("tool_id")) r.tool_id = f.integer("tool_id", 1, 16);
  r.tool_tcp = read_pose(f, "tool_tcp_mm_deg");
  r.safe_height_m = f.positive("safe_height_mm", 1000.0, "mm") * rig_detail::kMm;
  if (f.has("approach_speed_mm_per_s")) {
    r.approach_speed_m_per_s = f.positive("approach_speed_mm_per_s", 100.0, "mm/s") * rig_detail::kMm;
  }
  if (f.has("travel_speed_mm_per_s")) {
    r.travel_speed_m_per_s = f.positive("travel_speed_mm_per_s", 1000.0, "mm/s") * rig_detail::kMm;
  }
  if (f.has("contact_input")) r.contact_input = f.integer("contact_input", 1, 16);
  if (f.has("contact_threshold_mm")) {
    r.contact_threshold_m = f.positive("contact_threshold_mm", 10.0, "mm") * rig_detail::kMm;
  }
  if (f.has("watch_current_A")) r.watch_current_A = f.number("watch_current_A", 0.0, 3.0, "A");
  if (f.has("max_approach_mm")) r.max_approach_m = f.positive("max_approach_mm", 500.0, "mm") * rig_detail::kMm;
  if (f.has("tip_radius_mm")) r.tip_radius_m = f.positive("tip_radius_mm", 100.0, "mm") * rig_detail::kMm;
  if (f.has("work_object")) {
    const rig_detail::Fields w(f, "work_object", {"name", "pose_mm_deg"});
    w.require({"name", "pose_mm_deg"});
    r.work_object = WorkObject{w.text("name"), read_pose(w, "pose_mm_deg")};
  }
  return r;
}

Rig load_rig(const std::filesystem::path& file) {
  return parse_rig(rig_detail::read_file(file.string()), file.string());
}

std::string rig_to_json(const Rig& rig) {
  nlohmann::ordered_json j;
  j["format_version"] = 1;
  j["robot_uri"] = rig.robot_uri;
  j["probe_uri"] = rig.probe_uri;
  j["tool_id"] = rig.tool_id;
  j["tool_tcp_mm_deg"] = pose_to_mm_deg(rig.tool_tcp);
  j["safe_height_mm"] = rig.safe_height_m / rig_detail::kMm;
  j["approach_speed_mm_per_s"] = rig.approach_speed_m_per_s / rig_detail::kMm;
  j["travel_speed_mm_per_s"] = rig.travel_speed_m_per_s / rig_detail::kMm;
  j["contact_input"] = rig.contact_input;
  j["contact_threshold_mm"] = rig.contact_threshold_m / rig_detail::kMm;
  j["watch_current_A"] = rig.watch_current_A;
  j["max_approach_mm"] = rig.max_approach_m / rig_detail::kMm;
  j["tip_radius_mm"] = rig.tip_radius_m / rig_detail::kMm;
  if (rig.work_object) {
    nlohmann::ordered_json w;
    w["name"] = rig.work_object->name;
    w["pose_mm_deg"] = pose_to_mm_deg(rig.work_object->pose);
    j["work_object"] = w;
  }
  return j.dump(2) + "\n";
}

void save_rig(const std::filesystem::path& file, const Rig& rig) {
  const std::string text = rig_to_json(rig);
  std::filesystem::path tmp = file;
  tmp += ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw ConfigError(file.string() + ": cannot write the file");
    out << text;
    out.flush();
    if (!out) throw ConfigError(file.string() + ": cannot write the file");
  }
  std::error_code ec;
  std::filesystem::rename(tmp, file, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    throw ConfigError(file.string() + ": cannot replace the file");
  }
}

}  // namespace palp
