// The WebAssembly build's bindings, run by Node's test runner (scripts/build-web builds the package
// first): the lecture's impact laws, errors, queries, snapshots and hulls from JavaScript, and the
// built-in scenes' state hashes against the native build's reference table
// (tests/scene/reference_hashes_test.cpp) where docs/determinism.md says they are equal.
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { test } from 'node:test';

const root = new URL('../../', import.meta.url);
const packageDir = process.env.COLLIDE_WEB_PACKAGE ?? new URL('build/web/package/', root).pathname;
const { default: createCollide } = await import(`${packageDir}/collide.js`);
const collide = await createCollide();

// The native reference build's hashes and step counts (tests/scene/builtin_scene_runs.h).
const referenceText = readFileSync(new URL('tests/scene/reference_hashes_test.cpp', root), 'utf8');
const reference = Object.fromEntries(
  [...referenceText.matchAll(/\{"([a-z-]+)",\s*0x([0-9a-f]{16})\}/g)].map((m) => [m[1], m[2]]));
const stepsText = readFileSync(new URL('tests/scene/builtin_scene_runs.h', root), 'utf8');
const shorterRuns = Object.fromEntries(
  [...stepsText.matchAll(/\{"([a-z-]+)",\s*(\d+)\}/g)].map((m) => [m[1], Number(m[2])]));

// Scenes whose steps use only IEEE-exact arithmetic (+, -, *, /, sqrt) and no hull: the same bits
// as the native build (docs/determinism.md, "WebAssembly").
const sameAsNative = ['pile', 'rain', 'rain-jittered', 'pyramid', 'revert-soft', 'breakable', 'chain', 'bridge',
                      'machine', 'joint-grid', 'character'];

test('scenes without hulls or libm calls end in the native reference state', () => {
  for (const name of sameAsNative) {
    assert.ok(reference[name], `no reference hash for ${name}`);
    const run = collide.runScene(name, shorterRuns[name] ?? 120);
    assert.equal(run.stateHash, reference[name], name);
  }
});

test('every built-in scene runs the same twice in WebAssembly', () => {
  for (const name of ['billiards', 'terrain', 'proxies', 'ragdolls', 'tunneling']) {
    assert.equal(collide.runScene(name, 30).stateHash, collide.runScene(name, 30).stateHash, name);
  }
});

function headOn(m1, v1, m2, v2, e) {
  const world = new collide.World({ gravity: [0, 0, 0] });
  const sphere = collide.Shape.sphere(0.5);
  const a = world.createBody({ shape: sphere, position: [-1, 0, 0], velocity: [v1, 0, 0], mass: m1, bounciness: e, friction: 0 });
  const b = world.createBody({ shape: sphere, position: [1, 0, 0], velocity: [v2, 0, 0], mass: m2, bounciness: e, friction: 0 });
  world.step(1 / 60, 90);
  const result = [world.velocity(a)[0], world.velocity(b)[0], world.linearMomentum()[0]];
  world.delete();
  sphere.delete();
  return result;
}

test("the lecture's impacts: equal masses swap, Newton's law with momentum kept, inelastic shares", () => {
  let [u1, u2] = headOn(1, 1, 1, -1, 1);
  assert.ok(Math.abs(u1 + 1) < 0.01 && Math.abs(u2 - 1) < 0.01, `${u1} ${u2}`);
  const [m1, v1, m2, v2, e] = [2, 3, 1, -2, 0.5];
  const p0 = m1 * v1 + m2 * v2;
  const expected1 = (p0 + m2 * e * (v2 - v1)) / (m1 + m2);
  const expected2 = (p0 + m1 * e * (v1 - v2)) / (m1 + m2);
  let p;
  [u1, u2, p] = headOn(m1, v1, m2, v2, e);
  assert.ok(Math.abs(u1 - expected1) < 0.03 && Math.abs(u2 - expected2) < 0.03, `${u1} ${u2}`);
  assert.ok(Math.abs(p - p0) < 1e-3);
  [u1, u2] = headOn(2, 3, 1, -3, 0);
  assert.ok(Math.abs(u1 - 1) < 0.03 && Math.abs(u2 - 1) < 0.03, `${u1} ${u2}`);
});

test('bad input throws an Error with the library message and creates nothing', () => {
  assert.throws(() => collide.Shape.sphere(-1), /radius must be finite and > 0, got -1/);
  const world = new collide.World({});
  const ball = collide.Shape.sphere(0.5);
  assert.throws(() => world.createBody({ shape: ball, position: [NaN, 0, 0] }), /position/);
  assert.throws(() => world.createBody({ shape: ball, type: 'flying' }), /"static", "kinematic" or "dynamic"/);
  assert.throws(() => world.createBody({ position: [0, 0, 0] }), /shape: missing/);
  assert.equal(world.bodyCount(), 0);
  assert.throws(() => collide.World.fromScene('no-such-scene'), /no-such-scene/);
  assert.throws(() => collide.Shape.convexHull([0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0]), /coplanar/);
  assert.throws(() => world.loadSnapshot(new Uint8Array([1, 2, 3])), /snapshot/);
  world.delete();
  ball.delete();
});

