#!/usr/bin/env node
// The live view's cost to the simulation (docs/live.md): wall time of an
// unpaced run (the most sensitive case: the loop never sleeps) without the
// live view, with the live view and no page, and with the page open in
// headless Chromium (the run starts paused, the page resumes it; the paused
// wall time, printed by kestrel, is taken off).  Prints the median of N runs
// of each and the ratios (goal: >= 95 % of the real-time factor without).
//
//   NODE_PATH=build/host-release/report/npm/node_modules \
//     node bench/live_overhead.cjs build/host-release/harness/kestrel scenarios/s1_sun_pointing.yaml [N] [DURATION]
'use strict';
const fs = require('fs');
const os = require('os');
const path = require('path');
const { spawn } = require('child_process');

const [kestrel, scenario, nArg, durArg] = process.argv.slice(2);
if (!kestrel || !scenario) {
  console.error('usage: live_overhead.cjs KESTREL SCENARIO [N=3] [DURATION=6000]');
  process.exit(2);
}
const N = Number(nArg || 3);
const PACE = Number(process.env.KESTREL_PACE || 100);           // paced case: multiple of real time
const PACED_DURATION = Number(process.env.KESTREL_PACED_DURATION || 600);
const DURATION = Number(durArg || 6000);
const CHROMIUM = process.env.KESTREL_CHROMIUM || '/usr/bin/chromium';
const tmp = fs.mkdtempSync(path.join(os.tmpdir(), 'kestrel-live-bench-'));
// KESTREL_PIN=1: kestrel on core 0, Chromium on core 1 (taskset), as on a
// machine with a core to spare for the browser; otherwise both float.
const PIN = process.env.KESTREL_PIN === '1';
let browser = CHROMIUM;
if (PIN) {
  browser = path.join(tmp, 'chromium-pinned.sh');
  fs.writeFileSync(browser, `#!/bin/sh\nexec taskset -c 1 ${CHROMIUM} "$@"\n`, { mode: 0o755 });
}

function run(extra, onUrl) {
  return new Promise((resolve, reject) => {
    const dur = extra.includes('--realtime') ? [] : ['--set', `duration=${DURATION}`];
    const args = ['run', scenario, '--force', '-o', path.join(tmp, 'run'), ...dur, ...extra];
    const child = PIN ? spawn('taskset', ['-c', '0', kestrel, ...args], { stdio: ['ignore', 'pipe', 'pipe'] })
      : spawn(kestrel, args, { stdio: ['ignore', 'pipe', 'pipe'] });
    let out = '';
    let err = '';
    let started = false;
    child.stdout.on('data', (d) => {
      out += d;
      const m = out.match(/live view: (http:\S+)/);
      if (m && onUrl && !started) { started = true; onUrl(m[1]).catch(reject); }
    });
    child.stderr.on('data', (d) => { err += d; });
    child.on('exit', (code) => {
      const w = out.match(/simulated in ([0-9.e+-]+) s/);
      const p = out.match(/paused ([0-9.e+-]+) s of wall time/);
      const d = out.match(/(\d+) frames published, (\d+) dropped/);
      if (d) drops.push(`${d[2]}/${d[1]}`);
      if (code !== 0 || !w) return reject(new Error(`kestrel exit ${code}:\n${out}\n${err}`));
      resolve(Number(w[1]) - (p ? Number(p[1]) : 0));
    });
  });
}

const drops = []; // "dropped/published" of each --live run, in order
const median = (a) => a.slice().sort((x, y) => x - y)[Math.floor(a.length / 2)];
const min = (a) => Math.min(...a);

