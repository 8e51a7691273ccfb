// The minimap (issue 28, PlanViz users on huge maps): the whole map in the side panel, walls
// drawn once, every robot a dot in its state's colour, the camera's target as a cross; a click
// moves the view there. The canvas keeps its size (228 px) whatever the map's: a pixel covers
// 1/f cells (f < 1 on maps larger than the canvas, sampled once), and 10 000 dots cost one
// putImageData. Redrawn at most every kRefreshMs, so it never holds up a frame.
import { lookAt } from './view.js';

const kRefreshMs = 100;

// map: readMap's shape; cell: metres per cell; canvas: the minimap's <canvas>.
export function minimap(canvas, map, cell) {
  const box = Math.max(canvas.width, canvas.height, 64);
  const f = Math.min(box / map.width, box / map.height);  // pixels per cell
  const scale = f >= 1 ? Math.floor(f) : f;
  const w = Math.max(1, Math.round(map.width * scale)), h = Math.max(1, Math.round(map.height * scale));
  canvas.width = w;
  canvas.height = h;
  const g = canvas.getContext('2d');
  const image = g.createImageData(w, h);
  const walls = new Uint8ClampedArray(w * h * 4);
  for (let py = 0; py < h; py++) {
    for (let px = 0; px < w; px++) {
      const blocked = map.blocked(Math.min(map.width - 1, Math.floor(px / scale)),
                                  Math.min(map.height - 1, Math.floor(py / scale)));
      const o = (py * w + px) * 4;
      walls[o] = blocked ? 138 : 42; walls[o + 1] = blocked ? 143 : 47; walls[o + 2] = blocked ? 152 : 55;
      walls[o + 3] = 255;
    }
  }
  const dot = Math.max(1, Math.min(4, Math.round(scale * 0.6))), half = Math.floor(dot / 2);  // px
  let last = -Infinity;
  const m = { dots: 0, size: { w, h, scale } };
  const toPx = (x_m, y_m) => [Math.floor((x_m / cell + 0.5) * scale), Math.floor((map.height - 0.5 - y_m / cell) * scale)];
  // Robot i at (xy[2i], xy[2i + 1]) metres in colour colors[i] (0xRRGGBB); target: [x_m, y_m]
  // of the view's centre.
  m.draw = (robots, xy, colors, target, force = false) => {
    const now = performance.now();
    if (!force && now - last < kRefreshMs) return;
    last = now;
    const d = image.data;
    d.set(walls);
    const put = (px, py, c) => {
      if (px < 0 || py < 0 || px >= w || py >= h) return;
      const o = (py * w + px) * 4;
      d[o] = (c >> 16) & 255; d[o + 1] = (c >> 8) & 255; d[o + 2] = c & 255;
    };
    for (let i = 0; i < robots; i++) {
      const px = Math.floor((xy[2 * i] / cell + 0.5) * scale) - half;
      const py = Math.floor((map.height - 0.5 - xy[2 * i + 1] / cell) * scale) - half;
      const c = colors[i];
      for (let dy = 0; dy < dot; dy++) for (let dx = 0; dx < dot; dx++) put(px + dx, py + dy, c);
    }
    const [tx, ty] = toPx(target[0], target[1]);
    for (let k = -4; k <= 4; k++) { put(tx + k, ty, 0xff3b30); put(tx, ty + k, 0xff3b30); }
    g.putImageData(image, 0, 0);
    m.dots = robots;
  };
  // A click moves the view to that point of the map.
  canvas.addEventListener('click', (e) => {
    const r = canvas.getBoundingClientRect();
    const x = ((e.clientX - r.left) / r.width) * map.width, y = ((e.clientY - r.top) / r.height) * map.height;
    lookAt((x - 0.5) * cell, (map.height - 1 - (y - 0.5)) * cell);
    last = -Infinity;
  });
  return m;
}
