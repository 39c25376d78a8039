// SPDX-License-Identifier: Apache-2.0
// Proves the driver (cdp.js) sees what the page tests rely on: console.error calls and uncaught
// exceptions are collected, a click reaches the page, waitFor times out with the expression, and
// a screenshot is a PNG of what is drawn (a red square: red pixels present, not a blank page).
'use strict';
const assert = require('assert');
const fs = require('fs');
const os = require('os');
const path = require('path');
const {launch} = require('./cdp.js');
const {pngStats} = require('./png.js');

(async () => {
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'palp-driver-'));
  const html = path.join(dir, 'page.html');
  fs.writeFileSync(html, `<!doctype html><html><body style="margin:0;background:#fff">
    <div style="width:200px;height:200px;background:#f00"></div>
    <button id="b" onclick="window.clicked = (window.clicked || 0) + 1">press</button>
    <script>console.error('deliberate error'); setTimeout(() => { throw new Error('deliberate throw'); }, 0);</script>
    </body></html>`);
  const browser = await launch({width: 400, height: 300});
  try {
    const page = await browser.newPage();
    await page.goto('file://' + html);
    await page.waitFor('document.readyState === "complete"');
    await new Promise(r => setTimeout(r, 100));
    assert.ok(page.errors.some(e => e === 'console.error: deliberate error'), page.errors.join('\n'));
    assert.ok(page.errors.some(e => e.startsWith('exception: Error: deliberate throw')),
              page.errors.join('\n'));
    await page.click('#b');
    await page.click('#b');
    assert.strictEqual(await page.evaluate('window.clicked'), 2);
    await assert.rejects(page.waitFor('window.never', 200), /not true within 200 ms: window.never/);
    const png = await page.screenshot(path.join(dir, 'shot.png'));
    const s = pngStats(png);
    assert.strictEqual(s.width, 400);
    assert.strictEqual(s.height, 300);
    // 200 x 200 of 400 x 300 is red: a third of the pixels
    assert.ok(s.fraction(([r, g, b]) => r > 200 && g < 60 && b < 60) > 0.3, 'no red square');
  } finally {
    await browser.close();
    fs.rmSync(dir, {recursive: true, force: true});
  }
  console.log('driver self-test passed');
})().catch(e => { console.error(e.stack || e.message); process.exit(1); });
