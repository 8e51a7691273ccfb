// The SMART-DDS viewer, served by `smart serve`: picks the mode from the URL and the server's
// runs: ?watch (or a server with --watch and nothing asked) watches the DDS domain (watch.js),
// ?run=ID of a queued or running run shows it live (live.js), any other run is replayed
// (replay.js; default: the newest finished run). The 3D view all modes share is view.js.
import { $, fetchJson, viewer } from './page.js';
import { startLive } from './live.js';
import { startReplay } from './replay.js';
import { wireUpload } from './upload.js';
import { startWatch } from './watch.js';

async function start() {
  wireUpload();
  const params = new URLSearchParams(location.search);
  const [watching, runs] = await Promise.all([fetch('/api/watch').then((r) => r.ok), fetchJson('/api/runs')]);
  const want = params.has('watch') ? 'watch' : params.get('run') || (runs.filter((r) => r.state === 'done').pop() || {}).id;
  if (watching) $('runs').add(new Option('live on the DDS domain (watch)', 'watch', false, want === 'watch' || !want));
  for (const r of runs) $('runs').add(new Option(`${r.id} ${r.map} (${r.state})`, r.id, false, r.id === want));
  $('runs').onchange = (e) => { location.search = e.target.value === 'watch' ? '?watch' : `?run=${e.target.value}`; };
  if (watching && (want === 'watch' || !want)) return startWatch(params.get('run_id'));
  if (!want) throw new Error('no finished run to show yet; upload one with POST /api/runs');
  const chosen = runs.find((r) => r.id === want);
  if (chosen && (chosen.state === 'queued' || chosen.state === 'running')) return startLive(want);
  return startReplay(want);
}

start().catch((e) => { viewer.error = String(e); $('stats').textContent = String(e); });
