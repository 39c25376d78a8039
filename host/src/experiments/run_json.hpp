// SPDX-License-Identifier: Apache-2.0
// result.json's "run" block (docs/result-format.md): how a run went, one field table per
// experiment that the writer and the reader share (format/field_table.hpp).
//
//   indentation:    end, t_device_s, repetitions_done, samples, samples_missing, interrupted,
//                   float_z_mm
//   identification: end, t_device_s, samples, samples_missing, interrupted, control_rate_Hz
//
// end ("interrupted" when stopped by the host's cancel, else the program's end) and samples (the
// recording's) are written only: a reader derives them again.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "palp/identification.hpp"
#include "palp/indent.hpp"

namespace palp {

nlohmann::json indentation_run_json(const IndentationRun& run);
/// The block's t_device_s, repetitions_done, samples_missing, interrupted and float_z_mm into
/// `run`; ConfigError naming the key ("missing key \"run.float_z_mm\"").
void read_indentation_run(const nlohmann::json& run_block, IndentationRun& run);

nlohmann::json identification_run_json(const IdentificationRun& run);
/// The block's t_device_s, samples_missing, interrupted and control_rate_Hz into `run`;
/// ConfigError naming the key as read_indentation_run does.
void read_identification_run(const nlohmann::json& run_block, IdentificationRun& run);

}  // namespace palp
