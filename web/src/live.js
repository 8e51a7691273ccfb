// Live mode: a run of this server still going; its map, and every robot's newest state from the
// live stream (Server-Sent Events, GET /api/runs/{id}/live, about 4 a second), coloured by state
// as the replay colours them (moving, waiting, idle), a click or the search field selects a
// robot and shows its panel, and the finished-actions curve grows as the run goes (issue 26:
// every robot blue, nothing selectable, no progress); a lifelong run's tasks (tasks.js, polled
// as they stream in) and the minimap as in the replay; when the run ended, the page reloads into
// the replay.
import { readMap } from './recording.js';
import { liveStatus } from './panel.js';
import { drawProgress } from './plot.js';
import { minimap } from './minimap.js';
import { TASK_MARKS, taskLayer, taskRows } from './tasks.js';
import { $, fetchJson, setRows, viewer } from './page.js';
import { COLORS, buildMap, buildRobots, onRobotClick, placeRobot, resize, robotsMoved, setLabel, showLegend,
         startLoop, viewTarget } from './view.js';

export const LIVE_LEGEND = [['moving', COLORS.moving], ['waiting', COLORS.waiting],
  ['idle (done, or between windows)', COLORS.idle], ['selected', COLORS.selected]];

// The panel of robot i from the newest event, and with its detail (GET /api/runs/{id}/robots/{i}:
// its actions and their Type-2 predecessors) and every robot's finished count, its current action
// and who it waits for now: the predecessors of its current action not finished yet.
export function liveRobotRows(ev, i, detail) {
  const [x, y, yaw] = ev.poses[i];
  const rows = [['id', `robot ${i}`], ['pose', `x ${x.toFixed(2)} m, y ${y.toFixed(2)} m`],
    ['heading', `heading ${(yaw * 180 / Math.PI).toFixed(0)}°`], ['status', `status: ${ev.status[i]}`],
    ['queue', `queue: ${ev.queue[i]}`]];
  if (!detail || detail.robot !== i || !ev.finished) return rows;
  const s = liveStatus(detail.steps, ev.finished[i], (robot) => ev.finished[robot]);
  return rows.concat([['progress', `finished: ${ev.finished[i]} / ${s.total}`],
    ['current', s.current < 0 ? 'current: none (done)' : `current: #${s.current} ${s.type}`],
    ['waits-now', `waits now for: ${s.waits.join(', ') || 'none'}`]]);
}

// The stats lines: the run, its time, progress and how many robots are in each state.
function showStats(id, ev) {
  const n = { moving: 0, waiting: 0, idle: 0 };
  for (const s of ev.status) n[s] = (n[s] || 0) + 1;
  const p = ev.progress;
  setRows($('stats'), [['', `${id}: ${ev.state} (live)`], ['', `robots: ${ev.poses.length}`],
    ['', p ? `actions: ${p.finished} / ${p.total}` : 'actions: none finished yet'],
    ['', `moving ${n.moving}, waiting ${n.waiting}, idle ${n.idle}`]]);
  $('clock').textContent = `${ev.t_s.toFixed(1)} s (live)`;
}

// A lifelong run's tasks at the newest event: markers, lines, finished tasks and throughput.
function showLiveTasks(tasks, ev) {
  tasks.update(ev.t_s, (i, out) => { out[0] = ev.poses[i][0]; out[1] = ev.poses[i][1]; });
  const { finished, lastMin } = tasks.throughputAt(ev.t_s);
  $('plot').hidden = false;
  drawProgress($('plot'), tasks.curve, ev.t_s, finished, 'tasks');
  setRows($('throughput'), [['finished', `tasks finished: ${finished}`], ['rate', `throughput: ${lastMin} tasks in the last minute`],
    ['open', `open tasks: ${tasks.open}, robots with a task: ${tasks.lines}`]]);
  viewer.tasks = { open: tasks.open, lines: tasks.lines, finished, lastMin };
}

