// SPDX-License-Identifier: Apache-2.0
// The live view in headless Chromium against a real palp-sim and palpctl monitor --plot: the
// page loads without errors, receives samples with the idle device's values, refreshes at
// >= 20 Hz, Pause freezes the plots (the data keeps coming) and Resume redraws them, a gap
// marker appears when palp-sim drops frames, a fault marker and the fault in the status line when
// palp-sim's H-bridge driver asserts its fault, and the screenshot shows plots (not a blank page).
// Run: node test_live_view_page.js PALPCTL PALP_SIM (PALP_SCREENSHOT_DIR keeps the screenshot).
'use strict';
const assert = require('assert');
const fs = require('fs');
const os = require('os');
const path = require('path');
const {launch} = require('../../browser/cdp.js');
const {pngStats} = require('../../browser/png.js');
const {startSim, control, startMonitor, stop} = require('./processes.js');

const sleep = ms => new Promise(r => setTimeout(r, ms));

(async () => {
  const sim = await startSim();
  let monitor, browser;
  try {
    monitor = await startMonitor(sim, ['--seconds', '60']);
    browser = await launch({width: 1280, height: 900});
    const page = await browser.newPage();
    await page.goto(monitor.url);

    // samples arrive, with the values of an idle probe at rest: no current, z at the origin
    await page.waitFor('palpLive.points > 100 && palpLive.status !== null');
    const first = await page.evaluate(`(() => {
      const s = palpLive.status;
      return {state: s.state, fault: s.fault, rate_Hz: s.rate_Hz};
    })()`);
    assert.deepStrictEqual(first, {state: 'idle', fault: 'none', rate_Hz: 1000});
    const values = await page.evaluate(`(() => {
      const cur = palpLive.panels[0].rows.slice(-50), z = palpLive.panels[1].rows.slice(-50);
      return {i_cmd: Math.max(...cur.map(r => Math.abs(r[1]))),
              i: Math.max(...cur.map(r => Math.abs(r[2]))),
              z: Math.max(...z.map(r => Math.abs(r[1])))};
    })()`);
    assert.strictEqual(values.i_cmd, 0, 'i_cmd of an idle probe');
    assert.ok(values.i < 0.02, `|i| ${values.i} A at idle`);
    assert.ok(values.z < 0.01, `|z| ${values.z} mm at rest`);

    // refresh: samples events counted in the page over 2 s (palpctl pushes 30 a second)
    const perS = await page.evaluate(`new Promise(done => {
      const n0 = palpLive.sampleMessages, t0 = performance.now();
      setTimeout(() => done((palpLive.sampleMessages - n0) * 1000 / (performance.now() - t0)),
                 2000);
    })`);
    assert.ok(perS >= 20, `${perS.toFixed(1)} samples events/s in the page, want >= 20`);
    console.log(`the page received ${perS.toFixed(1)} samples events/s`);

    // Pause: the plots stop redrawing while the data keeps arriving; Resume redraws
    await page.click('#pause');
    assert.strictEqual(await page.evaluate('document.getElementById("pause").textContent'),
                       'Resume');
    await sleep(100);  // a frame already requested may still draw
    const paused = await page.evaluate('[palpLive.redraws, palpLive.sampleMessages]');
    await sleep(600);
    const later = await page.evaluate('[palpLive.redraws, palpLive.sampleMessages]');
    assert.strictEqual(later[0], paused[0], 'a paused view redrew');
    assert.ok(later[1] > paused[1] + 5, 'the data stopped while paused');
    await page.click('#pause');
    await page.waitFor(`palpLive.redraws > ${later[0]} + 5`, 5000);

    // a gap marker when palp-sim drops frames
    assert.match(await control(sim, 'drop-frames 40'), /^ok/);
    await page.waitFor('palpLive.markers.some(m => m.kind === "gap")', 5000);
    assert.match(await control(sim, 'drop-frames 0'), /^ok/);
    await page.waitFor('palpLive.status.samples_lost > 0 && palpLive.markersDrawn > 0', 5000);
    assert.match(await page.evaluate('document.getElementById("markers").textContent'),
                 /gap: \d+ samples lost \(transport\)/);

    // a fault marker and the fault in the status line when the H-bridge driver faults
    assert.match(await control(sim, 'fault driver'), /^ok/);
    await page.waitFor('palpLive.markers.some(m => m.kind === "fault")', 5000);
    const fault = await page.evaluate('palpLive.status.fault');
    assert.notStrictEqual(fault, 'none');
    assert.match(await page.evaluate('document.getElementById("status").textContent'),
                 new RegExp(`fault ${fault}`));
    await page.evaluate('document.getElementById("window").value = "5";' +
                        'document.getElementById("window").dispatchEvent(new Event("change"))');
    await sleep(400);

    const dir = process.env.PALP_SCREENSHOT_DIR || fs.mkdtempSync(path.join(os.tmpdir(), 'lv-'));
    const png = await page.screenshot(path.join(dir, 'live-view.png'));
    const s = pngStats(png);
    assert.strictEqual(s.width, 1280);
    assert.ok(s.distinctColours() > 20, `${s.distinctColours()} colours: a blank page`);
    // trace colours of the legend's palette are on the page (drawn lines, not only the frame)
    const near = ([r, g, b], [R, G, B]) => Math.abs(r - R) + Math.abs(g - G) + Math.abs(b - B) < 40;
    assert.ok(s.fraction(p => near(p, [0x56, 0xd4, 0xf5])) > 0.0005, 'no i trace (cyan)');
    assert.ok(s.fraction(p => near(p, [0xff, 0x4d, 0x4d])) > 0.0002, 'no fault marker (red)');
    if (!process.env.PALP_SCREENSHOT_DIR) fs.rmSync(dir, {recursive: true, force: true});

    assert.deepStrictEqual(page.errors, []);
    assert.strictEqual(await stop(monitor.proc), 0, 'palpctl after Ctrl-C');
  } finally {
    if (browser) await browser.close();
    if (monitor) await stop(monitor.proc);
    await stop(sim.proc);
  }
  console.log('live view page test passed');
})().catch(e => { console.error(e.stack || e.message); process.exit(1); });
