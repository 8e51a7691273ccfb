// The 3D view every mode draws in (three.js). World frame of the project (docs/architecture.md,
// "Coordinates"): x_w = column * cell, y_w = (height - 1 - row) * cell; three.js is y-up, so a
// world point (x_w, y_w) is drawn at (x_w, 0, -y_w). One robot placement (placeRobot), one
// render loop (startLoop), one pick by click (onRobotClick). For papers and demos (issue 26): the
// camera frames the map's bounds whatever its shape, robots keep a legible size when zoomed out,
// a legend names the colours, the selected robot carries a label.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { $, viewer } from './page.js';
import { wallBoxes } from './walls.js';

export const COLORS = { moving: 0x3d8bfd, waiting: 0xf0a030, done: 0x3cb371, idle: 0x3cb371, collided: 0xd63384, selected: 0xff3b30 };
// Overlays of a selected robot and the run's marks, each its own colour (none the path's red).
export const MARKS = { path: 0xff3b30, trail: 0xffffff, waitsFor: 0xff4dff, waitedBy: 0x33e0ff, start: 0xb0b8c4, goal: 0xffffff };

export const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
$('view').appendChild(renderer.domElement);
export const scene = new THREE.Scene();
scene.background = new THREE.Color(0x1d2127);
scene.add(new THREE.HemisphereLight(0xffffff, 0x404040, 2.5));
const camera = new THREE.PerspectiveCamera(45, 1, 0.1, 5000);
export const controls = new OrbitControls(camera, renderer.domElement);

export function resize() {
  const box = $('view').getBoundingClientRect();
  renderer.setSize(box.width, box.height);
  camera.aspect = box.width / Math.max(1, box.height);
  camera.updateProjectionMatrix();
  if (framed) frameBounds(framed);
}

// The camera looks down at the map from the south at this tilt from the vertical.
const kTilt = 0.6;  // rad, about 34 degrees
let framed = null;  // {cx, cz, w, d}: the map's bounds in three.js coordinates
// Frames a w x d rectangle centred at (cx, cz): the nearest camera on the tilted view line from
// which all of it shows, with a 4 % margin (issue 26: a non-square map filled a third of the view).
export function frameBounds(b) {
  framed = b;
  const v = THREE.MathUtils.degToRad(camera.fov) / 2, h = Math.atan(Math.tan(v) * camera.aspect);
  const across = (b.w / 2) / Math.tan(h);
  const deep = (b.d / 2) * Math.cos(kTilt) / Math.tan(v) + (b.d / 2) * Math.sin(kTilt);
  let dist = 1.04 * Math.max(across, deep);
  controls.target.set(b.cx, 0, b.cz);
  // Perspective widens the near edge: a few steps move the camera until the map's larger extent
  // on screen is 96 % of the view.
  for (let step = 0; step < 6; step++) {
    camera.position.set(b.cx, dist * Math.cos(kTilt), b.cz + dist * Math.sin(kTilt));
    camera.lookAt(controls.target);
    const s = viewer.mapOnScreen();
    dist *= Math.max(s.x, s.y) / 0.96;
  }
  camera.position.set(b.cx, dist * Math.cos(kTilt), b.cz + dist * Math.sin(kTilt));
  controls.update();
}

// What the browser tests read: the share of the view the map's bounds take on screen (x and y,
// 0-1), and a zoom by factor k (k > 1: farther).
viewer.mapOnScreen = () => {
  if (!framed) return null;
  camera.updateMatrixWorld();
  camera.updateProjectionMatrix();
  const xs = [], ys = [];
  for (const [dx, dz] of [[-1, -1], [1, -1], [-1, 1], [1, 1]]) {
    const p = new THREE.Vector3(framed.cx + dx * framed.w / 2, 0, framed.cz + dz * framed.d / 2).project(camera);
    xs.push(p.x);
    ys.push(p.y);
  }
  return { x: (Math.max(...xs) - Math.min(...xs)) / 2, y: (Math.max(...ys) - Math.min(...ys)) / 2 };
};
viewer.zoom = (k) => {
  camera.position.sub(controls.target).multiplyScalar(k).add(controls.target);
  controls.update();
};
window.addEventListener('resize', resize);

// Moves the view (camera and its target together, the angle kept) to look at world point
// (x_m, y_m): the minimap's click and camera follow.
export function lookAt(x, y) {
  const dx = x - controls.target.x, dz = -y - controls.target.z;
  controls.target.x += dx;
  controls.target.z += dz;
  camera.position.x += dx;
  camera.position.z += dz;
  controls.update();
}
// The world point the view looks at: [x_m, y_m].
export function viewTarget() { return [controls.target.x, -controls.target.z]; }
viewer.target = viewTarget;

