// Finished actions over time (GET /api/runs/{id}/progress, or a live run's progress; a lifelong
// run's finished tasks, tasks.js) as a step
// curve on a canvas, with axes (sim seconds, actions; issue 26: the plot had none), tick labels
// at round numbers, and a marker at the view's time. Plain 2D canvas: a few hundred points need
// no chart library.

// Round tick values from 0 to max: 1, 2 or 5 times a power of ten apart, at most `most` of them.
export function ticks(max, most = 4) {
  if (!(max > 0)) return [0];
  const raw = max / most, p = 10 ** Math.floor(Math.log10(raw));
  const step = [1, 2, 5, 10].map((k) => k * p).find((s) => s >= raw);
  const out = [];
  for (let v = 0; v <= max + 1e-9; v += step) out.push(Number(v.toPrecision(12)));
  return out;
}

// label: what the curve counts ('actions'; a lifelong run's 'tasks').
export function drawProgress(canvas, curve, t, total, label = 'actions') {
  const ctx = canvas.getContext('2d');
  const w = canvas.width, h = canvas.height;
  const left = 42, right = 6, top = 6, bottom = 26;
  ctx.clearRect(0, 0, w, h);
  ctx.fillStyle = '#2a2f37';
  ctx.fillRect(0, 0, w, h);
  const ts = curve.t_s, ns = curve.finished;
  const tMax = Math.max(ts.length ? ts[ts.length - 1] : 0, t, 1e-9);
  const nMax = Math.max(total || 0, ns.length ? ns[ns.length - 1] : 0, 1);
  const x = (s) => left + (s / tMax) * (w - left - right), y = (n) => h - bottom - (n / nMax) * (h - top - bottom);
  // Axes, ticks and labels.
  ctx.strokeStyle = '#8a8f98';
  ctx.fillStyle = '#c8ccd2';
  ctx.font = '10px system-ui, sans-serif';
  ctx.lineWidth = 1;
  ctx.beginPath();
  ctx.moveTo(left, top);
  ctx.lineTo(left, h - bottom);
  ctx.lineTo(w - right, h - bottom);
  ctx.stroke();
  ctx.textAlign = 'center';
  ctx.textBaseline = 'top';
  for (const v of ticks(tMax)) ctx.fillText(String(v), x(v), h - bottom + 3);
  ctx.fillText('sim time (s)', left + (w - left - right) / 2, h - 12);
  ctx.textAlign = 'right';
  ctx.textBaseline = 'middle';
  for (const v of ticks(nMax, 3)) ctx.fillText(String(v), left - 3, y(v));
  ctx.save();
  ctx.translate(9, top + (h - top - bottom) / 2);
  ctx.rotate(-Math.PI / 2);
  ctx.textAlign = 'center';
  ctx.fillText(label, 0, 0);
  ctx.restore();
  // The curve and the time marker.
  if (ts.length) {
    ctx.strokeStyle = '#3cb371';
    ctx.lineWidth = 1.5;
    ctx.beginPath();
    ctx.moveTo(x(0), y(0));
    ts.forEach((s, i) => { ctx.lineTo(x(s), y(i ? ns[i - 1] : 0)); ctx.lineTo(x(s), y(ns[i])); });
    ctx.stroke();
  }
  ctx.strokeStyle = '#ff3b30';
  ctx.beginPath();
  ctx.moveTo(x(Math.min(t, tMax)), top);
  ctx.lineTo(x(Math.min(t, tMax)), h - bottom);
  ctx.stroke();
  canvas.dataset.xTicks = ticks(tMax).join(',');
  canvas.dataset.yTicks = ticks(nMax, 3).join(',');
}

// Finished actions at time t from the curve (the last point at or before t).
export function finishedAt(curve, t) {
  let n = 0;
  for (let i = 0; i < curve.t_s.length && curve.t_s[i] <= t; i++) n = curve.finished[i];
  return n;
}
