// The demo page: collide's built-in scenes stepped in WebAssembly and drawn with three.js. Pick a
// scene, drag bodies (a ray cast through collide's broad phase, then a spring on the body), shoot
// spheres, draw contacts and bounding boxes, walk a scene's character with WASD; the panel shows the
// milliseconds of each step.
// With ?test=1 the page checks itself for CI (web/test/browser.test.mjs): it steps, draws, and
// writes what it saw into #test-result.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import createCollide from 'collide';

const params = new URLSearchParams(location.search);
const testMode = params.has('test');
const consoleErrors = [];
window.addEventListener('error', (e) => consoleErrors.push(String(e.message)));
window.addEventListener('unhandledrejection', (e) => consoleErrors.push(String(e.reason)));
const consoleError = console.error.bind(console);
console.error = (...args) => { consoleErrors.push(args.join(' ')); consoleError(...args); };

const collide = await createCollide();

// ---- three.js ----
const canvas = document.getElementById('view');
const renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: testMode });
renderer.setPixelRatio(Math.min(window.devicePixelRatio, 2));
const scene3 = new THREE.Scene();
scene3.background = new THREE.Color(0x20242a);
const camera = new THREE.PerspectiveCamera(50, 1, 0.05, 2000);
const controls = new OrbitControls(camera, canvas);
controls.mouseButtons = { LEFT: null, MIDDLE: THREE.MOUSE.DOLLY, RIGHT: THREE.MOUSE.ROTATE };
scene3.add(new THREE.HemisphereLight(0xffffff, 0x404040, 1.2));
const sun = new THREE.DirectionalLight(0xffffff, 1.5);
sun.position.set(10, 20, 8);
scene3.add(sun);

function resize() {
  const width = canvas.clientWidth || window.innerWidth;
  const height = canvas.clientHeight || window.innerHeight;
  renderer.setSize(width, height, false);
  camera.aspect = width / height;
  camera.updateProjectionMatrix();
}
window.addEventListener('resize', resize);

// ---- Shapes as three.js objects ----
const staticMaterial = new THREE.MeshStandardMaterial({ color: 0x8a9099, roughness: 0.9 });
const palette = [0xe07a5f, 0x81b29a, 0xf2cc8f, 0x3d85c6, 0xb56576, 0x6d9dc5, 0xe9c46a, 0x90be6d];
const materials = palette.map((color) => new THREE.MeshStandardMaterial({ color, roughness: 0.6 }));

function polyhedron(geometry) {
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.BufferAttribute(geometry.vertices, 3));
  g.setIndex(new THREE.BufferAttribute(geometry.indices, 1));
  const flat = g.toNonIndexed();
  flat.computeVertexNormals();
  return flat;
}

function object3d(geometry, material) {
  switch (geometry.type) {
    case 'sphere': return new THREE.Mesh(new THREE.SphereGeometry(geometry.radius, 24, 16), material);
    case 'box': {
      const [x, y, z] = geometry.halfExtents;
      return new THREE.Mesh(new THREE.BoxGeometry(2 * x, 2 * y, 2 * z), material);
    }
    case 'capsule': return new THREE.Mesh(new THREE.CapsuleGeometry(geometry.radius, 2 * geometry.halfHeight, 8, 16), material);
    case 'cylinder':
      return new THREE.Mesh(new THREE.CylinderGeometry(geometry.radius, geometry.radius, 2 * geometry.halfHeight, 24), material);
    case 'ellipsoid': {
      const mesh = new THREE.Mesh(new THREE.SphereGeometry(1, 24, 16), material);
      mesh.geometry.scale(...geometry.radii);
      return mesh;
    }
    case 'plane': {
      const mesh = new THREE.Mesh(new THREE.PlaneGeometry(400, 400), material);
      const normal = new THREE.Vector3(...geometry.normal);
      mesh.geometry.applyQuaternion(new THREE.Quaternion().setFromUnitVectors(new THREE.Vector3(0, 0, 1), normal));
      mesh.geometry.translate(...normal.multiplyScalar(geometry.distance).toArray());
      return mesh;
    }
    case 'convex_hull': case 'kdop': case 'mesh':
      return new THREE.Mesh(polyhedron(geometry), material);
    case 'compound': {
      const group = new THREE.Group();
      for (const child of geometry.children) {
        const part = object3d(child, material);
        part.position.fromArray(child.position);
        part.quaternion.fromArray(child.rotation);
        part.scale.setScalar(child.scale);
        group.add(part);
      }
      return group;
    }
    default: throw new Error(`unknown shape type ${geometry.type}`);
  }
}

