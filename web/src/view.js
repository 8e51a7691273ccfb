// The 3D view every mode draws in (three.js). World frame of the project (docs/architecture.md,
// "Coordinates"): x_w = column * cell, y_w = (height - 1 - row) * cell; three.js is y-up, so a
// world point (x_w, y_w) is drawn at (x_w, 0, -y_w). One robot placement (placeRobot), one
// render loop (startLoop), one pick by click (onRobotClick).
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { $ } from './page.js';

export const COLORS = { moving: 0x3d8bfd, waiting: 0xf0a030, done: 0x3cb371, idle: 0x3cb371, collided: 0xd63384, selected: 0xff3b30 };

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
}
window.addEventListener('resize', resize);

// The floor, its grid and the walls of `map` (readMap's shape: width, height, blocked(x, y)),
// the camera above it.
export function buildMap(map, cell) {
  const floor = new THREE.Mesh(new THREE.PlaneGeometry(map.width * cell, map.height * cell),
                               new THREE.MeshLambertMaterial({ color: 0x3a404a }));
  floor.rotation.x = -Math.PI / 2;
  floor.position.set((map.width - 1) * cell / 2, 0, -(map.height - 1) * cell / 2);
  scene.add(floor);
  const grid = new THREE.GridHelper(Math.max(map.width, map.height) * cell,
                                    Math.max(map.width, map.height), 0x555d69, 0x444a54);
  grid.position.set(floor.position.x, 0.001, floor.position.z);
  scene.add(grid);
  const cells = [];
  for (let y = 0; y < map.height; y++) for (let x = 0; x < map.width; x++) if (map.blocked(x, y)) cells.push([x, y]);
  const walls = new THREE.InstancedMesh(new THREE.BoxGeometry(cell, cell * 0.6, cell),
                                        new THREE.MeshLambertMaterial({ color: 0x8a8f98 }), cells.length);
  const m = new THREE.Matrix4();
  cells.forEach(([x, y], i) => walls.setMatrixAt(i, m.makeTranslation(x * cell, cell * 0.3, -(map.height - 1 - y) * cell)));
  scene.add(walls);
  const span = Math.max(map.width, map.height) * cell;
  camera.position.set(floor.position.x, span * 1.05, floor.position.z + span * 0.75);
  controls.target.copy(floor.position);
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
  for (let i = 0; i < count; i++) mesh.setColorAt(i, new THREE.Color(COLORS.moving));
  scene.add(mesh);
  return mesh;
}

const matrix = new THREE.Matrix4(), quat = new THREE.Quaternion(), up = new THREE.Vector3(0, 1, 0);
const scale = new THREE.Vector3(1, 1, 1), where = new THREE.Vector3(), color = new THREE.Color();

// Robot i of `mesh` at world pose (x_m, y_m, yaw_rad), in colour `hex` when given. The caller
// sets mesh.instanceMatrix/instanceColor.needsUpdate once per frame (robotsMoved).
export function placeRobot(mesh, i, x, y, yaw, hex) {
  quat.setFromAxisAngle(up, yaw);
  matrix.compose(where.set(x, mesh.userData.cell * 0.15, -y), quat, scale);
  mesh.setMatrixAt(i, matrix);
  if (hex !== undefined) mesh.setColorAt(i, color.setHex(hex));
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
