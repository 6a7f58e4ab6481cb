// SPDX-License-Identifier: BSD-3-Clause
// Opens a run's report.html (or another page of the folder: a campaign's campaign.html) in
// headless Chromium and checks that the browser draws it:
//   node check.mjs DIR SCREENSHOT.png [PAGE]
// The run folder is served over HTTP on 127.0.0.1 (so the page's images are same-origin and
// can be read back from a canvas). Every <img> must load, have the size its SVG declares and
// hold ink (not a blank page); the page must log no console error, raise no script error and
// request nothing that fails. Prints one JSON object: the figures and the problems found.
// Exit status 0 when there is none, 1 otherwise, 2 for bad arguments.
import fs from 'node:fs';
import http from 'node:http';
import path from 'node:path';
import { chromium } from 'playwright-core';

const [dir, screenshot, pageName = 'report.html'] = process.argv.slice(2);
if (!dir || !screenshot) {
  console.error('usage: node check.mjs DIR SCREENSHOT.png [PAGE]');
  process.exit(2);
}
const root = path.resolve(dir);
const kTypes = { '.html': 'text/html; charset=utf-8', '.svg': 'image/svg+xml', '.png': 'image/png' };
const kMinInk = 0.003;  // share of a figure's pixels that are not white

const server = http.createServer((req, res) => {
  const file = path.join(root, decodeURIComponent(new URL(req.url, 'http://localhost').pathname));
  if (!file.startsWith(root + path.sep)) {
    res.writeHead(403).end();
    return;
  }
  fs.readFile(file, (error, data) => {
    if (error) {
      res.writeHead(404).end();
      return;
    }
    res.writeHead(200, { 'Content-Type': kTypes[path.extname(file)] ?? 'application/octet-stream' }).end(data);
  });
});
await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
const { port } = server.address();

const problems = [];
const browser = await chromium.launch({
  executablePath: process.env.QUAD_CHROMIUM ?? '/usr/bin/chromium',
  args: ['--no-sandbox'],
});
try {
  const page = await browser.newPage({ viewport: { width: 1000, height: 900 } });
  page.on('console', (m) => m.type() === 'error' && problems.push(`console error: ${m.text()}`));
  page.on('pageerror', (e) => problems.push(`script error: ${e.message}`));
  page.on('requestfailed', (r) => problems.push(`request failed: ${r.url()}`));
  page.on('response', (r) => r.status() >= 400 && problems.push(`HTTP ${r.status()}: ${r.url()}`));
  await page.goto(`http://127.0.0.1:${port}/${pageName}`, { waitUntil: 'load' });
  const figures = await page.evaluate(async (minInk) => {
    const out = [];
    for (const img of document.images) {
      const loaded = await img.decode().then(() => true, () => false);
      const figure = { src: img.getAttribute('src'), loaded, width: img.naturalWidth, height: img.naturalHeight, ink: 0 };
      if (loaded && img.naturalWidth > 0 && img.naturalHeight > 0) {
        const canvas = document.createElement('canvas');
        canvas.width = img.naturalWidth;
        canvas.height = img.naturalHeight;
        const g = canvas.getContext('2d');
        g.drawImage(img, 0, 0);
        const d = g.getImageData(0, 0, canvas.width, canvas.height).data;
        let ink = 0;
        for (let i = 0; i < d.length; i += 4) {
          if (d[i + 3] > 0 && (d[i] < 200 || d[i + 1] < 200 || d[i + 2] < 200)) {
            ++ink;
          }
        }
        figure.ink = ink / (canvas.width * canvas.height);
      }
      out.push(figure);
    }
    return out;
  }, kMinInk);
  if (figures.length === 0) {
    problems.push('the page shows no figure');
  }
  for (const f of figures) {
    const text = fs.readFileSync(path.join(root, f.src), 'utf8');
    const declared = /<svg[^>]*\swidth="([\d.]+)"[^>]*\sheight="([\d.]+)"/.exec(text);
    f.declared = declared ? [Number(declared[1]), Number(declared[2])] : null;
    if (!f.loaded) {
      problems.push(`${f.src}: the browser could not draw it`);
    } else if (!declared || Math.round(f.declared[0]) !== f.width || Math.round(f.declared[1]) !== f.height) {
      problems.push(`${f.src}: drawn ${f.width}x${f.height}, declared ${f.declared}`);
    } else if (f.ink < kMinInk) {
      problems.push(`${f.src}: blank (${(100 * f.ink).toFixed(2)} % of its pixels drawn)`);
    }
  }
  await page.screenshot({ path: screenshot, fullPage: true });
  console.log(JSON.stringify({ figures, problems }));
} finally {
  await browser.close();
  server.close();
}
process.exit(problems.length === 0 ? 0 : 1);