// ---- The simulation ----
let world = null;
let bodies = [];
let objects = [];
let dynamic = [];
let stepMs = 0;
const bodyRoot = new THREE.Group();
scene3.add(bodyRoot);

function addBodyObject(id) {
  const shape = world.shape(id);
  const geometry = shape.geometry();
  shape.delete();
  const isDynamic = world.type(id) === 'dynamic';
  const object = object3d(geometry, isDynamic ? materials[objects.length % materials.length] : staticMaterial);
  object.scale.multiplyScalar(world.scale(id));
  bodyRoot.add(object);
  bodies.push(id);
  objects.push(object);
  dynamic.push(isDynamic);
}

function disposeObjects() {
  bodyRoot.traverse((o) => o.geometry?.dispose());
  bodyRoot.clear();
  bodies = [];
  objects = [];
  dynamic = [];
}

// The scene's characters (docs/character.md), drawn as capsules: they walk their paths, or the first
// walks where the keys say when "drive" is on.
const characterRoot = new THREE.Group();
scene3.add(characterRoot);
const characterMaterial = new THREE.MeshStandardMaterial({ color: 0xf4a261, roughness: 0.5 });
const driveLabel = document.getElementById('drive-label');

function loadScene(name) {
  disposeObjects();
  characterRoot.traverse((o) => o.geometry?.dispose());
  characterRoot.clear();
  world?.delete();
  world = collide.World.fromScene(name);
  for (const id of world.bodies()) addBodyObject(id);
  const c = world.characters();
  for (let i = 0; i < world.characterCount(); ++i) {
    characterRoot.add(new THREE.Mesh(new THREE.CapsuleGeometry(c[6 * i + 3], 2 * c[6 * i + 4], 8, 16), characterMaterial));
  }
  driveLabel.hidden = world.characterCount() === 0;
  syncObjects();
  frameCamera();
}

// WASD from the camera's view, space a jump: the first character's walk while "drive" is on.
const keys = new Set();
window.addEventListener('keydown', (e) => keys.add(e.code));
window.addEventListener('keyup', (e) => keys.delete(e.code));
let jumpQueued = false;
function playerWalk() {
  if (!document.getElementById('drive').checked || world.characterCount() === 0) return null;
  const forward = new THREE.Vector3();
  camera.getWorldDirection(forward);
  forward.y = 0;
  forward.normalize();
  const right = new THREE.Vector3(-forward.z, 0, forward.x);
  const walk = new THREE.Vector3();
  if (keys.has('KeyW')) walk.add(forward);
  if (keys.has('KeyS')) walk.sub(forward);
  if (keys.has('KeyD')) walk.add(right);
  if (keys.has('KeyA')) walk.sub(right);
  if (walk.lengthSq() > 0) walk.normalize().multiplyScalar(4);
  if (jumpQueued) walk.y = 5;
  jumpQueued = false;
  return walk.toArray();
}

function frameCamera() {
  const box = new THREE.Box3();
  const b = world.bounds();
  for (let i = 0; i < bodies.length; ++i) {
    if (!dynamic[i] && b[6 * i + 3] - b[6 * i] > 100) continue;  // planes and huge statics
    box.expandByPoint(new THREE.Vector3(b[6 * i], b[6 * i + 1], b[6 * i + 2]));
    box.expandByPoint(new THREE.Vector3(b[6 * i + 3], b[6 * i + 4], b[6 * i + 5]));
  }
  if (box.isEmpty()) box.set(new THREE.Vector3(-5, 0, -5), new THREE.Vector3(5, 5, 5));
  const center = box.getCenter(new THREE.Vector3());
  const size = Math.min(box.getSize(new THREE.Vector3()).length(), 150);
  controls.target.copy(center);
  camera.position.copy(center).add(new THREE.Vector3(0.6, 0.45, 1).normalize().multiplyScalar(size * 0.9 + 2));
  controls.update();
}

