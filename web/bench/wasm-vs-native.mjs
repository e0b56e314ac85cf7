// WebAssembly against native: ms per step of the same built-in scenes run the same way (the runner
// of `collide run`, from the scene's start, wall time), three runs each, the engines taking turns,
// medians and their ratio (docs/benchmarks.md, "WebAssembly against native").
//   node web/bench/wasm-vs-native.mjs [--steps N] [--runs N] [--native build/release/tools/collide] [SCENE...]
import { execFileSync } from 'node:child_process';
import { mkdtempSync, readFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';

const args = process.argv.slice(2);
const option = (name, fallback) => {
  const i = args.indexOf(name);
  return i < 0 ? fallback : args.splice(i, 2)[1];
};
const steps = Number(option('--steps', 300));
const runs = Number(option('--runs', 3));
const root = new URL('../../', import.meta.url).pathname;
const native = option('--native', join(root, 'build/release/tools/collide'));
const scenes = args.length ? args : ['pyramid', 'terrain'];
const { default: createCollide } = await import(join(root, 'build/web/package/collide.js'));
const collide = await createCollide();
const scratch = mkdtempSync(join(tmpdir(), 'collide-bench-'));
const median = (values) => [...values].sort((a, b) => a - b)[Math.floor(values.length / 2)];

console.log('scene,steps,wasm_ms_per_step,native_ms_per_step,wasm_over_native,same_state');
for (const scene of scenes) {
  const wasm = [], nativeMs = [];
  let wasmHash = '', nativeHash = '';
  for (let run = 0; run < runs; ++run) {
    const result = collide.runScene(scene, steps);
    wasm.push(result.msPerStep);
    wasmHash = result.stateHash;
    const json = join(scratch, `${scene}.json`);
    execFileSync(native, ['run', scene, '--steps', String(steps), '--json', json], { stdio: 'ignore' });
    const summary = JSON.parse(readFileSync(json, 'utf8'));
    nativeMs.push(summary.ms_per_step);
    nativeHash = summary.state_hash;
  }
  const w = median(wasm), n = median(nativeMs);
  console.log(`${scene},${steps},${w.toFixed(3)},${n.toFixed(3)},${(w / n).toFixed(2)},${wasmHash === nativeHash}`);
}
