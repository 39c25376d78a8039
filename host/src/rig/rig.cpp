// SPDX-License-Identifier: Apache-2.0
// rig.json: reading, writing (atomically) and the JSON form of palp::Rig.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <system_error>

#include "experiments/finite.hpp"
#include "json_fields.hpp"
#include "palp/error.hpp"
#include "palp/protocol/robot_bridge/check.hpp"
#include "palp/rig.hpp"

namespace palp {
namespace {

using format::Field;
using format::Need;

// rig.json's keys after format_version (docs/rig-and-plan.md), in the file's order
const Field<Rig> kRigFields[] = {
    {"robot_uri", &Rig::robot_uri},
    {"probe_uri", &Rig::probe_uri},
    // the bridge's own ranges (robot-bridge.md §6): one definition for the file and the bridge
    {"tool_id", &Rig::tool_id, 1.0, Need::optional, {1, proto::rb::kMaxTool}},
    {"tool_tcp_mm_deg", &Rig::tool_tcp},
    {"safe_height_mm", &Rig::safe_height_m, format::kMm, Need::required, {0, 1000.0, true, "mm"}},
    {"approach_speed_mm_per_s", &Rig::approach_speed_m_per_s, format::kMm, Need::optional,
     {0, 100.0, true, "mm/s"}},
    {"travel_speed_mm_per_s", &Rig::travel_speed_m_per_s, format::kMm, Need::optional,
     {0, 1000.0, true, "mm/s"}},
    {"contact_input", &Rig::contact_input, 1.0, Need::optional, {1, proto::rb::kMaxDigitalInput}},
    {"contact_threshold_mm", &Rig::contact_threshold_m, format::kMm, Need::optional,
     {0, 10.0, true, "mm"}},
    {"watch_current_A", &Rig::watch_current_A, 1.0, Need::optional, {0.0, 3.0, false, "A"}},
    {"max_approach_mm", &Rig::max_approach_m, format::kMm, Need::optional, {0, 500.0, true, "mm"}},
    {"tip_radius_mm", &Rig::tip_radius_m, format::kMm, Need::optional, {0, 100.0, true, "mm"}},
};
const Field<WorkObject> kWorkObjectFields[] = {
    {"name", &WorkObject::name},
    {"pose_mm_deg", &WorkObject::pose},
};

}  // namespace

Rig parse_rig(std::string_view text, std::string_view source) {
  const rig_detail::Fields f(text, std::string(source),
                             rig_detail::Fields::keys(kRigFields, {"format_version", "work_object"}));
  f.integer("format_version", 1, 1);
  Rig r;
  format::read_fields(f, r, kRigFields);
  if (f.has("work_object")) {
    const rig_detail::Fields w(f, "work_object", rig_detail::Fields::keys(kWorkObjectFields));
    WorkObject o;
    format::read_fields(w, o, kWorkObjectFields);
    r.work_object = o;
  }
  return r;
}

Rig load_rig(const std::filesystem::path& file) {
  return parse_rig(rig_detail::read_file(file.string()), file.string());
}

std::string rig_to_json(const Rig& rig) {
  nlohmann::ordered_json j;
  j["format_version"] = 1;
  format::write_fields(j, rig, kRigFields);
  if (rig.work_object) {
    nlohmann::ordered_json w;
    format::write_fields(w, *rig.work_object, kWorkObjectFields);
    j["work_object"] = w;
  }
  return j.dump(2) + "\n";
}

void Rig::validate() const {
  const Pose& t = tool_tcp;
  const Pose w = work_object ? work_object->pose : Pose{};
  experiment::require_finite(
      "rig", {{"safe_height_m", safe_height_m}, {"approach_speed_m_per_s", approach_speed_m_per_s},
              {"travel_speed_m_per_s", travel_speed_m_per_s}, {"contact_threshold_m", contact_threshold_m},
              {"watch_current_A", watch_current_A}, {"max_approach_m", max_approach_m},
              {"tip_radius_m", tip_radius_m}, {"tool_tcp.x_m", t.x_m}, {"tool_tcp.y_m", t.y_m},
              {"tool_tcp.z_m", t.z_m}, {"tool_tcp.a_rad", t.a_rad}, {"tool_tcp.b_rad", t.b_rad},
              {"tool_tcp.c_rad", t.c_rad}, {"work_object.pose.x_m", w.x_m}, {"work_object.pose.y_m", w.y_m},
              {"work_object.pose.z_m", w.z_m}, {"work_object.pose.a_rad", w.a_rad},
              {"work_object.pose.b_rad", w.b_rad}, {"work_object.pose.c_rad", w.c_rad}});
  parse_rig(rig_to_json(*this), "rig");  // the ranges of rig.json's reader, by its keys
}

void save_rig(const std::filesystem::path& file, const Rig& rig) {
  rig.validate();
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
