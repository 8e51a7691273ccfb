// A lifelong run's tasks in the view (issue 28), from GET /api/runs/{id}/tasks
// (serve/include/smart/serve/task_timeline.hpp), at the view's time t: each open task's next
// errand as a marker (grey: nobody has it yet; amber: assigned), a line from every robot with a
// task to its next errand, the selected robot's task for its panel, and the tasks-finished
// curve with the last minute's throughput. Cells are MovingAI (x = column, y = row); drawn at
// x_w = x * cell, y_w = (height - 1 - y) * cell, as view.js draws the map.
import * as THREE from 'three';
import { scene } from './view.js';

export const TASK_MARKS = { open: 0x9aa3ad, assigned: 0xffc940, line: 0xffc940 };
const openColor = new THREE.Color(TASK_MARKS.open), assignedColor = new THREE.Color(TASK_MARKS.assigned);
const OPEN = new THREE.Matrix4().elements, ASSIGNED = OPEN;  // identity; the translation is set after

// The errands of task `task` done by time t.
const doneBy = (task, t) => {
  let k = 0;
  while (k < task.done_s.length && task.done_s[k] <= t) k++;
  return k;
};
const open = (task, t) => task.revealed_s <= t && !(task.finished_s !== null && task.finished_s <= t);
const assignedBy = (task, t) => task.robot !== null && task.assigned_s !== null && task.assigned_s <= t;

// The times at which any of `tasks` changes, sorted.
function changeTimes(tasks) {
  const times = [];
  for (const task of tasks) {
    times.push(task.revealed_s, ...task.done_s);
    if (task.assigned_s !== null) times.push(task.assigned_s);
    if (task.finished_s !== null) times.push(task.finished_s);
  }
  return Float64Array.from(times).sort();
}
// How many of the sorted `times` are <= t (binary search).
function changesBefore(times, t) {
  let lo = 0, hi = times.length;
  while (lo < hi) {
    const mid = (lo + hi) >> 1;
    if (times[mid] <= t) lo = mid + 1; else hi = mid;
  }
  return lo;
}

export function taskLayer(data, map, cell, robots) {
  let tasks = data.tasks;
  const diamond = new THREE.RingGeometry(cell * 0.12, cell * 0.22, 4, 1).rotateX(-Math.PI / 2);
  let markers = null;
  let markerColor = null, colorsChanged = false;  // per marker: 0 open, 1 assigned (-1 unset)
  const makeMarkers = (capacity) => {
    if (markers) scene.remove(markers);
    markers = new THREE.InstancedMesh(diamond, new THREE.MeshBasicMaterial(), Math.max(1, capacity));
    markers.frustumCulled = false;
    markers.count = 0;
    markers.setColorAt(0, openColor);  // makes instanceColor
    markerColor = new Int8Array(Math.max(1, capacity)).fill(-1);
    scene.add(markers);
  };
  makeMarkers(tasks.length);
  const positions = new Float32Array(Math.max(1, robots) * 6);
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(positions, 3));
  const lines = new THREE.LineSegments(geometry, new THREE.LineBasicMaterial({ color: TASK_MARKS.line, transparent: true, opacity: 0.7 }));
  lines.frustumCulled = false;
  scene.add(lines);
  const byRobot = new Int32Array(Math.max(1, robots)).fill(-1);  // task index per robot at t
  const pose = new Float64Array(3);
  const layer = { open: 0, lines: 0, byRobot };

  // Every time at which some task changes (revealed, assigned, an errand done, finished),
  // sorted: between two of them the markers stay as they are (changesBefore).
  let changes = changeTimes(tasks), shown = { key: undefined, at: -1 };
  // Markers and lines at time t; poseAt(robot, out) writes the robot's pose at t. `poses`, when
  // given, names the poses poseAt reads (replay: the recording's frame): the same poses and no
  // task change since the last call leave everything as it is (10 000 robots, issue 28).
  layer.update = (t, poseAt, poses) => {
    const at = changesBefore(changes, t);
    if (poses !== undefined && poses === shown.key && at === shown.at) return;
    shown = { key: poses, at };
    let n = 0, m = 0;
    byRobot.fill(-1);
    const lift = cell * 0.05, top = (map.height - 1) * cell;
    const matrices = markers.instanceMatrix.array;
    for (let i = 0; i < tasks.length; i++) {
      const task = tasks[i];
      if (!open(task, t)) continue;
      const c = task.cells[Math.min(doneBy(task, t), task.cells.length - 1)];
      const x = c[0] * cell, z = c[1] * cell - top;  // -y_w
      const mine = assignedBy(task, t);
      // A translation: identity with (x, 0.02, z) in the last column (column-major).
      matrices.set(mine ? ASSIGNED : OPEN, n * 16);
      matrices[n * 16 + 12] = x;
      matrices[n * 16 + 13] = 0.02;
      matrices[n * 16 + 14] = z;
      if (markerColor[n] !== (mine ? 1 : 0)) {
        markerColor[n] = mine ? 1 : 0;
        markers.setColorAt(n, mine ? assignedColor : openColor);
        colorsChanged = true;
      }
      n++;
      if (!mine || task.robot >= robots) continue;
      byRobot[task.robot] = i;
      poseAt(task.robot, pose);
      const o = m * 6;
      positions[o] = pose[0]; positions[o + 1] = lift; positions[o + 2] = -pose[1];
      positions[o + 3] = x; positions[o + 4] = lift; positions[o + 5] = z;
      m++;
    }
    markers.count = n;
    markers.instanceMatrix.needsUpdate = true;
    if (markers.instanceColor && colorsChanged) markers.instanceColor.needsUpdate = true;
    colorsChanged = false;
    geometry.attributes.position.needsUpdate = true;
    geometry.setDrawRange(0, m * 2);
    layer.open = n;
    layer.lines = m;
  };

  // The task robot r holds at t: {id, errands, done, next: [x, y]} or null.
  layer.taskOf = (r, t) => {
    const i = byRobot[r];
    if (i < 0) return null;
    const task = tasks[i], done = doneBy(task, t);
    return { id: task.id, errands: task.cells.length, done, next: task.cells[Math.min(done, task.cells.length - 1)] };
  };

  // Tasks finished and the last minute's throughput at t (the last planning call at or before t).
  layer.throughputAt = (t) => {
    const th = data.throughput;  // the latest data (setData)
    let i = -1;
    while (i + 1 < th.t_s.length && th.t_s[i + 1] <= t) i++;
    return i < 0 ? { finished: 0, lastMin: 0 } : { finished: th.finished[i], lastMin: th.last_min[i] };
  };
  layer.curve = { t_s: data.throughput.t_s, finished: data.throughput.finished };
  // A running run's newer tasks (live mode polls them).
  layer.setData = (d) => {
    data = d;
    tasks = d.tasks;
    changes = changeTimes(tasks);
    shown = { key: undefined, at: -1 };
    if (tasks.length > markers.instanceMatrix.count) makeMarkers(2 * tasks.length);
    layer.curve = { t_s: d.throughput.t_s, finished: d.throughput.finished };
  };
  return layer;
}

// The panel's line for robot r's task at t (page.js setRows pairs).
export function taskRows(layer, r, t) {
  const task = layer.taskOf(r, t);
  if (!task) return [['task', 'task: none']];
  return [['task', `task: #${task.id}, errand ${task.done + 1} of ${task.errands} at (${task.next[0]}, ${task.next[1]})`]];
}
