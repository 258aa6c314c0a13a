#!/usr/bin/env node
// Writes synthetic mc_report_data.json files (the "Monte Carlo report" schema
// of docs/report.md) for the Monte Carlo report tests, made by a small model
// of a dispersed S1 campaign, not by the harness:
//   mc.json          60 runs (master seed 42): dispersed inertia angle, wheel
//                    failure time, initial rate; pointing error settling with a
//                    time constant that grows with the inertia angle, wheel
//                    speeds, body rates; criteria "settled" (pointing error
//                    after 300 s below 0.5 deg) and "wheel_speed_max" below
//                    4000 rpm; runs 7, 19, 33, 41 and 52 made to fail (and only they), run 11
//                    an invalid draw; percentiles 0/5/50/95/100 over all valid
//                    runs, 20 runs retained (failing first), relative report links
//   mc_thrusters.json 12 runs with a thruster force channel and levels 10/50/90
//   mc_big.json      1000 runs, 150 retained, 301 samples (size and speed)
//   mc_minimal.json  header only: no criteria, table, series
//   mc_empty.json    {}
//   mc_hostile.json  </script>, <!-- and quotes in every string, a javascript:
//                    and an absolute report link, non-numbers where numbers go,
//                    ragged and missing columns, unknown keys
// Also writes mc_expect.json: what the browser test must find (row order,
// counts), computed here from the model, not by the page's code.
// Usage: node make_mc_data.cjs OUTDIR
'use strict';
const fs = require('fs');
const path = require('path');

const out = process.argv[2] || '.';
fs.mkdirSync(out, { recursive: true });

let seed = 4242;
function rand() { // xorshift32, deterministic
  seed ^= seed << 13; seed >>>= 0; seed ^= seed >>> 17; seed ^= seed << 5; seed >>>= 0;
  return seed / 4294967296;
}
function gauss() { return Math.sqrt(-2 * Math.log(rand() + 1e-12)) * Math.cos(2 * Math.PI * rand()); }
const r6 = (v) => Number(v.toPrecision(7));

// nearest-rank percentile of sorted values
function pct(sorted, p) {
  if (!sorted.length) return null;
  const k = Math.min(sorted.length - 1, Math.max(0, Math.ceil((p / 100) * sorted.length) - 1));
  return sorted[k];
}

// One dispersed S1-like run on the time grid t.
function simulate(t, draw, forceFail) {
  // settling time constant [s]: at most about 25 + 5 * 6 = 55 s for a 3-sigma
  // angle, so e0 exp(-300 / 55) < 0.15 deg and only forced runs miss 0.5 deg
  const tau = 25 + 5 * Math.abs(draw.angle) + (forceFail ? 400 : 0);
  const e0 = 10 + 20 * rand();
  const floor = 0.02 + 0.01 * rand();
  const S = { pointing_error_deg: [], omega_BN_B_x: [], omega_BN_B_y: [], omega_BN_B_z: [],
    wheel_speed_rpm_0: [], wheel_speed_rpm_1: [], wheel_speed_rpm_2: [] };
  const w0 = [draw.rate, -0.5 * draw.rate, 0.3 * draw.rate];
  // at most 1000 + 1500 = 2500 rpm, x 1.3 after the failure: 3250 < 4000 rpm;
  // a forced run x 2.6: above 4000 rpm
  const spin = [800 + 200 * rand(), -700 - 200 * rand(), 500 + 100 * rand()];
  for (const ti of t) {
    const d = Math.exp(-ti / tau);
    S.pointing_error_deg.push(r6(e0 * d + floor * (1 + 0.2 * Math.sin(ti / 7))));
    ['x', 'y', 'z'].forEach((a, j) => S[`omega_BN_B_${a}`].push(r6(w0[j] * d + 1e-5 * Math.sin(ti / 3 + j))));
    const failed = ti >= draw.tfail;
    for (let i = 0; i < 3; i++) {
      // wheel 0 fails at tfail; the others take up its momentum
      let rpm = spin[i] + 1500 * (1 - d) * (i + 1) / 3;
      if (i === 0 && failed) rpm *= Math.exp(-(ti - draw.tfail) / 200);
      else if (failed) rpm *= 1 + (forceFail ? 1.6 : 0.3) * (1 - Math.exp(-(ti - draw.tfail) / 100));
      S[`wheel_speed_rpm_${i}`].push(r6(rpm));
    }
  }
  return S;
}

