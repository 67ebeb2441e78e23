// Opens an autobal HTML report in headless Chromium (Debian's package; playwright-core never
// downloads a browser) and checks what a reader would see:
//   - no console errors, no page errors, no request leaving the report's folder;
//   - every figure drawn by Plotly, with as many data points as the report embedded;
//   - every link of the table of contents lands on an element of the page;
//   - every static figure file linked (SVG, PNG) exists.
// Usage: node report.mjs REPORT_DIR [SCREENSHOT_DIR]
//   SCREENSHOT_DIR: also save the page's top and each figure as PNG there (to look at).
// Environment: AUTOBAL_CHROMIUM (default /usr/bin/chromium).
import { chromium } from 'playwright-core';
import { existsSync, mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';
import { pathToFileURL } from 'node:url';

const dir = resolve(process.argv[2] || 'autobal-report');
const shot = process.argv[3];
const exe = process.env.AUTOBAL_CHROMIUM || '/usr/bin/chromium';
const index = join(dir, 'index.html');
if (!existsSync(exe)) {
  console.error(`browser test: no Chromium at ${exe}; install it (Debian/Ubuntu: apt-get install chromium) or set AUTOBAL_CHROMIUM`);
  process.exit(3);
}
if (!existsSync(index)) {
  console.error(`browser test: no report at ${index}`);
  process.exit(2);
}
const profile = mkdtempSync(join(tmpdir(), 'autobal-chromium-'));
const failures = [];
let passed = 0;
function check(ok, what) {
  if (ok) { passed++; } else { failures.push(what); console.error('FAIL: ' + what); }
}
// a new empty profile (--user-data-dir) per run
const context = await chromium.launchPersistentContext(profile, {
  executablePath: exe,
  headless: true,
  viewport: { width: 1280, height: 900 },
  args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking',
    '--disable-component-update', '--disable-sync'],
});
try {
  const page = context.pages()[0] || await context.newPage();
  const errors = [];
  page.on('console', (m) => { if (m.type() === 'error') errors.push('console: ' + m.text()); });
  page.on('pageerror', (e) => errors.push('page error: ' + e.message));
  const base = pathToFileURL(dir).href;
  page.on('request', (r) => { const u = r.url(); if (!u.startsWith(base) && !u.startsWith('data:') && !u.startsWith('blob:')) errors.push('request outside the report folder: ' + u); });
  page.on('requestfailed', (r) => errors.push('failed request: ' + r.url()));
  const t0 = Date.now();
  await page.goto(pathToFileURL(index).href, { waitUntil: 'load' });
  const state = await page.evaluate(async () => {
    if (!window.autobalReport) return { missing: true };
    const s = await window.autobalReport.renderAll();
    return { total: s.total, rendered: s.rendered, errors: s.errors, points: s.points };
  });
  const ms = Date.now() - t0;
  check(!state.missing, 'report.js ran (window.autobalReport exists)');
  const figs = await page.$$eval('div.plot[data-fig]', (ds) => ds.map((d) => ({
    id: d.getAttribute('data-fig'),
    expected: Number(d.getAttribute('data-points')),
    drawn: Number(d.getAttribute('data-drawn-points') || -1),
    svg: d.querySelectorAll('svg.main-svg').length,
    traces: d.querySelectorAll('g.trace, g.hm, g.heatmaplayer image').length,
    legend: d.querySelectorAll('g.legend g.traces').length,
  })));
  check(figs.length > 0, 'the report has figures');
  check(state.rendered === figs.length, `every figure drawn: ${state.rendered} of ${figs.length}`);
  for (const f of figs) {
    check(f.svg > 0 && f.traces > 0, `figure ${f.id} is drawn (${f.svg} SVG layers, ${f.traces} traces)`);
    check(f.expected > 0, `figure ${f.id} has data points`);
    check(f.drawn === f.expected, `figure ${f.id}: the page holds ${f.drawn} of ${f.expected} data points`);
  }
  const toc = await page.$$eval('nav#toc a[href^="#"]', (as) => as.map((a) => ({ href: a.getAttribute('href'), ok: !!document.getElementById(a.getAttribute('href').slice(1)) })));
  check(toc.length > 0, 'the table of contents has links');
  for (const t of toc) check(t.ok, `contents link ${t.href} lands on the page`);
  const files = await page.$$eval('a[href$=".svg"], a[href$=".png"]', (as) => as.map((a) => a.getAttribute('href')));
  for (const f of files) check(existsSync(join(dir, decodeURIComponent(f))), `static figure ${f} exists`);
  check(errors.length === 0 && state.errors.length === 0, 'no console errors, page errors or outside requests' + (errors.length + state.errors.length ? ': ' + errors.concat(state.errors).join(' | ') : ''));
  if (shot) {
    await page.screenshot({ path: join(shot, 'page_top.png') });
    for (const f of figs) {
      const el = await page.$(`figure[id="${f.id}"]`);
      if (el) await el.screenshot({ path: join(shot, `${f.id}.png`) });
    }
  }
  console.log(`browser test: ${figs.length} figures drawn in ${ms} ms, ${toc.length} contents links, ${files.length} static files`);
} finally {
  await context.close();
  rmSync(profile, { recursive: true, force: true });
}
console.log(`${passed} passed, ${failures.length} failed`);
process.exit(failures.length ? 1 : 0);
