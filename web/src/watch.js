// Watch mode (`smart serve --watch`): every robot of the run live on the DDS domain (GET
// /api/watch/live), its status colour (watch_board.js), a click shows its panel; no map given:
// a floor under the robots.
import { readMap } from './recording.js';
import * as THREE from 'three';
import { WATCH_COLORS, extentOf, planRows, progressLine, robotPanel, runLabel, statusCounts } from './watch_board.js';
import { $, fetchJson, setRows, viewer } from './page.js';
import { MARKS, buildMap, buildRobots, onRobotClick, placeRobot, resize, robotsMoved, scene, setLabel, showLegend,
         startLoop } from './view.js';

let totalActions = 0;  // the plan's, when --watch --plan gave one
function showStats(ev) {
  const n = statusCounts(ev.robots), m = ev.monitor;
  const run = ev.run_id ? ev.name || `run ${ev.run_id}` : '(none yet)';
  setRows($('stats'), [['', `watching ${run}`],
    ['', `monitor: ${m ? `${m.host} pid ${m.pid}` : 'not seen'}`], ['', `robots: ${ev.robots.length}`],
    ['', `moving ${n.moving}, waiting ${n.waiting}, idle ${n.idle}, stale ${n.stale}`],
    ['progress', progressLine(ev.robots, totalActions)],
    ['', `dropped samples: ${ev.rejected_samples}`]]);
  $('clock').textContent = `${ev.t_s.toFixed(1)} s (live)`;
}

// Every run live on the domain, to pick from (issue 26: only the newest could be watched).
function showRuns(ev) {
  const pick = $('live-runs');
  pick.hidden = false;
  const ids = ev.runs.map((r) => String(r.run_id));
  if (ids.join() !== [...pick.options].map((o) => o.value).join()) {
    pick.replaceChildren(...ev.runs.map((r) => new Option('', String(r.run_id))));
  }
  ev.runs.forEach((r, i) => { pick.options[i].text = runLabel(r); });
  pick.value = String(ev.run_id);
}

export async function startWatch(runId) {
  const first = await fetchJson('/api/watch');
  const cell = first.cell_m || 1;
  totalActions = first.total_actions || 0;
  let detail = null, path = null;
  // The selected robot's planned path, with the plan (GET /api/watch/robots/{id}).
  const showPath = (id) => {
    detail = null;
    if (path) scene.remove(path);
    if (!totalActions) return;
    fetchJson(`/api/watch/robots/${id}`).then((d) => {
      detail = d;
      const pts = d.path.map(([x, y]) => new THREE.Vector3(x, cell * 0.05, -y));
      path = new THREE.Line(new THREE.BufferGeometry().setFromPoints(pts), new THREE.LineBasicMaterial({ color: MARKS.path }));
      scene.add(path);
      viewer.watchPath = pts.length;
    }).catch(() => {});
  };
  const mapResp = await fetch('/api/watch/map');
  if (mapResp.ok) buildMap(readMap(await mapResp.text()), cell);
  resize();
  Object.assign(viewer, { live: true, watch: true, liveEvents: 0 });
  showLegend(Object.entries(WATCH_COLORS).map(([name, hex]) => [name === 'idle' ? 'idle (done, or between windows)' : name, hex]));
  let framed = mapResp.ok, ids = [], mesh = null;
  const source = new EventSource(`/api/watch/live${runId ? `?run_id=${runId}` : ''}`);
  source.onmessage = (e) => {
    const ev = JSON.parse(e.data);
    if (!framed && ev.robots.length) {
      const x = extentOf(ev.robots, 2 * cell), cells = (v) => Math.ceil(v / cell);
      buildMap({ width: cells(x.maxX - x.minX), height: cells(x.maxY - x.minY), blocked: () => false }, cell);
      framed = true;
    }
    if (!mesh || mesh.count !== ev.robots.length) {
      if (mesh) scene.remove(mesh);
      mesh = ev.robots.length ? buildRobots(ev.robots.length, cell) : null;
    }
    ids = ev.robots.map((r) => r.id);
    ev.robots.forEach((r, i) => placeRobot(mesh, i, r.x_m, r.y_m, r.yaw_rad,
      r.id === viewer.selected ? WATCH_COLORS.selected : WATCH_COLORS[r.status]));
    if (mesh) robotsMoved(mesh);
    const picked = ev.robots.find((r) => r.id === viewer.selected);
    if (picked) {
      setRows($('robot'), robotPanel(picked).concat(planRows(picked, detail, ev.robots)));
      setLabel(`robot ${picked.id}`, picked.x_m, picked.y_m);
    }
    showStats(ev);
    showRuns(ev);
    Object.assign(viewer, { robots: ev.robots.length, runId: ev.run_id, runName: ev.name, runs: ev.runs,
                            watched: ev.robots, liveEvents: viewer.liveEvents + 1 });
  };
  viewer.select = (id) => {
    if (id !== viewer.selected) showPath(id);
    viewer.selected = id;
    return ids.includes(id);
  };
  $('live-runs').onchange = (e) => { location.search = `?watch&run_id=${e.target.value}`; };
  $('search').onchange = (e) => viewer.select(Number(e.target.value));
  onRobotClick(() => mesh, (i) => viewer.select(ids[i]));
  startLoop();
  viewer.ready = true;
}
