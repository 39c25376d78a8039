// SPDX-License-Identifier: Apache-2.0
// The self-contained HTML page of a report: header, contents, sections with their figures (Vega
// specs embedded as JSON, drawn as SVG in the browser by the inlined Vega modules) and tables.
// Written atomically; an existing file is replaced only when palp wrote it.
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>

#include "experiments/result_dir.hpp"
#include "palp/error.hpp"
#include "palp/probe.hpp"
#include "palp/report.hpp"
#include "recording/internal.hpp"
#include "report/report_internal.hpp"

namespace palp::report {

namespace fs = std::filesystem;

namespace {

std::string esc(const std::string& s) {
  std::string out;
  out.reserve(s.size());
  for (const char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

/// JSON that may stand inside <script type="application/json">: "</" and "<!--" occur only in
/// its strings, where "<\/" and "<\u0021--" read back as the same characters.
std::string embedded_json(const nlohmann::json& j) {
  std::string text = j.dump();
  for (std::size_t at = 0; (at = text.find("</", at)) != std::string::npos; at += 3) text.replace(at, 2, "<\\/");
  for (std::size_t at = 0; (at = text.find("<!--", at)) != std::string::npos; at += 9)
    text.replace(at, 4, "<\\u0021--");
  return text;
}

constexpr const char* kStyle = R"CSS(
:root { --ink: #1d2430; --muted: #5b6472; --rule: #d8dde5; --accent: #2f5d9b; }
body { font: 15px/1.5 "DejaVu Sans", "Helvetica Neue", Arial, sans-serif; color: var(--ink);
       max-width: 1180px; margin: 0 auto; padding: 24px 32px 48px; background: #fff; }
h1 { font-size: 26px; margin: 0 0 12px; }
h2 { font-size: 20px; margin: 36px 0 8px; padding-bottom: 4px; border-bottom: 2px solid var(--rule); }
h3 { font-size: 16px; margin: 20px 0 6px; }
a { color: var(--accent); }
table { border-collapse: collapse; margin: 8px 0 4px; font-size: 13.5px; }
th, td { border-bottom: 1px solid var(--rule); padding: 4px 10px; text-align: left; vertical-align: top; }
th { background: #f3f5f8; font-weight: 600; }
td.num { text-align: right; font-variant-numeric: tabular-nums; }
table.head th { background: none; width: 9em; color: var(--muted); font-weight: 600; }
nav ol { margin: 4px 0; padding-left: 22px; }
figure { margin: 16px 0 24px; break-inside: avoid; page-break-inside: avoid; }
figcaption, .caption { color: var(--muted); font-size: 13.5px; max-width: 860px; margin-top: 4px; }
div.vega { min-height: 40px; overflow-x: auto; }
div.vega.failed { color: #b00020; font-weight: 600; }
p.text { max-width: 860px; }
footer { margin-top: 40px; color: var(--muted); font-size: 12.5px; border-top: 1px solid var(--rule); padding-top: 8px; }
@media print {
  body { max-width: none; padding: 0; font-size: 11pt; }
  nav { page-break-after: always; }
  h2 { page-break-after: avoid; }
  a { color: inherit; text-decoration: none; }
  div.vega { overflow: visible; }
}
)CSS";

// Draws every figure: vega.View with the SVG renderer into its <div>, errors shown in its place
// and on the console. window.palpViews[id] and data-rendered="true" are for tests and users.
constexpr const char* kRender = R"JS(
(function () {
  'use strict';
  window.palpViews = {};
  window.palpRendered = 0;
  var figures = document.querySelectorAll('div.vega[data-figure]');
  window.palpFigures = figures.length;
  function fail(el, id, e) {
    el.textContent = 'This figure could not be drawn: ' + (e && e.message ? e.message : e);
    el.className += ' failed';
    console.error('palp report: figure ' + id + ': ' + (e && e.stack ? e.stack : e));
  }
  figures.forEach(function (el) {
    var id = el.getAttribute('data-figure');
    try {
      var spec = JSON.parse(document.getElementById('spec-' + id).textContent);
      var view = new vega.View(vega.parse(spec), {renderer: 'svg', container: el, hover: true});
      window.palpViews[id] = view;
      view.runAsync().then(function () {
        el.setAttribute('data-rendered', 'true');
        window.palpRendered += 1;
      }, function (e) { fail(el, id, e); });
    } catch (e) {
      fail(el, id, e);
    }
  });
})();
)JS";

std::string table_html(const Table& t) {
  std::string out = "<figure class=\"table\" id=\"table-" + esc(t.id) + "\">\n";
  if (!t.title.empty()) out += "<h3>" + esc(t.title) + "</h3>\n";
  out += "<table><thead><tr>";
  for (const std::string& c : t.columns) out += "<th>" + esc(c) + "</th>";
  out += "</tr></thead>\n<tbody>\n";
  for (const auto& row : t.rows) {
    out += "<tr>";
    for (const std::string& cell : row) {
      const bool numeric = !cell.empty() && (std::isdigit(static_cast<unsigned char>(cell[0])) != 0 ||
                                             cell[0] == '-' || cell[0] == '+' || cell[0] == '.');
      out += (numeric ? "<td class=\"num\">" : "<td>") + esc(cell) + "</td>";
    }
    out += "</tr>\n";
  }
  out += "</tbody></table>\n";
  if (!t.caption.empty()) out += "<figcaption>" + esc(t.caption) + "</figcaption>\n";
  return out + "</figure>\n";
}

std::string figure_html(const Figure& f) {
  std::string out = "<figure id=\"fig-" + esc(f.id) + "\">\n";
  if (!f.title.empty()) out += "<h3>" + esc(f.title) + "</h3>\n";
  out += "<div class=\"vega\" id=\"view-" + esc(f.id) + "\" data-figure=\"" + esc(f.id) + "\"></div>\n";
  out += "<script type=\"application/json\" id=\"spec-" + esc(f.id) + "\">" + embedded_json(f.spec) + "</script>\n";
  if (!f.caption.empty()) out += "<figcaption>" + esc(f.caption) + "</figcaption>\n";
  return out + "</figure>\n";
}

const OwnFileKind& report_kind() {
  static const OwnFileKind kind{kReportHtmlHead, "is not a report palp wrote (not a regular file)",
                                "is not a report palp wrote (it does not begin \"<!DOCTYPE html>\" and "
                                "\"<!-- palp report\")"};
  return kind;
}

}  // namespace

std::string report_html(const Report& report) {
  const std::string modules = detail::vega_modules_js();  // first: a missing module stops it all
  std::string out = std::string(kReportHtmlHead) + ": written by palp SDK " + sdk_version() +
                    " (palpctl report); self-contained, opens offline -->\n";
  out += "<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<meta name=\"generator\" content=\"palp SDK " +
         esc(sdk_version()) + "\">\n<title>" + esc(report.title) + "</title>\n<style>" + kStyle + "</style>\n</head>\n";
  out += "<body>\n<header>\n<h1>" + esc(report.title) + "</h1>\n<table class=\"head\">\n";
  for (const auto& [label, value] : report.header)
    out += "<tr><th>" + esc(label) + "</th><td>" + esc(value) + "</td></tr>\n";
  out += "</table>\n</header>\n<nav>\n<h2>Contents</h2>\n<ol>\n";
  for (const Section& s : report.sections) {
    out += "<li><a href=\"#sec-" + esc(s.id) + "\">" + esc(s.title) + "</a>";
    if (!s.figures.empty() || !s.tables.empty()) {
      out += "<ol>";
      for (const Figure& f : s.figures) out += "<li><a href=\"#fig-" + esc(f.id) + "\">" + esc(f.title) + "</a></li>";
      for (const Table& t : s.tables) out += "<li><a href=\"#table-" + esc(t.id) + "\">" + esc(t.title) + "</a></li>";
      out += "</ol>";
    }
    out += "</li>\n";
  }
  out += "</ol>\n</nav>\n<main>\n";
  for (const Section& s : report.sections) {
    out += "<section id=\"sec-" + esc(s.id) + "\">\n<h2>" + esc(s.title) + "</h2>\n";
    if (!s.text.empty()) out += "<p class=\"text\">" + esc(s.text) + "</p>\n";
    for (const Figure& f : s.figures) out += figure_html(f);
    for (const Table& t : s.tables) out += table_html(t);
    out += "</section>\n";
  }
  out += "</main>\n<footer>Made by palp SDK " + esc(sdk_version()) + " from " + esc(report.input) +
         ". Figures drawn with Vega (Debian's libjs-vega, inlined); the data are embedded in this file.</footer>\n";
  out += modules;
  out += "<script>" + std::string(kRender) + "</script>\n</body>\n</html>\n";
  return out;
}

void write_report_html(const fs::path& file, const Report& report, Overwrite overwrite) {
  write_own_file(file, overwrite, report_kind(), [&] { return report_html(report); });
}

}  // namespace palp::report
