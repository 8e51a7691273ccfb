// Measures the viewer on a run folder (docs/performance.md, "Viewer"): recording size, time to
// first frame (from the start of the navigation, read from the page's own clock) in a fresh
// browser (cold) and on a second visit (warm), time until playback may start (the whole
// recording loaded), and frame time while playing, in Debian's Chromium headless.
// Usage: node web/test/measure.mjs SMART_EXE RESULTS_DIR [WEB_DIST]
import { spawn } from 'node:child_process';
import { mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';
import puppeteer from 'puppeteer-core';
import { launchBrowser } from './serve.mjs';

const [exe, results, dist] = process.argv.slice(2);
const work = mkdtempSync(path.join(tmpdir(), 'smart-measure-'));
const args = ['serve', '--port', '0', '--data', work, '--open', results];
if (dist) args.push('--web', dist);
const server = spawn(exe, args);
const url = await new Promise((resolve) => {
  let text = '';
  server.stdout.on('data', (d) => { text += d; const m = text.match(/"listening":"([^"]+)"/); if (m) resolve(m[1]); });
});
const browser = await launchBrowser(puppeteer);

async function visit(page) {
  await page.goto(`${url}/?run=run-000001`);
  await page.waitForFunction(() => window.__viewer && window.__viewer.ready, { timeout: 60000 });
  return page.evaluate(() => ({ ...window.__viewer }));
}

// The page's own work for a frame that shows a new recorded frame (every robot placed, the task
// layer redone), whatever the display: 240 seeks to 120 points of the run (the second 120 timed,
// after the JIT warmed up), and the minimap's redraw (forced; at most every 100 ms in play).
function frameCosts() {
  const v = window.__viewer, end = v.endS, times = [], minimap = [];
  for (let pass = 0; pass < 2; pass++) {
    for (let k = 0; k < 120; k++) {
      const t0 = performance.now();
      v.seek((k / 120) * end);
      times.push(performance.now() - t0);
    }
  }
  for (let k = 0; k < 20; k++) {
    const t0 = performance.now();
    v.redrawMinimap();
    minimap.push(performance.now() - t0);
  }
  const hot = times.slice(120).sort((a, b) => a - b), mean = (xs) => xs.reduce((a, b) => a + b, 0) / xs.length;
  return { new_frame_ms_mean: mean(hot), new_frame_ms_p95: hot[113], new_frame_ms_max: hot[119], minimap_ms_mean: mean(minimap) };
}

try {
  const page = await browser.newPage();
  await page.setViewport({ width: 1280, height: 800 });
  const bytes = (await (await fetch(`${url}/api/runs/run-000001/recording`)).arrayBuffer()).byteLength;
  const cold = await visit(page);
  const warm = await visit(page);
  await page.select('#speed', '16');
  await page.click('#play');
  await new Promise((r) => setTimeout(r, 5000));
  const play = await page.evaluate(() => ({ update: window.__viewer.frameTimeMs, render: window.__viewer.renderMs }));
  await page.click('#play');
  const frames = await page.evaluate(frameCosts);
  console.log(JSON.stringify({ robots: cold.robots, recording_mb: bytes / 1e6,
    cold_first_frame_ms: cold.firstFrameAtMs, cold_ready_ms: cold.readyAtMs,
    warm_first_frame_ms: warm.firstFrameAtMs, warm_ready_ms: warm.readyAtMs,
    frame_update_ms: play.update, frame_render_ms: play.render, ...frames }));
} finally {
  await browser.close();
  server.kill('SIGTERM');
  rmSync(work, { recursive: true, force: true });
}
