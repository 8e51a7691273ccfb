// The SMART-DDS viewer: a run from `smart serve` in 3D (three.js). World frame of the project
// (docs/architecture.md, "Coordinates"): x_w = column * cell, y_w = (height - 1 - row) * cell;
// three.js is y-up, so a world point (x_w, y_w) is drawn at (x_w, 0, -y_w).
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { firstFrameBytes, readMap, readRecording } from './recording.js';
import { robotList, robotStatus } from './panel.js';
import { drawProgress } from './plot.js';
import { WATCH_COLORS, extentOf, robotPanel, statusCounts } from './watch.js';

const COLORS = { moving: 0x3d8bfd, waiting: 0xf0a030, done: 0x3cb371, collided: 0xd63384, selected: 0xff3b30 };
const $ = (id) => document.getElementById(id);
const viewer = { ready: false, robots: 0, selected: -1, frameTimeMs: 0, t: 0, error: '' };
window.__viewer = viewer;

const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
$('view').appendChild(renderer.domElement);
const scene = new THREE.Scene();
scene.background = new THREE.Color(0x1d2127);
scene.add(new THREE.HemisphereLight(0xffffff, 0x404040, 2.5));
const camera = new THREE.PerspectiveCamera(45, 1, 0.1, 5000);
const controls = new OrbitControls(camera, renderer.domElement);

function resize() {
  const box = $('view').getBoundingClientRect();
  renderer.setSize(box.width, box.height);
  camera.aspect = box.width / Math.max(1, box.height);
  camera.updateProjectionMatrix();
}
window.addEventListener('resize', resize);

async function fetchJson(url) {
  const r = await fetch(url);
  if (!r.ok) throw new Error(`${url}: HTTP ${r.status}`);
  return r.json();
}

