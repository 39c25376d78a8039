// SPDX-License-Identifier: Apache-2.0
// Frequency-response tables (issue 7, `palpctl analyze sweep --input table.csv`): a CSV with a
// header row naming one of two layouts, one line per row, '#' comment lines allowed:
//
//   f_Hz,re_m_per_N,im_m_per_N        real and imaginary part of G = Z/F
//   f_Hz,mag_m_per_N,phase_deg        magnitude and phase (degrees)
//
// An optional fourth column `sigma_m_per_N` gives each line's noise (sd of Re and of Im).
// Convention x = Re{X e^{jwt}}: a passive system has Im G <= 0. When most Im values are
// positive the table probably uses the opposite convention: the result carries a warning note
// (the data are used as they are).
//
// Errors: RecordingError(file, line, problem) for an unknown header, a row with the wrong
// number of cells, a cell that is not a finite number, f_Hz <= 0 or not increasing, mag < 0,
// fewer than 3 rows, a line longer than 64 KiB, a file larger than 16 MiB (docs/reliability.md
// §4). Nothing is dropped silently; a message quotes at most 60 bytes of the file, escaped.
#pragma once

#include <filesystem>
#include <string_view>

#include "palp/analysis/frf.hpp"

namespace palp::analysis {

/// Reads a table file (method "table"; notes hold the sign warning when it applies).
Frf read_frf_table(const std::filesystem::path& csv);
/// The same from text; `name` is only for messages.
Frf parse_frf_table(std::string_view text, const std::string& name);
/// Whether the file's first line that is neither blank nor a '#' comment starts with "f_Hz"
/// (a table, not a recording). Reads at most that line (64 KiB); RecordingError when the file
/// cannot be opened.
bool is_frf_table(const std::filesystem::path& file);

}  // namespace palp::analysis
