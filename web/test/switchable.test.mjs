// A switchable run's replay (issue 29) in a real browser: Debian's Chromium, headless, against a
// real `smart serve --open` of a real `smart run --execution switchable` (SMART's 100-robot
// warehouse plan under LoRR-style delays, lock-step). Checks: the robot panel's Type-2 edges are
// the ones the run ended with (every switch of switches.csv flipped an edge, marked as such), and
// a robot waiting for another because of a switch has its line drawn in the switch colour and
// that robot named in its panel.
// Environment: SMART_EXE, SMART_BENCHMARKS, SMART_WEB_DIST, SMART_DOMAIN, SMART_ARTIFACTS.
import { spawnSync } from 'node:child_process';
import { mkdirSync, mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';
import assert from 'node:assert/strict';
import puppeteer from 'puppeteer-core';
import { launchBrowser, startServer } from './serve.mjs';

const exe = process.env.SMART_EXE;
const bench = process.env.SMART_BENCHMARKS;
const dist = process.env.SMART_WEB_DIST;
const domain = process.env.SMART_DOMAIN || '86';
const artifacts = process.env.SMART_ARTIFACTS || tmpdir();
mkdirSync(artifacts, { recursive: true });
const work = mkdtempSync(path.join(tmpdir(), 'smart-switchable-web-'));
const robots = 100;

function switchableRun() {
  const out = path.join(work, 'results');
  const r = spawnSync(exe, ['run', '--map', path.join(bench, 'maps/warehouse-10-20-10-2-1.map'),
    '--scen', path.join(bench, 'scens/warehouse-10-20-10-2-1-random-1.scen'),
    '--plan', path.join(bench, 'smart-examples/scen_1_paths.txt'), '--axis', 'rowcol',
    '--agents', String(robots), '--delay-probability', '0.01', '--delay-min-s', '1', '--delay-max-s', '4',
    '--seed', '1', '--execution', 'switchable', '--domain', domain, '--out', out, '--no-progress'],
  { encoding: 'utf8' });
  assert.equal(r.status, 0, r.stderr);
  return out;
}


const out = switchableRun();
const switches = readFileSync(path.join(out, 'switches.csv'), 'utf8').trim().split('\n').slice(1)
  .map((l) => l.split(',').map(Number));
assert.ok(switches.length > 10, `${switches.length} switches: the fixture run should switch (lock-step, seed 1)`);
const { server, url } = await startServer({ exe, dist, work, results: out, domain });
const browser = await launchBrowser(puppeteer);
try {
  const page = await browser.newPage();
  await page.setViewport({ width: 1280, height: 800 });
  page.on('pageerror', (e) => { throw e; });
  await page.goto(`${url}/?run=run-000001`);
  await page.waitForFunction(() => window.__viewer && (window.__viewer.ready || window.__viewer.error), { timeout: 60000 });
  assert.equal(await page.evaluate(() => window.__viewer.error), '');

  // Every robot's edges as the panel gets them: the flipped ones (4th element true), and a
  // moment one of them holds a robot back (its source finishes well after the robot was ready).
  const seen = await page.evaluate(async (n) => {
    const flipped = [];
    let waiting = null;
    for (let r = 0; r < n; r++) {
      const d = await (await fetch(`/api/runs/run-000001/robots/${r}`)).json();
      d.steps.forEach((s, k) => s.in.forEach(([other, , f, sw]) => {
        if (sw !== true) return;
        flipped.push([other, r]);
        const ready = k > 0 ? d.steps[k - 1].finish_s : 0;
        if (!waiting && f !== null && ready !== null && f - ready > 0.5) waiting = { robot: r, other, t: (ready + f) / 2 };
      }));
    }
    return { flipped, waiting };
  }, robots);
  // Each switch made its late robot wait for the one that passed, unless a later switch at that
  // location moved the late robot again (another passed it, or it passed back): the pair is among
  // the flipped edges.
  const pairs = new Set(seen.flipped.map(([a, b]) => `${a}>${b}`));
  const kept = switches.filter(([, x, y, , second], i) => !switches.slice(i + 1)
    .some(([, x2, y2, f2, s2]) => x2 === x && y2 === y && (s2 === second || f2 === second)));
  const missing = kept.filter(([, , , first, second]) => !pairs.has(`${first}>${second}`));
  assert.deepEqual(missing, [], `switches without their flipped edge (of ${kept.length})`);
  assert.ok(seen.flipped.length >= switches.length, `${seen.flipped.length} flipped edges`);

  assert.ok(seen.waiting, 'no robot ever waits on a flipped edge in the fixture run (it should)');
  const { robot, other, t } = seen.waiting;
  await page.evaluate((r) => window.__viewer.select(r), robot);
  await page.waitForFunction((r) => window.__viewer.detail && window.__viewer.detail.robot === r, {}, robot);
  await page.evaluate((t) => window.__viewer.seek(t), t);
  const waitsNow = await page.$eval('#robot .waits-now', (e) => e.textContent);
  assert.ok(waitsNow.replace(/ \(\d+\)/g, '').split(': ')[1].split(', ').includes(String(other)), waitsNow);
  const lines = await page.evaluate(() => window.__viewer.edgeLines);
  const line = lines.find((l) => l.kind === 'waits' && l.robot === other);
  assert.ok(line && line.switched === true, JSON.stringify(lines));
  assert.ok(lines.filter((l) => l.switched).every((l) => pairs.has(l.kind === 'waits' ? `${l.robot}>${robot}` : `${robot}>${l.robot}`)),
    JSON.stringify(lines));
  // The stats panel names the execution, its switches and its knobs, as summary.json has them.
  const summary = JSON.parse(readFileSync(path.join(out, 'summary.json'), 'utf8'));
  const stats = await page.$eval('#stats', (e) => e.textContent);
  assert.ok(stats.includes(`execution: switchable, ${switches.length} switches; commit ` +
    `${summary.execution.options.commit_actions}, chains ${summary.execution.options.chain_locations}`), stats);
  const legend = await page.$$eval('#legend div', (ds) => ds.map((d) => d.textContent));
  assert.ok(legend.includes('switched passing order (passed first → planned first)'), legend.join('; '));
  await page.screenshot({ path: path.join(artifacts, 'viewer-switched-edge.png') });
  console.log(JSON.stringify({ switches: switches.length, flipped: seen.flipped.length, waiting: seen.waiting }));
} finally {
  await browser.close();
  server.kill();
  rmSync(work, { recursive: true, force: true });
}
