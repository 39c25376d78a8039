// SPDX-License-Identifier: Apache-2.0
// Checks a figure's SVG as vega-to-svg.js (Debian's node-vega) writes it, from its text alone:
//
//   node check_svg.js FIG.svg [checks...]
//     --mark NAME MIN          the named mark (Vega's class "role-mark NAME") draws >= MIN items
//                              (a symbol's points, a rule's lines, a line's one path, ...)
//     --axis TITLE             an axis titled exactly TITLE exists (the unit is in the title)
//     --axis-covers TITLE LO HI   that axis' numeric tick labels reach LO and HI (the smallest
//                              label <= LO, the largest >= HI: the data's range is on the axis)
//     --legend LABEL           a legend entry whose label starts with LABEL
//     --legend-covers TITLE LO HI  the gradient legend (colour bar) titled TITLE has labels
//                              reaching LO and HI
//     --text SUBSTRING         some text in the figure contains SUBSTRING
//
// Prints one line per failed check and exits 1 when any failed (2 on bad usage); prints what
// it found (marks and their item counts, axes and their label ranges) with --list.
// No dependencies: a small tokenizer reads the SVG's element tree (Vega writes well-formed SVG).
'use strict';
const fs = require('fs');

function parse(svg) {
  const root = {tag: '#root', attrs: {}, children: [], text: ''};
  const stack = [root];
  const re = /<(\/?)([A-Za-z][\w:-]*)((?:\s+[\w:-]+="[^"]*")*)\s*(\/?)>|([^<]+)/g;
  let m;
  while ((m = re.exec(svg)) !== null) {
    if (m[5] !== undefined) {
      stack[stack.length - 1].text += decode(m[5]);
      continue;
    }
    const [, closing, tag, attrText, selfClosing] = m;
    if (closing) {
      if (stack.length > 1 && stack[stack.length - 1].tag === tag) stack.pop();
      continue;
    }
    const attrs = {};
    for (const a of attrText.matchAll(/([\w:-]+)="([^"]*)"/g)) attrs[a[1]] = decode(a[2]);
    const el = {tag, attrs, children: [], text: ''};
    stack[stack.length - 1].children.push(el);
    if (!selfClosing) stack.push(el);
  }
  return root;
}

function decode(s) {
  return s.replace(/&lt;/g, '<').replace(/&gt;/g, '>').replace(/&quot;/g, '"')
          .replace(/&#(\d+);/g, (_, d) => String.fromCodePoint(+d))
          .replace(/&#x([0-9a-f]+);/gi, (_, h) => String.fromCodePoint(parseInt(h, 16)))
          .replace(/&amp;/g, '&');
}

function* walk(el) {
  yield el;
  for (const c of el.children) yield* walk(c);
}

const classes = el => (el.attrs.class || '').split(/\s+/);
// every <text>'s content; a multi-line text's lines (its <tspan>s) one by one
const allText = el => [...walk(el)].filter(e => e.tag === 'text').flatMap(
    e => e.children.some(c => c.tag === 'tspan') ? e.children.map(c => c.text.trim()) : [e.text.trim()]);

// A tick label as a number: d3's minus sign (U+2212), thousands separators and SI suffixes
// (k, M, m, µ, n) are read; anything else (a word) is not a number.
function number(label) {
  const s = label.replace(/\u2212/g, '-').replace(/,/g, '').trim();
  const m = /^(-?\d*\.?\d+(?:e[-+]?\d+)?)([kMGmµun]?)$/.exec(s);
  if (!m) return NaN;
  const scale = {'': 1, k: 1e3, M: 1e6, G: 1e9, m: 1e-3, 'µ': 1e-6, u: 1e-6, n: 1e-9}[m[2]];
  return parseFloat(m[1]) * scale;
}

function inspect(root) {
  const marks = {}, axes = [], legends = [];
  for (const el of walk(root)) {
    const c = classes(el);
    if (el.tag !== 'g') continue;
    if (c.includes('role-mark') && c.length >= 3) {
      const name = c[c.length - 1];
      marks[name] = (marks[name] || 0) + el.children.filter(x => x.tag !== 'g').length;
    } else if (c.includes('role-axis')) {
      const title = [...walk(el)].filter(e => classes(e).includes('role-axis-title'))
                                 .flatMap(allText).join(' ');
      const labels = [...walk(el)].filter(e => classes(e).includes('role-axis-label'))
                                  .flatMap(allText).filter(t => t !== '');
      axes.push({title, labels, values: labels.map(number).filter(Number.isFinite)});
    } else if (c.includes('role-legend')) {
      const title = [...walk(el)].filter(e => classes(e).includes('role-legend-title'))
                                 .flatMap(allText).join(' ');
      const labels = [...walk(el)].filter(e => classes(e).includes('role-legend-label'))
                                  .flatMap(allText);
      legends.push({title, labels, values: labels.map(number).filter(Number.isFinite)});
    }
  }
  return {marks, axes, legends, texts: allText(root)};
}

function covers(values, lo, hi) {
  return values.length > 0 && Math.min(...values) <= lo && Math.max(...values) >= hi;
}

function main(argv) {
  if (argv.length < 1 || argv[0] === '--help') {
    console.error('usage: node check_svg.js FIG.svg [--list] [--mark NAME MIN] [--axis TITLE] ' +
                  '[--axis-covers TITLE LO HI] [--legend LABEL] [--legend-covers TITLE LO HI] ' +
                  '[--text SUBSTRING] ...');
    return 2;
  }
  const file = argv[0];
  let svg;
  try {
    svg = fs.readFileSync(file, 'utf8');
  } catch (e) {
    console.error(`check_svg: ${file}: ${e.message}`);
    return 1;
  }
  if (!/^\s*<svg[\s>]/.test(svg)) {
    console.error(`check_svg: ${file}: not an SVG document`);
    return 1;
  }
  const found = inspect(parse(svg));
  const failures = [];
  const need = (i, n) => {
    if (i + n >= argv.length) throw new Error(`${argv[i]} needs ${n} argument(s)`);
    return argv.slice(i + 1, i + 1 + n);
  };
  const axis = title => found.axes.find(a => a.title === title);
  const range = v => v.length ? `[${Math.min(...v)}, ${Math.max(...v)}]` : 'none';
  for (let i = 1; i < argv.length; ++i) {
    const opt = argv[i];
    if (opt === '--list') {
      console.log(JSON.stringify({marks: found.marks, axes: found.axes.map(a => ({title: a.title, range: range(a.values)})),
                                  legends: found.legends.map(l => ({title: l.title, labels: l.labels}))}, null, 1));
    } else if (opt === '--mark') {
      const [name, min] = need(i, 2); i += 2;
      const n = found.marks[name] || 0;
      if (n < Number(min))
        failures.push(`mark "${name}": ${name in found.marks ? n + ' items' : 'absent'}, want >= ${min}`);
    } else if (opt === '--axis') {
      const [title] = need(i, 1); i += 1;
      if (!axis(title))
        failures.push(`no axis titled "${title}" (axes: ${found.axes.map(a => '"' + a.title + '"').join(', ')})`);
    } else if (opt === '--axis-covers') {
      const [title, lo, hi] = need(i, 3); i += 3;
      const a = axis(title);
      if (!a) failures.push(`no axis titled "${title}"`);
      else if (!covers(a.values, Number(lo), Number(hi)))
        failures.push(`axis "${title}": tick labels span ${range(a.values)}, do not cover [${lo}, ${hi}]`);
    } else if (opt === '--legend') {
      const [label] = need(i, 1); i += 1;
      if (!found.legends.some(l => l.labels.some(t => t.startsWith(label))))
        failures.push(`no legend entry "${label}…" (entries: ${found.legends.flatMap(l => l.labels).join(' | ')})`);
    } else if (opt === '--legend-covers') {
      const [title, lo, hi] = need(i, 3); i += 3;
      const l = found.legends.find(x => x.title === title);
      if (!l) failures.push(`no legend titled "${title}"`);
      else if (!covers(l.values, Number(lo), Number(hi)))
        failures.push(`legend "${title}": labels span ${range(l.values)}, do not cover [${lo}, ${hi}]`);
    } else if (opt === '--text') {
      const [sub] = need(i, 1); i += 1;
      if (!found.texts.some(t => t.includes(sub))) failures.push(`no text containing "${sub}"`);
    } else {
      throw new Error(`unknown option ${opt}`);
    }
  }
  for (const f of failures) console.log(`${file}: ${f}`);
  return failures.length ? 1 : 0;
}

if (require.main === module) {
  try {
    process.exitCode = main(process.argv.slice(2));
  } catch (e) {
    console.error(`check_svg: ${e.message}`);
    process.exitCode = 2;
  }
}
module.exports = {parse, inspect, number};
