// SPDX-License-Identifier: Apache-2.0
// A small browser driver for palp's page tests: Debian's Chromium (/usr/bin/chromium), headless,
// driven over the Chrome DevTools Protocol on a pipe (--remote-debugging-pipe: JSON messages
// separated by NUL bytes on file descriptors 3 (to the browser) and 4 (from it)). No npm package,
// no network: Node's own child_process is the whole transport.
//
//   const {launch} = require('./cdp.js');
//   const browser = await launch({width: 1200, height: 900});
//   const page = await browser.newPage();
//   await page.goto('file:///tmp/report.html');        // resolves on the load event
//   await page.waitFor('document.querySelectorAll("svg").length > 3', 10000);
//   const n = await page.evaluate('window.samplesReceived');
//   await page.screenshot('/tmp/report.png', {fullPage: true});
//   page.errors;   // console.error calls, uncaught exceptions, failed loads: must stay empty
//   await browser.close();
//
// Run by hand: node tests/browser/cdp.js URL [--screenshot out.png] [--wait 'expr']
// prints the page's errors (exit 1 if any).
'use strict';
const {spawn} = require('child_process');
const fs = require('fs');
const os = require('os');
const path = require('path');

const CHROMIUM = process.env.PALP_CHROMIUM || '/usr/bin/chromium';
// Without the background-networking flags Chromium keeps trying hosts this closed network
// refuses; --no-sandbox because CI runs as root.
const FLAGS = ['--headless=new', '--no-sandbox', '--disable-gpu', '--disable-quic',
               '--no-first-run', '--disable-background-networking', '--disable-component-update',
               '--disable-sync', '--disable-extensions', '--hide-scrollbars', '--mute-audio',
               '--remote-debugging-pipe'];

class Page {
  constructor(browser, sessionId) {
    this.browser = browser;
    this.sessionId = sessionId;
    this.errors = [];  // strings: "console.error: ...", "exception: ...", "log: ..."
    this.console = []; // every console message as "type: text"
    this.loadWaiters = [];
  }
  send(method, params = {}) { return this.browser.send(method, params, this.sessionId); }
  onEvent(method, params) {
    if (method === 'Runtime.consoleAPICalled') {
      const text = params.args.map(a => a.value !== undefined ? String(a.value)
                                                              : (a.description || a.type))
                              .join(' ');
      this.console.push(`${params.type}: ${text}`);
      if (params.type === 'error' || params.type === 'assert')
        this.errors.push(`console.${params.type}: ${text}`);
    } else if (method === 'Runtime.exceptionThrown') {
      const d = params.exceptionDetails;
      const text = (d.exception && d.exception.description) || d.text;
      this.errors.push(`exception: ${text} (line ${d.lineNumber + 1})`);
    } else if (method === 'Log.entryAdded') {
      if (params.entry.level === 'error')
        this.errors.push(`log: ${params.entry.text}${params.entry.url ? ' ' + params.entry.url : ''}`);
    } else if (method === 'Page.loadEventFired') {
      const w = this.loadWaiters;
      this.loadWaiters = [];
      w.forEach(f => f());
    }
  }
  /// Navigates and resolves once the page's load event fired (rejects after timeoutMs).
  async goto(url, timeoutMs = 15000) {
    const loaded = new Promise((resolve, reject) => {
      const t = setTimeout(() => reject(new Error(`${url}: no load event within ${timeoutMs} ms`)),
                           timeoutMs);
      this.loadWaiters.push(() => { clearTimeout(t); resolve(); });
    });
    const r = await this.send('Page.navigate', {url});
    if (r.errorText) throw new Error(`${url}: ${r.errorText}`);
    await loaded;
  }
  /// The value of a JavaScript expression in the page (promises awaited); an exception rejects.
  async evaluate(expression) {
    const r = await this.send('Runtime.evaluate',
                              {expression, returnByValue: true, awaitPromise: true});
    if (r.exceptionDetails) {
      const d = r.exceptionDetails;
      throw new Error(`evaluate(${expression}): ${(d.exception && d.exception.description) || d.text}`);
    }
    return r.result.value;
  }
  /// Polls `expression` until it is truthy; rejects with the expression after timeoutMs.
  async waitFor(expression, timeoutMs = 10000, pollMs = 50) {
    const end = Date.now() + timeoutMs;
    for (;;) {
      const v = await this.evaluate(expression);
      if (v) return v;
      if (Date.now() > end) throw new Error(`not true within ${timeoutMs} ms: ${expression}`);
      await new Promise(r => setTimeout(r, pollMs));
    }
  }
  /// Clicks the first element matching a CSS selector (a real mouse press and release at its
  /// centre, as a user's click; rejects when nothing matches).
  async click(selector) {
    const box = await this.evaluate(`(() => { const e = document.querySelector(${JSON.stringify(selector)});
      if (!e) return null; const r = e.getBoundingClientRect();
      return {x: r.left + r.width / 2, y: r.top + r.height / 2}; })()`);
    if (!box) throw new Error(`click: nothing matches ${selector}`);
    for (const type of ['mousePressed', 'mouseReleased'])
      await this.send('Input.dispatchMouseEvent',
                      {type, x: box.x, y: box.y, button: 'left', clickCount: 1});
  }
  /// Writes a PNG of the viewport (or the whole page with {fullPage: true}); returns its bytes.
  async screenshot(file, {fullPage = false} = {}) {
    const params = {format: 'png'};
    if (fullPage) {
      const m = await this.send('Page.getLayoutMetrics');
      const s = m.cssContentSize || m.contentSize;
      params.clip = {x: 0, y: 0, width: Math.ceil(s.width), height: Math.ceil(s.height), scale: 1};
      params.captureBeyondViewport = true;
    }
    const r = await this.send('Page.captureScreenshot', params);
    const png = Buffer.from(r.data, 'base64');
    if (file) fs.writeFileSync(file, png);
    return png;
  }
}

