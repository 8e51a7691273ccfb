// The upload forms: a new run (POST /api/runs) or a results folder to replay (POST
// /api/results); problems are listed as `smart check-plan` prints them; an accepted upload is
// shown (a new run live until it ended, then replayed).
import { $, authHeaders, fetchJson } from './page.js';

// A folder's files keep their paths inside it (webkitRelativePath: the problem JSON names its map,
// agents and tasks files relative to itself); the server checks each path.
const pathOf = (file) => file.webkitRelativePath || file.name;

function formData(form) {
  const data = new FormData($(form));
  const folder = $(form).querySelector('input[webkitdirectory]');
  if (folder && !folder.disabled) for (const f of folder.files) data.append('folder', f, pathOf(f));
  return data;
}

function wireForm(form, url, status, problems) {
  $(form).onsubmit = async (e) => {
    e.preventDefault();
    $(problems).replaceChildren();
    $(status).textContent = 'uploading...';
    const r = await fetch(url, { method: 'POST', body: formData(form), headers: authHeaders() });
    const body = await r.json();
    if (!r.ok) {
      $(status).textContent = body.error;
      for (const p of body.problems || []) {
        const li = document.createElement('li');
        li.textContent = `${p.file}:${p.line}${p.robot >= 0 ? ` robot ${p.robot}` : ''}: ${p.message}`;
        $(problems).appendChild(li);
      }
      return;
    }
    location.search = `?run=${body.id}`;
  };
}

// Kinodynamic sliders: they start at the chosen model's limits (GET /api/robots); moving one
// writes its number field, which the upload sends (empty: the model's own value).
async function wireSliders() {
  const models = await fetchJson('/api/robots').catch(() => []);
  if (!models.length) return;
  $('up-robot').replaceChildren();
  for (const m of models) $('up-robot').add(new Option(m.name, m.name, false, m.name === 'footbot'));
  const field = (key) => $('upload').querySelector(`input[name=${key}]`);
  // Each slider spans up to twice the model's own limit (issue 26: they stopped at 3 m/s for a
  // 5 m/s model), in steps of 1 % of it; the limit itself is shown beside the field.
  const reset = () => {
    const m = models.find((x) => x.name === $('up-robot').value) || models[0];
    for (const s of document.querySelectorAll('#upload .slider')) {
      const own = m[s.dataset.for];
      Object.assign(s, { min: String(own / 100), max: String(2 * own), step: String(own / 100) });
      s.value = own;
      field(s.dataset.for).value = '';
      field(s.dataset.for).placeholder = `model's: ${own}`;
    }
  };
  for (const s of document.querySelectorAll('#upload .slider')) s.oninput = () => { field(s.dataset.for).value = s.value; };
  $('up-robot').onchange = reset;
  reset();
}

// The run's kind: a plan needs its scen and plan files; a lifelong run (issue 28) a map, its
// fleet size and task settings (POST /api/runs kind=lifelong: `smart run --tasks random`), or a
// LoRR problem folder (kind=lorr: `smart run --lifelong`). The fields of other kinds are hidden
// and disabled (not sent, not required).
function wireKind() {
  const show = () => {
    const kind = $('up-kind').value;
    for (const el of document.querySelectorAll('#upload [data-kinds]')) {
      const mine = el.dataset.kinds.split(' ').includes(kind);
      el.hidden = !mine;
      for (const input of el.querySelectorAll('input, select')) input.disabled = !mine;
    }
  };
  $('up-kind').onchange = show;
  show();
}

// The folder's problem JSONs (those at its top) to choose from, the only one chosen.
function wireFolder() {
  $('up-folder').onchange = () => {
    const paths = [...$('up-folder').files].map(pathOf);
    const depth = (p) => p.split('/').length, top = Math.min(...paths.map(depth));
    const problems = paths.filter((p) => p.endsWith('.json') && depth(p) === top).sort();
    $('up-problem').replaceChildren(...problems.map((p) => new Option(p, p)));
  };
}

export function wireUpload() {
  wireSliders();
  wireKind();
  wireFolder();
  wireForm('upload', '/api/runs', 'upload-status', 'upload-problems');
  wireForm('replay', '/api/results', 'replay-status', 'replay-problems');
}
