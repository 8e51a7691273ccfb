// Replay mode: a finished run's recording (SMRC, recording.js) played back, scrubbed, stepped;
// robots coloured moving, waiting, done or collided; a click shows a robot's panel (panel.js),
// its path, trail and the robots it waits for; the finished-actions curve (plot.js). A lifelong
// run also shows its tasks (tasks.js: errand markers, robot-to-errand lines, the robot's task,
// finished tasks and throughput); every run has the minimap (minimap.js), robot search and
// camera follow.
import * as THREE from 'three';
import { firstFrameBytes, readMap, readRecording } from './recording.js';
import { robotList, robotStatus } from './panel.js';
import { drawProgress } from './plot.js';
import { minimap } from './minimap.js';
import { TASK_MARKS, taskLayer, taskRows } from './tasks.js';
import { SWITCH_MARK, switchLayer } from './switches.js';
import { $, fetchJson, setRows, viewer } from './page.js';
import { COLORS, MARKS, buildMap, buildRobots, lookAt, onRobotClick, placeRobot, pngDataUrl,
         renderOnce, resize, robotsMoved, scene, setLabel, showLegend, showMarks, startLoop,
         viewTarget } from './view.js';

const state = { rec: null, mesh: null, cell: 1, playing: false, speed: 8, t: 0, summary: null,
                collided: new Set(), collisionFrame: Infinity, progress: null, tasks: null,
                minimap: null, colors: null, xy: null, placed: {}, switches: null };
// Scratch poses, written by rec.pose().
const pose = new Float64Array(3), prev = new Float64Array(3), last = new Float64Array(3);

// Every robot's last recorded (x, y), once per recording (10 000 robots: a pose read less per
// robot and frame).
function endPoses(rec) {
  if (state.ends && state.endsOf === rec) return state.ends;
  state.ends = new Float64Array(2 * rec.robots);
  state.endsOf = rec;
  for (let i = 0; i < rec.robots; i++) {
    rec.pose(rec.frames - 1, i, last);
    state.ends[2 * i] = last[0];
    state.ends[2 * i + 1] = last[1];
  }
  return state.ends;
}

// Poses and colours of every robot at time t: moving, waiting (stands still before its end),
// done (at its final pose for good).
function showFrame(t) {
  const { rec, mesh } = state;
  // Still: the same pose as the frame before (at the first frame, the one after: issue 26, every
  // robot was "waiting" at t = 0).
  const f = rec.frameAt(t), end = rec.frames - 1, fp = f > 0 ? f - 1 : Math.min(1, end);
  if (placeRobots(f, fp)) robotsMoved(mesh);
  if (state.tasks) showTasks(t, f);
  if (state.switches) {
    state.switches.update(t, f, (i, out) => rec.pose(f, i, out));
    viewer.switches = { count: state.switches.count, shown: state.switches.shown };
  }
  if (state.minimap) state.minimap.draw(rec.robots, state.xy, state.colors, viewTarget());
  viewer.t = t;
  viewer.frameT = rec.times[f];
  $('clock').textContent = `${t.toFixed(1)} s`;
  $('scrub').value = String(Math.round((t / rec.times[end]) * 1000));
  if (viewer.selected >= 0) showRobot(viewer.selected, f);
  if (state.progress) drawProgress($('plot'), state.progress, t, state.summary.total_actions);
}

