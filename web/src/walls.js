// The map's walls as few boxes (issue 28): blocked cells merged into rectangles, so a LoRR map
// of 1800 x 1912 cells (1.2 million blocked) is drawn as about 10 000 boxes instead of one box
// per cell (15 million triangles a frame, which kept a software-rendered view at a frame every
// few seconds). Pure: map in (readMap's shape), rectangles out; view.js draws them.
//
// Greedy, row by row: each row's runs of blocked cells; a run that spans exactly the columns of
// a rectangle still open from the row above extends it downwards, any other run opens a new one.
// The rectangles cover every blocked cell once and no free cell.

// map: { width, height, blocked(x, y) } -> Int32Array of (x, y, w, h) per rectangle, x = column
// and y = row of its top-left cell (MovingAI).
export function wallBoxes(map) {
  const out = [];
  let open = new Map();  // x0 -> index in out of the rectangle ending on the row above, x1 checked
  for (let y = 0; y < map.height; y++) {
    const next = new Map();
    for (let x = 0; x < map.width;) {
      if (!map.blocked(x, y)) { x++; continue; }
      const x0 = x;
      while (x < map.width && map.blocked(x, y)) x++;
      const above = open.get(x0);
      if (above !== undefined && out[above + 2] === x - x0) {
        out[above + 3]++;
        next.set(x0, above);
      } else {
        next.set(x0, out.length);
        out.push(x0, y, x - x0, 1);
      }
    }
    open = next;
  }
  return Int32Array.from(out);
}
