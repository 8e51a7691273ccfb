// Test support: a real `smart serve` replaying a results folder, on a free port; resolves with the
// process and its URL once it says where it listens. `onStderr` sees its log (it must be read,
// or the server blocks).
import { spawn } from 'node:child_process';
import path from 'node:path';

export function startServer({ exe, dist, work, results, domain, onStderr = () => {}, args = [] }) {
  const server = spawn(exe, ['serve', '--port', '0', '--data', path.join(work, 'data'), '--web', dist,
    '--open', results, '--domain', domain, ...args]);
  server.stderr.on('data', onStderr);
  return new Promise((resolve, reject) => {
    let text = '';
    server.stdout.on('data', (d) => {
      text += d;
      const m = text.match(/"listening":"(http:\/\/[^"]+)"/);
      if (m) resolve({ server, url: m[1] });
    });
    server.on('exit', (code) => reject(new Error(`smart serve exited (${code}): ${text}`)));
  });
}

// The system's headless Chromium (never a downloaded one). Its launch waits for the DevTools
// endpoint Chromium prints, an event; puppeteer's default guard of 30 s ran out once beside
// another test on the 2-core CI machine (web_viewer, 2026-11-27), so the guard is 180 s.
export async function launchBrowser(puppeteer, extraArgs = []) {
  return puppeteer.launch({
    executablePath: '/usr/bin/chromium', headless: true, timeout: 180000,
    args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', ...extraArgs],
  });
}