// Every robot of frame f (fp: the frame it is compared with) in place and colour; false when
// they already are (same recording, frame, selection and collision: most animation frames fall
// between two recorded frames, issue 28).
function placeRobots(f, fp) {
  const { rec, mesh } = state, key = state.placed;
  if (key.rec === rec && key.f === f && key.selected === viewer.selected && key.hit === state.collisionFrame) return false;
  state.placed = { rec, f, selected: viewer.selected, hit: state.collisionFrame };
  const ends = endPoses(rec);
  for (let i = 0; i < rec.robots; i++) {
    rec.pose(f, i, pose);
    rec.pose(fp, i, prev);
    // Squared distances: Math.hypot costs a third of a 10 000-robot frame in V8.
    const dx = pose[0] - prev[0], dy = pose[1] - prev[1], ex = pose[0] - ends[2 * i], ey = pose[1] - ends[2 * i + 1];
    const still = dx * dx + dy * dy < 1e-6 && Math.abs(pose[2] - prev[2]) < 1e-3;
    const atEnd = ex * ex + ey * ey < 1e-6;
    const hit = state.collided.has(i) && f >= state.collisionFrame;
    const kind = i === viewer.selected ? 'selected' : hit ? 'collided' : still ? (atEnd ? 'done' : 'waiting') : 'moving';
    placeRobot(mesh, i, pose[0], pose[1], pose[2], COLORS[kind]);
    state.colors[i] = COLORS[kind];
    state.xy[2 * i] = pose[0];
    state.xy[2 * i + 1] = pose[1];
  }
  return true;
}