function syncObjects() {
  const c = world.characters();
  characterRoot.children.forEach((mesh, i) => mesh.position.set(c[6 * i], c[6 * i + 1], c[6 * i + 2]));
  const p = world.positions();
  const q = world.rotations();
  for (let i = 0; i < objects.length; ++i) {
    objects[i].position.set(p[3 * i], p[3 * i + 1], p[3 * i + 2]);
    objects[i].quaternion.set(q[4 * i], q[4 * i + 1], q[4 * i + 2], q[4 * i + 3]);
  }
}

// ---- Debug drawing: contacts and bounds ----
const contactLines = new THREE.LineSegments(new THREE.BufferGeometry(), new THREE.LineBasicMaterial({ color: 0xff3030 }));
const boundLines = new THREE.LineSegments(new THREE.BufferGeometry(), new THREE.LineBasicMaterial({ color: 0x40e0d0 }));
contactLines.frustumCulled = boundLines.frustumCulled = false;
scene3.add(contactLines, boundLines);

function drawContacts(on) {
  contactLines.visible = on;
  if (!on) return;
  const c = world.contactPoints();
  const lines = new Float32Array((c.length / 6) * 6);
  for (let i = 0; i < c.length; i += 6) {
    lines.set([c[i], c[i + 1], c[i + 2], c[i] + 0.3 * c[i + 3], c[i + 1] + 0.3 * c[i + 4], c[i + 2] + 0.3 * c[i + 5]], i);
  }
  contactLines.geometry.setAttribute('position', new THREE.BufferAttribute(lines, 3));
}

function drawBounds(on) {
  boundLines.visible = on;
  if (!on) return;
  const b = world.bounds();
  const edges = [[0, 1], [1, 3], [3, 2], [2, 0], [4, 5], [5, 7], [7, 6], [6, 4], [0, 4], [1, 5], [2, 6], [3, 7]];
  const out = [];
  for (let i = 0; i < bodies.length; ++i) {
    const lo = [b[6 * i], b[6 * i + 1], b[6 * i + 2]];
    const hi = [b[6 * i + 3], b[6 * i + 4], b[6 * i + 5]];
    if (hi[0] - lo[0] > 1000) continue;  // a plane's box is infinite
    const corner = (k) => [k & 1 ? hi[0] : lo[0], k & 2 ? hi[1] : lo[1], k & 4 ? hi[2] : lo[2]];
    for (const [a, c] of edges) out.push(...corner(a), ...corner(c));
  }
  boundLines.geometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(out), 3));
}

// ---- Interaction: drag and shoot ----
let drag = null;  // { body, depth, target }
const pointer = new THREE.Vector2();
const raycaster = new THREE.Raycaster();

function pointerRay(event) {
  const rect = canvas.getBoundingClientRect();
  pointer.set(((event.clientX - rect.left) / rect.width) * 2 - 1, -((event.clientY - rect.top) / rect.height) * 2 + 1);
  raycaster.setFromCamera(pointer, camera);
  return raycaster.ray;
}

canvas.addEventListener('pointerdown', (event) => {
  if (event.button !== 0) return;
  const ray = pointerRay(event);
  const hit = world.castRay(ray.origin.toArray(), ray.direction.toArray(), 1000);
  if (!hit || world.type(hit.body) !== 'dynamic') return;
  drag = { body: hit.body, depth: hit.distance, target: new THREE.Vector3(...hit.point),
           offset: new THREE.Vector3(...hit.point).sub(new THREE.Vector3(...world.position(hit.body))) };
  canvas.setPointerCapture(event.pointerId);
});
canvas.addEventListener('pointermove', (event) => {
  if (!drag) return;
  const ray = pointerRay(event);
  drag.target.copy(ray.origin).addScaledVector(ray.direction, drag.depth);
});
canvas.addEventListener('pointerup', () => { drag = null; });

function pullDragged(dt) {
  if (!drag || !world.isValid(drag.body)) { drag = null; return; }
  // A stiff, damped spring towards the pointer, as a velocity.
  const at = new THREE.Vector3(...world.position(drag.body)).add(drag.offset);
  const v = drag.target.clone().sub(at).multiplyScalar(8);
  world.setVelocity(drag.body, v.toArray());
  world.setAngularVelocity(drag.body, world.angularVelocity(drag.body).map((w) => w * 0.9));
  void dt;
}

