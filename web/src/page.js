// The page's shared pieces: element lookup, the state tests read (window.__viewer), JSON fetches.
export const $ = (id) => document.getElementById(id);

// What the browser tests read and drive: ready, robots, selected, poses, timings, error.
export const viewer = { ready: false, robots: 0, selected: -1, frameTimeMs: 0, t: 0, error: '' };
viewer.select = () => false;  // each mode puts its own
window.__viewer = viewer;

export async function fetchJson(url) {
  const r = await fetch(url);
  if (!r.ok) throw new Error(`${url}: HTTP ${r.status}`);
  return r.json();
}