// A lifelong run's tasks at time t (frame f): markers, lines, the finished-tasks curve and the
// last minute's throughput.
function showTasks(t, f) {
  const { tasks, rec } = state;
  tasks.update(t, (i, out) => rec.pose(f, i, out), f);
  const { finished, lastMin } = tasks.throughputAt(t);
  const total = tasks.curve.finished.length ? tasks.curve.finished[tasks.curve.finished.length - 1] : 0;
  drawProgress($('plot'), tasks.curve, t, total, 'tasks');
  setRows($('throughput'), [['finished', `tasks finished: ${finished}`], ['rate', `throughput: ${lastMin} tasks in the last minute`],
    ['open', `open tasks: ${tasks.open}, robots with a task: ${tasks.lines}`]]);
  viewer.tasks = { open: tasks.open, lines: tasks.lines, finished, lastMin };
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

const row = (cls, text) => [[cls, text]];  // a panel line, shown as text (page.js setRows)

// The panel's lines from the robot's detail (GET /api/runs/{id}/robots/{robot}) at frame f.
function detailRows(d, s) {
  let rows = row('path', `path: ${d.path.length - 1} cells, ${d.actions} actions`);
  if (s.timed) {
    rows = rows.concat(row('progress', `finished: ${s.finished} / ${s.total}`),
      row('current', s.current >= 0 ? `current: #${s.current} ${s.type}` : 'current: none (done)'),
      row('waits-now', `waits now for: ${robotList(s.waitsNow)}`),
      row('waited-now', `waited for now by: ${robotList(s.waitedByNow)}`));
  }
  const res = d.results;
  if (typeof res.finish_time_s === 'number') {
    rows = rows.concat(row('finish', `finished at ${res.finish_time_s.toFixed(1)} s, waited ${res.waiting_time_s.toFixed(1)} s`));
    if (typeof res.lower_bound_s === 'number') rows = rows.concat(row('bound', `alone it needs at least ${res.lower_bound_s.toFixed(1)} s`));
  } else if (res.finish_time_s === null) {
    rows = rows.concat(row('finish', 'did not finish'));
  }
  const list = (xs) => xs.map((x) => `${x.robot}${x.edges > 1 ? ` (${x.edges})` : ''}`).join(', ') || 'none';
  return rows.concat(row('waits', `in the run waits for: ${list(d.waits_for)}`), row('waited', `in the run waited by: ${list(d.waited_by)}`));
}

function showRobot(id, f) {
  const p = state.rec.pose(f, id, new Float64Array(3));
  const offGoal = (state.summary && state.summary.robots_off_goal || []).includes(id);
  const d = state.detail && state.detail.robot === id ? state.detail : null;
  let rows = [].concat(row('id', `robot ${id}`), row('pose', `x ${p[0].toFixed(2)} m, y ${p[1].toFixed(2)} m`),
    row('heading', `heading ${(p[2] * 180 / Math.PI).toFixed(0)}°`), row('queue', `queue: ${state.rec.queue(f, id)}`),
    offGoal ? row('off-goal', 'NOT AT GOAL') : [], state.collided.has(id) ? row('collided', 'COLLIDED') : [],
    state.tasks ? taskRows(state.tasks, id, state.t) : []);
  if (d) {
    const s = robotStatus(d, state.rec.times[f]);
    viewer.status = s;
    rows = rows.concat(detailRows(d, s));
    drawEdges(id, f, d, s);
  }
  setRows($('robot'), rows);
  drawTrail(id, f);
  if ($('follow').checked) lookAt(p[0], p[1]);
  setLabel(`robot ${id}`, p[0], p[1]);
}

// The selected robot's planned path, its trail, and lines to the robots it waits for.
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
  overlay.trail = new THREE.Line(g, new THREE.LineBasicMaterial({ color: MARKS.trail }));
  scene.add(overlay.trail);
  viewer.trailPoints = f + 1;
}
function drawPath(d) {
  if (overlay.path) scene.remove(overlay.path);
  const pts = d.path.map(([x, y]) => new THREE.Vector3(x, state.cell * 0.05, -y));
  overlay.path = new THREE.Line(new THREE.BufferGeometry().setFromPoints(pts), new THREE.LineBasicMaterial({ color: MARKS.path }));
  scene.add(overlay.path);
}
// Dashed lines from the selected robot to who it waits for now (magenta) and who waits for it
// now (cyan), at their poses at this frame, above the walls (issue 26: 1 px, in the path's red,
// hidden by walls); a run without action times draws every partner.
function drawEdges(id, f, d, status) {
  if (overlay.edges) scene.remove(overlay.edges);
  const me = state.rec.pose(f, id, new Float64Array(3)), other = new Float64Array(3);
  const pts = [], colors = [], h = state.cell * 0.75;  // walls are 0.6 cells tall
  const groups = status.timed ? [[status.waitsNow, MARKS.waitsFor, 'waits'], [status.waitedByNow, MARKS.waitedBy, 'waited']]
    : [[d.waits_for, MARKS.waitsFor, 'waits'], [d.waited_by, MARKS.waitedBy, 'waited']];
  viewer.edgeLines = [];
  const flipped = new THREE.Color(SWITCH_MARK);  // an edge a switch made (switches.js)
  for (const [group, hex, kind] of groups) {
    const c = new THREE.Color(hex);
    for (const robot of new Set(group.map((g) => g.robot))) {
      const switched = group.some((g) => g.robot === robot && g.switched);
      const col = switched ? flipped : c;
      state.rec.pose(f, robot, other);
      pts.push(me[0], h, -me[1], other[0], h, -other[1]);
      colors.push(col.r, col.g, col.b, col.r, col.g, col.b);
      viewer.edgeLines.push({ kind, robot, switched, from: [me[0], me[1]], to: [other[0], other[1]] });
    }
  }
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.Float32BufferAttribute(pts, 3));
  g.setAttribute('color', new THREE.Float32BufferAttribute(colors, 3));
  overlay.edges = new THREE.LineSegments(g, new THREE.LineDashedMaterial({
    vertexColors: true, dashSize: state.cell * 0.3, gapSize: state.cell * 0.15, depthTest: false }));
  overlay.edges.computeLineDistances();
  overlay.edges.renderOrder = 2;  // drawn over walls and robots
  scene.add(overlay.edges);
  viewer.edgeStyle = { dashed: true, heightCells: h / state.cell, waitsFor: MARKS.waitsFor, waitedBy: MARKS.waitedBy };
}

function select(id) {
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
}
const seek = (t) => { state.t = Math.max(0, Math.min(t, state.rec.times[state.rec.frames - 1])); showFrame(state.t); };

// The robot model's limits the run used, as its summary records them (the upload's choice).
export function limitsText(l) {
  if (!l || typeof l !== 'object') return 'limits: not recorded';
  const n = (v, unit) => (typeof v === 'number' ? `${Number(v.toPrecision(3))} ${unit}` : '?');
  return `limits (${l.robot ?? 'robot'}): ${n(l.max_speed_mps, 'm/s')}, ${n(l.max_accel_mps2, 'm/s²')}, ` +
    `${n(l.max_turn_rate_radps, 'rad/s')}`;
}