async function main() {
  const { chromium } = require('playwright-core');
  const profile = fs.mkdtempSync(path.join(tmp, 'chromium-'));
  const ctx = await chromium.launchPersistentContext(profile, {
    executablePath: browser, headless: true, viewport: { width: 1400, height: 1000 },
    args: ['--no-sandbox', '--disable-gpu', '--no-first-run', '--disable-background-networking', '--enable-unsafe-swiftshader', '--use-angle=swiftshader'],
  });
  const res = { plain: [], live: [], poll: [], page: [] };
  let frames = [];
  for (let i = 0; i < N; i++) {
    res.plain.push(await run([]));
    res.live.push(await run(['--live', '--live-wait', '0', '--live-linger', '0']));
    // a client that polls like the page (every 100 ms) but draws nothing: the server's own cost
    let polling = true;
    res.poll.push(await run(['--live', '--live-wait', '0', '--live-linger', '0'], async (url) => {
      const u = new URL(url);
      const tok = u.searchParams.get('token');
      let since = 0;
      while (polling) {
        try {
          const r = await fetch(`${u.origin}/api/frames?since=${since}`, { headers: { 'X-Kestrel-Token': tok } });
          const j = await r.json();
          since = j.last;
        } catch (e) { break; }
        await new Promise((r) => setTimeout(r, 100));
      }
    }));
    polling = false;
    const page = await ctx.newPage();
    res.page.push(await run(['--live', '--live-paused', '--live-linger', '0'], async (url) => {
      await page.goto(url, { waitUntil: 'load' });
      await page.waitForFunction(() => window.kestrelLive && window.kestrelLive.state === 'paused' && window.kestrelLive.frames >= 1, null, { timeout: 30000 });
      await page.click('#resume');
    }));
    frames.push(await page.evaluate(() => window.kestrelLive.frames));
    await page.close();
  }
  // paced at PACE x real time (the way a run is watched): the real-time
  // factor kestrel reports, without and with the page (PACED_DURATION s)
  const paced = { plain: [], page: [] };
  for (let i = 0; i < Math.min(N, 3); i++) {
    const pacedArgs = ['--realtime', '--rt-scale', String(PACE), '--set', `duration=${PACED_DURATION}`];
    paced.plain.push(await run(pacedArgs));
    const page = await ctx.newPage();
    paced.page.push(await run([...pacedArgs, '--live', '--live-paused', '--live-linger', '0'], async (url) => {
      await page.goto(url, { waitUntil: 'load' });
      await page.waitForFunction(() => window.kestrelLive && window.kestrelLive.state === 'paused' && window.kestrelLive.frames >= 1, null, { timeout: 30000 });
      await page.click('#resume');
    }));
    await page.close();
  }
  await ctx.close();
  fs.rmSync(tmp, { recursive: true, force: true });
  const m = { plain: median(res.plain), live: median(res.live), poll: median(res.poll), page: median(res.page) };
  const rtf = (w) => (DURATION / w).toFixed(0);
  console.log(`kestrel live-view overhead: ${path.basename(scenario)}, ${DURATION} s unpaced, median of ${N}` +
    (PIN ? ', kestrel on core 0, Chromium on core 1' : ', kestrel and Chromium on any core'));
  const best = { plain: min(res.plain), live: min(res.live), poll: min(res.poll), page: min(res.page) };
  const pct = (k) => `${(100 * m.plain / m[k]).toFixed(1)} % (median), ${(100 * best.plain / best[k]).toFixed(1)} % (fastest)`;
  console.log('  real-time factor relative to the run without --live, from the median and from the fastest run of each:');
  for (const [k, label] of [['live', '--live, no page'], ['poll', '--live, polling client'], ['page', '--live, page in Chromium']])
    console.log(`    ${label.padEnd(26)} ${pct(k)}`);
  console.log(`  without --live            ${m.plain.toFixed(3)} s wall  (${rtf(m.plain)}x real time)  runs ${res.plain.map((x) => x.toFixed(3)).join(' ')}`);
  console.log(`  --live, no page           ${m.live.toFixed(3)} s wall  (${rtf(m.live)}x)  ${(100 * m.plain / m.live).toFixed(1)} % of the real-time factor without  runs ${res.live.map((x) => x.toFixed(3)).join(' ')}`);
  console.log(`  --live, polling client    ${m.poll.toFixed(3)} s wall  (${rtf(m.poll)}x)  ${(100 * m.plain / m.poll).toFixed(1)} % of the real-time factor without  runs ${res.poll.map((x) => x.toFixed(3)).join(' ')}`);
  const pm = { plain: median(paced.plain), page: median(paced.page) };
  console.log(`  paced at ${PACE}x, ${PACED_DURATION} s: real-time factor without --live ${(PACED_DURATION / pm.plain).toFixed(2)}x ` +
    `(runs ${paced.plain.map((x) => (PACED_DURATION / x).toFixed(2)).join(' ')}), with the page ${(PACED_DURATION / pm.page).toFixed(2)}x ` +
    `(runs ${paced.page.map((x) => (PACED_DURATION / x).toFixed(2)).join(' ')}): ${(100 * pm.plain / pm.page).toFixed(1)} %`);
  console.log(`  frames dropped/published by the server, every --live run in order: ${drops.join(' ')}`);
  console.log(`  --live, page in Chromium  ${m.page.toFixed(3)} s wall  (${rtf(m.page)}x)  ${(100 * m.plain / m.page).toFixed(1)} % of the real-time factor without  runs ${res.page.map((x) => x.toFixed(3)).join(' ')}; frames the page received ${frames.join(' ')}`);
}

main().catch((e) => { console.error(e && e.stack ? e.stack : e); process.exit(1); });
