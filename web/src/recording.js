// Reads the SMRC recording (serve/include/smart/serve/recording.hpp): fixed-size frames of
// quantized poses, decoded on demand so a 1000-robot run loads without a copy per frame.
export function readRecording(buffer) {
  const view = new DataView(buffer);
  const magic = String.fromCharCode(...new Uint8Array(buffer, 0, 4));
  if (magic !== 'SMRC' || view.getUint32(4, true) !== 1) throw new Error('not an SMRC v1 recording');
  const robots = view.getUint32(8, true);
  const frames = view.getUint32(12, true);
  const minX = view.getFloat64(16, true);
  const minY = view.getFloat64(24, true);
  const quantum = view.getFloat64(32, true);
  const header = 40;
  const stride = 4 + robots * 6;
  if (buffer.byteLength !== header + frames * stride) throw new Error('recording size mismatch');
  const times = new Float32Array(frames);
  for (let f = 0; f < frames; f++) times[f] = view.getFloat32(header + f * stride, true);
  // Pose of `robot` in frame `f`: [x_m, y_m, yaw_rad] in the world frame.
  function pose(f, robot, out) {
    const at = header + f * stride + 4 + robot * 6;
    out[0] = minX + view.getUint16(at, true) * quantum;
    out[1] = minY + view.getUint16(at + 2, true) * quantum;
    out[2] = view.getInt16(at + 4, true) * 1e-4;
    return out;
  }
  // Last frame index whose time is <= t (binary search).
  function frameAt(t) {
    let lo = 0, hi = frames - 1;
    while (lo < hi) {
      const mid = (lo + hi + 1) >> 1;
      if (times[mid] <= t) lo = mid; else hi = mid - 1;
    }
    return lo;
  }
  return { robots, frames, times, pose, frameAt };
}

// MovingAI map text -> { width, height, blocked(x, y) } (x = column, y = row).
export function readMap(text) {
  const lines = text.split(/\r?\n/);
  let width = 0, height = 0, at = 0;
  for (; at < lines.length; at++) {
    const [key, value] = lines[at].trim().split(/\s+/);
    if (key === 'width') width = Number(value);
    if (key === 'height') height = Number(value);
    if (key === 'map') { at++; break; }
  }
  const rows = lines.slice(at, at + height);
  const free = new Set(['.', 'G', 'S']);
  return { width, height, blocked: (x, y) => !free.has((rows[y] || '')[x] || '@') };
}
