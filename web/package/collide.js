// collide in the browser and in Node: the WebAssembly module with its hull builder.
//
//   import createCollide from 'collide-wasm';
//   const collide = await createCollide();
//   const world = new collide.World({ gravity: [0, -9.81, 0] });
//
// Debian has no Qhull for WebAssembly, so this build of collide takes a convex hull's triangles
// from three.js's ConvexHull (Module.hullTriangles below); collide merges coplanar ones into faces
// and builds its own polyhedron from them (docs/web.md).
import createCollideModule from './collide_wasm.js';
import { Vector3 } from 'three';
import { ConvexHull } from 'three/addons/math/ConvexHull.js';

// The hull of the points (x, y, z, x, y, z, ...) as triangle vertex indices, or null.
export function hullTriangles(xyz) {
  const points = [];
  for (let i = 0; i < xyz.length; i += 3) points.push(new Vector3(xyz[i], xyz[i + 1], xyz[i + 2]));
  const index = new Map(points.map((p, i) => [p, i]));
  const hull = new ConvexHull().setFromPoints(points);
  if (hull.faces.length === 0) return null;
  const triangles = [];
  for (const face of hull.faces) {
    const loop = [];
    let edge = face.edge;
    do {
      loop.push(index.get(edge.head().point));
      edge = edge.next;
    } while (edge !== face.edge);
    for (let k = 1; k + 1 < loop.length; ++k) triangles.push(loop[0], loop[k], loop[k + 1]);
  }
  return triangles;
}

// Loads the module. In Node the .wasm is read from beside this file; in a browser it is fetched
// from there. `options` go to emscripten's module factory (print, printErr, locateFile, ...).
export default async function createCollide(options = {}) {
  const settings = { ...options, hullTriangles };
  if (typeof process !== 'undefined' && process.versions?.node) {
    // emscripten 3.1.6's Node glue is CommonJS inside the ES module: it names require and
    // __dirname, which an ES module does not have.
    const { createRequire } = await import('node:module');
    const { fileURLToPath } = await import('node:url');
    const { dirname } = await import('node:path');
    globalThis.require ??= createRequire(import.meta.url);
    globalThis.__dirname ??= dirname(fileURLToPath(import.meta.url));
    if (!settings.wasmBinary) {
      const { readFile } = await import('node:fs/promises');
      settings.wasmBinary = await readFile(new URL('./collide_wasm.wasm', import.meta.url));
    }
  }
  const module = await createCollideModule(settings);
  module.installHullFinder();
  // embind checks argument counts: the joints' trailing options object may be left out.
  const optional = { createHingeJoint: 5, createSliderJoint: 5, createConeJoint: 5, createFixedJoint: 3 };
  for (const [name, count] of Object.entries(optional)) {
    const create = module.World.prototype[name];
    module.World.prototype[name] = function (...args) {
      while (args.length < count) args.push({});
      return create.apply(this, args);
    };
  }
  return module;
}