// The run's execution as its summary records it (summary.json "execution", results_format.hpp
// summary_key::kExecution): plain ADG, or a switching one with its switches and the knobs that
// made them (`smart run --switch-*`).
export function executionText(e) {
  if (!e || typeof e !== 'object' || typeof e.mode !== 'string') return 'execution: not recorded';
  if (e.mode === 'adg') return 'execution: adg';
  let text = `execution: ${e.mode}, ${e.switches ?? '?'} switches`;
  if (e.anticipated) text += ` (${e.anticipated} anticipated)`;
  const o = e.options;
  if (!o || typeof o !== 'object') return text;
  const knobs = [`commit ${o.commit_actions}`, `chains ${o.chain_locations}`];
  if (o.anticipate && o.lookahead_actions > 0) {
    knobs.push(`lookahead ${o.lookahead_actions} actions`, `margin ${o.lookahead_margin_s} s`);
    if (o.window_pairs > 0) knobs.push(`window ${o.window_pairs} pairs`);
  } else if (o.anticipate) {
    knobs.push(`margin ${o.margin_s} s`, `horizon ${o.horizon_actions}`);
  }
  return `${text}; ${knobs.join(', ')}`;
}

function showStats(s) {
  const num = (v, unit) => `${(typeof v === 'number' ? v : NaN).toFixed(1)}${unit}`;
  setRows($('stats'), [['', `success: ${s.success}`], ['', `robots: ${s.robots}`], ['', `AET: ${num(s.aet_s, ' s')}`],
    ['', `makespan: ${num(s.makespan_s, ' s')}`], ['', `sim speed: ${num(s.sim_speed ?? 0, '×')}`],
    ['', `actions: ${s.finished_actions} / ${s.total_actions}`], ['', `collisions: ${s.collisions}`],
    ['limits', limitsText(s.limits)], ['execution', executionText(s.execution)]]);
}

// Every robot's start and goal cell from the run's plan (GET /api/runs/{id}/marks); a replay
// without plan files marks where each robot was first and last (a run that succeeded ends every
// robot on its goal cell: README, "success").
async function markStartsAndGoals(id) {
  const marks = await fetchJson(`/api/runs/${id}/marks`).catch(() => null);
  if (marks && marks.starts.length === state.rec.robots) {
    showMarks(marks.starts, marks.goals, state.cell);
    viewer.marksFrom = 'plan';
    return 'goal';
  }
  const { rec } = state, p = new Float64Array(3), starts = [], ends = [];
  for (let i = 0; i < rec.robots; i++) {
    rec.pose(0, i, p);
    starts.push([p[0], p[1]]);
    rec.pose(rec.frames - 1, i, p);
    ends.push([p[0], p[1]]);
  }
  showMarks(starts, ends, state.cell);
  viewer.marksFrom = 'recording';
  return 'last position';
}

// A lifelong run's tasks (GET /api/runs/{id}/tasks; none for a plan run).
async function loadTasks(id, map) {
  const data = await fetchJson(`/api/runs/${id}/tasks`).catch(() => null);
  if (!data) return;
  state.tasks = taskLayer(data, map, state.cell, state.rec.robots);
  $('throughput').hidden = false;
  viewer.taskOf = (r) => state.tasks.taskOf(r, state.t);
  state.legend = replayLegend('last position').concat([['errand (open)', TASK_MARKS.open],
    ['errand (assigned)', TASK_MARKS.assigned], ['robot to its next errand', TASK_MARKS.line]]);
  showLegend(state.legend);
}

// A switchable run's switches of passing orders (GET /api/runs/{id}/switches; none otherwise).
async function loadSwitches(id, map) {
  const data = await fetchJson(`/api/runs/${id}/switches`).catch(() => null);
  if (!data || !Array.isArray(data.t_s)) return null;
  state.switches = switchLayer(data, map.height, state.cell);
  return [['switched passing order (passed first → planned first)', SWITCH_MARK]];
}

