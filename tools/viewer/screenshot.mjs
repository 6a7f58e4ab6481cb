// SPDX-License-Identifier: BSD-3-Clause
// Plays a recording in a web build of Lichtblick with quad's layout, in Debian's Chromium
// (headless, software WebGL), and saves a screenshot when the playback ends:
//   node screenshot.mjs LICHTBLICK_DIR RECORDING.mcap LAYOUT.json OUT.png
// LICHTBLICK_DIR is a built Lichtblick web app (the folder holding its index.html). It, the
// recording and the layout are served on 127.0.0.1 (the recording with HTTP ranges, as the
// viewer's remote-file source reads it), and the viewer is opened on them as a user would
// open a recording by its URL. Exit status 0 with the screenshot written, 1 when the viewer
// reports a script error or the playback does not end in time, 2 for bad arguments.
import fs from 'node:fs';
import http from 'node:http';
import path from 'node:path';
import { chromium } from 'playwright-core';

const [app, recording, layout, out] = process.argv.slice(2);
if (!app || !recording || !layout || !out) {
  console.error('usage: node screenshot.mjs LICHTBLICK_DIR RECORDING.mcap LAYOUT.json OUT.png');
  process.exit(2);
}
for (const [what, file] of [['Lichtblick build', path.join(app, 'index.html')], ['recording', recording], ['layout', layout]]) {
  if (!fs.existsSync(file)) {
    console.error(`screenshot: ${what}: ${file} does not exist`);
    process.exit(2);
  }
}
const kPlayTimeoutMs = 10 * 60 * 1000;  // software rendering plays slower than real time
const root = path.resolve(app);
const served = { '/recording.mcap': path.resolve(recording), '/layout.json': path.resolve(layout) };
const kTypes = { '.html': 'text/html; charset=utf-8', '.js': 'text/javascript', '.wasm': 'application/wasm',
                 '.json': 'application/json', '.png': 'image/png', '.ttf': 'font/ttf' };

// Serves a file whole, or the byte range a request asks for.
function send(req, res, file) {
  fs.stat(file, (error, stat) => {
    if (error || !stat.isFile()) {
      res.writeHead(404).end();
      return;
    }
    const headers = { 'Content-Type': kTypes[path.extname(file)] ?? 'application/octet-stream', 'Accept-Ranges': 'bytes' };
    const range = /^bytes=(\d+)-(\d*)$/.exec(req.headers.range ?? '');
    let [first, last] = [0, stat.size - 1];
    if (range) {
      first = Number(range[1]);
      last = range[2] ? Math.min(Number(range[2]), stat.size - 1) : stat.size - 1;
      if (first > last) {
        res.writeHead(416, { 'Content-Range': `bytes */${stat.size}` }).end();
        return;
      }
      headers['Content-Range'] = `bytes ${first}-${last}/${stat.size}`;
    }
    res.writeHead(range ? 206 : 200, { ...headers, 'Content-Length': last - first + 1 });
    if (req.method === 'HEAD' || stat.size === 0) {
      res.end();
      return;
    }
    fs.createReadStream(file, { start: first, end: last }).pipe(res);
  });
}

const server = http.createServer((req, res) => {
  const name = decodeURIComponent(new URL(req.url, 'http://localhost').pathname);
  const file = served[name] ?? path.join(root, name === '/' ? 'index.html' : name);
  if (!served[name] && !file.startsWith(root + path.sep)) {
    res.writeHead(403).end();
    return;
  }
  send(req, res, file);
});
await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
const base = `http://127.0.0.1:${server.address().port}`;

const errors = [];
const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM ?? '/usr/bin/chromium',
  args: ['--use-gl=angle', '--use-angle=swiftshader', '--enable-unsafe-swiftshader'],
});
try {
  const page = await browser.newPage({ viewport: { width: 1600, height: 900 } });
  page.on('pageerror', (error) => errors.push(String(error)));
  const query = new URLSearchParams({ ds: 'remote-file', 'ds.url': `${base}/recording.mcap`, layoutUrl: `${base}/layout.json` });
  await page.goto(`${base}/?${query}`);
  await page.getByRole('button', { name: 'Hide left sidebar' }).click({ timeout: 60000 });
  // Play is shown before the recording is indexed, and a click then starts nothing: click
  // until the playback runs.
  const start = Date.now();
  while ((await page.locator('button[title="Pause"]').count()) === 0) {
    if (Date.now() - start > 120000) {
      throw new Error('the playback did not start within 120 s');
    }
    await page.locator('button[title="Play"]').click({ timeout: 60000 });
    await page.waitForTimeout(2000);
  }
  await page.locator('button[title="Play"]').waitFor({ timeout: kPlayTimeoutMs });  // the end
  await page.waitForTimeout(3000);  // the last frame drawn
  await page.screenshot({ path: out, timeout: 120000 });
} catch (error) {
  errors.push(String(error));
} finally {
  await browser.close();
  server.close();
}
console.log(JSON.stringify({ screenshot: out, errors }));
process.exit(errors.length === 0 ? 0 : 1);