const speedInput = document.getElementById('speed');
speedInput.addEventListener('input', () => { document.getElementById('speed-value').textContent = speedInput.value; });
const ballShape = collide.Shape.sphere(0.25);
function shoot() {
  const direction = new THREE.Vector3();
  camera.getWorldDirection(direction);
  const id = world.createBody({ shape: ballShape, position: camera.position.toArray(),
                                velocity: direction.multiplyScalar(Number(speedInput.value)).toArray(),
                                density: 2000, ccd: true });
  addBodyObject(id);
}
document.getElementById('shoot').addEventListener('click', shoot);
window.addEventListener('keydown', (e) => {
  if (e.code !== 'Space') return;
  e.preventDefault();
  if (document.getElementById('drive').checked && world.characterCount() > 0) jumpQueued = true;
  else shoot();
});

// ---- The panel ----
const sceneSelect = document.getElementById('scene');
for (const name of collide.builtinScenes()) {
  if (name === 'large-pile') continue;  // 65,536 cubes: a benchmark, not a demo
  sceneSelect.add(new Option(name, name));
}
sceneSelect.value = params.get('scene') ?? 'pyramid';
sceneSelect.addEventListener('change', () => loadScene(sceneSelect.value));
document.getElementById('restart').addEventListener('click', () => loadScene(sceneSelect.value));
const stats = document.getElementById('stats');
const option = (id) => document.getElementById(id).checked;

function frame() {
  const dt = world.sceneDt();
  if (!option('paused')) {
    pullDragged(dt);
    const ms = world.step(dt, 1);
    stepMs = stepMs === 0 ? ms : 0.9 * stepMs + 0.1 * ms;
    if (world.characterCount() > 0) world.updateCharacters(dt, playerWalk());
  }
  syncObjects();
  drawContacts(option('contacts'));
  drawBounds(option('bounds'));
  stats.textContent = `${world.source()}\n${world.bodyCount()} bodies\n${stepMs.toFixed(2)} ms per step`;
  renderer.render(scene3, camera);
}

resize();
loadScene(sceneSelect.value);

if (!testMode) {
  renderer.setAnimationLoop(frame);
} else {
  runSelfTest();
}

// ---- The self-test (CI: web/test/browser.test.mjs) ----
function pixelSample() {
  const gl = renderer.getContext();
  const width = gl.drawingBufferWidth, height = gl.drawingBufferHeight;
  const pixels = new Uint8Array(width * height * 4);
  gl.readPixels(0, 0, width, height, gl.RGBA, gl.UNSIGNED_BYTE, pixels);
  return pixels;
}

async function runSelfTest() {
  const result = { scene: sceneSelect.value, frames: 0, errors: consoleErrors };
  try {
    document.getElementById('contacts').checked = true;
    document.getElementById('bounds').checked = true;
    // Frame by frame, the browser's tasks run between them (a timer: headless Chromium's virtual
    // time runs timers, not animation frames).
    const nextFrame = () => new Promise((done) => setTimeout(done, 0));
    for (let i = 0; i < 10; ++i, ++result.frames) { frame(); await nextFrame(); }
    const first = pixelSample();
    shoot();
    for (let i = 0; i < 30; ++i, ++result.frames) { frame(); await nextFrame(); }
    const second = pixelSample();
    const background = [0x20, 0x24, 0x2a];
    let drawn = 0, changed = 0;
    for (let i = 0; i < first.length; i += 4) {
      if (Math.abs(first[i] - background[0]) + Math.abs(first[i + 1] - background[1]) + Math.abs(first[i + 2] - background[2]) > 24) ++drawn;
      if (first[i] !== second[i] || first[i + 1] !== second[i + 1] || first[i + 2] !== second[i + 2]) ++changed;
    }
    const total = first.length / 4;
    result.drawnFraction = drawn / total;
    result.changedFraction = changed / total;
    result.bodies = world.bodyCount();
    result.msPerStep = stepMs;
    result.webgl = renderer.capabilities.isWebGL2 ? 'webgl2' : 'webgl1';
  } catch (e) {
    consoleErrors.push(String(e?.stack ?? e));
  }
  result.pass = consoleErrors.length === 0 && result.drawnFraction > 0.05 && result.changedFraction > 0.001;
  const out = document.getElementById('test-result');
  out.textContent = JSON.stringify(result);
  out.hidden = false;
  document.title = result.pass ? 'collide-test: pass' : 'collide-test: fail';
  renderer.setAnimationLoop(frame);  // and on, as the page runs for a person
}
