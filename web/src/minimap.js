// The minimap (issue 28, PlanViz users on huge maps): the whole map in the side panel, walls
// drawn once, every robot a dot in its state's colour, the camera's target as a cross; a click
// moves the view there. Drawn into one ImageData per refresh (10 000 dots cost one putImageData),
// at most every kRefreshMs, so it never holds up a frame.
import { lookAt } from './view.js';

const kRefreshMs = 100;

// map: readMap's shape; cell: metres per cell; canvas: the minimap's <canvas>.
export function minimap(canvas, map, cell) {
  const scale = Math.max(1, Math.floor(Math.min(canvas.width / map.width, canvas.height / map.height)));
  const w = map.width * scale, h = map.height * scale;
  canvas.width = w;
  canvas.height = h;
  const g = canvas.getContext('2d');
  const image = g.createImageData(w, h);
  const walls = new Uint8ClampedArray(w * h * 4);
  for (let y = 0; y < map.height; y++) {
    for (let x = 0; x < map.width; x++) {
      const v = map.blocked(x, y) ? [138, 143, 152] : [42, 47, 55];
      for (let dy = 0; dy < scale; dy++) {
        for (let dx = 0; dx < scale; dx++) walls.set([...v, 255], (((y * scale + dy) * w) + x * scale + dx) * 4);
      }
    }
  }
  const dot = Math.max(1, Math.min(4, Math.round(scale * 0.6))), half = Math.floor(dot / 2);  // px
  let last = -Infinity;
  const m = { dots: 0 };
  // Robot i's pose (x_m, y_m) by poseOf(i, out) and its colour by colorOf(i) (0xRRGGBB);
  // target: [x_m, y_m] of the view's centre.
  m.draw = (robots, poseOf, colorOf, target, force = false) => {
    const now = performance.now();
    if (!force && now - last < kRefreshMs) return;
    last = now;
    image.data.set(walls);
    const p = new Float64Array(3), d = image.data;
    const put = (px, py, c) => {
      if (px < 0 || py < 0 || px >= w || py >= h) return;
      const o = (py * w + px) * 4;
      d[o] = (c >> 16) & 255; d[o + 1] = (c >> 8) & 255; d[o + 2] = c & 255; d[o + 3] = 255;
    };
    const toPx = (x_m, y_m) => [Math.round((x_m / cell) * scale + scale / 2 - 0.5),
      Math.round((map.height - 1 - y_m / cell) * scale + scale / 2 - 0.5)];
    for (let i = 0; i < robots; i++) {
      poseOf(i, p);
      const [px, py] = toPx(p[0], p[1]), c = colorOf(i);
      for (let dy = 0; dy < dot; dy++) for (let dx = 0; dx < dot; dx++) put(px + dx - half, py + dy - half, c);
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
  m.size = { w, h, scale };
  return m;
}
