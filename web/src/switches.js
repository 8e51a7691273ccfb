// A switchable run's switches of passing orders (issue 29) in the view, from
// GET /api/runs/{id}/switches (serve/src/server.cpp get_switches, read from switches.csv:
// monitor/include/smart/monitor/results_format.hpp SwitchRow). For SHOW_S seconds after each
// switch: a lime ring at the location, and a solid lime line from the robot that passed first to
// the robot planned first, the flipped Type-2 edge (the late robot now waits for it), unlike the
// dashed magenta and cyan Type-2 lines of the selected robot. Cells are MovingAI (x = column,
// y = row, .5 on an edge midpoint); drawn at x_w = x * cell, y_w = (height - 1 - y) * cell.
import * as THREE from 'three';
import { scene } from './view.js';

export const SWITCH_MARK = 0xc0ff00;  // lime: unlike the amber errands and the dashed Type-2 lines
export const SHOW_S = 3;

// Indices of the switches shown at t (t_s <= t < t_s + showS), in time order; `times` sorted.
export function shownAt(times, t, showS = SHOW_S) {
  let lo = 0, hi = times.length;
  while (lo < hi) {
    const mid = (lo + hi) >> 1;
    if (times[mid] <= t) lo = mid + 1; else hi = mid;
  }
  const out = [];
  for (let i = lo - 1; i >= 0 && times[i] > t - showS; i--) out.push(i);
  return out.reverse();
}

// The layer: update(t, f, poseOf) redraws when the switches shown or the frame change;
// `shown` lists them as {first, second, at: [x_w, y_w], from, to} (tests read it).
export function switchLayer(data, mapHeight, cell) {
  const ring = new THREE.RingGeometry(cell * 0.3, cell * 0.42, 24).rotateX(-Math.PI / 2);
  const ringMaterial = new THREE.MeshBasicMaterial({ color: SWITCH_MARK, depthTest: false });
  const lineMaterial = new THREE.LineBasicMaterial({ color: SWITCH_MARK, depthTest: false });
  const group = new THREE.Group();
  scene.add(group);
  const top = (mapHeight - 1) * cell, lift = cell * 0.8, a = new Float64Array(3), b = new Float64Array(3);
  let key = '';
  const layer = { count: data.t_s.length, shown: [] };
  layer.update = (t, f, poseOf) => {
    const ids = shownAt(data.t_s, t);
    const k = `${f}:${ids.join(',')}`;
    if (k === key) return;
    key = k;
    group.clear();
    const pts = [];
    layer.shown = ids.map((i) => {
      const at = [data.x[i] * cell, top - data.y[i] * cell];
      const mark = new THREE.Mesh(ring, ringMaterial);
      mark.position.set(at[0], lift, -at[1]);
      mark.renderOrder = 3;
      group.add(mark);
      poseOf(data.first[i], a);
      poseOf(data.second[i], b);
      pts.push(a[0], lift, -a[1], b[0], lift, -b[1]);
      return { first: data.first[i], second: data.second[i], at, from: [a[0], a[1]], to: [b[0], b[1]] };
    });
    if (pts.length) {
      const g = new THREE.BufferGeometry();
      g.setAttribute('position', new THREE.Float32BufferAttribute(pts, 3));
      const lines = new THREE.LineSegments(g, lineMaterial);
      lines.renderOrder = 3;
      group.add(lines);
    }
  };
  return layer;
}