class Browser {
  constructor(proc, userDataDir, options) {
    this.proc = proc;
    this.userDataDir = userDataDir;
    this.options = options;
    this.nextId = 1;
    this.pending = new Map();
    this.pages = new Map();
    this.buffer = Buffer.alloc(0);
    this.stderr = '';
    this.exited = false;
    proc.stdio[4].on('data', chunk => this.onData(chunk));
    proc.stderr.on('data', d => { this.stderr = (this.stderr + d).slice(-4000); });
    proc.on('exit', code => {
      this.exited = true;
      for (const {reject, method} of this.pending.values())
        reject(new Error(`chromium exited (${code}) during ${method}: ${this.stderr.trim()}`));
      this.pending.clear();
    });
  }
  onData(chunk) {
    this.buffer = Buffer.concat([this.buffer, chunk]);
    let end;
    while ((end = this.buffer.indexOf(0)) >= 0) {
      const msg = JSON.parse(this.buffer.subarray(0, end).toString('utf8'));
      this.buffer = this.buffer.subarray(end + 1);
      if (msg.id !== undefined) {
        const p = this.pending.get(msg.id);
        if (!p) continue;
        this.pending.delete(msg.id);
        if (msg.error) p.reject(new Error(`${p.method}: ${msg.error.message}`));
        else p.resolve(msg.result);
      } else if (msg.sessionId && this.pages.has(msg.sessionId)) {
        this.pages.get(msg.sessionId).onEvent(msg.method, msg.params);
      }
    }
  }
  send(method, params = {}, sessionId = undefined) {
    if (this.exited) return Promise.reject(new Error(`chromium has exited: ${method}`));
    const id = this.nextId++;
    const msg = {id, method, params};
    if (sessionId) msg.sessionId = sessionId;
    return new Promise((resolve, reject) => {
      this.pending.set(id, {resolve, reject, method});
      this.proc.stdio[3].write(JSON.stringify(msg) + '\0');
    });
  }
  /// A new tab of the launch size, with console, exception and log events collected.
  async newPage() {
    const {targetId} = await this.send('Target.createTarget', {url: 'about:blank'});
    const {sessionId} = await this.send('Target.attachToTarget', {targetId, flatten: true});
    const page = new Page(this, sessionId);
    this.pages.set(sessionId, page);
    await page.send('Page.enable');
    await page.send('Runtime.enable');
    await page.send('Log.enable');
    await page.send('Emulation.setDeviceMetricsOverride',
                    {width: this.options.width, height: this.options.height,
                     deviceScaleFactor: 1, mobile: false});
    return page;
  }
  async close() {
    if (!this.exited) {
      const gone = new Promise(r => this.proc.once('exit', r));
      this.send('Browser.close').catch(() => {});
      const t = setTimeout(() => this.proc.kill('SIGKILL'), 5000);
      await gone;
      clearTimeout(t);
    }
    fs.rmSync(this.userDataDir, {recursive: true, force: true});  // the profile this driver made
  }
}

/// Starts headless Chromium with a new empty profile. options: width, height (the viewport, CSS
/// pixels; 1280 x 900 by default).
async function launch(options = {}) {
  const o = Object.assign({width: 1280, height: 900}, options);
  if (!fs.existsSync(CHROMIUM))
    throw new Error(`${CHROMIUM} not found: install Debian's chromium (scripts/install-deps)`);
  const userDataDir = fs.mkdtempSync(path.join(os.tmpdir(), 'palp-chromium-'));
  const proc = spawn(CHROMIUM, [...FLAGS, `--user-data-dir=${userDataDir}`,
                                `--window-size=${o.width},${o.height}`, 'about:blank'],
                     {stdio: ['ignore', 'ignore', 'pipe', 'pipe', 'pipe']});
  const browser = new Browser(proc, userDataDir, o);
  await browser.send('Target.setDiscoverTargets', {discover: false});
  return browser;
}

module.exports = {launch};

if (require.main === module) {
  const args = process.argv.slice(2);
  const url = args[0];
  const opt = name => { const i = args.indexOf(name); return i >= 0 ? args[i + 1] : undefined; };
  if (!url || url === '--help') {
    console.log('usage: node cdp.js URL [--screenshot out.png] [--wait EXPR] [--full-page]');
    process.exit(url ? 0 : 2);
  }
  (async () => {
    const browser = await launch();
    try {
      const page = await browser.newPage();
      await page.goto(url);
      if (opt('--wait')) await page.waitFor(opt('--wait'));
      if (opt('--screenshot'))
        await page.screenshot(opt('--screenshot'), {fullPage: args.includes('--full-page')});
      page.errors.forEach(e => console.log(e));
      process.exitCode = page.errors.length ? 1 : 0;
    } finally {
      await browser.close();
    }
  })().catch(e => { console.error(e.message); process.exit(1); });
}
