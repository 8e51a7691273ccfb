// Live mode: a run of this server still going; its map, and every robot's newest pose from the
// live stream (Server-Sent Events, GET /api/runs/{id}/live, about 4 a second); when it ended,
// the page reloads into the replay.
import { readMap } from './recording.js';
import { $, fetchJson, viewer } from './page.js';
import { buildMap, buildRobots, placeRobot, resize, robotsMoved, startLoop } from './view.js';

export async function startLive(id) {
  const [run, mapText] = await Promise.all([fetchJson(`/api/runs/${id}`), fetch(`/api/runs/${id}/map`).then((r) => r.text())]);
  const cell = 1;
  buildMap(readMap(mapText), cell);
  resize();
  Object.assign(viewer, { live: true, liveEvents: 0 });
  $('stats').textContent = `${id}: ${run.state} (live)`;
  let mesh = null;
  const source = new EventSource(`/api/runs/${id}/live`);
  source.onmessage = (e) => {
    const ev = JSON.parse(e.data);
    if (!mesh && ev.poses.length) mesh = buildRobots(ev.poses.length, cell);
    ev.poses.forEach(([x, y, yaw], i) => placeRobot(mesh, i, x, y, yaw));
    if (mesh) robotsMoved(mesh);
    viewer.liveEvents++;
    viewer.robots = ev.poses.length;
    $('clock').textContent = `${ev.t_s.toFixed(1)} s (live)`;
    $('stats').textContent = `${id}: ${ev.state} (live)`;
    if (ev.state === 'done' || ev.state === 'failed') { source.close(); location.reload(); }
  };
  startLoop();
}