function buildMap(map, cell) {
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

function buildRobots(count, cell) {
  // A robot: a disc with a nose, so its heading shows from above.
  const body = new THREE.CylinderGeometry(cell * 0.3, cell * 0.3, cell * 0.25, 20);
  const nose = new THREE.BoxGeometry(cell * 0.3, cell * 0.27, cell * 0.12).translate(cell * 0.2, 0, 0);
  const geometry = mergeGeometries(body, nose);
  const mesh = new THREE.InstancedMesh(geometry, new THREE.MeshLambertMaterial(), count);
  mesh.frustumCulled = false;  // instances move all over the map
  for (let i = 0; i < count; i++) mesh.setColorAt(i, new THREE.Color(COLORS.moving));
  scene.add(mesh);
  return mesh;
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

const state = { rec: null, mesh: null, cell: 1, playing: false, speed: 8, t: 0, summary: null,
                collided: new Set(), collisionFrame: Infinity, progress: null };
// Scratch poses, written by rec.pose().
const pose = new Float64Array(3), prev = new Float64Array(3), last = new Float64Array(3);
const matrix = new THREE.Matrix4(), quat = new THREE.Quaternion(), up = new THREE.Vector3(0, 1, 0);
const scale = new THREE.Vector3(1, 1, 1), color = new THREE.Color();

// Poses and colours of every robot at time t: moving, waiting (stands still before its end),
// done (at its final pose for good).
function showFrame(t) {
  const { rec, mesh, cell } = state;
  const f = rec.frameAt(t), fp = Math.max(0, f - 1), end = rec.frames - 1;
  for (let i = 0; i < rec.robots; i++) {
    rec.pose(f, i, pose);
    rec.pose(fp, i, prev);
    rec.pose(end, i, last);
    quat.setFromAxisAngle(up, pose[2]);
    matrix.compose(new THREE.Vector3(pose[0], cell * 0.15, -pose[1]), quat, scale);
    mesh.setMatrixAt(i, matrix);
    const still = Math.hypot(pose[0] - prev[0], pose[1] - prev[1]) < 1e-3 && Math.abs(pose[2] - prev[2]) < 1e-3;
    const atEnd = Math.hypot(pose[0] - last[0], pose[1] - last[1]) < 1e-3;
    const hit = state.collided.has(i) && f >= state.collisionFrame;
    const kind = i === viewer.selected ? 'selected' : hit ? 'collided' : still ? (atEnd ? 'done' : 'waiting') : 'moving';
    mesh.setColorAt(i, color.setHex(COLORS[kind]));
  }
  mesh.instanceMatrix.needsUpdate = true;
  mesh.instanceColor.needsUpdate = true;
  viewer.t = t;
  viewer.frameT = rec.times[f];
  $('clock').textContent = `${t.toFixed(1)} s`;
  $('scrub').value = String(Math.round((t / rec.times[end]) * 1000));
  if (viewer.selected >= 0) showRobot(viewer.selected, f);
  if (state.progress) drawProgress($('plot'), state.progress, t, state.summary.total_actions);
}

// The pair the sim host reported colliding (summary.first_collision) is drawn as collided from
// the frame they came closest on: the sim reports that they touched, not when.
function findCollision() {
  const pair = state.summary && state.summary.first_collision;
  if (!Array.isArray(pair) || pair.length !== 2) return;
  const [a, b] = pair, pa = new Float64Array(3), pb = new Float64Array(3);
  let best = Infinity;
  for (let f = 0; f < state.rec.frames; f++) {
    state.rec.pose(f, a, pa);
    state.rec.pose(f, b, pb);
    const d = Math.hypot(pa[0] - pb[0], pa[1] - pb[1]);
    if (d < best) { best = d; state.collisionFrame = f; }
  }
  state.collided = new Set(pair);
  viewer.collided = [...state.collided];
}

function showRobot(id, f) {
  const p = state.rec.pose(f, id, new Float64Array(3));
  const offGoal = (state.summary && state.summary.robots_off_goal || []).includes(id);
  const d = state.detail && state.detail.robot === id ? state.detail : null;
  const row = (cls, text) => `<div class="${cls}">${text}</div>`;
  let html = row('id', `robot ${id}`) + row('pose', `x ${p[0].toFixed(2)} m, y ${p[1].toFixed(2)} m`) +
    row('heading', `heading ${(p[2] * 180 / Math.PI).toFixed(0)}°`) + row('queue', `queue: ${state.rec.queue(f, id)}`) +
    (offGoal ? row('off-goal', 'NOT AT GOAL') : '') + (state.collided.has(id) ? row('collided', 'COLLIDED') : '');
  if (d) {
    const s = robotStatus(d, state.rec.times[f]);
    viewer.status = s;
    html += row('path', `path: ${d.path.length - 1} cells, ${d.actions} actions`);
    if (s.timed) {
      html += row('progress', `finished: ${s.finished} / ${s.total}`) +
        row('current', s.current >= 0 ? `current: #${s.current} ${s.type}` : 'current: none (done)') +
        row('waits-now', `waits now for: ${robotList(s.waitsNow)}`) +
        row('waited-now', `waited for now by: ${robotList(s.waitedByNow)}`);
    }
    const res = d.results;
    if (typeof res.finish_time_s === 'number') {
      html += row('finish', `finished at ${res.finish_time_s.toFixed(1)} s, waited ${res.waiting_time_s.toFixed(1)} s`);
      if (typeof res.lower_bound_s === 'number') html += row('bound', `alone it needs at least ${res.lower_bound_s.toFixed(1)} s`);
    } else if (res.finish_time_s === null) {
      html += row('finish', 'did not finish');
    }
    const list = (xs) => xs.map((x) => `${x.robot}${x.edges > 1 ? ` (${x.edges})` : ''}`).join(', ') || 'none';
    html += row('waits', `in the run waits for: ${list(d.waits_for)}`) + row('waited', `in the run waited by: ${list(d.waited_by)}`);
    drawEdges(id, f, d, s);
  }
  $('robot').innerHTML = html;
  drawTrail(id, f);
  if ($('follow').checked) controls.target.set(p[0], 0, -p[1]);
}

// The selected robot's planned path, and lines to the robots it waits for (red) and that wait
// for it (orange), at their current poses.
const overlay = { path: null, edges: null, trail: null };
// Where the selected robot has been so far (one point per recorded frame, up to frame f).
function drawTrail(id, f) {
  if (overlay.trail) scene.remove(overlay.trail);
  const pts = new Float32Array((f + 1) * 3), p = new Float64Array(3);
  for (let i = 0; i <= f; i++) {
    state.rec.pose(i, id, p);
    pts.set([p[0], state.cell * 0.08, -p[1]], i * 3);
  }
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.BufferAttribute(pts, 3));
  overlay.trail = new THREE.Line(g, new THREE.LineBasicMaterial({ color: 0xffffff }));
  scene.add(overlay.trail);
  viewer.trailPoints = f + 1;
}
function drawPath(d) {
  if (overlay.path) scene.remove(overlay.path);
  const pts = d.path.map(([x, y]) => new THREE.Vector3(x, state.cell * 0.05, -y));
  overlay.path = new THREE.Line(new THREE.BufferGeometry().setFromPoints(pts), new THREE.LineBasicMaterial({ color: COLORS.selected }));
  scene.add(overlay.path);
}
// Lines from the selected robot to who it waits for now (red) and who waits for it now
// (orange), at their poses at this frame; a run without action times draws every partner.
function drawEdges(id, f, d, status) {
  if (overlay.edges) scene.remove(overlay.edges);
  const me = state.rec.pose(f, id, new Float64Array(3)), other = new Float64Array(3);
  const pts = [], colors = [], h = state.cell * 0.4;
  const groups = status.timed ? [[status.waitsNow, 0xff3b30, 'waits'], [status.waitedByNow, 0xf0a030, 'waited']]
    : [[d.waits_for, 0xff3b30, 'waits'], [d.waited_by, 0xf0a030, 'waited']];
  viewer.edgeLines = [];
  for (const [group, hex, kind] of groups) {
    const c = new THREE.Color(hex);
    for (const robot of new Set(group.map((g) => g.robot))) {
      state.rec.pose(f, robot, other);
      pts.push(me[0], h, -me[1], other[0], h, -other[1]);
      colors.push(c.r, c.g, c.b, c.r, c.g, c.b);
      viewer.edgeLines.push({ kind, robot, from: [me[0], me[1]], to: [other[0], other[1]] });
    }
  }
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.Float32BufferAttribute(pts, 3));
  g.setAttribute('color', new THREE.Float32BufferAttribute(colors, 3));
  overlay.edges = new THREE.LineSegments(g, new THREE.LineBasicMaterial({ vertexColors: true }));
  scene.add(overlay.edges);
}

