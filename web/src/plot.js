// Finished actions over time (GET /api/runs/{id}/progress) as a step curve on a canvas, with a
// marker at the replay's time. Plain 2D canvas: a few hundred points need no chart library.
export function drawProgress(canvas, curve, t, total) {
  const ctx = canvas.getContext('2d');
  const w = canvas.width, h = canvas.height, pad = 4;
  ctx.clearRect(0, 0, w, h);
  ctx.fillStyle = '#2a2f37';
  ctx.fillRect(0, 0, w, h);
  const ts = curve.t_s, ns = curve.finished;
  if (!ts.length) return;
  const tMax = ts[ts.length - 1] || 1, nMax = Math.max(total || 0, ns[ns.length - 1], 1);
  const x = (s) => pad + (s / tMax) * (w - 2 * pad), y = (n) => h - pad - (n / nMax) * (h - 2 * pad);
  ctx.strokeStyle = '#3cb371';
  ctx.lineWidth = 1.5;
  ctx.beginPath();
  ctx.moveTo(x(0), y(0));
  ts.forEach((s, i) => { ctx.lineTo(x(s), y(i ? ns[i - 1] : 0)); ctx.lineTo(x(s), y(ns[i])); });
  ctx.stroke();
  ctx.strokeStyle = '#ff3b30';
  ctx.beginPath();
  ctx.moveTo(x(Math.min(t, tMax)), pad);
  ctx.lineTo(x(Math.min(t, tMax)), h - pad);
  ctx.stroke();
}

// Finished actions at time t from the curve (the last point at or before t).
export function finishedAt(curve, t) {
  let n = 0;
  for (let i = 0; i < curve.t_s.length && curve.t_s[i] <= t; i++) n = curve.finished[i];
  return n;
}