// The floor, its grid and the walls of `map` (readMap's shape: width, height, blocked(x, y)),
// the camera above it.
export function buildMap(map, cell) {
  const floor = new THREE.Mesh(new THREE.PlaneGeometry(map.width * cell, map.height * cell),
                               new THREE.MeshLambertMaterial({ color: 0x3a404a }));
  floor.rotation.x = -Math.PI / 2;
  floor.position.set((map.width - 1) * cell / 2, 0, -(map.height - 1) * cell / 2);
  scene.add(floor);
  scene.add(floorGrid(map, cell));
  // Merged into rectangles (walls.js): a box scaled to each, its top 0.6 cells high.
  const boxes = wallBoxes(map), count = boxes.length / 4;
  const walls = new THREE.InstancedMesh(new THREE.BoxGeometry(cell, cell * 0.6, cell),
                                        new THREE.MeshLambertMaterial({ color: 0x8a8f98 }), count);
  const m = new THREE.Matrix4();
  for (let i = 0; i < count; i++) {
    const [x, y, w, h] = boxes.subarray(4 * i, 4 * i + 4);
    m.makeScale(w, 1, h).setPosition((x + (w - 1) / 2) * cell, cell * 0.3, -(map.height - 1 - (y + (h - 1) / 2)) * cell);
    walls.setMatrixAt(i, m);
  }
  viewer.wallBoxes = count;
  scene.add(walls);
  frameBounds({ cx: floor.position.x, cz: floor.position.z, w: map.width * cell, d: map.height * cell });
}

// The cell lines of the floor, exactly over it (a square GridHelper overhung non-square maps).
function floorGrid(map, cell) {
  const x0 = -cell / 2, x1 = (map.width - 0.5) * cell, z0 = cell / 2, z1 = -(map.height - 0.5) * cell;
  const pts = [];
  for (let i = 0; i <= map.width; i++) pts.push(x0 + i * cell, 0.001, z0, x0 + i * cell, 0.001, z1);
  for (let j = 0; j <= map.height; j++) pts.push(x0, 0.001, z0 - j * cell, x1, 0.001, z0 - j * cell);
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.Float32BufferAttribute(pts, 3));
  return new THREE.LineSegments(g, new THREE.LineBasicMaterial({ color: 0x4a505b }));
}

function mergeGeometries(a, b) {
  const pa = a.toNonIndexed().attributes.position.array, pb = b.toNonIndexed().attributes.position.array;
  const g = new THREE.BufferGeometry();
  const all = new Float32Array(pa.length + pb.length);
  all.set(pa);
  all.set(pb, pa.length);
  g.setAttribute('position', new THREE.BufferAttribute(all, 3));
  g.computeVertexNormals();
  return g;
}

// `count` robots, one instanced mesh: a disc with a nose, so its heading shows from above.
export function buildRobots(count, cell) {
  const body = new THREE.CylinderGeometry(cell * 0.3, cell * 0.3, cell * 0.25, 20);
  const nose = new THREE.BoxGeometry(cell * 0.3, cell * 0.27, cell * 0.12).translate(cell * 0.2, 0, 0);
  const mesh = new THREE.InstancedMesh(mergeGeometries(body, nose), new THREE.MeshLambertMaterial(), count);
  mesh.frustumCulled = false;  // instances move all over the map
  mesh.userData.cell = cell;
  mesh.userData.scale = 1;
  mesh.userData.hexes = new Uint32Array(count);  // each instance's colour + 1 (placeRobot)
  robotMeshes.add(mesh);
  for (let i = 0; i < count; i++) mesh.setColorAt(i, new THREE.Color(COLORS.moving));
  mesh.userData.hexes.fill(COLORS.moving + 1);
  scene.add(mesh);
  return mesh;
}

const matrix = new THREE.Matrix4(), color = new THREE.Color();

// Robot i of `mesh` at world pose (x_m, y_m, yaw_rad), in colour `hex` when given. The caller
// sets mesh.instanceMatrix/instanceColor.needsUpdate once per frame (robotsMoved).
// Written straight into the instance arrays (a rotation about +y by yaw, column-major, as
// Matrix4.makeRotationY; the colour only when it changed): 10 000 robots a frame (issue 28).
export function placeRobot(mesh, i, x, y, yaw, hex) {
  const c = Math.cos(yaw), s = Math.sin(yaw), m = mesh.instanceMatrix.array, o = 16 * i;
  m[o] = c; m[o + 1] = 0; m[o + 2] = -s; m[o + 3] = 0;
  m[o + 4] = 0; m[o + 5] = 1; m[o + 6] = 0; m[o + 7] = 0;
  m[o + 8] = s; m[o + 9] = 0; m[o + 10] = c; m[o + 11] = 0;
  m[o + 12] = x; m[o + 13] = mesh.userData.cell * 0.15; m[o + 14] = -y; m[o + 15] = 1;
  if (hex === undefined) return;
  const hexes = mesh.userData.hexes;
  if (hexes[i] === hex + 1) return;  // 0: not set yet
  hexes[i] = hex + 1;
  mesh.setColorAt(i, color.setHex(hex));
}

