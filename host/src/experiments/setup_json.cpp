// SPDX-License-Identifier: Apache-2.0
// The sidecar's description of the setup (result.hpp): the device block (one field table, written
// and read), the calibration and zeroing blocks, and the sidecar's common part the experiments and
// palpctl's recordings share.
#include <cmath>
#include <cstdio>
#include <string>

#include "experiment_common.hpp"
#include "format/field_table.hpp"
#include "palp/result.hpp"

namespace palp {

namespace {

using nlohmann::json;
using format::Field;
using format::Need;
using experiment::f32;

// "protocol" ("major.minor") is written and read by hand: two members in one key. Every key is
// optional for the reader: a device block may come from an older SDK or palpctl.
const Field<DeviceInfo> kDeviceFields[] = {
    {"serial", &DeviceInfo::serial, 1.0, Need::optional},
    {"board", &DeviceInfo::board, 1.0, Need::optional},
    {"firmware_version", &DeviceInfo::firmware_version, 1.0, Need::optional},
    {"git_hash", &DeviceInfo::git_hash, 1.0, Need::optional},
    {"schema_hash", &DeviceInfo::schema_hash, 1.0, Need::optional},
    {"capabilities", &DeviceInfo::capabilities, 1.0, Need::optional},
    {"max_current_A", &DeviceInfo::max_current_A, 1.0, Need::optional},
    {"control_rate_Hz", &DeviceInfo::control_rate_Hz, 1.0, Need::optional},
    {"max_stream_rate_Hz", &DeviceInfo::max_stream_rate_Hz, 1.0, Need::optional},
    {"heartbeat_timeout_s", &DeviceInfo::heartbeat_timeout_s, 1.0, Need::optional},
    {"max_payload_bytes", &DeviceInfo::max_payload, 1.0, Need::optional},
};

std::uint32_t bit(proto::Capability c) { return 1u << static_cast<unsigned>(c); }

}  // namespace

json device_json(const DeviceInfo& d) {
  json j;
  format::write_fields(j, d, kDeviceFields);
  j["protocol"] = std::to_string(d.protocol_major) + "." + std::to_string(d.protocol_minor);
  return j;
}

DeviceInfo device_info_from_json(const json& j, const std::string& where) {
  if (!j.is_object()) throw ConfigError(where + ": the device block is not an object");
  const format::JsonSource src(j, where);
  DeviceInfo d;
  format::read_fields(src, d, kDeviceFields);
  // palpctl before issue 16 wrote "protocol_version" and, instead of "capabilities", the two
  // it decoded: "simulated" and "pressure_channels"
  const char* protocol_key = src.has("protocol") ? "protocol" : "protocol_version";
  if (src.has(protocol_key)) {
    const std::string text = src.text(protocol_key);
    int major = 0, minor = 0;
    char dot = 0;
    if (std::sscanf(text.c_str(), "%d%c%d", &major, &dot, &minor) != 3 || dot != '.')
      src.fail(protocol_key, "must be \"major.minor\", not \"" + text + "\"");
    d.protocol_major = major;
    d.protocol_minor = minor;
  }
  if (!src.has("capabilities")) {
    if (src.has("simulated") && src.boolean("simulated")) d.capabilities |= bit(proto::Capability::simulated);
    if (src.has("pressure_channels") && src.integer("pressure_channels", {}) > 0)
      d.capabilities |= bit(proto::Capability::pressure);
  }
  return d;
}

json calibration_json(const Calibration& c) {
  json table = json::array();
  for (std::size_t k = 0; k < c.kf_position_counts.size && k < c.kf_N_per_A.size; ++k)
    table.push_back({{"position_mm", c.kf_position_counts.items[k] * 1e-3},
                     {"kf_N_per_A", f32(c.kf_N_per_A.items[k])}});
  json pressure_offset = json::array(), pressure_gain = json::array();
  for (float v : c.pressure_offset_Pa) pressure_offset.push_back(f32(v));
  for (float v : c.pressure_gain) pressure_gain.push_back(f32(v));
  json j = {{"layout_version", c.layout_version},
            {"kf_table", table},
            {"current_offset_A", f32(c.current_offset_A)},
            {"current_gain", f32(c.current_gain)},
            {"pressure_offset_Pa", pressure_offset},
            {"pressure_gain", pressure_gain},
            {"spring_k_N_per_mm", f32(c.spring_k_N_per_m) * format::kNPerMm},
            {"stroke_origin_valid", c.stroke_origin_valid != 0}};
  if (c.stroke_origin_valid != 0) {
    j["stroke_origin_mm"] = c.stroke_origin_counts * 1e-3;
  } else {
    j["stroke_origin_mm"] = nullptr;
    j["stroke_origin_mm_reason"] = "not homed (palpctl calibrate home)";
  }
  return j;
}

json zeroing_json(const ZeroingRecord& z) {
  // the recording sidecar's form (recording.hpp): offsets are the calibration block's f32 values,
  // the home origin a whole encoder count in mm
  const bool home = z.what == "home";
  json values = json::array();
  for (double v : z.values)
    values.push_back(home ? static_cast<double>(std::llround(v * 1e6)) * 1e-3 : f32(static_cast<float>(v)));
  const char* unit = home ? "mm" : z.what == "current_offset" ? "A" : z.what == "pressure_zero" ? "Pa" : "";
  return {{"what", z.what}, {"t_device_s", z.t_device_s}, {"values", values},
          {"values_unit", unit}, {"committed", z.committed}};
}

Sidecar setup_sidecar(Probe& probe) {
  Sidecar side;
  side.sdk_version = sdk_version();
  side.device = device_json(probe.info());
  side.device["uri"] = probe.uri();
  const Calibration cal = probe.calibration();
  side.calibration = calibration_json(cal);
  if (cal.stroke_origin_valid != 0) {
    side.stroke_origin_z_mm = cal.stroke_origin_counts * 1e-3;
  } else {
    side.stroke_origin_z_mm_reason = "the device's stroke origin is not homed (palpctl calibrate home)";
  }
  for (const auto& z : probe.zeroing()) side.zeroing.push_back(zeroing_json(z));
  const StreamInfo& stream = probe.stream_info();
  side.extra["stream"] = {{"rate_Hz", stream.rate_Hz},
                          {"period_s", stream.period_s},
                          {"channels", stream.channels},
                          {"batch_samples", stream.batch_samples}};
  return side;
}

}  // namespace palp
