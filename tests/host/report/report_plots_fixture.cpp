// SPDX-License-Identifier: Apache-2.0
// palp-report-plots-fixture DIR [--paper-like]: writes the known synthetic results
// (report_plots_synth.hpp) under DIR, builds their report sections and writes each figure's Vega
// spec as DIR/<id>.json, for vega-to-svg.js and check_svg.js (the report_plots.svg.* tests).
// --paper-like: the noisier examples instead, for people to look at (render them with
// vega-to-svg.js); no test checks them.
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>

#include "report/sections.hpp"
#include "report_plots_synth.hpp"

namespace {

void write_specs(const std::filesystem::path& dir, const palp::report::Section& s) {
  for (const auto& f : s.figures) std::ofstream(dir / (f.id + ".json")) << f.spec.dump(1) << '\n';
}

}  // namespace

int main(int argc, char** argv) {
  const bool paper_like = argc == 3 && std::string(argv[2]) == "--paper-like";
  if (argc != 2 && !paper_like) {
    std::fprintf(stderr, "usage: palp-report-plots-fixture DIR [--paper-like]\n");
    return 2;
  }
  try {
    namespace rt = palp_test::report;
    const std::filesystem::path dir = argv[1];
    std::filesystem::create_directories(dir);
    const auto indentation = palp::load_result(paper_like ? rt::write_paper_like_indentation(dir / "indentation")
                                                          : rt::write_known_indentation(dir / "indentation"));
    write_specs(dir, palp::report::indentation_section(indentation));
    write_specs(dir, palp::report::pressure_section(indentation));
    const auto id = paper_like ? rt::write_paper_like_identification(dir / "identification")
                               : rt::write_known_identification(dir / "identification");
    write_specs(dir, palp::report::identification_section(palp::load_result(id)));
    write_specs(dir, palp::report::trace_section(rt::known_trace()));
    // the heat-map helper as the map's report uses it: soft columns 2, 5, 8 outlined
    std::ofstream(dir / "heat-map-outlines.json") << rt::known_outlined_heat_map().dump(1) << '\n';
  } catch (const std::exception& e) {
    std::fprintf(stderr, "palp-report-plots-fixture: %s\n", e.what());
    return 1;
  }
  return 0;
}
