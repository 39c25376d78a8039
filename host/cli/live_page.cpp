// SPDX-License-Identifier: Apache-2.0
#include "live_page.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <string_view>

#include "format/text_input.hpp"
#include "palp/error.hpp"

namespace palpctl {

namespace {
constexpr std::size_t kMaxDygraphsFileBytes = 4u << 20;

// Text for inlining into <script> or <style>: no "</script" or "</style" that would end the element
// early (where one could stand, in a string, "<\/" is the same text; checked case-blind, as HTML
// does), and no source-map comment pointing at a file the page cannot fetch.
std::string inlinable(std::string text) {
  const auto lower = [](char c) {
    return static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  };
  for (const std::string_view end : {std::string_view("</script"), std::string_view("</style")})
    for (std::size_t at = 0; at + end.size() <= text.size(); ++at)
      if (std::equal(end.begin(), end.end(), text.begin() + static_cast<std::ptrdiff_t>(at),
                     [&](char a, char b) { return a == lower(b); }))
        text.replace(at, 2, "<\\/");
  for (const char* marker : {"//# sourceMappingURL=", "/*# sourceMappingURL="}) {
    const auto at = text.find(marker);
    if (at != std::string::npos) text.erase(at, text.find('\n', at) - at);
  }
  return text;
}

// The page's own style and script; %CSS% and %JS% stand for dygraphs.
constexpr std::string_view kPage = R"PAGE(<!doctype html>
<html lang="en"><head><meta charset="utf-8">
<title>palp live view</title>
<link rel="icon" href="data:,">
<style>%CSS%</style>
<style>
  html, body { margin: 0; background: #101418; color: #d8dee6;
               font: 14px/1.3 "DejaVu Sans", "Liberation Sans", Arial, sans-serif; }
  header { display: flex; align-items: center; gap: 18px; padding: 8px 16px;
           background: #1b2129; border-bottom: 1px solid #2c3540; }
  header h1 { font-size: 16px; margin: 0; font-weight: 600; color: #fff; }
  #status { flex: 1; font-family: "DejaVu Sans Mono", monospace; font-size: 13px; }
  #status .bad { color: #ff5c5c; font-weight: 700; }
  #status .ok { color: #7ee787; }
  button, select { background: #2a3340; color: #e6edf3; border: 1px solid #485566;
                   border-radius: 4px; padding: 4px 12px; font: inherit; cursor: pointer; }
  button.paused { background: #8a6d1a; border-color: #d6a520; }
  main { padding: 4px 12px 0 4px; }
  .panel { position: relative; margin-top: 6px; }
  .panel .legend { position: absolute; top: 2px; left: 84px; z-index: 20;
                   font-family: "DejaVu Sans Mono", monospace; font-size: 12px; color: #c9d1d9; }
  .panel .legend span { margin-right: 12px; }
  .panel .readout { position: absolute; top: 2px; right: 12px; z-index: 20; text-align: right;
                    font-family: "DejaVu Sans Mono", monospace; font-size: 12px; }
  .panel .readout span { margin-left: 14px; }
  .plot { width: 100%; height: calc((100vh - 130px) / 3); min-height: 170px; }
  .waiting { color: #7d8590; padding: 100px 0 0 120px; }
  #markers { font-family: "DejaVu Sans Mono", monospace; font-size: 12px; color: #9aa5b1;
             padding: 2px 16px; height: 32px; overflow: auto; }
  .dygraph-axis-label { color: #aeb8c4; font-size: 12px; }
  .dygraph-label, .dygraph-ylabel, .dygraph-xlabel { color: #d8dee6; font-size: 13px; }
  .dygraph-legend { background: transparent; width: auto; }
</style></head>
<body>
<header>
  <h1>palp live view</h1>
  <div id="status">connecting&hellip;</div>
  <label>window <select id="window">
    <option value="1">last 1 s</option><option value="2">last 2 s</option>
    <option value="5">last 5 s</option><option value="10" selected>last 10 s</option>
    <option value="30">last 30 s</option><option value="60">last 60 s</option>
  </select></label>
  <button id="pause" type="button">Pause</button>
</header>
<main>
  <div class="panel">
    <div class="legend" id="legend-current"></div><div class="readout" id="readout-current"></div>
    <div class="plot" id="plot-current"><div class="waiting">waiting for samples&hellip;</div></div>
  </div>
  <div class="panel">
    <div class="legend" id="legend-z"></div><div class="readout" id="readout-z"></div>
    <div class="plot" id="plot-z"></div></div>
  <div class="panel">
    <div class="legend" id="legend-p"></div><div class="readout" id="readout-p"></div>
    <div class="plot" id="plot-p"></div></div>
</main>
<div id="markers"></div>
<script>%JS%</script>
<script>
'use strict';
const KEEP_S = 120;  // data older than this behind the newest sample is forgotten
const L = window.palpLive = {sampleMessages: 0, points: 0, redraws: 0, paused: false,
                             windowS: 10, markers: [], markersDrawn: 0, status: null,
                             connected: false, viewHz: 0};
const PANELS = [
  {id: 'current', ylabel: 'current (A)', names: ['i_cmd (A)', 'i (A)'], digits: 4,
   colors: ['#f2cc60', '#56d4f5'], pick: (m, k) => [m.i_cmd_A[k], m.i_A[k]]},
  {id: 'z', ylabel: 'position z (mm)', names: ['z (mm)'], digits: 4,
   colors: ['#7ee787'], pick: (m, k) => [m.z_mm[k]]},
  {id: 'p', ylabel: 'pressure (Pa)',
   names: ['p1', 'p2', 'p3', 'p4', 'p5', 'p6'].map(n => n + ' (Pa)'),
   digits: 1,
   colors: ['#ff7b72', '#ffa657', '#f2cc60', '#7ee787', '#79c0ff', '#d2a8ff'],
   pick: (m, k) => m.p_Pa.map(col => col[k])},
];
for (const P of PANELS) P.rows = [];
L.panels = PANELS;  // each panel's rows: [t_s, values...] as plotted
const MARK_COLOURS = {gap: '#ffa657', fault: '#ff4d4d', state: '#8b949e'};

function drawMarkers(ctx, area, g, labels) {
  const [x0, x1] = g.xAxisRange();
  let drawn = 0;
  for (const m of L.markers) {
    if (m.t_s < x0 || m.t_s > x1) continue;
    const x = g.toDomXCoord(m.t_s);
    ctx.save();
    ctx.strokeStyle = MARK_COLOURS[m.kind];
    ctx.lineWidth = m.kind === 'fault' ? 2.5 : 1.5;
    ctx.setLineDash(m.kind === 'gap' ? [6, 4] : m.kind === 'state' ? [2, 3] : []);
    ctx.beginPath(); ctx.moveTo(x, area.y); ctx.lineTo(x, area.y + area.h); ctx.stroke();
    if (labels) {  // gap labels at the bottom, fault and state labels at the top: both readable
      ctx.font = '12px "DejaVu Sans", sans-serif';
      const y = m.kind === 'gap' ? area.y + area.h - 8 : area.y + 30;
      const w = ctx.measureText(m.label).width;
      ctx.fillStyle = 'rgba(16, 20, 24, 0.85)';
      ctx.fillRect(x + 3, y - 12, w + 4, 16);
      ctx.fillStyle = MARK_COLOURS[m.kind];
      ctx.fillText(m.label, x + 5, y);
    }
    ctx.restore();
    ++drawn;
  }
  if (labels) L.markersDrawn = drawn;
}

function makeGraph(P, first) {
  const el = document.getElementById('plot-' + P.id);
  el.textContent = '';
  P.graph = new Dygraph(el, P.rows, {
    labels: ['t (s)'].concat(P.names), colors: P.colors, ylabel: P.ylabel,
    xlabel: P.id === 'p' ? 'device time (s)' : undefined, xLabelHeight: 16, yLabelWidth: 18,
    legend: 'always', labelsDiv: 'legend-' + P.id, labelsSeparateLines: false,
    strokeWidth: 1.4, yRangePad: 8, gridLineColor: '#2c3540', axisLineColor: '#6e7681',
    axisLabelFontSize: 12, drawAxesAtZero: false, connectSeparatedPoints: false,
    digitsAfterDecimal: P.digits,
    axes: {x: {axisLabelFormatter: v => v.toFixed(1),
               valueFormatter: v => 't ' + v.toFixed(3) + ' s'},
           y: {axisLabelWidth: 62}},
    interactionModel: {},  // no zoom by drag: the window selector sets the range
    underlayCallback: (ctx, area, g) => drawMarkers(ctx, area, g, first),
  });
}

// The newest values as a scope's measurement readout: the mean over the last 0.1 s of points.
function showReadout(P) {
  const recent = [];
  const tEnd = P.rows[P.rows.length - 1][0];
  for (let k = P.rows.length - 1; k >= 0 && P.rows[k][0] > tEnd - 0.1; --k) recent.push(P.rows[k]);
  const html = P.names.map((name, c) => {
    const v = recent.map(r => r[c + 1]).filter(x => x !== null);
    const mean = v.length ? (v.reduce((a, b) => a + b, 0) / v.length).toFixed(P.digits) : '\u2013';
    const shown = /^-0\.?0*$/.test(mean) ? mean.slice(1) : mean;  // no "-0.0"
    const [label, unit] = name.split(' ');
    return `<span style="color:${P.colors[c]}">${label} ${shown} ${unit.slice(1, -1)}</span>`;
  });
  document.getElementById('readout-' + P.id).innerHTML = html.join('');
}

window.addEventListener('resize', () => PANELS.forEach(P => P.graph && P.graph.resize()));

let scheduled = false;
function redraw() {
  scheduled = false;
  if (L.paused || PANELS[0].rows.length === 0) return;
  const rows = PANELS[0].rows;
  // a scope's sweep: the trace fills the window from the left, then scrolls
  const tMax = Math.max(rows[rows.length - 1][0], rows[0][0] + L.windowS);
  const t0 = tMax - L.windowS;
  PANELS.forEach((P, n) => {
    let lo = 0, hi = P.rows.length;  // first row with t >= t0
    while (lo < hi) {
      const mid = (lo + hi) >> 1;
      if (P.rows[mid][0] < t0) lo = mid + 1; else hi = mid;
    }
    const file = P.rows.slice(Math.max(0, lo - 1));
    if (!P.graph) makeGraph(P, n === 0);
    P.graph.updateOptions({file, dateWindow: [t0, tMax]});
    showReadout(P);
  });
  ++L.redraws;
}
function schedule() {
  // a timer, not requestAnimationFrame: a tab in the background (or a headless one) still
  // follows the stream, and the pushes (30 a second) already pace the redraws
  if (!scheduled && !L.paused) { scheduled = true; setTimeout(redraw, 0); }
}

function forgetOld() {
  for (const P of PANELS) {
    const n = P.rows.length;
    if (n === 0) continue;
    const t0 = P.rows[n - 1][0] - KEEP_S;
    let k = 0;
    while (k < n && P.rows[k][0] < t0) ++k;
    if (k > 1000) P.rows.splice(0, k);
  }
  const n = PANELS[0].rows.length;
  if (n > 0) {
    const t0 = PANELS[0].rows[n - 1][0] - KEEP_S;
    L.markers = L.markers.filter(m => m.t_s >= t0);
  }
}

const pushTimes = [];
function onSamples(m) {
  ++L.sampleMessages;
  const last = PANELS[0].rows.length ? PANELS[0].rows[PANELS[0].rows.length - 1][0] : -Infinity;
  if (m.t_s.length > 0 && m.t_s[0] < last) {  // the device's clock restarted: start afresh
    for (const P of PANELS) P.rows.length = 0;
    L.markers = [];
  }
  const now = performance.now();
  pushTimes.push(now);
  while (pushTimes.length > 0 && pushTimes[0] < now - 1000) pushTimes.shift();
  L.viewHz = pushTimes.length;
  for (let k = 0; k < m.t_s.length; ++k)
    for (const P of PANELS) P.rows.push([m.t_s[k]].concat(P.pick(m, k)));
  L.points += m.t_s.length;
  if (m.t_s.length > 0) { forgetOld(); schedule(); }
}

function addMarker(kind, t_s, label) {
  L.markers.push({kind, t_s, label});
  const line = document.createElement('div');
  line.textContent = `${t_s.toFixed(3)} s  ${kind}: ${label}`;
  line.style.color = MARK_COLOURS[kind];
  const box = document.getElementById('markers');
  box.prepend(line);
  while (box.childElementCount > 50) box.lastElementChild.remove();
  schedule();
}

function showStatus() {
  const s = L.status;
  if (!s) return;
  const fault = s.fault === 'none' ? `<span class="ok">none</span>`
                                    : `<span class="bad">${s.fault}</span>`;
  const lost = s.samples_lost > 0 ? `<span class="bad">${s.samples_lost}</span>` : '0';
  document.getElementById('status').innerHTML =
    `state <b>${s.state}</b> &middot; fault ${fault}` +
    ` &middot; ${s.samples_per_s.toFixed(0)} samples/s` +
    ` &middot; lost ${lost} in ${s.gaps} gaps &middot; t ${s.t_device_s.toFixed(1)} s` +
    ` &middot; view ${L.viewHz} Hz` +
    (L.connected ? '' : ' &middot; <span class="bad">disconnected</span>') +
    (L.paused ? ' &middot; <span class="bad">paused</span>' : '');
}

const es = new EventSource('/events');
es.onopen = () => { L.connected = true; showStatus(); };
es.onerror = () => { L.connected = false; showStatus(); };
es.addEventListener('samples', e => onSamples(JSON.parse(e.data)));
es.addEventListener('gap', e => {
  const g = JSON.parse(e.data);
  addMarker('gap', g.t_device_s, `${g.count} samples lost (${g.source})`);
});
es.addEventListener('state', e => {
  const s = JSON.parse(e.data);
  if (s.fault !== 'none' && s.fault !== s.previous_fault) addMarker('fault', s.t_device_s, s.fault);
  else addMarker('state', s.t_device_s, `${s.previous_state} \u2192 ${s.state}`);
});
es.addEventListener('status', e => { L.status = JSON.parse(e.data); showStatus(); });

document.getElementById('pause').addEventListener('click', ev => {
  L.paused = !L.paused;
  ev.target.textContent = L.paused ? 'Resume' : 'Pause';
  ev.target.classList.toggle('paused', L.paused);
  showStatus();
  schedule();
});
document.getElementById('window').addEventListener('change', ev => {
  L.windowS = Number(ev.target.value);
  schedule();
});
</script>
</body></html>
)PAGE";

}  // namespace

std::string dygraphs_dir() {
  const char* env = std::getenv("PALP_DYGRAPHS_DIR");
  return env != nullptr && *env != '\0' ? env : "/usr/share/javascript/dygraphs";
}

DygraphsFiles load_dygraphs() {
  const std::string dir = dygraphs_dir();
  const auto read = [&](const char* name) {
    const std::string path = dir + "/" + name;
    const auto fail = [&](const std::string& problem) {
      throw palp::Error("live view: " + path + ": " + problem +
                        " (the page's plots need Debian's libjs-dygraphs: apt-get install "
                        "libjs-dygraphs, or scripts/install-deps)");
    };
    return palp::format::read_bounded_or(path, kMaxDygraphsFileBytes, fail);
  };
  return {read("dygraph.min.js"), read("dygraph.min.css")};
}

std::string live_page_html(const DygraphsFiles& dygraphs) {
  // both places found in the template before either is filled: the library's own text is never
  // searched for the keys (%JS% comes after %CSS%, so it is filled first)
  std::string page(kPage);
  const auto css_at = page.find("%CSS%");
  const auto js_at = page.find("%JS%");
  page.replace(js_at, 4, inlinable(dygraphs.js));
  page.replace(css_at, 5, inlinable(dygraphs.css));
  return page;
}

}  // namespace palpctl
