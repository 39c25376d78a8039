// SPDX-License-Identifier: Apache-2.0
// The report's sections, one builder per kind of result (palp/report.hpp's types). Internal to
// palp_report: the public entry points (make_report, the HTML and SVG writers) choose the builders
// by what the input is.
#pragma once

#include <filesystem>

#include "palp/map.hpp"
#include "palp/report.hpp"
#include "palp/result.hpp"
#include "palp/trace.hpp"

namespace palp::report {

/// An indentation result (experiment "indentation"): F_o–δ of every repetition, the mean ± s.d.
/// band, the linear/Hertz/Sneddon fits with their contact points, δ0 and the tangent at the bias;
/// the parameter table with s.e. and s.d.
Section indentation_section(const LoadedResult& result);

/// The pressure channels of an indentation result against F_o, each with its regression line and
/// R², and the Boyle ΔV. A section without figures (and a text saying why) when the recording has
/// no pressure channels.
Section pressure_section(const LoadedResult& result);

/// An identification result (experiment "identification"; its frf.csv beside result.json): Bode
/// magnitude and phase with the measured points and their σ, the fitted second-order model, ω_n
/// and ζ with s.e.; free-air m_v and b_v; E′(ω), E″(ω) and tan δ when the result has them.
Section identification_section(const LoadedResult& result);

/// A traced surface (trace.json): the contact heights on the grid and the normals' tilts, as maps.
Section trace_section(const TracedSurface& surface);

/// A stiffness map (map.json and its points/): the k_fd heat map with a colour bar, the soft and
/// stiff rows and columns marked, each point's values on hover and its indentation on selection;
/// the surface the map was measured on.
Section map_section(const StiffnessMap& map, const MapAnalysis& analysis,
                    const std::filesystem::path& dir);

/// A dynamic map's grids (map_dynamic.hpp): a heat map per quantity (ω_n, ζ, m_eff, b_o, E′, E″)
/// with each point's standard error on hover and a link to its identification; column means.
Section map_dynamic_section(const StiffnessMap& map);

}  // namespace palp::report