function campaign({ runs, nT, dtT, keep, failing, invalid, levels, scenario, thrusters = false }) {
  const t = Array.from({ length: nT }, (_, k) => r6(k * dtT));
  const criteria = [
    { name: 'settled', metric: 'settled', op: 'below', threshold: 0.5, unit: 'deg', what: 'max pointing_error_deg for t >= 300 s' },
    { name: 'wheels', metric: 'wheel_speed_max', op: 'below', threshold: 4000, unit: 'rpm', what: 'max |wheel_speed_rpm_*|' },
  ];
  const drawn = [{ name: 'spacecraft.inertia.angle_deg', unit: 'deg' }, { name: 'events[0].t', unit: 's' },
    { name: 'initial.omega_BN_B[0]', unit: 'rad/s' }];
  const metrics = [{ name: 'settled', unit: 'deg' }, { name: 'wheel_speed_max', unit: 'rpm' }, { name: 'final_error', unit: 'deg' }];
  const channels = [
    { name: 'pointing_error', unit: 'deg', columns: ['pointing_error_deg'] },
    { name: 'omega_BN_B', unit: 'rad/s', columns: ['omega_BN_B_x', 'omega_BN_B_y', 'omega_BN_B_z'] },
    { name: 'wheel_speed', unit: 'rpm', columns: ['wheel_speed_rpm_0', 'wheel_speed_rpm_1', 'wheel_speed_rpm_2'] },
  ];
  if (thrusters) channels.push({ name: 'thruster_force', unit: 'N', columns: ['thruster_force_0', 'thruster_force_1'] });
  const table = [];
  const all = []; // series of every valid run, for the percentiles
  for (let k = 0; k < runs; k++) {
    const draw = { angle: 2 * gauss(), tfail: 100 + 400 * rand(), rate: 0.02 * gauss() };
    const row = { index: k, seed: String(1000000000000000000n + BigInt(k) * 7919n), pass: true, invalid: false, reason: '',
      drawn: [r6(draw.angle), r6(draw.tfail), r6(draw.rate)], metrics: [null, null, null], report: `runs/${String(k).padStart(6, '0')}/report.html` };
    if (invalid.includes(k)) {
      Object.assign(row, { pass: false, invalid: true, reason: 'invalid draw: inertia not positive definite', report: null });
      table.push(row);
      continue;
    }
    const S = simulate(t, draw, failing.includes(k));
    if (thrusters) {
      S.thruster_force_0 = t.map((ti) => r6(ti < 100 ? 1 + 0.05 * draw.rate * 100 : 0));
      S.thruster_force_1 = t.map((ti) => r6(ti >= draw.tfail && ti < draw.tfail + 50 ? 1 : 0));
    }
    const settled = Math.max(...S.pointing_error_deg.filter((_, i) => t[i] >= 300));
    const wmax = Math.max(...[0, 1, 2].map((i) => Math.max(...S[`wheel_speed_rpm_${i}`].map(Math.abs))));
    row.metrics = [r6(settled), r6(wmax), S.pointing_error_deg[nT - 1]];
    const reasons = [];
    if (!(settled < 0.5)) reasons.push(`settled ${r6(settled)} deg >= 0.5 deg`);
    if (!(wmax < 4000)) reasons.push(`wheel_speed_max ${r6(wmax)} rpm >= 4000 rpm`);
    row.pass = reasons.length === 0;
    row.reason = reasons.join('; ');
    table.push(row);
    all.push({ index: k, pass: row.pass, S });
  }
  const columns = channels.flatMap((c) => c.columns);
  const pcols = {};
  for (const c of columns) {
    pcols[c] = levels.map(() => []);
    for (let i = 0; i < nT; i++) {
      const v = all.map((r) => r.S[c][i]).sort((a, b) => a - b);
      levels.forEach((p, j) => pcols[c][j].push(pct(v, p)));
    }
  }
  const retained = all.filter((r) => !r.pass).concat(all.filter((r) => r.pass)).slice(0, keep)
    .map((r) => ({ index: r.index, pass: r.pass, columns: r.S }));
  const failed = table.filter((r) => !r.pass && !r.invalid).length;
  // the summary table as kestrel mc writes it: failing first
  table.sort((a, b) => (a.pass - b.pass) || (a.index - b.index));
  return {
    kind: 'kestrel_mc_report', schema: 1, kestrel_version: '0.1.0', scenario, master_seed: 42,
    runs, failed, invalid: invalid.length, wall_seconds: r6(runs * 0.8),
    criteria, drawn, metrics, table,
    series: { t, channels, percentiles: { levels, columns: pcols }, runs: retained },
    // what drives the failures, as kestrel mc writes it (figures made up: the page only shows them)
    drivers: [
      { criterion: 'settled', runs: runs - invalid.length, failed: failing.length, failing, ranked_by: 'delta',
        ranked: [{ drawn: 'events[0].t', unit: 's', n: runs - invalid.length, auc: 0.95, delta: 0.9, p: 1e-4, rho: 0.7 },
          { drawn: 'initial.omega_BN_B[0]', unit: 'rad/s', n: runs - invalid.length, auc: 0.55, delta: 0.1, p: 0.6, rho: 0.05 },
          { drawn: 'spacecraft.inertia.angle_deg', unit: 'deg', n: runs - invalid.length, auc: 0.48, delta: -0.04, p: 0.8, rho: null }] },
      { criterion: 'wheels', runs: runs - invalid.length, failed: 0, failing: [], ranked_by: 'rho', ranked: [] },
    ],
  };
}

