// Measures the viewer on a run folder (docs/performance.md, "Viewer"): recording size, time to
// first frame and frame time while playing, in Debian's Chromium headless.
// Usage: node web/test/measure.mjs SMART_EXE RESULTS_DIR [WEB_DIST]
import { spawn } from 'node:child_process';
import { mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';
import puppeteer from 'puppeteer-core';

const [exe, results, dist] = process.argv.slice(2);
const work = mkdtempSync(path.join(tmpdir(), 'smart-measure-'));
const args = ['serve', '--port', '0', '--data', work, '--open', results];
if (dist) args.push('--web', dist);
const server = spawn(exe, args);
const url = await new Promise((resolve) => {
  let text = '';
  server.stdout.on('data', (d) => { text += d; const m = text.match(/"listening":"([^"]+)"/); if (m) resolve(m[1]); });
});
const browser = await puppeteer.launch({ executablePath: '/usr/bin/chromium', headless: true,
  args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader'] });
try {
  const page = await browser.newPage();
  await page.setViewport({ width: 1280, height: 800 });
  const bytes = (await (await fetch(`${url}/api/runs/run-000001/recording`)).arrayBuffer()).byteLength;
  const t0 = Date.now();
  await page.goto(`${url}/?run=run-000001`);
  await page.waitForFunction(() => window.__viewer && window.__viewer.ready, { timeout: 60000 });
  const loadMs = Date.now() - t0;
  const v = await page.evaluate(() => ({ ...window.__viewer }));
  await page.select('#speed', '16');
  await page.click('#play');
  await new Promise((r) => setTimeout(r, 5000));
  const play = await page.evaluate(() => ({ update: window.__viewer.frameTimeMs, render: window.__viewer.renderMs }));
  console.log(JSON.stringify({ robots: v.robots, recording_mb: bytes / 1e6, page_to_first_frame_ms: loadMs,
    app_first_frame_ms: v.firstFrameMs, frame_update_ms: play.update, frame_render_ms: play.render }));
} finally {
  await browser.close();
  server.kill('SIGTERM');
  rmSync(work, { recursive: true, force: true });
}