export const replayLegend = (goal) => [['moving', COLORS.moving], ['waiting', COLORS.waiting], ['done', COLORS.done],
  ['collided', COLORS.collided], ['selected', COLORS.selected], ['start', MARKS.start], [goal, MARKS.goal],
  ['planned path', MARKS.path], ['waits for (Type-2)', MARKS.waitsFor], ['waited for by (Type-2)', MARKS.waitedBy]];

// Export: every results file of the run as a download (GET /api/runs/{id}/results/{name}).
function showFiles(id, files) {
  $('files').replaceChildren();
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
  $('step').onclick = () => seek(state.rec.times[Math.min(state.rec.frames - 1, state.rec.frameAt(state.t) + 1)]);
  $('speed').onchange = (e) => { state.speed = Number(e.target.value); };
  $('scrub').oninput = (e) => seek((Number(e.target.value) / 1000) * state.rec.times[state.rec.frames - 1]);
  $('search').onchange = (e) => select(Number(e.target.value));
  $('png').onclick = () => { const a = document.createElement('a'); a.download = 'smart-run.png'; a.href = pngDataUrl(); a.click(); };
  onRobotClick(() => state.mesh, select);
}

// Playback in the render loop; frame time = pose update + render (what a frame costs this page,
// whatever the display rate).
const frameTimes = [];
function play(dt) {
  if (!state.playing) return;
  const t0 = performance.now();
  seek(state.t + dt * state.speed);
  frameTimes.push(performance.now() - t0);
  if (frameTimes.length > 120) frameTimes.shift();
  viewer.frameTimeMs = frameTimes.reduce((a, b) => a + b, 0) / frameTimes.length;
}
function rendered(ms) {
  if (state.playing) viewer.renderMs = 0.9 * (viewer.renderMs || 0) + 0.1 * ms;
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

// Run `id` replayed: the first frame as soon as it is there, the controls once all of it is.
export async function startReplay(id) {
  const t0 = performance.now();
  const [run, mapText] = await Promise.all([fetchJson(`/api/runs/${id}`), fetch(`/api/runs/${id}/map`).then((r) => r.text())]);
  const { first, rest } = await loadRecording(id, run.summary.robots);
  Object.assign(state, { summary: run.summary, run: id, cell: run.summary.cell_m || 1, rec: first });
  const map = readMap(mapText);
  buildMap(map, state.cell);
  state.mesh = buildRobots(state.rec.robots, state.cell);
  state.colors = new Uint32Array(state.rec.robots);
  state.xy = new Float32Array(2 * state.rec.robots);
  state.minimap = minimap($('minimap'), map, state.cell);
  $('minimap').hidden = false;
  viewer.minimap = state.minimap;
  viewer.redrawMinimap = () => state.minimap.draw(state.rec.robots, state.xy, state.colors, viewTarget(), true);
  showStats(run.summary);
  showFiles(id, run.files);
  resize();
  showFrame(0);
  renderOnce();
  Object.assign(viewer, { select, seek, robots: state.rec.robots, firstFrameMs: performance.now() - t0 });
  viewer.pose = (i) => Array.from(state.rec.pose(state.rec.frameAt(state.t), i, new Float64Array(3)));
  viewer.firstFrameAtMs = performance.now();  // since the navigation started
  startLoop({ update: play, rendered });
  state.rec = await rest;
  findCollision();
  state.legend = replayLegend(await markStartsAndGoals(id));
  showLegend(state.legend);
  state.progress = await fetchJson(`/api/runs/${id}/progress`).catch(() => null);
  await loadTasks(id, map);
  const switchLegend = await loadSwitches(id, map);
  if (switchLegend) showLegend(state.legend.concat(switchLegend));
  $('plot').hidden = !state.progress && !state.tasks;
  wireControls();
  showFrame(0);
  viewer.endS = state.rec.times[state.rec.frames - 1];
  viewer.loadedMs = performance.now() - t0;
  viewer.readyAtMs = performance.now();
  viewer.ready = true;
}