viewer.select = (id) => {
  if (!state.rec || id < 0 || id >= state.rec.robots) return false;
  viewer.selected = id;
  showFrame(state.t);
  fetchJson(`/api/runs/${state.run}/robots/${id}`).then((d) => {
    state.detail = d;
    drawPath(d);
    viewer.detail = d;
    showFrame(state.t);
  }).catch(() => {});  // runs replayed without their plan files have no detail
  return true;
};
viewer.pose = (i) => Array.from(state.rec.pose(state.rec.frameAt(state.t), i, new Float64Array(3)));
viewer.seek = (t) => { state.t = Math.max(0, Math.min(t, state.rec.times[state.rec.frames - 1])); showFrame(state.t); };

function showStats(s) {
  const row = (k, v) => `<div>${k}: ${v}</div>`;
  $('stats').innerHTML = row('success', s.success) + row('robots', s.robots) + row('AET', `${(s.aet_s ?? NaN).toFixed(1)} s`) +
    row('makespan', `${(s.makespan_s ?? NaN).toFixed(1)} s`) + row('sim speed', `${(s.sim_speed ?? 0).toFixed(1)}×`) +
    row('actions', `${s.finished_actions} / ${s.total_actions}`) + row('collisions', s.collisions);
}

// Export: every results file of the run as a download (GET /api/runs/{id}/results/{name}).
function showFiles(id, files) {
  $('files').innerHTML = '';
  for (const name of files || []) {
    const a = document.createElement('a');
    a.href = `/api/runs/${id}/results/${name}`;
    a.download = `${id}-${name}`;
    a.textContent = name;
    $('files').appendChild(a);
  }
}

