// Shared by the report browser tests: headless Debian Chromium through
// playwright-core (no downloaded browser, a new temporary profile) and a page
// opened from file:// with its console errors, page errors and every request
// that is not file:/data:/blob:/about: recorded (and aborted).
'use strict';
const fs = require('fs');
const os = require('os');
const path = require('path');

const CHROMIUM = process.env.KESTREL_CHROMIUM || '/usr/bin/chromium';

// Exits 77 (skipped) when there is no Chromium.
function requireChromium() {
  if (!fs.existsSync(CHROMIUM)) {
    console.log(`SKIP: ${CHROMIUM} not found (apt-get install chromium, or scripts/install-deps.sh host)`);
    process.exit(77);
  }
}

async function launch() {
  const { chromium } = require('playwright-core');
  const profile = fs.mkdtempSync(path.join(os.tmpdir(), 'kestrel-report-chromium-'));
  const ctx = await chromium.launchPersistentContext(profile, {
    executablePath: CHROMIUM,
    headless: true,
    viewport: { width: 1400, height: 900 },
    args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking',
      '--disable-component-update', '--disable-sync', '--enable-unsafe-swiftshader', '--use-angle=swiftshader'],
  });
  const close = async () => {
    await ctx.close();
    fs.rmSync(profile, { recursive: true, force: true });
  };
  return { ctx, close };
}

// Opens file and waits for window.kestrelReport.ready (ms: how long that took).
async function openReport(ctx, file) {
  const page = await ctx.newPage();
  const errors = [];
  const external = [];
  page.on('console', (m) => {
    if (m.type() === 'error') errors.push(`console.error: ${m.text()}`);
    else if (m.type() === 'warning') console.log(`  (console warning: ${m.text().slice(0, 160)})`);
  });
  page.on('pageerror', (e) => errors.push(`page error: ${e.message}`));
  await page.route('**/*', (route) => {
    const u = route.request().url();
    if (/^(file|data|blob|about):/.test(u)) return route.continue();
    external.push(u);
    return route.abort();
  });
  const t0 = Date.now();
  await page.goto('file://' + file, { waitUntil: 'load' });
  await page.waitForFunction(() => window.kestrelReport && window.kestrelReport.ready, null, { timeout: 15000 });
  return { page, errors, external, ms: Date.now() - t0 };
}

// Luminance spread and colour count of a PNG screenshot (is it blank?).
function stats(pngBuf) {
  const { PNG } = require('pngjs');
  const png = PNG.sync.read(pngBuf);
  const n = png.width * png.height;
  let s = 0;
  let s2 = 0;
  const colours = new Set();
  for (let i = 0; i < n; i++) {
    const r = png.data[4 * i];
    const g = png.data[4 * i + 1];
    const b = png.data[4 * i + 2];
    const y = 0.299 * r + 0.587 * g + 0.114 * b;
    s += y;
    s2 += y * y;
    if (colours.size < 5000) colours.add((r << 16) | (g << 8) | b);
  }
  const mean = s / n;
  return { width: png.width, height: png.height, mean, std: Math.sqrt(Math.max(0, s2 / n - mean * mean)), colours: colours.size };
}

// The command line of a browser test (HTML_DIR OUT_DIR; exit 2 on a usage
// error, 77 without Chromium).
function parseArgs(script) {
  const [htmlDir, outDir] = process.argv.slice(2);
  if (!htmlDir || !outDir) {
    console.error(`usage: ${script} HTML_DIR OUT_DIR`);
    process.exit(2);
  }
  requireChromium();
  fs.mkdirSync(outDir, { recursive: true });
  return { htmlDir, outDir };
}

// Opens each case's page (c.file in htmlDir) and runs check(c, opened, fail);
// prints a summary and exits 0 if nothing failed, 1 otherwise.
function runCases(name, htmlDir, cases, check) {
  const run = async () => {
    const failures = [];
    const t0 = Date.now();
    const { ctx, close } = await launch();
    try {
      for (const c of cases) {
        const fail = (msg) => { failures.push(`${c.file}: ${msg}`); console.log(`  FAIL ${msg}`); };
        const file = path.resolve(htmlDir, c.file);
        console.log(c.file);
        if (!fs.existsSync(file)) { fail('not generated'); continue; }
        const opened = await openReport(ctx, file);
        await check(c, opened, fail);
        for (const e of opened.errors) fail(e); // also those raised by the check's clicks
        for (const u of opened.external) fail(`tried to fetch ${u}`);
        await opened.page.close();
      }
    } finally {
      await close();
    }
    console.log(`${name}: ${((Date.now() - t0) / 1000).toFixed(1)} s`);
    const passed = cases.length - new Set(failures.map((f) => f.split(':')[0])).size;
    console.log(`${passed} passed, ${cases.length - passed} failed`);
    process.exit(failures.length ? 1 : 0);
  };
  run().catch((e) => {
    console.error(e && e.stack ? e.stack : e);
    process.exit(1);
  });
}

module.exports = { CHROMIUM, requireChromium, launch, openReport, stats, parseArgs, runCases };
