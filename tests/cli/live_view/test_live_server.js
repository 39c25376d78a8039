// SPDX-License-Identifier: Apache-2.0
// palpctl monitor --plot's server without a browser: which binds it refuses (exact messages, exit
// 2, before the device is contacted), the answers to requests other than the page and the
// stream (404, 405, 400, 431 for a 100 KB request line, 403 for a foreign Host), a stream that
// goes on for the other clients when one disconnects, the page being self-contained, a missing
// libjs-dygraphs named, and Ctrl-C or --seconds ending it with a summary.
// Run: node test_live_server.js PALPCTL PALP_SIM
'use strict';
const assert = require('assert');
const {startSim, waitNoClient, startMonitor, stop, rawRequest, runPalpctl} =
    require('./processes.js');

const UNREACHABLE = 'sim://127.0.0.1:1';  // refusals must come before any connection attempt

// The events a raw /events request receives within ms, counted by name.
function countEvents(port, ms) {
  return rawRequest(port, 'GET /events HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n', ms).then(text => ({
    head: text.slice(0, text.indexOf('\r\n\r\n')),
    samples: (text.match(/^event: samples$/mg) || []).length,
    status: (text.match(/^event: status$/mg) || []).length,
  }));
}

(async () => {
  // binds: loopback only unless --allow-remote; refused before the device is contacted
  let r = await runPalpctl(['monitor', '--plot', '--bind', '0.0.0.0', '--uri', UNREACHABLE]);
  assert.strictEqual(r.code, 2, r.err);
  assert.strictEqual(r.err,
      'palpctl: --bind 0.0.0.0 is not a loopback address: the live view has no authentication ' +
      "and would show the instrument's signals to the network; add --allow-remote to serve it " +
      'there anyway\n');
  r = await runPalpctl(['monitor', '--plot', '--bind', 'example.org', '--uri', UNREACHABLE]);
  assert.strictEqual(r.code, 2, r.err);
  assert.strictEqual(r.err, "palpctl: --bind: 'example.org' is not an IPv4 address\n");
  r = await runPalpctl(['monitor', '--port', '8080', '--uri', UNREACHABLE]);
  assert.strictEqual(r.code, 2, r.err);
  assert.match(r.err, /--port requires --plot/);
  // a missing libjs-dygraphs is named (exit 1, before the device: not a connection error)
  r = await runPalpctl(['monitor', '--plot', '--uri', UNREACHABLE],
                       {PALP_DYGRAPHS_DIR: '/nonexistent/dygraphs'});
  assert.strictEqual(r.code, 1, r.err);
  assert.strictEqual(r.err, 'palpctl: live view: /nonexistent/dygraphs/dygraph.min.js: cannot ' +
      "open: No such file or directory (the page's plots need Debian's libjs-dygraphs: apt-get " +
      'install libjs-dygraphs, or scripts/install-deps)\n');

  const sim = await startSim();
  let monitor;
  try {
    monitor = await startMonitor(sim, ['--seconds', '60']);
    const port = monitor.port;

    const page = await rawRequest(port, 'GET / HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n');
    assert.match(page, /^HTTP\/1\.1 200 OK\r\nContent-Type: text\/html; charset=utf-8\r\n/);
    assert.match(page, /Dygraph/, 'dygraphs is inlined');
    assert.doesNotMatch(page, /<script[^>]* src=|<link[^>]* rel="stylesheet"/,
                        'the page loads nothing from elsewhere');

    const status = async request => (await rawRequest(port, request)).split('\r\n')[0];
    assert.strictEqual(await status('GET /nope HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n'),
                       'HTTP/1.1 404 Not Found');
    assert.strictEqual(await status('POST / HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n'),
                       'HTTP/1.1 405 Method Not Allowed');
    assert.strictEqual(await status('GET / HTTP/9\r\n\r\n'), 'HTTP/1.1 400 Bad Request');
    assert.strictEqual(await status('GET /' + 'a'.repeat(100 * 1024) + ' HTTP/1.1\r\n\r\n'),
                       'HTTP/1.1 431 Request Header Fields Too Large');
    assert.strictEqual(await status('GET / HTTP/1.1\r\nHost: evil.example:' + port + '\r\n\r\n'),
                       'HTTP/1.1 403 Forbidden');

    // a client that disconnects mid-stream leaves the stream running for the next one
    const a = await countEvents(port, 500);
    assert.match(a.head, /^HTTP\/1\.1 200 OK\r\nContent-Type: text\/event-stream/);
    assert.ok(a.samples >= 5, `${a.samples} samples events in 0.5 s`);
    const b = await countEvents(port, 1000);
    assert.ok(b.samples >= 15 && b.status >= 2, JSON.stringify(b));

    // Ctrl-C ends it with exit 0 and a summary line
    let rest = '';
    monitor.proc.stdout.on('data', d => { rest += d; });
    assert.strictEqual(await stop(monitor.proc), 0, 'exit after Ctrl-C');
    const summary = JSON.parse(rest.trim().split('\n').pop());
    assert.ok(summary.samples > 1000 && summary.samples_missing === 0 && summary.pushes > 30, rest);
    monitor = null;

    // --seconds ends it too; without --json the URL and the summary are lines of text
    await waitNoClient(sim);
    r = await runPalpctl(['monitor', '--plot', '--port', '0', '--seconds', '0.5',
                          '--uri', sim.uri]);
    assert.strictEqual(r.code, 0, r.err);
    assert.match(r.out, /^live view: http:\/\/127\.0\.0\.1:\d+\/ \(Ctrl-C ends it\)\n/);
    assert.match(r.out, /\nlive view ended after 0\.\d s: \d+ samples, 0 lost in 0 gaps\n$/);

    // --allow-remote lets a non-loopback bind serve (and answer any Host)
    await waitNoClient(sim);
    monitor = await startMonitor(sim, ['--bind', '0.0.0.0', '--allow-remote']);
    assert.strictEqual(monitor.url, `http://0.0.0.0:${monitor.port}/`);
    assert.match(await rawRequest(monitor.port, 'GET / HTTP/1.1\r\nHost: lab-pc.example\r\n\r\n'),
                 /^HTTP\/1\.1 200 OK\r\n/);
    assert.strictEqual(await stop(monitor.proc), 0, 'exit after Ctrl-C');
    monitor = null;
  } finally {
    if (monitor) await stop(monitor.proc);
    await stop(sim.proc);
  }
  console.log('live server test passed');
})().catch(e => { console.error(e.stack || e.message); process.exit(1); });