function wireControls() {
  $('play').onclick = () => { state.playing = !state.playing; $('play').textContent = state.playing ? 'pause' : 'play'; };
  $('step').onclick = () => viewer.seek(state.rec.times[Math.min(state.rec.frames - 1, state.rec.frameAt(state.t) + 1)]);
  $('speed').onchange = (e) => { state.speed = Number(e.target.value); };
  $('scrub').oninput = (e) => viewer.seek((Number(e.target.value) / 1000) * state.rec.times[state.rec.frames - 1]);
  $('search').onchange = (e) => viewer.select(Number(e.target.value));
  $('png').onclick = () => { const a = document.createElement('a'); a.download = 'smart-run.png'; a.href = renderer.domElement.toDataURL('image/png'); a.click(); };
  const ray = new THREE.Raycaster(), mouse = new THREE.Vector2();
  renderer.domElement.addEventListener('click', (e) => {
    const r = renderer.domElement.getBoundingClientRect();
    mouse.set(((e.clientX - r.left) / r.width) * 2 - 1, -((e.clientY - r.top) / r.height) * 2 + 1);
    ray.setFromCamera(mouse, camera);
    const hit = ray.intersectObject(state.mesh)[0];
    if (hit) viewer.select(hit.instanceId);
  });
}

let lastNow = performance.now();
const frameTimes = [];
function loop(now) {
  const dt = (now - lastNow) / 1000;
  lastNow = now;
  if (state.playing) {
    const t0 = performance.now();
    viewer.seek(state.t + dt * state.speed);
    frameTimes.push(performance.now() - t0);
    if (frameTimes.length > 120) frameTimes.shift();
    viewer.frameTimeMs = frameTimes.reduce((a, b) => a + b, 0) / frameTimes.length;
  }
  controls.update();
  const r0 = performance.now();
  renderer.render(scene, camera);
  // Frame time = pose update + render (what a frame costs this page, whatever the display rate).
  if (state.playing) viewer.renderMs = 0.9 * (viewer.renderMs || 0) + 0.1 * (performance.now() - r0);
  requestAnimationFrame(loop);
}

// The upload forms: a new run (POST /api/runs) or a results folder to replay (POST
// /api/results); problems are listed as `smart check-plan` prints them; an accepted upload is
// shown (a new run live until it ended, then replayed).
function wireForm(form, url, status, problems) {
  $(form).onsubmit = async (e) => {
    e.preventDefault();
    $(problems).innerHTML = '';
    $(status).textContent = 'uploading...';
    const r = await fetch(url, { method: 'POST', body: new FormData($(form)) });
    const body = await r.json();
    if (!r.ok) {
      $(status).textContent = body.error;
      for (const p of body.problems || []) {
        const li = document.createElement('li');
        li.textContent = `${p.file}:${p.line}${p.robot >= 0 ? ` robot ${p.robot}` : ''}: ${p.message}`;
        $(problems).appendChild(li);
      }
      return;
    }
    location.search = `?run=${body.id}`;
  };
}
// Kinodynamic sliders: they start at the chosen model's limits (GET /api/robots); moving one
// writes its number field, which the upload sends (empty: the model's own value).
async function wireSliders() {
  const models = await fetchJson('/api/robots').catch(() => []);
  if (!models.length) return;
  $('up-robot').innerHTML = '';
  for (const m of models) $('up-robot').add(new Option(m.name, m.name, false, m.name === 'footbot'));
  const field = (key) => $('upload').querySelector(`input[name=${key}]`);
  const reset = () => {
    const m = models.find((x) => x.name === $('up-robot').value) || models[0];
    for (const s of document.querySelectorAll('#upload .slider')) { s.value = m[s.dataset.for]; field(s.dataset.for).value = ''; }
  };
  for (const s of document.querySelectorAll('#upload .slider')) s.oninput = () => { field(s.dataset.for).value = s.value; };
  $('up-robot').onchange = reset;
  reset();
}

function wireUpload() {
  wireSliders();
  wireForm('upload', '/api/runs', 'upload-status', 'upload-problems');
  wireForm('replay', '/api/results', 'replay-status', 'replay-problems');
}

