#!/usr/bin/env node
// The live view in headless Debian Chromium (the report's browser-test
// set-up: playwright-core, /usr/bin/chromium, a new temporary profile):
// starts `kestrel run S1 --live --live-paused` paced at 10x real time, opens
// the printed URL, resumes the run, sees the page update from pushed frames
// (server-sent events: no /api/frames request), checks the gain boxes show
// the scenario's gains and follow a gain_K command, the device panel below
// the telemetry under the scenario's device names, clicks "fail_off" of rw2 (wheel 2), waits for
// the run to end and the report link, and checks in the recorded
// telemetry.csv that wheel 2's torque (wheel_torque_1) is 0 from the row of
// the tick the command entered at, and not in the row before, that
// `kestrel run manifest.json` reproduces telemetry.csv byte for byte, and
// that "save state" shows the checkpoint it wrote into the results folder
// (name, tick, size: the file's).  Requests to
// anything but the live server are aborted and count as failures.
//
//   NODE_PATH=<build>/report/npm/node_modules node live_browser_test.cjs KESTREL S1.yaml OUT_DIR
// Exit: 0 pass, 1 fail, 77 skipped (no chromium).
'use strict';
const fs = require('fs');
const os = require('os');
const path = require('path');
const { spawn } = require('child_process');

const CHROMIUM = process.env.KESTREL_CHROMIUM || '/usr/bin/chromium';
const [kestrel, scenario, outDir] = process.argv.slice(2);
if (!kestrel || !scenario || !outDir) {
  console.error('usage: live_browser_test.cjs KESTREL SCENARIO OUT_DIR');
  process.exit(2);
}
if (!fs.existsSync(CHROMIUM)) {
  console.log(`SKIP: ${CHROMIUM} not found (apt-get install chromium, or scripts/install-deps.sh host)`);
  process.exit(77);
}
const { chromium } = require('playwright-core');

const failures = [];
const fail = (msg) => { failures.push(msg); console.log(`  FAIL ${msg}`); };

// S1 as the closed-loop tests run it fast: 4 Hz plant and FSW, 60 s; at 10x
// real time the run takes 6 s of wall time, long enough to see it and click.
// It starts paused (the browser takes a few seconds to come up); the page resumes it.
const RUN_ARGS = ['run', scenario, '--live', '--live-paused', '--live-linger', '60', '--realtime', '--rt-scale', '10', '--csv', '--force',
  '--set', 'rates.dt=0.25', '--set', 'rates.fsw_divisor=1', '--set', 'rates.record_divisor=1',
  '--set', 'wheel_defaults.model=balanced', '--set', 'duration=60', '-o', path.join(outDir, 'run')];

function startRun() {
  return new Promise((resolve, reject) => {
    const child = spawn(kestrel, RUN_ARGS, { stdio: ['ignore', 'pipe', 'pipe'] });
    let out = '';
    const timer = setTimeout(() => reject(new Error('no URL printed within 20 s:\n' + out)), 20000);
    child.stdout.on('data', (d) => {
      out += d;
      const m = out.match(/live view: (http:\/\/127\.0\.0\.1:\d+\/\?token=[0-9a-f]{32})/);
      if (m) { clearTimeout(timer); resolve({ child, url: m[1], output: () => out }); }
    });
    child.stderr.on('data', (d) => process.stdout.write(`  [kestrel] ${d}`));
    child.on('exit', (code) => reject(new Error(`kestrel exited (${code}) before printing the URL:\n${out}`)));
  });
}

function readCsv(file) {
  const lines = fs.readFileSync(file, 'utf8').trim().split('\n');
  const names = lines[0].split(',').map((h) => h.replace(/ \[.*\]$/, '').trim());
  return { names, rows: lines.slice(1).map((l) => l.split(',').map(Number)) };
}

