// The viewer in a real browser: Debian's Chromium, headless, driven by puppeteer-core against a
// real `smart serve` (serving the built viewer) replaying a real `smart run --out` folder.
// Checks: the run loads, every robot is drawn (pixels of the robot colours where robots stand),
// scrubbing moves the clock, selecting a robot fills its panel (path, progress, current action,
// queue, who it waits for now, checked against the run's own actions.csv and states.csv, and the
// lines drawn to those robots), results files download byte for byte, the finished-actions plot
// is drawn, a bad upload is refused with its problem list, an upload runs live then replays, a
// results folder uploaded through the form replays (collided robots in their colour); prints
// the time to first frame and the frame time while playing.
// Environment: SMART_EXE, SMART_BENCHMARKS, SMART_WEB_DIST, SMART_DOMAIN, SMART_ARTIFACTS.
import { spawn, spawnSync } from 'node:child_process';
import { copyFileSync, mkdtempSync, mkdirSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';
import assert from 'node:assert/strict';
import puppeteer from 'puppeteer-core';
import { launchBrowser, startServer } from './serve.mjs';

const exe = process.env.SMART_EXE;
const bench = process.env.SMART_BENCHMARKS;
const dist = process.env.SMART_WEB_DIST;
const domain = process.env.SMART_DOMAIN || '160';
const artifacts = process.env.SMART_ARTIFACTS || tmpdir();
const work = mkdtempSync(path.join(tmpdir(), 'smart-web-'));
const files = {
  map: path.join(bench, 'maps/random-32-32-20.map'),
  scen: path.join(bench, 'scens/random-32-32-20-random-1.scen'),
  plan: path.join(bench, 'smart-examples/example_paths_xy.txt'),
};

function runResults() {
  const out = path.join(work, 'results');
  const r = spawnSync(exe, ['run', '--map', files.map, '--scen', files.scen, '--plan', files.plan,
    '--axis', 'xy', '--agents', '20', '--domain', domain, '--out', out, '--no-progress'],
  { encoding: 'utf8' });
  assert.equal(r.status, 0, r.stderr);
  return { out, summary: JSON.parse(readFileSync(path.join(out, 'summary.json'), 'utf8')) };
}

let serverLog = '';  // the tail of smart serve's log, shown when a check fails

// Pixels of the canvas in robot colours (view.js COLORS): 'robots' counts moving (blue), done
// (green) and waiting (orange); 'collided' the collided magenta.
async function robotPixels(page, kind = 'robots') {
  return page.evaluate((kind) => {
    const src = document.querySelector('#view canvas');
    const c = document.createElement('canvas');
    c.width = src.width; c.height = src.height;
    const g = c.getContext('2d');
    g.drawImage(src, 0, 0);
    const d = g.getImageData(0, 0, c.width, c.height).data;
    const is = {
      robots: (r, gg, b) => (b > 150 && r < 120 && gg > 80 && gg < 180) || (gg > 120 && r < 110 && b < 140 && gg - b > 30) ||
        (r > 180 && gg > 110 && gg < 200 && b < 90),
      collided: (r, gg, b) => r > 140 && gg < 90 && b > 80 && b < 200,
    }[kind];
    let n = 0;
    for (let i = 0; i < d.length; i += 4) if (is(d[i], d[i + 1], d[i + 2])) n++;
    return n;
  }, kind);
}

// Robot pixels once at least `min` are seen (the live views render on their own schedule, and a
// WebGL canvas read between frames may be blank: under load a single read found none).
async function waitForPixels(page, min, kind = 'robots') {
  let n = 0;
  for (const until = Date.now() + 20000; Date.now() < until; await new Promise((r) => setTimeout(r, 100))) {
    if ((n = await robotPixels(page, kind)) >= min) break;
  }
  return n;
}

// actions.csv and states.csv of the run, read here (not through the server): robot -> finish
// times in order; robot -> [[t, queue]].
function readResults(out) {
  const finish = new Map(), queue = new Map();
  for (const line of readFileSync(path.join(out, 'actions.csv'), 'utf8').trim().split('\n').slice(1)) {
    const [robot, , , t] = line.split(',');
    if (!finish.has(+robot)) finish.set(+robot, []);
    finish.get(+robot).push(t === '' ? Infinity : +t);
  }
  for (const line of readFileSync(path.join(out, 'states.csv'), 'utf8').trim().split('\n').slice(1)) {
    const c = line.split(',');
    if (!queue.has(+c[1])) queue.set(+c[1], []);
    queue.get(+c[1]).push([+c[0], +c[9]]);
  }
  return { finish, queue };
}

// A robot at a moment it waits for another (a Type-2 edge whose source finished after the robot
// was ready): the panel's current action, finished count and queue match the run's files, it
// names the robot it waits for, and the line drawn ends at that robot.
async function checkWaiting(page, out) {
  const { finish, queue } = readResults(out);
  const found = await page.evaluate(async (robots) => {
    for (let r = 0; r < robots; r++) {
      const d = await (await fetch(`/api/runs/run-000001/robots/${r}`)).json();
      for (let k = 1; k < d.steps.length; k++) {
        const ready = d.steps[k - 1].finish_s;
        for (const [other, , f] of d.steps[k].in) if (f - ready > 0.5) return { robot: r, step: k, other, t: (ready + f) / 2 };
      }
    }
    return null;
  }, 20);
  assert.ok(found, 'no robot in this run ever waits for another (the fixture should have one)');
  const { robot, step, other, t } = found;
  await page.evaluate((r, t) => { window.__viewer.select(r); window.__viewer.seek(t); }, robot, t);
  await page.waitForFunction((r) => window.__viewer.detail && window.__viewer.detail.robot === r, {}, robot);
  await page.evaluate((t) => window.__viewer.seek(t), t);
  const frameT = await page.evaluate(() => window.__viewer.frameT);
  const panel = await page.$eval('#robot', (e) => e.textContent);
  const done = finish.get(robot).filter((f) => f <= frameT).length;
  assert.equal(done, step, `robot ${robot} at ${frameT} s: ${done} finished per actions.csv`);
  assert.ok(panel.includes(`finished: ${step} / ${finish.get(robot).length}`), panel);
  assert.ok(panel.includes(`current: #${step}`), panel);
  const waitsNow = await page.$eval('#robot .waits-now', (e) => e.textContent);
  assert.ok(waitsNow.replace(/ \(\d+\)/g, '').split(': ')[1].split(', ').includes(String(other)), waitsNow);
  const rows = queue.get(robot).filter(([tt]) => tt <= frameT);
  assert.ok(panel.includes(`queue: ${Math.min(255, rows[rows.length - 1][1])}`), `${panel} vs states.csv`);
  const lines = await page.evaluate(() => window.__viewer.edgeLines);
  const line = lines.find((l) => l.kind === 'waits' && l.robot === other);
  assert.ok(line, JSON.stringify(lines));
  const at = await page.evaluate((o) => window.__viewer.pose(o), other);
  assert.ok(Math.hypot(line.to[0] - at[0], line.to[1] - at[1]) < 1e-6, `line to ${line.to}, robot ${other} at ${at}`);
  // And the other robot, selected, says it is waited for by this one.
  await page.evaluate((o) => window.__viewer.select(o), other);
  await page.waitForFunction((o) => window.__viewer.detail && window.__viewer.detail.robot === o, {}, other);
  await page.evaluate((t) => window.__viewer.seek(t), t);
  const waitedNow = await page.$eval('#robot .waited-now', (e) => e.textContent);
  assert.ok(waitedNow.replace(/ \(\d+\)/g, '').split(': ')[1].split(', ').includes(String(robot)), waitedNow);
  await page.screenshot({ path: path.join(artifacts, 'viewer-waiting.png') });
}

// The results files offered for download are the run's files, byte for byte; the finished
// actions plot is drawn.
async function checkExportAndPlot(page, out) {
  const links = await page.$$eval('#files a', (as) => as.map((a) => a.getAttribute('href')));
  for (const name of ['summary.json', 'robots.csv', 'actions.csv', 'states.csv', 'stats.csv']) {
    const href = links.find((h) => h.endsWith(`/${name}`));
    assert.ok(href, `no download of ${name} in ${links}`);
    const body = await page.evaluate(async (h) => (await fetch(h)).text(), href);
    assert.equal(body, readFileSync(path.join(out, name), 'utf8'), name);
  }
  const green = await page.$eval('#plot', (c) => {
    const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    let n = 0;
    for (let i = 0; i < d.length; i += 4) if (d[i + 1] > 150 && d[i] < 100) n++;
    return n;
  });
  assert.ok(green > 50, `finished-actions plot not drawn (${green} green pixels)`);
  // Its axes (issue 26: none): round ticks from 0 past the run's end and its actions.
  const axes = await page.$eval('#plot', (c) => ({ x: c.dataset.xTicks.split(',').map(Number), y: c.dataset.yTicks.split(',').map(Number) }));
  assert.ok(axes.x.length >= 3 && axes.x[0] === 0, JSON.stringify(axes));
  assert.ok(axes.y.length >= 2 && axes.y[0] === 0, JSON.stringify(axes));
}

// A view for papers and demos (issue 26): the map framed whatever its shape, a legend, start and
// goal marks, a label on the selected robot, Type-2 lines dashed above the walls in their own
// colours, robots legible when zoomed out, the run's limits shown; a screenshot kept.
async function checkPaperView(page, id, summary, name) {
  const onScreen = await page.evaluate(() => window.__viewer.mapOnScreen());
  assert.ok(Math.max(onScreen.x, onScreen.y) > 0.85 && onScreen.x <= 1.001 && onScreen.y <= 1.001,
    `the map takes ${JSON.stringify(onScreen)} of the view`);
  const legend = await page.$$eval('#legend div', (ds) => ds.map((d) => d.textContent));
  for (const entry of ['moving', 'waiting', 'done', 'collided', 'start', 'goal', 'waits for (Type-2)', 'waited for by (Type-2)']) {
    assert.ok(legend.includes(entry), `legend ${legend.join('; ')} lacks ${entry}`);
  }
  const marks = await page.evaluate(() => window.__viewer.marks);
  assert.deepEqual(marks, { starts: summary.robots, goals: summary.robots });
  // From the plan: robot 3's goal mark is its path's last cell.
  assert.equal(await page.evaluate(() => window.__viewer.marksFrom), 'plan');
  const [detail3, marks3] = await page.evaluate(async (id) => [await (await fetch(`/api/runs/${id}/robots/3`)).json(),
    await (await fetch(`/api/runs/${id}/marks`)).json()], id);
  assert.deepEqual(marks3.goals[3], detail3.path[detail3.path.length - 1]);
  assert.deepEqual(marks3.starts[3], detail3.path[0]);
  await page.evaluate(() => window.__viewer.select(3));
  await page.waitForFunction(() => { const l = document.querySelector('#label'); return l && !l.hidden && l.textContent === 'robot 3'; }, { timeout: 5000 });
  const style = await page.evaluate(() => window.__viewer.edgeStyle);
  if (style) {
    assert.ok(style.dashed && style.heightCells > 0.6, JSON.stringify(style));
    assert.notEqual(style.waitsFor, 0xff3b30);
    assert.notEqual(style.waitedBy, 0xff3b30);
  }
  const stats = await page.$eval('#stats', (e) => e.textContent);
  assert.match(stats, new RegExp(`limits \\(${summary.limits.robot}\\): ${Number(summary.limits.max_speed_mps.toPrecision(3))} m/s`));
  assert.ok(stats.includes(`execution: ${summary.execution.mode}`), stats);
  await page.screenshot({ path: path.join(artifacts, `${name}.png`) });
  // Zoomed far out, robots grow to stay legible; back in, they are as they were.
  const before = await page.evaluate(() => window.__viewer.robotScale);
  await page.evaluate(() => window.__viewer.zoom(6));
  await page.waitForFunction((b) => window.__viewer.robotScale >= 2 * b, { timeout: 5000 }, before);
  await page.evaluate(() => window.__viewer.zoom(1 / 6));
  await page.waitForFunction((b) => window.__viewer.robotScale === b, { timeout: 5000 }, before);
}

// A results folder uploaded through the replay form is replayed; this one's summary claims that
// robots 0 and 1 collided, so they are drawn in the collided colour.
async function checkResultsUpload(page, out, summary) {
  const forged = path.join(work, 'forged');
  mkdirSync(forged, { recursive: true });
  for (const f of ['states.csv', 'robots.csv', 'actions.csv', 'stats.csv']) copyFileSync(path.join(out, f), path.join(forged, f));
  // Its finished_actions is markup (issue 25: an uploaded summary.json's markup ran as script).
  writeFileSync(path.join(forged, 'summary.json'), JSON.stringify({ ...summary, success: false, collisions: 1, first_collision: [0, 1],
    finished_actions: '<img src=x onerror="window.__pwned=1">' }));
  await page.goto(`${url}/?run=run-000001`);
  await page.waitForFunction(() => window.__viewer && window.__viewer.ready, { timeout: 20000 });
  await (await page.$('#rp-files')).uploadFile(...['summary.json', 'states.csv', 'robots.csv', 'actions.csv', 'stats.csv'].map((f) => path.join(forged, f)));
  await (await page.$('#rp-map')).uploadFile(files.map);
  await (await page.$('#rp-scen')).uploadFile(files.scen);
  await (await page.$('#rp-plan')).uploadFile(files.plan);
  await Promise.all([page.waitForNavigation({ timeout: 20000 }), page.click('#rp-go')]).catch(async (e) => {
    const status = await page.$eval('#replay', (el) => el.querySelector('#replay-status').textContent + ' ' +
      el.querySelector('#replay-problems').textContent + ` (${el.querySelector('#rp-files').files.length} files)`).catch(() => '?');
    throw new Error(`no navigation after the results upload (${e.message}); the form says: ${status}`);
  });
  await page.waitForFunction(() => window.__viewer && (window.__viewer.ready || window.__viewer.error), { timeout: 20000 });
  const v = await page.evaluate(() => ({ ...window.__viewer }));
  assert.equal(v.error, '', v.error);
  assert.deepEqual(v.collided, [0, 1]);
  await page.evaluate(() => window.__viewer.seek(1e9));
  await page.screenshot({ path: path.join(artifacts, 'viewer-collided.png') });
  const magenta = await robotPixels(page, 'collided');
  assert.ok(magenta > 20, `collided robots not drawn in their colour (${magenta} pixels)`);
  // The markup is shown as text, never run, and the page's policy would not let it run anyway.
  const shown = await page.evaluate(() => ({ pwned: window.__pwned, imgs: document.querySelectorAll('#stats img').length,
    text: document.querySelector('#stats').textContent }));
  assert.equal(shown.pwned, undefined, 'markup from an uploaded summary.json ran as script');
  assert.equal(shown.imgs, 0);
  assert.ok(shown.text.includes('<img src=x onerror='), shown.text);
  const csp = await page.evaluate(async () => (await fetch('/')).headers.get('Content-Security-Policy'));
  assert.match(csp || '', /script-src 'self' 'sha256-/);
  assert.ok(!/unsafe-inline/.test(csp), csp);
}

// `smart serve --watch`: a run going on the domain (real time, 20 robots) is shown live,
// read-only, with every robot drawn and seen moving; the run is stopped after the check.
async function checkWatch(browser) {
  const data = path.join(work, 'watch-data');
  const watcher = spawn(exe, ['serve', '--port', '0', '--data', data, '--web', dist, '--watch',
    '--map', files.map, '--scen', files.scen, '--plan', files.plan, '--axis', 'xy', '--agents', '20', '--domain', domain]);
  const watchUrl = await new Promise((resolve, reject) => {
    let text = '';
    watcher.stdout.on('data', (d) => { text += d; const m = text.match(/"listening":"(http:\/\/[^"]+)"/); if (m) resolve(m[1]); });
    watcher.on('exit', (code) => reject(new Error(`smart serve --watch exited (${code}): ${text}`)));
  });
  const run = spawn(exe, ['run', '--map', files.map, '--scen', files.scen, '--plan', files.plan, '--axis', 'xy',
    '--agents', '20', '--clock', 'realtime', '--domain', domain, '--no-progress'], { stdio: 'ignore' });
  const page = await browser.newPage();
  let intruder = null;
  try {
    await page.setViewport({ width: 1280, height: 800 });
    await page.goto(`${watchUrl}/?watch`);
    await page.waitForFunction(() => window.__viewer && window.__viewer.watch && window.__viewer.robots === 20 &&
      window.__viewer.watched.some((r) => r.status === 'moving') && window.__viewer.runName, { timeout: 30000 });
    // The run's name (issue 26: a 19-digit id), and the live runs to pick from.
    assert.match(await page.$eval('#stats', (e) => e.textContent), /watching run-\d+-\d+.*robots: 20/);
    const picks = await page.$$eval('#live-runs option', (os) => os.map((o) => o.textContent));
    assert.ok(picks.some((t) => /^run-\d+-\d+ \(20 robots/.test(t)), picks.join('; '));
    // Statuses from what the hosts say they do: a robot moving is executing an action.
    const watched = await page.evaluate(() => window.__viewer.watched);
    for (const r of watched) {
      assert.ok(['moving', 'waiting', 'idle'].includes(r.status), JSON.stringify(r));
      if (r.status === 'moving') assert.ok(r.executing_seq > r.finished_seq, JSON.stringify(r));
    }
    await page.evaluate(() => window.__viewer.select(5));
    await page.waitForFunction(() => /robot 5.*status: (moving|waiting|idle)/.test(document.querySelector('#robot').textContent), { timeout: 5000 });
    // With the run's plan: robot 5's path, current action and whom it waits for now; the run's
    // progress out of its actions (issue 26: no paths or waits in the watch).
    await page.waitForFunction(() => window.__viewer.watchPath > 1 &&
      /current: (#\d+ (move|rotate) of \d+|none).*waits now for: /.test(document.querySelector('#robot').textContent), { timeout: 10000 });
    const total = await page.evaluate(async () => (await (await fetch('/api/watch')).json()).total_actions);
    assert.match(await page.$eval('#stats', (e) => e.textContent), new RegExp(`actions: \\d+ / ${total}`));
    await page.screenshot({ path: path.join(artifacts, 'viewer-watch.png') });
    const pixels = await waitForPixels(page, 20 * 10 + 1);
    assert.ok(pixels > 20 * 10, `watched robots not drawn: ${pixels} robot-coloured pixels`);
    // A monitor announced with a host name of markup (issue 25: it ran as script): shown as text.
    intruder = spawn(process.env.SMART_ANNOUNCE_MONITOR, [domain, '<img src=x onerror="window.__pwned=1">'], { stdio: 'ignore' });
    await page.waitForFunction(() => document.querySelector('#stats').textContent.includes('monitor: <img src=x'), { timeout: 30000 });
    assert.equal(await page.evaluate(() => window.__pwned), undefined, 'a host name from DDS ran as script');
    assert.equal(await page.$$eval('#stats img', (xs) => xs.length), 0);
  } finally {
    await page.close();
    if (intruder) intruder.kill('SIGTERM');
    run.kill('SIGTERM');
    watcher.kill('SIGTERM');
  }
}

const { out, summary } = runResults();
const { server, url } = await startServer({ exe, dist, work, results: out, domain,
  onStderr: (d) => { serverLog = (serverLog + d).slice(-4000); } });
const browser = await launchBrowser(puppeteer, ['--window-size=1280,800']);
try {
  const page = await browser.newPage();
  await page.setViewport({ width: 1280, height: 800 });
  await page.goto(`${url}/?run=run-000001`);
  await page.waitForFunction(() => window.__viewer && (window.__viewer.ready || window.__viewer.error), { timeout: 20000 });
  const v = await page.evaluate(() => ({ ...window.__viewer }));
  assert.equal(v.error, '', v.error);
  assert.equal(v.robots, summary.robots);
  const stats = await page.$eval('#stats', (e) => e.textContent);
  assert.match(stats, new RegExp(`AET: ${summary.aet_s.toFixed(1)} s`));
  mkdirSync(artifacts, { recursive: true });
  await page.screenshot({ path: path.join(artifacts, 'viewer-start.png') });
  const atStart = await robotPixels(page);
  assert.ok(atStart > 20 * 20, `robots not drawn: ${atStart} robot-coloured pixels`);
  // Scrub to the end: the clock says the run's end, and the robots are still drawn.
  const end = await page.evaluate(() => { window.__viewer.seek(1e9); return window.__viewer.t; });
  assert.ok(Math.abs(end - summary.sim_time_s) < 1.0, `end ${end} vs sim time ${summary.sim_time_s}`);
  assert.match(await page.$eval('#clock', (e) => e.textContent), /\d+\.\d s/);
  // Select robot 3: its panel names it and shows its pose.
  await page.type('#search', '3');
  await page.keyboard.press('Tab');
  assert.match(await page.$eval('#robot', (e) => e.textContent), /robot 3.*x .* m, y .* m/);
  // Its planned path and Type-2 partners, as the API gives them from the run's ADG.
  await page.waitForFunction(() => window.__viewer.detail && window.__viewer.detail.robot === 3, { timeout: 10000 });
  const detail = await page.evaluate(() => window.__viewer.detail);
  const panel = await page.$eval('#robot', (e) => e.textContent);
  assert.match(panel, new RegExp(`path: ${detail.path.length - 1} cells, ${detail.actions} actions`));
  const names = (xs) => xs.map((x) => `${x.robot}${x.edges > 1 ? ` (${x.edges})` : ''}`).join(', ') || 'none';
  assert.ok(panel.includes(`in the run waits for: ${names(detail.waits_for)}`), panel);
  assert.ok(panel.includes(`in the run waited by: ${names(detail.waited_by)}`), panel);
  assert.ok(panel.includes(`finished: ${detail.actions} / ${detail.actions}`), panel);  // at the end
  // Its executed trail: one point per recorded frame up to now (the end of the run).
  const frames = await page.evaluate(() => window.__viewer.trailPoints);
  assert.ok(frames > 100, `trail of ${frames} points`);
  await page.screenshot({ path: path.join(artifacts, 'viewer-end-robot3.png') });
  await checkWaiting(page, out);
  await checkExportAndPlot(page, out);
  await checkPaperView(page, 'run-000001', summary, 'viewer-paper-random');
  // Play from the start at 64x for a second: the frame time while all robots move.
  await page.evaluate(() => window.__viewer.seek(0));
  await page.select('#speed', '64');
  await page.click('#play');
  await new Promise((r) => setTimeout(r, 1500));
  const played = await page.evaluate(() => ({ t: window.__viewer.t, ms: window.__viewer.frameTimeMs + window.__viewer.renderMs }));
  assert.ok(played.t > 10, `playing did not advance the clock (${played.t} s)`);
  console.log(JSON.stringify({ first_frame_ms: v.firstFrameMs, frame_ms: played.ms, robot_pixels: atStart }));
  // A bad upload through the page's form: its problems are listed with file and line.
  const jump = path.join(work, 'jump.txt');
  writeFileSync(jump, 'Agent 0:(1,1)->(9,9)->\n');
  await (await page.$('#up-map')).uploadFile(files.map);
  await (await page.$('#up-scen')).uploadFile(files.scen);
  await (await page.$('#up-plan')).uploadFile(jump);
  await page.$eval('#upload input[name=agents]', (e) => { e.value = '1'; });
  await page.click('#up-go');
  await page.waitForFunction(() => document.querySelectorAll('#upload-problems li').length > 0, { timeout: 10000 });
  assert.match(await page.$eval('#upload-problems', (e) => e.textContent), /jump\.txt:1/);
  // A good upload through the form is shown live while it runs, then replayed: SMART's
  // warehouse plan, 50 robots, paced by the form's speed choice to 50x real time (about 11 s of
  // wall time; as fast as possible it ends in about 2 s, before the page could show it live).
  await (await page.$('#up-map')).uploadFile(path.join(bench, 'maps/warehouse-10-20-10-2-1.map'));
  await (await page.$('#up-scen')).uploadFile(path.join(bench, 'scens/warehouse-10-20-10-2-1-random-1.scen'));
  await (await page.$('#up-plan')).uploadFile(path.join(bench, 'smart-examples/scen_1_1000_paths.txt'));
  await page.select('#upload select[name=axis]', 'rowcol');
  await page.$eval('#upload input[name=agents]', (e) => { e.value = '50'; });
  await page.select('#upload select[name=real_time_factor]', '50');
  // A limit from the form's slider, which starts at the model's own limit.
  const models = await page.evaluate(async () => (await fetch('/api/robots')).json());
  const footbot = models.find((m) => m.name === 'footbot');
  assert.ok(footbot && models.some((m) => m.name === 'jetbot'), JSON.stringify(models));
  const slider = '#upload .slider[data-for=max_accel_mps2]';
  assert.equal(Number(await page.$eval(slider, (e) => e.value)), footbot.max_accel_mps2);
  // Up to twice the model's limit (issue 26: sliders stopped at 3 m/s for a 5 m/s model).
  for (const key of ['max_speed_mps', 'max_accel_mps2', 'max_turn_rate_radps']) {
    const max = Number(await page.$eval(`#upload .slider[data-for=${key}]`, (e) => e.max));
    assert.equal(max, 2 * footbot[key], key);
  }
  await page.$eval(slider, (e) => { e.value = '0.5'; e.dispatchEvent(new Event('input')); });
  assert.equal(await page.$eval('#upload input[name=max_accel_mps2]', (e) => e.value), '0.5');
  await Promise.all([page.waitForNavigation({ timeout: 90000 }), page.click('#up-go')]).catch(async (e) => {
    const status = await page.$eval('#upload', (el) => el.querySelector('#upload-status').textContent + ' ' + el.querySelector('#upload-problems').textContent).catch(() => '?');
    throw new Error(`no navigation after the upload (${e.message}); the form says: ${status}`);
  });
  assert.match(page.url(), /run=run-000002/);
  // Live = replay (issue 26): robots coloured by state, one selected with its panel, progress.
  let sawLive = false, replay = null, last = null, sawStates = false, sawPanel = false, sawProgress = false;
  for (const until = Date.now() + 150000; Date.now() < until && !replay;) {
    const s = await page.evaluate(() => window.__viewer && { ...window.__viewer }).catch(() => null);  // reloads
    if (s && s.live && s.liveEvents > 0 && s.robots === 50) sawLive = true;
    if (s && s.live && s.liveStatus && s.liveStatus.length === 50) {
      assert.ok(s.liveStatus.every((x) => ['moving', 'waiting', 'idle'].includes(x)), s.liveStatus.join());
      if (s.liveStatus.includes('moving')) sawStates = true;
      if (s.progress && s.progress.finished > 0) {
        assert.ok(s.progress.finished <= s.progress.total, JSON.stringify(s.progress));
        sawProgress = await page.$eval('#plot', (e) => !e.hidden).catch(() => false) || sawProgress;
      }
      const panel = await page.evaluate(() => window.__viewer.select(3) && document.querySelector('#robot').textContent).catch(() => '');
      if (/robot 3.*status: (moving|waiting|idle).*queue: \d+.*finished: \d+ \/ \d+.*current: (#\d+ (move|rotate)|none).*waits now for: /.test(panel || '')) sawPanel = true;
    }
    if (s && s.ready) replay = s;
    if (s) last = s;
    if (s && s.error) break;  // the page gave up: say why below
    await new Promise((r) => setTimeout(r, 100));
  }
  assert.ok(sawLive, 'the run was never shown live with its 50 robots');
  assert.ok(sawStates, 'no live robot was ever shown moving (states from the live stream)');
  assert.ok(sawPanel, 'a live robot could not be selected and shown in the panel');
  assert.ok(sawProgress, 'the live view never showed the run\'s progress');
  if (!replay) {
    // Everything that says why: the page's state, the server's word on the run, the run's output.
    const run = await page.evaluate(async () => (await fetch('/api/runs/run-000002')).text()).catch((e) => String(e));
    const out = (() => { try { return readFileSync(path.join(work, 'data', 'run-000002', 'run.out'), 'utf8'); } catch (e) { return String(e); } })();
    assert.fail(`the finished run was not replayed; page: ${JSON.stringify(last)}; server: ${run}; run.out (last 4000 bytes): ${out.slice(-4000)}; serve's log: ${serverLog}`);
  }
  assert.equal(replay.robots, 50);
  // The warehouse is 161 x 63 cells: framed to fill the view's width; its limits as uploaded.
  const warehouse = await page.evaluate(async () => (await (await fetch('/api/runs/run-000002')).json()).summary);
  assert.equal(warehouse.limits.max_accel_mps2, 0.5);
  await checkPaperView(page, 'run-000002', warehouse, 'viewer-paper-warehouse');
  assert.match(readFileSync(path.join(work, 'data', 'run-000002', 'robot.yaml'), 'utf8'), /max_accel_mps2: 0\.5/);
  await checkResultsUpload(page, out, summary);
  await checkWatch(browser);
  // A bad upload is refused with its problem list (the API directly).
  const bad = await page.evaluate(async () => {
    const f = new FormData();
    f.append('map', new Blob(['type octile\nheight 1\nwidth 2\nmap\n..\n']), 'm.map');
    f.append('scen', new Blob(['version 1\n']), 's.scen');
    f.append('plan', new Blob(['Agent 0:(0,0)->(5,5)->\n']), 'p.txt');
    const r = await fetch('/api/runs', { method: 'POST', body: f });
    return { status: r.status, body: await r.json() };
  });
  assert.equal(bad.status, 400);
  assert.ok(bad.body.problems.length > 0, JSON.stringify(bad.body));
} finally {
  await browser.close();
  server.kill('SIGTERM');
  rmSync(work, { recursive: true, force: true });
}
console.log('viewer test passed');
