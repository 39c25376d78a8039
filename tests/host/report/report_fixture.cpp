// SPDX-License-Identifier: Apache-2.0
// palp-report-fixture OUT_DIR: writes the report tests' known map (report_fixture.hpp) as
// OUT_DIR/map, its report as OUT_DIR/map-report.html and its figures as OUT_DIR/map-svg/*.svg,
// for the page test (test_report_page.js) and the SVG checks. OUT_DIR is replaced.
#include <filesystem>
#include <iostream>

#include "palp/report.hpp"
#include "report_fixture.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: palp-report-fixture OUT_DIR\n";
    return 2;
  }
  namespace fs = std::filesystem;
  const fs::path out = argv[1];
  try {
    fs::remove_all(out);
    fs::create_directories(out);
    palp::test::write_report_map(out / "map");
    const palp::report::Report r = palp::report::make_report(out / "map");
    palp::report::write_report_html(out / "map-report.html", r);
    for (const fs::path& f : palp::report::write_report_svgs(out / "map-svg", r)) std::cout << f.string() << "\n";
    std::cout << (out / "map-report.html").string() << "\n";
  } catch (const std::exception& e) {
    std::cerr << "palp-report-fixture: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
