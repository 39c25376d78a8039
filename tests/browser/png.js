// SPDX-License-Identifier: Apache-2.0
// Reads a PNG screenshot's pixels (8-bit RGB or RGBA, non-interlaced: what Chromium writes) with
// Node's zlib, so page tests can check that something was drawn: pngStats(buffer) gives width,
// height, fraction(predicate over [r, g, b, a]) and distinctColours (a blank page has one).
'use strict';
const zlib = require('zlib');

function pngStats(buf) {
  const sig = Buffer.from([0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a]);
  if (buf.length < 8 || !buf.subarray(0, 8).equals(sig)) throw new Error('not a PNG');
  let off = 8, width = 0, height = 0, depth = 0, type = 0, interlace = 0;
  const idat = [];
  while (off + 8 <= buf.length) {
    const len = buf.readUInt32BE(off);
    const kind = buf.toString('latin1', off + 4, off + 8);
    const data = buf.subarray(off + 8, off + 8 + len);
    if (kind === 'IHDR') {
      width = data.readUInt32BE(0); height = data.readUInt32BE(4);
      depth = data[8]; type = data[9]; interlace = data[12];
    } else if (kind === 'IDAT') idat.push(data);
    else if (kind === 'IEND') break;
    off += 12 + len;
  }
  const channels = {2: 3, 6: 4}[type];
  if (depth !== 8 || !channels || interlace !== 0)
    throw new Error(`PNG of depth ${depth}, colour type ${type}, interlace ${interlace}: not read`);
  const raw = zlib.inflateSync(Buffer.concat(idat));
  const stride = width * channels;
  const px = Buffer.alloc(height * stride);
  for (let y = 0; y < height; ++y) {
    const f = raw[y * (stride + 1)];
    const line = raw.subarray(y * (stride + 1) + 1, (y + 1) * (stride + 1));
    for (let x = 0; x < stride; ++x) {
      const a = x >= channels ? px[y * stride + x - channels] : 0;
      const b = y > 0 ? px[(y - 1) * stride + x] : 0;
      const c = x >= channels && y > 0 ? px[(y - 1) * stride + x - channels] : 0;
      let v = line[x];
      if (f === 1) v += a;
      else if (f === 2) v += b;
      else if (f === 3) v += (a + b) >> 1;
      else if (f === 4) {
        const p = a + b - c, pa = Math.abs(p - a), pb = Math.abs(p - b), pc = Math.abs(p - c);
        v += pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
      }
      px[y * stride + x] = v & 0xff;
    }
  }
  const pixel = i => [px[i], px[i + 1], px[i + 2], channels === 4 ? px[i + 3] : 255];
  return {
    width, height,
    fraction(pred) {
      let n = 0;
      for (let i = 0; i < px.length; i += channels) if (pred(pixel(i))) ++n;
      return n / (width * height);
    },
    distinctColours(limit = 1000) {
      const seen = new Set();
      for (let i = 0; i < px.length && seen.size < limit; i += channels)
        seen.add(pixel(i).join(','));
      return seen.size;
    },
  };
}

module.exports = {pngStats};
