// The watch board (pure): whatever run is live on the DDS domain (`smart serve --watch`, GET
// /api/watch/live), simulated and physical robots alike, read-only. Robots are drawn in the
// order the server lists them (by id; ids may have gaps in a mixed run).
import { liveStatus } from './panel.js';

// Statuses (serve/include/smart/serve/watch_board.hpp): moving = executing an action, waiting =
// actions queued but none executing, idle = nothing queued; the replay's colours for the same.
export const WATCH_COLORS = { moving: 0x3d8bfd, waiting: 0xf0a030, idle: 0x3cb371, stale: 0x777777, selected: 0xff3b30 };

// Counts of robots per status, for the stats panel.
export function statusCounts(robots) {
  const n = { moving: 0, waiting: 0, idle: 0, stale: 0 };
  for (const r of robots) n[r.status] = (n[r.status] || 0) + 1;
  return n;
}

// The world rectangle the robots stand in (for a floor when no map was given), with a margin.
export function extentOf(robots, margin) {
  const xs = robots.map((r) => r.x_m), ys = robots.map((r) => r.y_m);
  return { minX: Math.min(...xs) - margin, maxX: Math.max(...xs) + margin,
           minY: Math.min(...ys) - margin, maxY: Math.max(...ys) + margin };
}

// The live runs to pick from: the name its monitor announced, else its id.
export function runLabel(run) {
  return `${run.name || `run ${run.run_id}`} (${run.robots} robots, heard ${run.heard_s_ago.toFixed(0)} s ago)`;
}

// With the run's plan (--watch --plan): a robot's current action and whom it waits for now,
// from its actions' Type-2 predecessors (detail.steps[k].in: [robot, action, ...]) and every
// robot's finished_seq (finished count = finished_seq + 1).
export function planRows(r, detail, robots) {
  if (!detail || detail.robot !== r.id) return [];
  const finished = new Map(robots.map((x) => [x.id, x.finished_seq + 1]));
  const s = liveStatus(detail.steps, r.finished_seq + 1, (robot) => finished.get(robot) ?? 0);
  return [['current', s.current < 0 ? 'current: none (done)' : `current: #${s.current} ${s.type} of ${s.total}`],
    ['waits-now', `waits now for: ${s.waits.join(', ') || 'none'}`]];
}

// Finished actions of the run: every robot's count (with the plan, out of its total).
export function progressLine(robots, total) {
  const done = robots.reduce((n, r) => n + r.finished_seq + 1, 0);
  return total ? `actions: ${done} / ${total}` : `actions finished: ${done}`;
}

export function robotPanel(r) {
  return [['id', `robot ${r.id}`], ['pose', `x ${r.x_m.toFixed(2)} m, y ${r.y_m.toFixed(2)} m`],
    ['heading', `heading ${(r.yaw_rad * 180 / Math.PI).toFixed(0)}°`], ['status', `status: ${r.status}`],
    ['speed', `speed: ${r.linear_mps.toFixed(2)} m/s`], ['queue', `queue: ${r.queue}`],
    ['finished', `finished actions: ${r.finished_seq + 1}`],
    ['current', r.executing_seq >= 0 ? `executing: #${r.executing_seq}` : 'executing: nothing']];
}