async function main() {
  fs.mkdirSync(outDir, { recursive: true });
  const t0 = Date.now();
  const run = await startRun();
  const origin = new URL(run.url).origin;
  console.log(`live run at ${origin}`);
  const profile = fs.mkdtempSync(path.join(os.tmpdir(), 'kestrel-live-chromium-'));
  const ctx = await chromium.launchPersistentContext(profile, {
    executablePath: CHROMIUM,
    headless: true,
    viewport: { width: 1400, height: 1000 },
    args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking',
      '--disable-component-update', '--disable-sync', '--enable-unsafe-swiftshader', '--use-angle=swiftshader'],
  });
  try {
    const page = await ctx.newPage();
    const errors = [];
    const external = [];
    const asked = { frames: 0, stream: 0 };
    page.on('request', (r) => {
      const u = r.url();
      if (u.includes('/api/frames')) asked.frames++;
      if (u.includes('/api/stream')) asked.stream++;
    });
    page.on('console', (m) => { if (m.type() === 'error') errors.push(`console.error: ${m.text()}`); });
    page.on('pageerror', (e) => errors.push(`page error: ${e.message}`));
    await page.route('**/*', (route) => {
      const u = route.request().url();
      if (u.startsWith(origin + '/') || /^(data|blob|about):/.test(u)) return route.continue();
      external.push(u);
      return route.abort();
    });
    await page.goto(run.url, { waitUntil: 'load' });
    // paused at t = 0; resume from the page, then it updates: frames arrive and sim time advances
    await page.waitForFunction(() => window.kestrelLive && window.kestrelLive.frames >= 1 && window.kestrelLive.state === 'paused',
      null, { timeout: 15000 });
    const a = await page.evaluate(() => window.kestrelLive.t);
    if (a !== 0) fail(`a run started paused shows t = ${a}`);
    await page.click('#resume');
    await page.waitForFunction((ta) => window.kestrelLive.t > ta + 1, a, { timeout: 15000 });
    const st = await page.evaluate(() => ({
      t: window.kestrelLive.t, state: window.kestrelLive.state, replay: window.kestrelLive.replay,
      plots: [...document.querySelectorAll('#plots .card')].map((e) => e.id),
      devices: document.querySelectorAll('#devices button').length,
      sim: document.getElementById('simtime').textContent, rtf: document.getElementById('rtf').textContent,
    }));
    console.log(`  page: t ${st.t} s, ${st.state}, plots [${st.plots.join(', ')}], ${st.devices} device buttons, ` +
      `3D ${st.replay}, "${st.sim}", "${st.rtf}"`);
    for (const p of ['plot-pointing', 'plot-rates', 'plot-wheel-speed', 'plot-wheel-torque'])
      if (!st.plots.includes(p)) fail(`no ${p}`);
    if (st.replay !== 'ok') fail(`3D view ${st.replay}`);
    if (st.t >= 60) fail('the run ended before the click: nothing to test');
    // pushed, not polled: at least 20 distinct frames, none twice, no /api/frames request
    await page.waitForFunction(() => window.kestrelLive.frames >= 20, null, { timeout: 15000 });
    const push = await page.evaluate(() => ({ tr: window.kestrelLive.transport, n: window.kestrelLive.frames,
      m: window.kestrelLive.messages, d: window.kestrelLive.dupes }));
    console.log(`  push: ${push.n} frames in ${push.m} messages (${push.tr}), ${asked.stream} stream request(s), ` +
      `${asked.frames} /api/frames requests`);
    if (push.tr !== 'push' || asked.frames !== 0 || asked.stream < 1 || push.d !== 0) fail(`not pushed: ${JSON.stringify(push)}, ${JSON.stringify(asked)}`);
    // the gain boxes now, compared with the scenario's gains (the manifest's) after the run
    const boxes = () => page.evaluate(() => ({ K: Number(document.querySelector('input[data-gain="K"]').value),
      P: Number(document.querySelector('input[data-gain="P"]').value) }));
    const g0 = await boxes();
    // a gain command (sent as a script would: not through the box) changes the box to the gain in force
    const K1 = g0.K * 0.5;
    const sent = await page.evaluate(async (k) => (await fetch('/api/command', { method: 'POST',
      headers: { 'X-Kestrel-Token': new URLSearchParams(location.search).get('token'), 'Content-Type': 'application/json' },
      body: JSON.stringify({ op: 'event', device: 'fsw', action: 'gain_K', value: k }) })).status, K1);
    if (sent !== 202) fail(`gain_K command: HTTP ${sent}`);
    await page.waitForFunction((k) => Number(document.querySelector('input[data-gain="K"]').value) === k, K1, { timeout: 15000 });
    const g1 = await boxes();
    console.log(`  gains: boxes K ${g0.K}, P ${g0.P}; after gain_K ${K1}: K ${g1.K}, P ${g1.P}`);
    if (g1.P !== g0.P) fail(`P box ${g1.P} after a gain_K command (was ${g0.P})`);
    const names = await page.evaluate(() => [...document.querySelectorAll('#devices button')].map((b) => b.dataset.device));
    const below = await page.evaluate(() => document.getElementById('sec-devices').getBoundingClientRect().top >=
      document.getElementById('sec-series').getBoundingClientRect().bottom);
    if (!below) fail('the device panel is not below the telemetry');
    // click "fail wheel 2"
    await page.click('#devices button[data-device="rw2"][data-action="fail_off"]');
    await page.waitForFunction(() => [...document.querySelectorAll('#commands tr')].some((r) => r.textContent.includes('rw2 fail_off') && r.textContent.includes('applied')),
      null, { timeout: 15000 });
    const cmdRow = await page.evaluate(() => [...document.querySelectorAll('#commands tr')].find((r) => r.textContent.includes('rw2 fail_off')).textContent);
    const tick = Number((cmdRow.match(/tick (\d+)/) || [])[1]);
    console.log(`  command: ${cmdRow}`);
    // save state: the page shows the checkpoint's name, tick, time and size
    await page.click('#save');
    await page.waitForFunction(() => /^(saved|not saved)/.test(document.getElementById('saved').textContent), null, { timeout: 15000 });
    const saved = await page.evaluate(() => document.getElementById('saved').textContent);
    console.log(`  save state: ${saved}`);
    const sm = saved.match(/^saved (checkpoint-(\d+)\.kckp): tick (\d+), t = [0-9.e+-]+ s, ([0-9.]+) kB$/);
    if (!sm || sm[2] !== sm[3]) fail(`save state shows "${saved}"`);
    await page.waitForTimeout(500); // a few more frames and 3D drawings
    await page.screenshot({ path: path.join(outDir, 'live.png'), fullPage: true });
    // the end: state and the report link
    await page.waitForFunction(() => window.kestrelLive.state === 'ended' && document.getElementById('report-link'), null, { timeout: 30000 });
    const reportOk = await page.evaluate(async () => {
      const r = await fetch(document.getElementById('report-link').href);
      return r.status === 200 && (await r.text()).includes('Kestrel run report');
    });
    if (!reportOk) fail('the report link does not serve the report');
    await page.screenshot({ path: path.join(outDir, 'live_end.png'), fullPage: true });
    for (const e of errors) fail(e);
    for (const u of external) fail(`tried to fetch ${u}`);

    // the recorded results: rw2 torque 0 from the tick the command entered at
    run.child.kill('SIGINT'); // ends the linger
    await new Promise((r) => run.child.on('exit', r));
    const csv = readCsv(path.join(outDir, 'run', 'telemetry.csv'));
    const ct = csv.names.indexOf('t');
    const cw = csv.names.indexOf('wheel_torque_1');
    if (cw < 0) fail('no wheel_torque_1 column');
    if (!(tick > 0)) fail(`no tick in the command log: ${cmdRow}`);
    const tk = tick * 0.25;
    const at = csv.rows.findIndex((r) => r[ct] === tk);
    if (at <= 0) fail(`no row at t = ${tk}`);
    else {
      if (csv.rows[at - 1][cw] === 0) fail(`rw2 torque already 0 before the command (t = ${csv.rows[at - 1][ct]})`);
      const bad = csv.rows.slice(at).filter((r) => r[cw] !== 0);
      if (bad.length) fail(`rw2 torque not 0 at t = ${bad[0][ct]} after the command at t = ${tk}`);
      console.log(`  telemetry: rw2 torque ${csv.rows[at - 1][cw]} N m at t = ${csv.rows[at - 1][ct]} s, 0 from t = ${tk} s ` +
        `to ${csv.rows[csv.rows.length - 1][ct]} s (${csv.rows.length - at} rows)`);
    }
    if (sm) {
      const f = path.join(outDir, 'run', sm[1]);
      const bytes = fs.existsSync(f) ? fs.statSync(f).size : -1;
      if (!(Math.abs(bytes / 1000 - Number(sm[4])) <= 0.0005 * bytes / 1000)) fail(`${f}: ${bytes} bytes, the page said ${sm[4]} kB`);
      else console.log(`  ${sm[1]} in the results folder: ${bytes} bytes`);
    }
    const man = JSON.parse(fs.readFileSync(path.join(outDir, 'run', 'manifest.json'), 'utf8'));
    // the gain boxes showed the scenario's gains; the page names the devices as the scenario does
    const K0 = man.scenario.fsw.mrp_fb.K, P0 = man.scenario.fsw.mrp_fb.P;
    if (g0.K !== K0 || g0.P !== P0) fail(`gain boxes K ${g0.K}, P ${g0.P}; the scenario's K ${K0}, P ${P0}`);
    else console.log(`  gain boxes at the start = the scenario's fsw.mrp_fb K ${K0}, P ${P0}`);
    const wheels = (man.scenario.wheels || []).map((w) => w.name);
    if (!wheels.length) fail('no wheel names in the manifest');
    for (const w of wheels) if (!names.includes(w)) fail(`no device row named ${w}`);
    const ev = man.scenario.events || [];
    const rw = ev.filter((e) => e.actions[0].device === 'rw2');
    const gk = ev.filter((e) => e.actions[0].device === 'fsw' && e.actions[0].action === 'gain_K');
    if (ev.length !== 2 || rw.length !== 1 || rw[0].t !== tk || gk.length !== 1) fail(`manifest events ${JSON.stringify(ev)}`);
    // the manifest replays the page-driven run bit for bit (telemetry.csv holds every value as %.17g)
    const replayDir = path.join(outDir, 'replay');
    const code = await new Promise((resolve) => {
      const c = spawn(kestrel, ['run', path.join(outDir, 'run', 'manifest.json'), '--csv', '--force', '-o', replayDir], { stdio: 'ignore' });
      c.on('exit', resolve);
    });
    if (code !== 0) fail(`kestrel run manifest.json exited ${code}`);
    else if (fs.readFileSync(path.join(replayDir, 'telemetry.csv'), 'utf8') !== fs.readFileSync(path.join(outDir, 'run', 'telemetry.csv'), 'utf8'))
      fail('the manifest replay differs from the live run (telemetry.csv)');
    else console.log('  manifest replay: telemetry.csv identical');
  } finally {
    await ctx.close();
    if (run.child.exitCode === null) run.child.kill('SIGINT');
    fs.rmSync(profile, { recursive: true, force: true });
  }
  console.log(`${failures.length ? 'FAILED' : 'passed'} in ${((Date.now() - t0) / 1000).toFixed(1)} s`);
  process.exit(failures.length ? 1 : 0);
}

main().catch((e) => { console.error(e && e.stack ? e.stack : e); process.exit(1); });
