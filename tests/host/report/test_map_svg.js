// SPDX-License-Identifier: Apache-2.0
// The known map's SVG files (palp-report-fixture's map-svg/): every figure is a standalone SVG
// with marks in it; the map's figure has the heat map's 81 cells, the colour bar's title with its
// unit, the detail plot's axis titles with units, and the 'soft' labels of columns 2, 5 and 8.
//
//   node test_map_svg.js SVG_DIR
'use strict';
const assert = require('assert');
const fs = require('fs');
const path = require('path');

const dir = process.argv[2];
if (!dir) {
  console.error('usage: node test_map_svg.js SVG_DIR');
  process.exit(2);
}
const files = fs.readdirSync(dir).filter(f => f.endsWith('.svg'));
assert.ok(files.includes('map-stiffness.svg'), `no map-stiffness.svg in ${dir}: ${files.join(', ')}`);
for (const f of files) {
  const svg = fs.readFileSync(path.join(dir, f), 'utf8');
  assert.ok(svg.startsWith('<svg'), `${f} is not an SVG`);
  assert.ok((svg.match(/<path /g) || []).length > 10, `${f} has almost no marks`);
}
const svg = fs.readFileSync(path.join(dir, 'map-stiffness.svg'), 'utf8');
const texts = [...svg.matchAll(/<text[^>]*>([^<]*)<\/text>/g)].map(m => m[1]);
for (const title of ['k_fd (N/mm)', 'δ (mm)', 'F_o (N)', 'column', 'row'])
  assert.ok(texts.includes(title), `no axis or legend title "${title}"`);
assert.strictEqual(texts.filter(t => t === 'soft').length, 3, 'not three soft labels');
// the cells' value labels: 81 numbers with two decimals
assert.strictEqual(texts.filter(t => /^\d+\.\d\d$/.test(t)).length >= 81, true, 'not 81 cell values');
console.log(`ok: ${files.length} SVG files, map-stiffness.svg with its units and 3 soft columns`);