// A run still going: its map, and every robot's newest pose from the live stream (Server-Sent
// Events, about 4 a second); when it ended, the page reloads into the replay.
async function startLive(id) {
  const [run, mapText] = await Promise.all([fetchJson(`/api/runs/${id}`), fetch(`/api/runs/${id}/map`).then((r) => r.text())]);
  buildMap(readMap(mapText), state.cell);
  resize();
  viewer.live = true;
  viewer.liveEvents = 0;
  $('stats').textContent = `${id}: ${run.state} (live)`;
  const source = new EventSource(`/api/runs/${id}/live`);
  source.onmessage = (e) => {
    const ev = JSON.parse(e.data);
    if (!state.mesh && ev.poses.length) state.mesh = buildRobots(ev.poses.length, state.cell);
    ev.poses.forEach(([x, y, yaw], i) => {
      quat.setFromAxisAngle(up, yaw);
      matrix.compose(new THREE.Vector3(x, state.cell * 0.15, -y), quat, scale);
      state.mesh.setMatrixAt(i, matrix);
    });
    if (state.mesh) state.mesh.instanceMatrix.needsUpdate = true;
    viewer.liveEvents++;
    viewer.robots = ev.poses.length;
    $('clock').textContent = `${ev.t_s.toFixed(1)} s (live)`;
    $('stats').textContent = `${id}: ${ev.state} (live)`;
    if (ev.state === 'done' || ev.state === 'failed') { source.close(); location.reload(); }
  };
  requestAnimationFrame(function live() { controls.update(); renderer.render(scene, camera); if (viewer.live) requestAnimationFrame(live); });
}

// The recording in two steps: the header and first frame (a range request, a few kB) are drawn
// at once, then the whole file replaces it; playback starts when it is there.
async function loadRecording(id, robots) {
  const url = `/api/runs/${id}/recording`;
  const head = await fetch(url, { headers: { Range: `bytes=0-${firstFrameBytes(robots) - 1}` } });
  if (head.status === 206) {
    const first = readRecording(await head.arrayBuffer());
    if (first.frames > 0) return { first, rest: fetch(url).then((r) => r.arrayBuffer()).then(readRecording) };
  }
  const all = readRecording(await fetch(url).then((r) => r.arrayBuffer()));
  return { first: all, rest: Promise.resolve(all) };
}

// `smart serve --watch`: every robot of the run live on the domain, its status colour, a click
// shows its panel; no map given: a floor under the robots.
async function startWatch(runId) {
  const first = await fetchJson('/api/watch');
  state.cell = first.cell_m || 1;
  const mapResp = await fetch('/api/watch/map');
  if (mapResp.ok) buildMap(readMap(await mapResp.text()), state.cell);
  resize();
  Object.assign(viewer, { live: true, watch: true, liveEvents: 0 });
  let framed = mapResp.ok, ids = [];
  const source = new EventSource(`/api/watch/live${runId ? `?run_id=${runId}` : ''}`);
  source.onmessage = (e) => {
    const ev = JSON.parse(e.data);
    if (!framed && ev.robots.length) {
      const x = extentOf(ev.robots, 2 * state.cell), cells = (v) => Math.ceil(v / state.cell);
      const w = cells(x.maxX - x.minX), h = cells(x.maxY - x.minY);
      buildMap({ width: w, height: h, blocked: () => false }, state.cell);
      framed = true;
    }
    if (!state.mesh || state.mesh.count !== ev.robots.length) {
      if (state.mesh) scene.remove(state.mesh);
      state.mesh = ev.robots.length ? buildRobots(ev.robots.length, state.cell) : null;
    }
    ids = ev.robots.map((r) => r.id);
    ev.robots.forEach((r, i) => {
      quat.setFromAxisAngle(up, r.yaw_rad);
      matrix.compose(new THREE.Vector3(r.x_m, state.cell * 0.15, -r.y_m), quat, scale);
      state.mesh.setMatrixAt(i, matrix);
      state.mesh.setColorAt(i, color.setHex(r.id === viewer.selected ? WATCH_COLORS.selected : WATCH_COLORS[r.status]));
    });
    if (state.mesh) { state.mesh.instanceMatrix.needsUpdate = true; state.mesh.instanceColor.needsUpdate = true; }
    const picked = ev.robots.find((r) => r.id === viewer.selected);
    if (picked) $('robot').innerHTML = robotPanel(picked);
    const n = statusCounts(ev.robots), m = ev.monitor;
    $('stats').innerHTML = `<div>watching run ${ev.run_id || '(none yet)'}</div>` +
      `<div>monitor: ${m ? `${m.host} pid ${m.pid}` : 'not seen'}</div><div>robots: ${ev.robots.length}</div>` +
      `<div>moving ${n.moving}, idle ${n.idle}, stale ${n.stale}</div><div>dropped samples: ${ev.rejected_samples}</div>`;
    $('clock').textContent = `${ev.t_s.toFixed(1)} s (live)`;
    Object.assign(viewer, { robots: ev.robots.length, runId: ev.run_id, watched: ev.robots, liveEvents: viewer.liveEvents + 1 });
  };
  viewer.select = (id) => { viewer.selected = id; return ids.includes(id); };
  $('search').onchange = (e) => viewer.select(Number(e.target.value));
  const ray = new THREE.Raycaster(), mouse = new THREE.Vector2();
  renderer.domElement.addEventListener('click', (e) => {
    const r = renderer.domElement.getBoundingClientRect();
    mouse.set(((e.clientX - r.left) / r.width) * 2 - 1, -((e.clientY - r.top) / r.height) * 2 + 1);
    ray.setFromCamera(mouse, camera);
    const hit = state.mesh && ray.intersectObject(state.mesh)[0];
    if (hit) viewer.select(ids[hit.instanceId]);
  });
  requestAnimationFrame(function live() { controls.update(); renderer.render(scene, camera); requestAnimationFrame(live); });
  viewer.ready = true;
}

