// SPDX-License-Identifier: Apache-2.0
// The device's state in lab units as JSON (result.hpp: params_json, health_json, fault_json,
// program_result_json): one definition for the recorder's sidecar and palpctl's --json.
#include <string>

#include "experiment_common.hpp"
#include "palp/result.hpp"

namespace palp {

namespace {


template <class E>
std::string enum_text(E value) {
  const char* n = proto::enum_name(value);
  return n != nullptr ? n : std::to_string(static_cast<unsigned>(value)) + " (unknown)";
}

double mm_of_counts(std::int64_t c) { return static_cast<double>(c) / 1e3; }
double s_of_ms(double ms) { return ms / 1e3; }

}  // namespace

nlohmann::json params_json(const Params& p) {
  return {{"current_clamp_A", experiment::f32(p.current_clamp_A)},
          {"i2t_continuous_A", experiment::f32(p.i2t_continuous_A)},
          {"i2t_limit_A2_s", experiment::f32(p.i2t_limit_A2s)},
          {"i2t_tau_s", experiment::f32(p.i2t_tau_s)},
          {"travel_min_mm", mm_of_counts(p.travel_min_counts)},
          {"travel_max_mm", mm_of_counts(p.travel_max_counts)},
          {"heartbeat_timeout_s", s_of_ms(p.heartbeat_timeout_ms)},
          {"control_rate_Hz", p.control_rate_Hz},
          {"supply_V", experiment::f32(p.supply_V)},
          {"contact_output", enum_text(p.contact_output)},
          {"contact_output_hold_s", s_of_ms(p.contact_output_hold_ms)}};
}

nlohmann::json health_json(const HealthCounters& h) {
  nlohmann::json device = nullptr;
  if (h.device_valid)
    device = {{"time_s", static_cast<double>(h.device_time_us) * 1e-6},
              {"frames_rx", h.device_frames_rx},
              {"frames_tx", h.device_frames_tx},
              {"rx_rejected", h.device_rx_rejected},
              {"isr_queue_overflows", h.isr_queue_overflows},
              {"stream_backlog_max", h.stream_backlog_max},
              {"stream_samples_lost", h.stream_samples_lost},
              {"usb_in_not_drained", h.usb_in_not_drained},
              {"tx_frames_dropped", h.tx_frames_dropped},
              {"control_overruns", h.control_overruns},
              {"stream_gaps", h.device_stream_gaps}};
  nlohmann::json j = {{"device", device},
            {"host",
             {{"frames_rx", h.host_frames_rx},
              {"rx_rejected", h.host_rx_rejected},
              {"samples_received", h.host_samples_received},
              {"samples_missing", h.host_samples_missing},
              {"queue_dropped", h.host_queue_dropped},
              {"queue_max", h.host_queue_max},
              {"gaps", h.host_gaps},
              {"reconnects", h.reconnects},
              {"requests_resent", h.requests_resent}}}};
  if (!h.device_valid) j["device_reason"] = "no Health reply received";
  return j;
}

nlohmann::json fault_json(const FaultInfo& f) {
  return {{"reason", enum_text(f.reason)},
          {"latched", f.reason != proto::FaultReason::none},
          {"t_device_s", f.t_device_s},
          {"detail", f.detail},
          {"text", f.text}};
}

nlohmann::json program_result_json(const ProgramResult& r) {
  return {{"program", enum_text(r.kind)},
          {"end", enum_text(r.end)},
          {"t_device_s", r.t_device_s},
          {"repetitions_done", r.repetitions_done}};
}

}  // namespace palp
