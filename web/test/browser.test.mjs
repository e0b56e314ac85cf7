// The demo page in headless Chromium (Debian's), as CI runs it: served over HTTP, opened with
// ?test=1, the page steps a scene, shoots a sphere, draws with contacts and bounds on, and reports
// in #test-result whether it drew (a tenth of the pixels not background), whether the pixels
// changed between frames, and every console error. A screenshot goes to build/web/demo.png.
// WebGL in headless Chromium needs SwiftShader: --enable-unsafe-swiftshader (TOOLING.md).
import { execFile } from 'node:child_process';
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { promisify } from 'node:util';

import { startServer } from '../serve.mjs';

const run = promisify(execFile);
const webDir = process.env.COLLIDE_WEB_DIR ?? new URL('../../build/web', import.meta.url).pathname;
const chromium = process.env.CHROMIUM ?? 'chromium';
const flags = ['--headless', '--no-sandbox', '--enable-unsafe-swiftshader', '--use-angle=swiftshader',
               '--window-size=960,540', '--virtual-time-budget=60000', '--hide-scrollbars'];

for (const scene of ['billiards', 'terrain']) {
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
      await run(chromium, [...flags, `--screenshot=${webDir}/demo-${scene}.png`, url], { timeout: 240000 });
    } finally {
      server.close();
    }
  });
}