// Robots stay at least kMinRobotPx across on screen: zoomed out over 1000 robots they are grown
// (by their geometry, so the instances stay where they are) instead of shrinking to dots.
const kMinRobotPx = 7;
const robotMeshes = new Set();
function keepRobotsLegible() {
  const height = renderer.domElement.height / renderer.getPixelRatio();
  const dist = camera.position.distanceTo(controls.target);
  const pxPerM = height / (2 * dist * Math.tan(THREE.MathUtils.degToRad(camera.fov) / 2));
  for (const mesh of robotMeshes) {
    if (!mesh.parent) { robotMeshes.delete(mesh); continue; }
    const diameterPx = 0.6 * mesh.userData.cell * pxPerM;
    const want = Math.max(1, Math.ceil((kMinRobotPx / diameterPx) * 4) / 4);  // steps of 0.25
    if (want !== mesh.userData.scale) {
      const k = want / mesh.userData.scale;
      mesh.geometry.scale(k, k, k);
      mesh.userData.scale = want;
    }
  }
  viewer.robotScale = Math.max(1, ...[...robotMeshes].map((m) => m.userData.scale));
}

// A label that follows a world point (the selected robot): its text, or null to hide it.
const label = { el: null, at: new THREE.Vector3() };
export function setLabel(text, x, y) {
  if (!label.el) {
    label.el = document.createElement('div');
    label.el.id = 'label';
    $('view').appendChild(label.el);
  }
  label.el.hidden = text === null;
  if (text === null) return;
  label.el.textContent = text;
  label.at.set(x, 0, -y);
}
const projected = new THREE.Vector3();
function placeLabel() {
  if (!label.el || label.el.hidden) return;
  projected.copy(label.at).setY(0.6).project(camera);
  const box = renderer.domElement;
  label.el.style.left = `${((projected.x + 1) / 2) * box.clientWidth}px`;
  label.el.style.top = `${((1 - projected.y) / 2) * box.clientHeight}px`;
}

// The legend: what each colour of this view means, as text with swatches (never markup).
export function showLegend(entries) {
  let el = $('legend');
  if (!el) {
    el = document.createElement('div');
    el.id = 'legend';
    $('view').appendChild(el);
  }
  el.replaceChildren(...entries.map(([name, hex]) => {
    const row = document.createElement('div');
    const swatch = document.createElement('span');
    swatch.className = 'swatch';
    swatch.style.background = `#${hex.toString(16).padStart(6, '0')}`;
    row.append(swatch, document.createTextNode(name));
    return row;
  }));
  viewer.legend = entries.map(([name]) => name);
}

// Start and goal marks of every robot: flat rings at the starts, flat squares at the goals, on
// the floor below the robots. starts, goals: [[x_m, y_m], ...].
export function showMarks(starts, goals, cell) {
  const ring = new THREE.RingGeometry(cell * 0.22, cell * 0.3, 16).rotateX(-Math.PI / 2);
  const square = new THREE.RingGeometry(cell * 0.16, cell * 0.24, 4, 1).rotateX(-Math.PI / 2);
  for (const [geometry, points, hex] of [[ring, starts, MARKS.start], [square, goals, MARKS.goal]]) {
    const mesh = new THREE.InstancedMesh(geometry, new THREE.MeshBasicMaterial({ color: hex }), points.length);
    points.forEach(([x, y], i) => mesh.setMatrixAt(i, matrix.makeTranslation(x, 0.01, -y)));
    scene.add(mesh);
  }
  viewer.marks = { starts: starts.length, goals: goals.length };
}

export function robotsMoved(mesh) {
  mesh.instanceMatrix.needsUpdate = true;
  if (mesh.instanceColor) mesh.instanceColor.needsUpdate = true;
}

// The render loop: every animation frame, update(dt_s) (the mode's own work, may be absent),
// then the orbit controls and the render; rendered(ms) gets the render's cost.
export function startLoop({ update, rendered } = {}) {
  let last = performance.now();
  requestAnimationFrame(function frame(now) {
    const dt = (now - last) / 1000;
    last = now;
    if (update) update(dt);
    controls.update();
    keepRobotsLegible();
    placeLabel();
    const r0 = performance.now();
    renderer.render(scene, camera);
    if (rendered) rendered(performance.now() - r0);
    requestAnimationFrame(frame);
  });
}

export function renderOnce() { renderer.render(scene, camera); }

// Clicks on the canvas that hit a robot of meshOf() call pick(instance index).
export function onRobotClick(meshOf, pick) {
  const ray = new THREE.Raycaster(), mouse = new THREE.Vector2();
  renderer.domElement.addEventListener('click', (e) => {
    const r = renderer.domElement.getBoundingClientRect();
    mouse.set(((e.clientX - r.left) / r.width) * 2 - 1, -((e.clientY - r.top) / r.height) * 2 + 1);
    ray.setFromCamera(mouse, camera);
    const mesh = meshOf();
    const hit = mesh && ray.intersectObject(mesh)[0];
    if (hit) pick(hit.instanceId);
  });
}

export function pngDataUrl() { return renderer.domElement.toDataURL('image/png'); }