const mc = campaign({ runs: 60, nT: 201, dtT: 3, keep: 20, failing: [7, 19, 33, 41, 52], invalid: [11],
  levels: [0, 5, 50, 95, 100], scenario: 's1_monte_carlo' });
fs.writeFileSync(path.join(out, 'mc.json'), JSON.stringify(mc));
const status = (r) => (r.invalid ? 'invalid' : r.pass ? 'pass' : 'fail');
const rank = { fail: 0, invalid: 1, pass: 2 };
const order = [...mc.table].sort((a, b) => rank[status(a)] - rank[status(b)] || a.index - b.index).map((r) => r.index);
fs.writeFileSync(path.join(out, 'mc_expect.json'), JSON.stringify({
  rows: mc.table.length, order, failing: mc.table.filter((r) => status(r) === 'fail').map((r) => r.index).sort((a, b) => a - b),
  invalid: mc.table.filter((r) => r.invalid).map((r) => r.index), retained: mc.series.runs.length,
  // sorted by the first drawn value, ascending (nulls last: none here)
  byDrawn0: [...mc.table].sort((a, b) => a.drawn[0] - b.drawn[0] || a.index - b.index).map((r) => r.index),
  failedHeader: mc.failed,
}));

fs.writeFileSync(path.join(out, 'mc_thrusters.json'), JSON.stringify(campaign({ runs: 12, nT: 101, dtT: 6, keep: 12,
  failing: [3], invalid: [], levels: [10, 50, 90], scenario: 's1_thrusters', thrusters: true })));
fs.writeFileSync(path.join(out, 'mc_big.json'), JSON.stringify(campaign({ runs: 1000, nT: 301, dtT: 2, keep: 150,
  failing: Array.from({ length: 20 }, (_, k) => 7 + 50 * k), invalid: [5, 500], levels: [0, 5, 50, 95, 100], scenario: 's1_big' })));
fs.writeFileSync(path.join(out, 'mc_minimal.json'), JSON.stringify({ kind: 'kestrel_mc_report', schema: 1, scenario: 'minimal', master_seed: 1, runs: 0, failed: 0, invalid: 0 }));
fs.writeFileSync(path.join(out, 'mc_empty.json'), '{}');

function hostile() {
  const evil = '</script><script>window.__pwned=1</script><!-- "q" \'s\' & \u2028 \u00e9';
  const d = campaign({ runs: 6, nT: 21, dtT: 30, keep: 6, failing: [2], invalid: [4], levels: [95, 'x', 5, 50], scenario: 'hostile ' + evil });
  d.criteria[0].name = evil;
  d.criteria[0].what = '<img src=x onerror="window.__pwned=2">';
  d.criteria.push({ name: 'no_metric', metric: null, op: 'never', threshold: 'NaN' });
  d.drawn[1].name = '<b>bold</b>';
  d.metrics[2].unit = '</style>';
  d.table[0].reason = evil;
  d.table[0].report = 'javascript:window.__pwned=3';
  d.table[1].report = 'https://example.invalid/x.html';
  d.table[2].report = '//example.invalid/y.html';
  d.table[3].seed = 12345;
  d.table[3].drawn = ['1', null, { a: 1 }, 7];
  d.table[3].metrics = [1];
  d.table.push(null, 'x', { index: 'nine' });
  d.series.channels.push({ name: 'ghost', unit: 'm', columns: ['not_in_any_run'] }, { name: 'bad', columns: 'x' }, 7);
  d.series.runs[0].columns.pointing_error_deg = d.series.runs[0].columns.pointing_error_deg.slice(0, 5);
  d.series.runs[1].columns.omega_BN_B_x = 'oops';
  d.series.runs.push({ index: 99, pass: false, columns: { pointing_error_deg: [1, 'a', null, -1] } }, { pass: true });
  d.series.percentiles.columns.wheel_speed_rpm_0 = null;
  d.extra = { '</script>': '<!--' };
  return d;
}
fs.writeFileSync(path.join(out, 'mc_hostile.json'), JSON.stringify(hostile()));
console.log(`Monte Carlo report data written to ${out}`);
