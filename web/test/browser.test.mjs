// The demo page in headless Chromium (Debian's), as CI runs it: served over HTTP, opened with
// ?test=1, the page steps a scene, shoots a sphere, draws with contacts and bounds on, and reports
// in #test-result whether it drew (a twentieth of the pixels not background), whether the pixels
// changed between frames, and every console error. A screenshot of the page (build/web/demo-SCENE.png)
// must show more than the background beside the panel.
// WebGL in headless Chromium needs SwiftShader: --enable-unsafe-swiftshader (TOOLING.md).
import { execFile } from 'node:child_process';
import { readFileSync } from 'node:fs';
import { inflateSync } from 'node:zlib';
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { promisify } from 'node:util';

import { startServer } from '../serve.mjs';

const run = promisify(execFile);
const webDir = process.env.COLLIDE_WEB_DIR ?? new URL('../../build/web', import.meta.url).pathname;
const chromium = process.env.CHROMIUM ?? 'chromium';
const flags = ['--headless', '--no-sandbox', '--enable-unsafe-swiftshader', '--use-angle=swiftshader',
               '--window-size=960,540', '--virtual-time-budget=60000', '--hide-scrollbars'];

// The share of a PNG's pixels (8-bit RGB or RGBA, not interlaced, as Chromium writes them) right of
// x0 that differ from the colour `background` by more than 24 in sum.
function drawnShareOfPng(file, background, x0) {
  const png = readFileSync(file);
  const width = png.readUInt32BE(16), height = png.readUInt32BE(20);
  const channels = { 2: 3, 6: 4 }[png[25]];
  assert.ok(png[24] === 8 && channels && png[28] === 0, 'an 8-bit RGB(A) PNG without interlacing');
  const chunks = [];
  for (let at = 8; at < png.length;) {
    const length = png.readUInt32BE(at), type = png.toString('latin1', at + 4, at + 8);
    if (type === 'IDAT') chunks.push(png.subarray(at + 8, at + 8 + length));
    at += 12 + length;
  }
  const raw = inflateSync(Buffer.concat(chunks));
  const stride = width * channels;
  const rows = Buffer.alloc(height * stride);
  for (let y = 0; y < height; ++y) {  // undo each row's filter (PNG spec, section 9)
    const filter = raw[y * (stride + 1)];
    for (let i = 0; i < stride; ++i) {
      const x = raw[y * (stride + 1) + 1 + i];
      const a = i >= channels ? rows[y * stride + i - channels] : 0;
      const b = y > 0 ? rows[(y - 1) * stride + i] : 0;
      const c = y > 0 && i >= channels ? rows[(y - 1) * stride + i - channels] : 0;
      const p = a + b - c, pa = Math.abs(p - a), pb = Math.abs(p - b), pc = Math.abs(p - c);
      const predictor = [0, a, b, (a + b) >> 1, pa <= pb && pa <= pc ? a : pb <= pc ? b : c][filter];
      rows[y * stride + i] = (x + predictor) & 255;
    }
  }
  let drawn = 0, counted = 0;
  for (let y = 0; y < height; ++y) {
    for (let x = x0; x < width; ++x, ++counted) {
      const i = y * stride + x * channels;
      const off = Math.abs(rows[i] - background[0]) + Math.abs(rows[i + 1] - background[1]) + Math.abs(rows[i + 2] - background[2]);
      if (off > 24) ++drawn;
    }
  }
  return drawn / counted;
}

for (const scene of ['billiards', 'terrain', 'character']) {
  test(`the demo steps and draws ${scene} in headless Chromium without console errors`, async () => {
    const server = await startServer(webDir);
    try {
      const url = `http://127.0.0.1:${server.address().port}/demo/index.html?test=1&scene=${scene}`;
      const { stdout } = await run(chromium, [...flags, '--dump-dom', url], { maxBuffer: 1 << 26, timeout: 240000 });
      const match = stdout.match(/<pre id="test-result">([^<]*)<\/pre>/);
      assert.ok(match, `the page wrote no result (it did not load or threw before the test): ${stdout.slice(0, 400)}`);
      const result = JSON.parse(match[1].replaceAll('&quot;', '"').replaceAll('&amp;', '&'));
      console.log(JSON.stringify(result));
      assert.deepEqual(result.errors, []);
      assert.ok(result.drawnFraction > 0.05, `drawn ${result.drawnFraction}`);
      assert.ok(result.changedFraction > 0.001, `changed ${result.changedFraction}`);
      assert.ok(result.frames >= 40);
      const screenshot = `${webDir}/demo-${scene}.png`;
      await run(chromium, [...flags, `--screenshot=${screenshot}`, url], { timeout: 240000 });
      // The screenshot right of the panel (270 px wide) is not the page's background alone.
      const share = drawnShareOfPng(screenshot, [0x20, 0x24, 0x2a], 270);
      assert.ok(share > 0.05, `the screenshot is blank right of the panel (${share} drawn)`);
    } finally {
      server.close();
    }
  });
}
