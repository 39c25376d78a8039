// SPDX-License-Identifier: Apache-2.0
// The live-view tests' processes: palp-sim on ephemeral loopback ports (real-time pace, so the
// stream has the rate a user sees), palpctl monitor --plot --json against it (its first line
// names the page's URL), palp-sim's control channel, and raw HTTP requests.
'use strict';
const {spawn} = require('child_process');
const net = require('net');
const readline = require('readline');

const [PALPCTL, PALP_SIM] = process.argv.slice(2);
if (!PALPCTL || !PALP_SIM) throw new Error('usage: node TEST.js PALPCTL PALP_SIM');

/// The first line a process prints on stdout (rejects when it exits first or after timeoutMs).
function firstLine(proc, what, timeoutMs = 15000) {
  return new Promise((resolve, reject) => {
    let err = '';
    proc.stderr.on('data', d => { err += d; });
    const t = setTimeout(() => reject(new Error(`${what}: no line within ${timeoutMs} ms ${err}`)),
                         timeoutMs);
    readline.createInterface({input: proc.stdout}).once('line', line => {
      clearTimeout(t);
      resolve(line);
    });
    proc.once('exit', code => reject(new Error(`${what} exited (${code}) before a line: ${err}`)));
  });
}

/// palp-sim; resolves with {proc, uri, controlPort}.
async function startSim() {
  const proc = spawn(PALP_SIM, ['--port', '0', '--control-port', '0'],
                     {stdio: ['ignore', 'pipe', 'pipe']});
  const line = await firstLine(proc, 'palp-sim');
  const m = /tcp:\/\/127\.0\.0\.1:(\d+) \(device protocol\), control on tcp:\/\/127\.0\.0\.1:(\d+)/
                .exec(line);
  if (!m) throw new Error(`palp-sim banner not understood: ${line}`);
  return {proc, uri: `sim://127.0.0.1:${m[1]}`, controlPort: Number(m[2])};
}

/// One line on palp-sim's control channel; resolves with the reply line.
function control(sim, line) {
  return new Promise((resolve, reject) => {
    const s = net.connect(sim.controlPort, '127.0.0.1', () => s.write(line + '\n'));
    let reply = '';
    s.on('data', d => {
      reply += d;
      if (reply.includes('\n')) { s.end(); resolve(reply.trim()); }
    });
    s.on('error', reject);
  });
}

/// Resolves once palp-sim has seen its device client go (it serves one at a time).
async function waitNoClient(sim, timeoutMs = 5000) {
  const end = Date.now() + timeoutMs;
  while (!(await control(sim, 'status')).includes(' client=0 ')) {
    if (Date.now() > end) throw new Error('palp-sim still holds its client');
    await new Promise(r => setTimeout(r, 20));
  }
}

/// palpctl monitor --plot --json --port 0 [extra] against sim; resolves with {proc, url} once
/// it printed its URL line.
async function startMonitor(sim, extra = []) {
  const proc = spawn(PALPCTL, ['monitor', '--plot', '--port', '0', '--json', '--uri', sim.uri,
                               ...extra], {stdio: ['ignore', 'pipe', 'pipe']});
  const line = await firstLine(proc, 'palpctl monitor --plot');
  const j = JSON.parse(line);
  if (!/^http:\/\/[\d.]+:\d+\/$/.test(j.url)) throw new Error(`not a URL line: ${line}`);
  return {proc, url: j.url, port: j.port};
}

/// Resolves with the exit code once proc ends (SIGINT first when it is still running).
function stop(proc) {
  if (proc.exitCode !== null || proc.signalCode !== null) return Promise.resolve(proc.exitCode);
  return new Promise(resolve => { proc.once('exit', code => resolve(code)); proc.kill('SIGINT'); });
}

/// Sends `request` (raw bytes) to 127.0.0.1:port; resolves with what came back before the server
/// closed (or after timeoutMs).
function rawRequest(port, request, timeoutMs = 5000) {
  return new Promise((resolve, reject) => {
    const s = net.connect(port, '127.0.0.1', () => s.write(request));
    let reply = '';
    const t = setTimeout(() => { s.destroy(); resolve(reply); }, timeoutMs);
    s.on('data', d => { reply += d; });
    s.on('end', () => { clearTimeout(t); resolve(reply); });
    s.on('error', e => { clearTimeout(t); reject(e); });
  });
}

/// palpctl with arguments (and environment variables added) to its end: {code, out, err}.
function runPalpctl(args, env = {}) {
  return new Promise(resolve => {
    const p = spawn(PALPCTL, args, {stdio: ['ignore', 'pipe', 'pipe'],
                                    env: Object.assign({}, process.env, env)});
    let out = '', err = '';
    p.stdout.on('data', d => { out += d; });
    p.stderr.on('data', d => { err += d; });
    p.on('exit', code => resolve({code, out, err}));
  });
}

module.exports = {startSim, control, waitNoClient, startMonitor, stop, rawRequest, runPalpctl};