test('state arrays, queries and snapshots', () => {
  const world = new collide.World({});
  world.createBody({ shape: collide.Shape.plane([0, 1, 0], 0), type: 'static' });
  const box = collide.Shape.box([0.5, 0.5, 0.5]);
  for (let i = 0; i < 5; ++i) world.createBody({ shape: box, position: [0, 1 + 1.1 * i, 0] });
  world.step(1 / 60, 30);
  const positions = world.positions();
  assert.equal(positions.length, 3 * world.bodyCount());
  const bodies = world.bodies();
  assert.deepEqual(Array.from(positions.slice(3, 6)), world.position(bodies[1]));
  assert.equal(world.rotations().length, 4 * world.bodyCount());

  const hit = world.castRay([3, 0.5, 0], [-1, 0, 0], 10);
  assert.ok(Math.abs(hit.distance - 2.5) < 0.05, `${hit.distance}`);
  assert.equal(world.castRay([3, 20, 3], [0, 1, 0], 10), null);

  const saved = world.saveSnapshot();
  world.step(1 / 60, 60);
  const after = Array.from(world.positions());
  world.loadSnapshot(saved);
  world.step(1 / 60, 60);
  assert.deepEqual(Array.from(world.positions()), after);
  world.delete();
  box.delete();
});

test("hulls from three.js's ConvexHull: a cube's faces merge, a hull rests on the ground", () => {
  const corners = [];
  for (let i = 0; i < 8; ++i) corners.push(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1);
  const cube = collide.Shape.convexHull(corners);
  const geometry = cube.geometry();
  assert.equal(geometry.vertices.length, 24);
  assert.equal(geometry.faceCount, 6);  // three.js's twelve triangles merged into six quads
  assert.equal(geometry.indices.length, 36);  // two triangles each when drawn
  const world = new collide.World({});
  world.createBody({ shape: collide.Shape.plane([0, 1, 0], 0), type: 'static' });
  const body = world.createBody({ shape: cube, position: [0, 3, 0] });
  world.step(1 / 60, 180);
  assert.ok(Math.abs(world.position(body)[1] - 1) < 0.01, `${world.position(body)}`);
  world.delete();
  cube.delete();
});

test('joints: a slider keeps to its axis up to its limit, a fixed joint breaks past its force', () => {
  const world = new collide.World({ gravity: [-3, -9.81, 2] });
  const small = collide.Shape.box([0.2, 0.2, 0.2]);
  const rail = world.createBody({ shape: small, type: 'static', position: [0, 2, 0] });
  const cart = world.createBody({ shape: small, position: [0, 2, 0], mass: 5 });
  const slider = world.createSliderJoint(rail, cart, [0, 2, 0], [1, 0, 0], { limits: [-1, 1] });
  const heavy = world.createBody({ shape: small, position: [0, 5, 3], mass: 100 });
  const post = world.createBody({ shape: small, type: 'static', position: [0, 5, 2.5] });
  const weld = world.createFixedJoint(post, heavy, { breakForce: 200 });
  const breaks = [];
  for (let i = 0; i < 180; ++i) {
    world.step(1 / 60, 1);
    breaks.push(...world.jointBreakEvents());
  }
  const [x, y, z] = world.position(cart);
  assert.ok(Math.abs(y - 2) < 1e-3 && Math.abs(z) < 1e-3, `${x} ${y} ${z}`);
  assert.ok(Math.abs(x + 1) < 0.01 && Math.abs(world.jointPosition(slider) + 1) < 0.01, `${x}`);
  assert.equal(breaks.length, 1);
  assert.deepEqual(breaks[0].joint, weld);
  assert.equal(world.jointCount(), 1);
  assert.throws(() => world.createHingeJoint(rail, cart, [0, 0, 0], [0, 0, 1], { limits: [1] }), /limits: must be/);
  world.delete();
  small.delete();
});

test('the character mover: 10 m in 2 s on flat ground, and a scene character walks its path', () => {
  const world = new collide.World({});
  const ground = collide.Shape.box([50, 0.5, 50]);
  world.createBody({ shape: ground, type: 'static', position: [0, -0.5, 0] });
  const character = new collide.Character({ position: [0, 0.92, 0] });
  for (let i = 0; i < 120; ++i) {
    world.step(1 / 60, 1);
    character.update(world, [5, 0, 0], 1 / 60);
    assert.equal(character.groundState(), 'on ground');
  }
  assert.ok(Math.abs(character.position()[0] - 10) < 0.1, `${character.position()}`);
  assert.ok(Math.abs(character.footPosition()[1] - 0.02) < 1e-3);
  assert.throws(() => new collide.Character({ position: [0, 1, 0], radius: -1 }), /radius/);
  character.delete();
  world.delete();
  ground.delete();

  const level = collide.World.fromScene('character');
  assert.equal(level.characterCount(), 1);
  const start = Array.from(level.characters().slice(0, 3));
  for (let i = 0; i < 300; ++i) {
    level.step(level.sceneDt(), 1);
    level.updateCharacters(level.sceneDt(), null);
  }
  const now = Array.from(level.characters().slice(0, 3));
  assert.ok(Math.hypot(now[0] - start[0], now[2] - start[2]) > 3, `${start} -> ${now}`);
  level.delete();
});
