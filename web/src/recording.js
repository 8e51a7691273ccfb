// Reads the SMRC recording (serve/include/smart/serve/recording.hpp, version 2): fixed-size
// frames of quantized poses and queue lengths, decoded on demand so a 1000-robot run loads
// without a copy per frame. A prefix of the file (a range request) reads as the frames it holds
// (`complete` false), so the first frame can be drawn before the rest arrived.
export const HEADER_BYTES = 40;
export const ROBOT_BYTES = 7;

export function readRecording(buffer) {
  const view = new DataView(buffer);
  if (buffer.byteLength < HEADER_BYTES) throw new Error('recording is truncated');
  const magic = String.fromCharCode(...new Uint8Array(buffer, 0, 4));
  if (magic !== 'SMRC' || view.getUint32(4, true) !== 2) throw new Error('not an SMRC v2 recording');
  const robots = view.getUint32(8, true);
  const total = view.getUint32(12, true);
  const minX = view.getFloat64(16, true);
  const minY = view.getFloat64(24, true);
  const quantum = view.getFloat64(32, true);
  const stride = 4 + robots * ROBOT_BYTES;
  const size = HEADER_BYTES + total * stride;
  if (buffer.byteLength > size) throw new Error('recording size mismatch');
  const frames = Math.floor((buffer.byteLength - HEADER_BYTES) / stride);
  const times = new Float32Array(frames);
  for (let f = 0; f < frames; f++) times[f] = view.getFloat32(HEADER_BYTES + f * stride, true);
  // Pose of `robot` in frame `f`: [x_m, y_m, yaw_rad] in the world frame.
  function pose(f, robot, out) {
    const at = HEADER_BYTES + f * stride + 4 + robot * ROBOT_BYTES;
    out[0] = minX + view.getUint16(at, true) * quantum;
    out[1] = minY + view.getUint16(at + 2, true) * quantum;
    out[2] = view.getInt16(at + 4, true) * 1e-4;
    return out;
  }
  // Queue length of `robot` in frame `f` (actions sent to it, not finished; 255 = 255 or more).
  const queue = (f, robot) => view.getUint8(HEADER_BYTES + f * stride + 4 + robot * ROBOT_BYTES + 6);
  // Last frame index whose time is <= t (binary search).
  function frameAt(t) {
    let lo = 0, hi = frames - 1;
    while (lo < hi) {
      const mid = (lo + hi + 1) >> 1;
      if (times[mid] <= t) lo = mid; else hi = mid - 1;
    }
    return lo;
  }
  return { robots, frames, times, pose, queue, frameAt, complete: frames === total, size };
}

// Bytes needed for the header and the first frame of a recording of `robots` robots.
export const firstFrameBytes = (robots) => HEADER_BYTES + 4 + robots * ROBOT_BYTES;

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
