// SPDX-License-Identifier: Apache-2.0
// An adaptive map's report page (palp-report-sim-map --adaptive: rows 1..3 of the pad, 14 of the
// 27 points measured on palp-sim) in headless Chromium from file://: no errors while Vega draws;
// a dot on every measured cell and on no other; every other cell interpolated (pale, its value in
// parentheses, between the smallest and largest measured value); the soft columns 2, 5 and 8
// marked; a full-page screenshot that is not blank.
//
//   node test_adaptive_map_page.js REPORT.html SHOT.png MEASURED CELLS
'use strict';
const assert = require('assert');
const path = require('path');
const {launch} = require('../../browser/cdp.js');
const {pngStats} = require('../../browser/png.js');

const [html, shot, measuredArg, cellsArg] = process.argv.slice(2);
const measured = Number(measuredArg), cells = Number(cellsArg);
if (!html || !shot || !(measured > 0) || !(cells > measured)) {
  console.error('usage: node test_adaptive_map_page.js REPORT.html SHOT.png MEASURED CELLS');
  process.exit(2);
}

(async () => {
  const browser = await launch({width: 1280, height: 900});
  try {
    const page = await browser.newPage();
    await page.goto('file://' + path.resolve(html));
    await page.waitFor('window.palpFigures > 0 && window.palpRendered === window.palpFigures',
                       30000);
    assert.deepStrictEqual(page.errors, [], 'errors while drawing');
    const view = `palpViews['map-stiffness']`;
    const all = await page.evaluate(
        `${view}.data('cells').map(d => [d.row, d.column, d.value, d.measured])`);
    assert.strictEqual(all.length, cells, `${all.length} cells`);
    const meas = all.filter(c => c[3] === true), interp = all.filter(c => c[3] === false);
    assert.strictEqual(meas.length, measured, `${meas.length} measured cells`);
    assert.strictEqual(interp.length, cells - measured, `${interp.length} interpolated cells`);
    // the dots: one per measured cell, drawn at those cells
    const dots = await page.evaluate(
        `${view}.data('measured_cells').map(d => d.row + ',' + d.column).sort()`);
    assert.deepStrictEqual(dots, meas.map(c => c[0] + ',' + c[1]).sort());
    const drawn = await page.evaluate(`document.querySelectorAll(
      '#view-map-stiffness svg .mark-symbol.role-mark path').length`);
    assert.strictEqual(drawn, measured, `${drawn} dots drawn`);
    // interpolated values lie within the measured ones, and their labels are in parentheses
    const values = meas.map(c => c[2]).filter(v => v !== null);
    const lo = Math.min(...values), hi = Math.max(...values);
    for (const [r, c, v] of interp)
      assert.ok(v === null || (v >= lo - 1e-9 && v <= hi + 1e-9),
                `row ${r} column ${c}: ${v} outside ${lo}..${hi}`);
    const labels = await page.evaluate(
        `[...document.querySelectorAll('#view-map-stiffness svg text')]
          .map(t => t.textContent).filter(t => /^\\(\\d/.test(t)).length`);
    assert.strictEqual(labels, interp.filter(c => c[2] !== null).length,
                       `${labels} labels in parentheses`);
    const soft = await page.evaluate(
        `${view}.data('soft_columns_data').map(d => d.index).join(',')`);
    assert.strictEqual(soft, '2,5,8');
    const s = pngStats(await page.screenshot(shot, {fullPage: true}));
    assert.ok(s.distinctColours() > 100, `${s.distinctColours()} colours: a blank page?`);
    console.log(`ok: ${measured} measured cells dotted, ${interp.length} interpolated, ` +
                `soft columns ${soft}, ` +
                `${s.width}x${s.height} screenshot ${shot}`);
  } finally {
    await browser.close();
  }
})().catch(e => {
  console.error(e.stack || String(e));
  process.exit(1);
});
