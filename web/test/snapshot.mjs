// A picture of the viewer replaying a results folder, for the docs (README "ROS 2 tools"):
// Debian's Chromium headless against a real `smart serve --open`, at a fraction of the run with a
// robot selected.
// Usage: node web/test/snapshot.mjs SMART_EXE RESULTS_DIR OUT.png [WEB_DIST] [FRACTION] [ROBOT]
import { mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';
import puppeteer from 'puppeteer-core';
import { launchBrowser, startServer } from './serve.mjs';

const [exe, results, out, dist, fraction = '0.3', robot = '0'] = process.argv.slice(2);
const work = mkdtempSync(path.join(tmpdir(), 'smart-snapshot-'));
const { server, url } = await startServer({ exe, dist, work, results, domain: '0' });
const browser = await launchBrowser(puppeteer);
try {
  const page = await browser.newPage();
  await page.setViewport({ width: 1280, height: 800 });
  await page.goto(`${url}/?run=run-000001`);
  await page.waitForFunction(() => window.__viewer && window.__viewer.ready, { timeout: 60000 });
  await page.evaluate((f, r) => { window.__viewer.seek(f * window.__viewer.endS); window.__viewer.select(r); },
    Number(fraction), Number(robot));
  await page.waitForFunction(() => window.__viewer.detail, { timeout: 10000 });
  await page.screenshot({ path: out });
} finally {
  await browser.close();
  server.kill();
  rmSync(work, { recursive: true, force: true });
}