async function start() {
  wireUpload();
  const params = new URLSearchParams(location.search);
  const [watching, runs] = await Promise.all([fetch('/api/watch').then((r) => r.ok), fetchJson('/api/runs')]);
  const want = params.has('watch') ? 'watch' : params.get('run') || (runs.filter((r) => r.state === 'done').pop() || {}).id;
  if (watching) $('runs').add(new Option('live on the DDS domain (watch)', 'watch', false, want === 'watch' || !want));
  for (const r of runs) $('runs').add(new Option(`${r.id} ${r.map} (${r.state})`, r.id, false, r.id === want));
  $('runs').onchange = (e) => { location.search = e.target.value === 'watch' ? '?watch' : `?run=${e.target.value}`; };
  if (watching && (want === 'watch' || !want)) return startWatch(params.get('run_id'));
  if (!want) throw new Error('no finished run to show yet; upload one with POST /api/runs');
  const chosen = runs.find((r) => r.id === want);
  if (chosen && (chosen.state === 'queued' || chosen.state === 'running')) return startLive(want);
  const t0 = performance.now();
  const [run, mapText] = await Promise.all([fetchJson(`/api/runs/${want}`), fetch(`/api/runs/${want}/map`).then((r) => r.text())]);
  const { first, rest } = await loadRecording(want, run.summary.robots);
  state.summary = run.summary;
  state.run = want;
  state.cell = run.summary.cell_m || 1;
  state.rec = first;
  buildMap(readMap(mapText), state.cell);
  state.mesh = buildRobots(state.rec.robots, state.cell);
  showStats(run.summary);
  showFiles(want, run.files);
  resize();
  showFrame(0);
  renderer.render(scene, camera);
  viewer.robots = state.rec.robots;
  viewer.firstFrameMs = performance.now() - t0;
  viewer.firstFrameAtMs = performance.now();  // since the navigation started
  requestAnimationFrame(loop);
  state.rec = await rest;
  findCollision();
  state.progress = await fetchJson(`/api/runs/${want}/progress`).catch(() => null);
  $('plot').hidden = !state.progress;
  wireControls();
  showFrame(0);
  viewer.loadedMs = performance.now() - t0;
  viewer.readyAtMs = performance.now();
  viewer.ready = true;
}

start().catch((e) => { viewer.error = String(e); $('stats').textContent = String(e); });
