// SPDX-License-Identifier: Apache-2.0
// A map's report page with columns 2, 5 and 8 soft (palp-report-fixture's known 9 x 9 map, or
// palp-report-sim-map's real 3 x 9 one from palp-sim: CELLS is the grid's size) in headless
// Chromium from file://, one browser for every check: no console errors or exceptions while the
// inlined Vega draws; every figure rendered an <svg>; the heat map marks columns 2, 5 and 8 soft
// (the view's data and the drawn labels) and no row; hovering the cell at row 3, column 5 shows
// its values, clicking it selects it and draws its curve; a full-page screenshot that is not blank.
//
//   node test_report_page.js REPORT.html SHOT.png [CELLS (81)]
'use strict';
const assert = require('assert');
const path = require('path');
const {launch} = require('../../browser/cdp.js');
const {pngStats} = require('../../browser/png.js');

const [html, shot, cellsArg] = process.argv.slice(2);
const cells = cellsArg === undefined ? 81 : Number(cellsArg);
if (!html || !shot || !(cells > 0)) {
  console.error('usage: node test_report_page.js REPORT.html SHOT.png [CELLS]');
  process.exit(2);
}

(async () => {
  const browser = await launch({width: 1280, height: 900});
  try {
    const page = await browser.newPage();
    await page.goto('file://' + path.resolve(html));
    await page.waitFor('window.palpFigures > 0 && window.palpRendered === window.palpFigures', 30000);
    const figures = await page.evaluate(`[...document.querySelectorAll('div.vega')].map(d =>
      ({id: d.dataset.figure, svg: !!d.querySelector('svg'), marks: d.querySelectorAll('svg path, svg text').length}))`);
    assert.ok(figures.length >= 1, 'no figures in the page');
    for (const f of figures) {
      assert.ok(f.svg, `figure ${f.id} drew no <svg>`);
      assert.ok(f.marks > 10, `figure ${f.id} drew ${f.marks} marks`);
    }
    assert.deepStrictEqual(page.errors, [], 'errors while drawing');

    // the soft lines: in the view's data, and drawn as labels over those columns
    const lines = await page.evaluate(`(() => { const v = palpViews['map-stiffness'];
      return ['soft_columns', 'stiff_columns', 'soft_rows', 'stiff_rows']
        .map(n => n + ':' + v.data(n + '_data').map(d => d.index).join(',')); })()`);
    assert.deepStrictEqual(lines, ['soft_columns:2,5,8', 'stiff_columns:', 'soft_rows:', 'stiff_rows:']);
    const labels = await page.evaluate(`[...document.querySelectorAll('#view-map-stiffness svg text')]
      .filter(t => t.textContent === 'soft').length`);
    assert.strictEqual(labels, 3, `${labels} 'soft' labels drawn`);
    // the soft columns are the low end of the colour scale: every soft cell below every other
    const k = await page.evaluate(`palpViews['map-stiffness'].data('cells').map(p => [p.column, p.value])`);
    const soft = k.filter(([c]) => [2, 5, 8].includes(c)).map(([, v]) => v);
    const other = k.filter(([c]) => ![2, 5, 8].includes(c)).map(([, v]) => v);
    assert.strictEqual(soft.length + other.length, cells);
    assert.ok(Math.max(...soft) < Math.min(...other), `soft ${Math.max(...soft)} vs ${Math.min(...other)}`);

    // a click on row 3, column 5 selects it and draws its curve
    const at = await page.evaluate(`(() => {
      document.getElementById('view-map-stiffness').scrollIntoView();
      const v = palpViews['map-stiffness'], x = v.scale('x'), y = v.scale('y'), o = v.origin();
      const r = document.querySelector('#view-map-stiffness svg').getBoundingClientRect();
      return {x: r.left + o[0] + x(5) + x.bandwidth() / 2, y: r.top + o[1] + y(3) + y.bandwidth() / 2}; })()`);
    // hovering shows the point's values (Vega's tooltip: the title of the view's element)
    await page.send('Input.dispatchMouseEvent', {type: 'mouseMoved', x: at.x - 100, y: at.y - 100});
    await page.send('Input.dispatchMouseEvent', {type: 'mouseMoved', x: at.x, y: at.y});
    const tip = await page.waitFor(`(() => { const e = document.querySelector('#view-map-stiffness[title], #view-map-stiffness [title]');
      return e && e.getAttribute('title').includes('row 3, column 5') ? e.getAttribute('title') : ''; })()`, 5000);
    for (const key of ['k_fd (N/mm)', 'δ0 (mm)', 'k_tangent (N/mm)', 'reason'])
      assert.ok(tip.includes(key), `the tooltip has no ${key}: ${tip}`);
    for (const type of ['mousePressed', 'mouseReleased'])
      await page.send('Input.dispatchMouseEvent', {type, x: at.x, y: at.y, button: 'left', clickCount: 1});
    await page.waitFor(`(() => { const s = palpViews['map-stiffness'].signal('selected');
      return s.row === 3 && s.column === 5; })()`, 5000);
    await page.waitFor(`palpViews['map-stiffness'].data('detail').length > 20 &&
      palpViews['map-stiffness'].data('detail').every(d => d.row === 3 && d.column === 5)`, 5000);
    assert.deepStrictEqual(page.errors, [], 'errors after the click');

    const s = pngStats(await page.screenshot(shot, {fullPage: true}));
    assert.ok(s.distinctColours() > 100, `${s.distinctColours()} colours: a blank page?`);
    const ink = s.fraction(([r, g, b]) => r < 200 || g < 200 || b < 200);
    assert.ok(ink > 0.05, `only ${(100 * ink).toFixed(1)} % of the page is drawn`);
    console.log(`ok: ${figures.length} figures, soft columns 2 5 8, click selects row 3 column 5, ` +
                `${s.width}x${s.height} screenshot ${shot}`);
  } finally {
    await browser.close();
  }
})().catch(e => {
  console.error(e.stack || String(e));
  process.exit(1);
});
