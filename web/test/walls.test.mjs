// web/src/walls.js: the rectangles cover every blocked cell exactly once and no free cell, and
// merge what they can (tiny maps, one per case; a random map checked cell by cell).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readMap } from '../src/recording.js';
import { wallBoxes } from '../src/walls.js';

const mapOf = (rows) => readMap(`type octile\nheight ${rows.length}\nwidth ${rows[0].length}\nmap\n${rows.join('\n')}\n`);
const boxes = (rows) => Array.from(wallBoxes(mapOf(rows)));

// Every cell's count of covering rectangles equals 1 if blocked, 0 if free.
function assertExactCover(map, b) {
  const cover = new Int32Array(map.width * map.height);
  for (let i = 0; i < b.length; i += 4) {
    for (let y = b[i + 1]; y < b[i + 1] + b[i + 3]; y++) for (let x = b[i]; x < b[i] + b[i + 2]; x++) cover[y * map.width + x]++;
  }
  for (let y = 0; y < map.height; y++) {
    for (let x = 0; x < map.width; x++) assert.equal(cover[y * map.width + x], map.blocked(x, y) ? 1 : 0, `cell (${x}, ${y})`);
  }
}

test('a block of walls is one box', () => assert.deepEqual(boxes(['.@@.', '.@@.', '....']), [1, 0, 2, 2]));
test('a free map has no box', () => assert.deepEqual(boxes(['...', '...']), []));
test('runs of different widths stay apart', () => assert.deepEqual(boxes(['@@.', '@..']), [0, 0, 2, 1, 0, 1, 1, 1]));
test('a run is merged only with the run right above it', () =>
  assert.deepEqual(boxes(['@@.', '...', '@@.']), [0, 0, 2, 1, 0, 2, 2, 1]));
test('T and O are walls as @ is', () => assert.deepEqual(boxes(['T@', 'O.']), [0, 0, 2, 1, 0, 1, 1, 1]));

test('a random map is covered exactly', () => {
  let seed = 7;
  const rand = () => { seed = (seed * 1103515245 + 12345) % 2147483648; return seed / 2147483648; };
  const rows = Array.from({ length: 40 }, () => Array.from({ length: 37 }, () => (rand() < 0.45 ? '@' : '.')).join(''));
  const map = mapOf(rows), b = wallBoxes(map);
  assertExactCover(map, b);
  let blocked = 0;
  for (const r of rows) for (const c of r) blocked += c === '@';
  assert.ok(b.length / 4 < blocked, `${b.length / 4} boxes for ${blocked} blocked cells`);
});
