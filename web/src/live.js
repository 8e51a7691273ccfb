// Live mode: a run of this server still going; its map, and every robot's newest state from the
// live stream (Server-Sent Events, GET /api/runs/{id}/live, about 4 a second), coloured by state
// as the replay colours them (moving, waiting, idle), a click or the search field selects a
// robot and shows its panel, and the finished-actions curve grows as the run goes (issue 26:
// every robot blue, nothing selectable, no progress); when the run ended, the page reloads into
// the replay.
import { readMap } from './recording.js';
import { liveStatus } from './panel.js';
import { drawProgress } from './plot.js';
import { $, fetchJson, setRows, viewer } from './page.js';
import { COLORS, buildMap, buildRobots, onRobotClick, placeRobot, resize, robotsMoved, setLabel, showLegend,
         startLoop } from './view.js';

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

export async function startLive(id) {
  const [, mapText] = await Promise.all([fetchJson(`/api/runs/${id}`), fetch(`/api/runs/${id}/map`).then((r) => r.text())]);
  const cell = 1;
  buildMap(readMap(mapText), cell);
  resize();
  Object.assign(viewer, { live: true, liveEvents: 0 });
  showLegend(LIVE_LEGEND);
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
    if (viewer.selected >= 0 && viewer.selected < ev.poses.length) {
      setRows($('robot'), liveRobotRows(ev, viewer.selected, detail));
      setLabel(`robot ${viewer.selected}`, ev.poses[viewer.selected][0], ev.poses[viewer.selected][1]);
    }
    if (ev.progress && ev.progress.finished !== curve.finished[curve.finished.length - 1]) {
      curve.t_s.push(ev.progress.t_s);
      curve.finished.push(ev.progress.finished);
    }
    if (curve.t_s.length) {
      $('plot').hidden = false;
      drawProgress($('plot'), curve, ev.t_s, ev.progress.total);
    }
    showStats(id, ev);
    Object.assign(viewer, { liveEvents: viewer.liveEvents + 1, robots: ev.poses.length, liveStatus: ev.status, progress: ev.progress });
    if (ev.state === 'done' || ev.state === 'failed') { source.close(); location.reload(); }
  };
  startLoop();
}
