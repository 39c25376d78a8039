// SPDX-License-Identifier: Apache-2.0
// Renders Vega specs to standalone SVG files, server-side, with Debian's node-vega (no browser):
//
//   node vega-to-svg.js SPEC.json OUT.svg [SPEC2.json OUT2.svg ...]
//
// Debian 12's `require('vega')` fails on Node 20 (its index is ES-module source), so this loads
// the built sub-packages from /usr/share/nodejs and registers their transforms as vega's own
// index does. Without a canvas, text widths are estimated. Exit 1 with the spec's file name and
// Vega's message when a spec does not parse or render; exit 3 when node-vega's modules cannot be
// loaded (palp's write_report_svgs says to install node-vega then).
'use strict';
const fs = require('fs');
const path = require('path');
const Module = require('module');

const NODE_DIR = process.env.PALP_NODE_VEGA_DIR || '/usr/share/nodejs';
// The sub-packages require each other by name: let them find their siblings.
process.env.NODE_PATH = [NODE_DIR, process.env.NODE_PATH].filter(Boolean).join(path.delimiter);
Module._initPaths();

function load(name) {
  try {
    return require(name);
  } catch (e) {
    console.error(`vega-to-svg: cannot load ${name} from ${NODE_DIR} (Debian's node-vega): ` +
                  e.message.split('\n')[0]);
    process.exit(3);
  }
}
const dataflow = load('vega-dataflow');
Object.assign(dataflow.transforms, load('vega-transforms'), load('vega-view-transforms'),
              load('vega-encode'));
const {parse} = load('vega-parser');
const {View} = load('vega-view');

async function render(specFile, outFile) {
  const spec = JSON.parse(fs.readFileSync(specFile, 'utf8'));
  const view = new View(parse(spec), {renderer: 'none'});
  const svg = await view.toSVG();
  view.finalize();
  fs.writeFileSync(outFile, svg);
}

(async () => {
  const args = process.argv.slice(2);
  if (args.length === 0 || args.length % 2 !== 0 || args[0] === '--help') {
    console.error('usage: node vega-to-svg.js SPEC.json OUT.svg [SPEC2.json OUT2.svg ...]');
    process.exit(2);
  }
  for (let i = 0; i < args.length; i += 2) {
    try {
      await render(args[i], args[i + 1]);
    } catch (e) {
      console.error(`vega-to-svg: ${args[i]}: ${e.message}`);
      process.exit(1);
    }
  }
})();