export async function startLive(id) {
  const [, mapText] = await Promise.all([fetchJson(`/api/runs/${id}`), fetch(`/api/runs/${id}/map`).then((r) => r.text())]);
  const cell = 1;
  const map = readMap(mapText);
  buildMap(map, cell);
  resize();
  Object.assign(viewer, { live: true, liveEvents: 0 });
  showLegend(LIVE_LEGEND);
  const mini = minimap($('minimap'), map, cell);
  $('minimap').hidden = false;
  viewer.minimap = mini;
  let tasks = null, xy = new Float32Array(0), colors = new Uint32Array(0);
  // A lifelong run's tasks, polled while it goes (none: not a lifelong run). The layer is sized
  // for the fleet, so it waits for an event with the robots' poses (at 1x real time the first
  // events come before any state: a layer made then drew no robot's line, ever).
  const pollTasks = async () => {
    const d = await fetchJson(`/api/runs/${id}/tasks`).catch(() => null);
    if (d && last && last.poses.length) {
      if (!tasks) {
        tasks = taskLayer(d, map, cell, last.poses.length);
        $('throughput').hidden = false;
        showLegend(LIVE_LEGEND.concat([['errand (open)', TASK_MARKS.open], ['errand (assigned)', TASK_MARKS.assigned],
          ['robot to its next errand', TASK_MARKS.line]]));
      } else {
        tasks.setData(d);
      }
    }
    setTimeout(pollTasks, 1000);
  };
  pollTasks();
  let mesh = null, last = null, detail = null;
  const curve = { t_s: [], finished: [] };
  viewer.select = (i) => {
    if (!last || i < 0 || i >= last.poses.length) return false;
    if (viewer.selected !== i) {
      detail = null;
      fetchJson(`/api/runs/${id}/robots/${i}`).then((d) => { detail = d; }).catch(() => {});
    }
    viewer.selected = i;
    return true;
  };
  $('search').onchange = (e) => viewer.select(Number(e.target.value));
  onRobotClick(() => mesh, (i) => viewer.select(i));
  const source = new EventSource(`/api/runs/${id}/live`);
  source.onmessage = (e) => {
    const ev = JSON.parse(e.data);
    last = ev;
    if (!mesh && ev.poses.length) mesh = buildRobots(ev.poses.length, cell);
    ev.poses.forEach(([x, y, yaw], i) => placeRobot(mesh, i, x, y, yaw, COLORS[i === viewer.selected ? 'selected' : ev.status[i]]));
    if (mesh) robotsMoved(mesh);
    if (tasks) showLiveTasks(tasks, ev);
    if (xy.length !== 2 * ev.poses.length) { xy = new Float32Array(2 * ev.poses.length); colors = new Uint32Array(ev.poses.length); }
    ev.poses.forEach(([x, y], i) => { xy[2 * i] = x; xy[2 * i + 1] = y; colors[i] = COLORS[i === viewer.selected ? 'selected' : ev.status[i]]; });
    mini.draw(ev.poses.length, xy, colors, viewTarget());
    if (viewer.selected >= 0 && viewer.selected < ev.poses.length) {
      setRows($('robot'), liveRobotRows(ev, viewer.selected, detail).concat(tasks ? taskRows(tasks, viewer.selected, ev.t_s) : []));
      setLabel(`robot ${viewer.selected}`, ev.poses[viewer.selected][0], ev.poses[viewer.selected][1]);
    }
    if (ev.progress && ev.progress.finished !== curve.finished[curve.finished.length - 1]) {
      curve.t_s.push(ev.progress.t_s);
      curve.finished.push(ev.progress.finished);
    }
    if (curve.t_s.length && !tasks) {
      $('plot').hidden = false;
      drawProgress($('plot'), curve, ev.t_s, ev.progress.total);
    }
    showStats(id, ev);
    Object.assign(viewer, { liveEvents: viewer.liveEvents + 1, robots: ev.poses.length, liveStatus: ev.status, progress: ev.progress });
    if (ev.state === 'done' || ev.state === 'failed') { source.close(); location.reload(); }
  };
  startLoop();
}
