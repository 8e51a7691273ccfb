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

// Shows rows of text in an element (<div class="cls">text</div> each), never markup: what the
// server or the network says (a host name, an uploaded summary) is displayed, never run (issue
// 25). rows: [cls, text] pairs; cls may be ''.
export function setRows(el, rows) {
  el.replaceChildren(...rows.map(([cls, text]) => {
    const div = document.createElement('div');
    if (cls) div.className = cls;
    div.textContent = String(text);
    return div;
  }));
}

// The server's token for uploads, from the page's address (#token=...), kept for the session.
export function authHeaders() {
  const m = location.hash.match(/token=([^&]+)/);
  if (m) sessionStorage.setItem('smartToken', decodeURIComponent(m[1]));
  const token = sessionStorage.getItem('smartToken');
  return token ? { Authorization: `Bearer ${token}` } : {};
}
