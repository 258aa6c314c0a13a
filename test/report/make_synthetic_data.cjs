#!/usr/bin/env node
// Writes synthetic report_data.json files (the schema of docs/report.md) for
// the report tests, made by small physical models, not by the harness:
//   s1.json       4 pyramid wheels, no thrusters: tumble, sun acquisition, hold,
//                 wheel-imbalance jitter on the body rates; DOT with message nodes
//   s2.json       8 thrusters, no wheels: main-engine burn with misalignment,
//                 pulsed ACS thrusters, propellant; DOT with labelled edges
//   minimal.json  meta and t only
//   empty.json    {}
//   long.json     200 001 samples of a few series (decimation, big arrays)
//   s3.json       an Earth-orbit run: circular 500 km orbit with the Sun in its
//                 plane (eclipses), gravity-gradient and magnetic torques on a
//                 body held fixed in N, their accumulated momentum taken up by
//                 the wheels, the field in B and three magnetorquer dipoles
//   hostile.json  </script>, <!-- and quotes in strings, NaN-like nulls, ragged
//                 series, a malformed DOT
//   alias.json    the end of s1 with wheels at 3000 to 4500 rpm recorded at 10 Hz
// Usage: node make_synthetic_data.cjs OUTDIR
'use strict';
const fs = require('fs');
const path = require('path');

const out = process.argv[2] || '.';
fs.mkdirSync(out, { recursive: true });

let seed = 12345;
function rand() { // xorshift32, deterministic
  seed ^= seed << 13; seed >>>= 0; seed ^= seed >>> 17; seed ^= seed << 5; seed >>>= 0;
  return seed / 4294967296;
}
function gauss() { return Math.sqrt(-2 * Math.log(rand() + 1e-12)) * Math.cos(2 * Math.PI * rand()); }
const r6 = (v) => Number(v.toPrecision(7));

function qmul(a, b) { // scalar-first Hamilton product
  return [a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
    a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
    a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
    a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0]];
}
function qnorm(q) { const n = Math.hypot(...q); return q.map((v) => v / n); }
// Euler-parameter kinematics dq/dt = 1/2 B(q) w (q_BN, w = omega_BN in B)
function qstep(q, w, dt) {
  const dq = qmul(q, [0, w[0], w[1], w[2]]).map((v) => 0.5 * v * dt);
  return qnorm(q.map((v, i) => v + dq[i]));
}
const principalDeg = (q) => (2 * Math.acos(Math.min(1, Math.abs(q[0]))) * 180) / Math.PI;

function s1() {
  const dt = 0.1;
  const T = 1200;
  const n = Math.round(T / dt) + 1;
  const I = [900, 800, 600];
  const Js = 0.15; // wheel inertia about spin axis [kg m^2]
  const b = Math.atan(1 / Math.sqrt(2)); // pyramid elevation
  const G = [0, 1, 2, 3].map((i) => { const a = (Math.PI / 2) * i + Math.PI / 4; return [Math.cos(b) * Math.cos(a), Math.cos(b) * Math.sin(a), Math.sin(b)]; });
  let q = qnorm([0.3, -0.6, 0.5, 0.55]);
  let w = [0.035, -0.026, 0.018];
  const Om = [150, -120, 90, 200].map((r) => (r * 2 * Math.PI) / 60);
  const S = { t: [], pointing_error_deg: [], omega_BN_B_x: [], omega_BN_B_y: [], omega_BN_B_z: [] };
  for (let i = 0; i < 4; i++) { S[`wheel_speed_rpm_${i}`] = []; S[`wheel_torque_${i}`] = []; }
  const att = { t: [], q_BN: [] };
  for (let k = 0; k < n; k++) {
    const t = k * dt;
    // control: rate damping first, then MRP-like PD towards q_BN = identity
    const sgn = q[0] < 0 ? -1 : 1;
    const e = [q[1] * sgn, q[2] * sgn, q[3] * sgn];
    const Kp = t < 60 ? 0 : 0.15;
    const P = 4;
    // PD plus gyroscopic feed-forward w x (I w + h_wheels), as an MRP feedback law does
    const hw0 = G.reduce((acc, g, i) => acc.map((v, j) => v + Js * Om[i] * g[j]), [0, 0, 0]);
    const H0 = [I[0] * w[0] + hw0[0], I[1] * w[1] + hw0[1], I[2] * w[2] + hw0[2]];
    const ff = [w[1] * H0[2] - w[2] * H0[1], w[2] * H0[0] - w[0] * H0[2], w[0] * H0[1] - w[1] * H0[0]];
    let L = [0, 1, 2].map((j) => -Kp * e[j] * I[j] / 100 - P * w[j] * I[j] / 100 + ff[j]);
    L = L.map((v) => Math.max(-0.2, Math.min(0.2, v)));
    // minimum-norm wheel torques: u = G^T (G G^T)^-1 (-L); G G^T = (4/3) I for this pyramid
    const u = G.map((g) => -(0.75) * (g[0] * L[0] + g[1] * L[1] + g[2] * L[2]));
    const jit = G.reduce((acc, g, i) => acc.map((v, j) => v + 4e-6 * Math.sin(Om[i] * t + i) * g[j]), [0, 0, 0]);
    S.t.push(r6(t));
    S.pointing_error_deg.push(r6(principalDeg(q)));
    ['x', 'y', 'z'].forEach((a, j) => S[`omega_BN_B_${a}`].push(r6(w[j] + jit[j] + 2e-7 * gauss())));
    for (let i = 0; i < 4; i++) {
      S[`wheel_speed_rpm_${i}`].push(r6((Om[i] * 60) / (2 * Math.PI)));
      S[`wheel_torque_${i}`].push(r6(u[i]));
    }
    if (k % 5 === 0) { att.t.push(r6(t)); att.q_BN.push(q.map(r6)); }
    // dynamics: I dw = L - w x (I w + hw), crude but fine for a picture
    const hw = G.reduce((acc, g, i) => acc.map((v, j) => v + Js * Om[i] * g[j]), [0, 0, 0]);
    const H = [I[0] * w[0] + hw[0], I[1] * w[1] + hw[1], I[2] * w[2] + hw[2]];
    const wxH = [w[1] * H[2] - w[2] * H[1], w[2] * H[0] - w[0] * H[2], w[0] * H[1] - w[1] * H[0]];
    const dw = [0, 1, 2].map((j) => (L[j] - wxH[j]) / I[j]);
    for (let i = 0; i < 4; i++) Om[i] += (u[i] / Js) * dt;
    q = qstep(q, w, dt);
    w = w.map((v, j) => v + dw[j] * dt);
  }
  const units = { t: 's', pointing_error_deg: 'deg', omega_BN_B_x: 'rad/s', omega_BN_B_y: 'rad/s', omega_BN_B_z: 'rad/s' };
  for (let i = 0; i < 4; i++) { units[`wheel_speed_rpm_${i}`] = 'rpm'; units[`wheel_torque_${i}`] = 'N m'; }
  // the harness's style: components "c:<name>" as boxes, messages "m:<name>" as ellipses
  const comps = { css: 'plant', imu: 'plant', fsw: 'FSW application', wheels: 'plant', hub: 'plant', recorder: '' };
  const msgs = { CssArrayMsg: ['css', ['fsw', 'recorder']], ImuMsg: ['imu', ['fsw']], RwSpeedMsg: ['wheels', ['fsw', 'recorder']],
    RwCmdMsg: ['fsw', ['wheels', 'recorder']], CmdTorqueMsg: ['fsw', ['recorder']], AttGuidMsg: ['fsw', ['recorder']],
    TruthMsg: ['hub', ['css', 'imu', 'recorder']], MetricsMsg: ['hub', ['recorder']] };
  let dot = 'digraph "S1 sun pointing" {\n  rankdir=LR;\n  node [fontname="Helvetica", fontsize=10];\n';
  for (const [c, what] of Object.entries(comps)) dot += `  "c:${c}" [shape=box, style="rounded,filled", fillcolor="#dde8f5", label="${what ? c + ' (' + what + ')' : c}"];\n`;
  for (const m of Object.keys(msgs)) dot += `  "m:${m}" [shape=ellipse, label="${m}"];\n`;
  for (const [m, [w, rs]] of Object.entries(msgs)) {
    dot += `  "c:${w}" -> "m:${m}";\n`;
    for (const r of rs) dot += `  "m:${m}" -> "c:${r}";\n`;
  }
  dot += '}\n';
  // a few of the other columns the harness records
  S.sigma_BN_x = []; S.sigma_BN_y = []; S.sigma_BN_z = []; S.E_rot = [];
  for (let i = 0; i < 4; i++) S[`wheel_cmd_${i}`] = S[`wheel_torque_${i}`].map((v) => r6(v * 1.02));
  for (let k = 0; k < S.t.length; k++) {
    const j = Math.min(att.q_BN.length - 1, Math.floor(k / 5));
    const q = att.q_BN[j];
    const d = 1 + q[0];
    S.sigma_BN_x.push(r6(q[1] / d)); S.sigma_BN_y.push(r6(q[2] / d)); S.sigma_BN_z.push(r6(q[3] / d));
    S.E_rot.push(r6(0.5 * (I[0] * S.omega_BN_B_x[k] ** 2 + I[1] * S.omega_BN_B_y[k] ** 2 + I[2] * S.omega_BN_B_z[k] ** 2)));
  }
  Object.assign(units, { sigma_BN_x: '-', sigma_BN_y: '-', sigma_BN_z: '-', E_rot: 'J', wheel_cmd_0: 'N*m', wheel_cmd_1: 'N*m', wheel_cmd_2: 'N*m', wheel_cmd_3: 'N*m' });
  // the reference is the identity attitude, so sigma_BR = sigma_BN; FSW
  // statuses and flags as the harness records them: most constant (a table
  // row each), the cycle status and the wheel-saturation stage FSW_W_SAT
  // (2) while the torque limit acts in the first 30 s; a conserved
  // momentum whose components vary by 1e-7 N m s about (1234.5678, -56.78, 0.9)
  ['x', 'y', 'z'].forEach((a) => { S[`sigma_BR_${a}`] = S[`sigma_BN_${a}`].slice(); units[`sigma_BR_${a}`] = '-'; });
  const flat = (v) => S.t.map(() => v);
  S.fsw_status = S.t.map((t) => (t < 30 ? 2 : 0));
  S.fsw_stage_rw_sat = S.fsw_status.slice();
  for (const k of ['fsw_safe_output', 'fsw_stage_css', 'fsw_stage_thr_map', 'fsw_stage_bdot', 'fsw_mode']) S[k] = flat(0);
  S.sun_valid = flat(1);
  for (let i = 0; i < 4; i++) S[`fsw_rw_failed_${i}`] = flat(0);
  ['x', 'y', 'z'].forEach((a, j) => {
    S[`H_C_N_${a}`] = S.t.map((t) => [1234.5678, -56.78, 0.9][j] + 1e-7 * Math.sin(0.01 * t + j));
    units[`H_C_N_${a}`] = 'kg*m^2/s';
  });
  const sensors = { css: { fov_deg: 80, normals_B: [[0, 0.7071, 0.7071], [0.7071, 0, 0.7071], [0, -0.7071, 0.7071], [-0.7071, 0, 0.7071], [0, 0, -1]] },
    star_tracker: { boresight_B: [0, 0, 1], sun_exclusion_deg: 30 } };
  return {
    meta: { scenario: 'S1 deep-space sun pointing (synthetic)', description: 'Synthetic test data: tumble, rate damping, slew to the Sun, hold; 4 pyramid wheels.',
      seed: 42, version: '0.1.0', dt, duration: T, record_period: dt, fsw_period: 0.1, fsw_mode: 'sun_safe', num_wheels: 4, num_thrusters: 0 },
    series: S, units, attitude: att,
    geometry: { wheel_axes_B: G.map((g) => g.map(r6)), wheel_positions_B: G.map((g) => g.map((v) => r6(0.3 * v))), thrusters: [],
      wheel_names: ['rw1', 'rw2', 'rw3', 'rw4'], sensors, sun: { t: [0], r_N: [[1.495978707e11, 0, 0]] } },
    dataflow_dot: dot,
    events: [{ name: 'rw2_fails', tick: 60000, t: 600, actions: 'rw2 fail_off' },
      { name: 'rw2_flagged', tick: 60010, t: 600.1, actions: 'rw2 command_unavailable' }],
  };
}

function s2() {
  const dt = 0.1;
  const T = 300;
  const n = Math.round(T / dt) + 1;
  const thr = [];
  for (let i = 0; i < 8; i++) { // 4 pairs at the +-z corners, firing tangentially
    const a = (Math.PI / 2) * (i >> 1) + Math.PI / 4;
    const r = [1.1 * Math.cos(a), 1.1 * Math.sin(a), i % 2 ? -0.9 : 0.9];
    const s = (i % 4 < 2 ? 1 : -1);
    thr.push({ name: `acs_${i}`, r_B: r.map(r6), dir_B: [-Math.sin(a) * s, Math.cos(a) * s, 0].map(r6) });
  }
  const S = { t: [], pointing_error_deg: [], omega_BN_B_x: [], omega_BN_B_y: [], omega_BN_B_z: [], propellant_kg: [] };
  for (let i = 0; i < 8; i++) { S[`thruster_on_time_${i}`] = []; S[`thruster_force_${i}`] = []; }
  const att = { t: [], q_BN: [] };
  let q = [1, 0, 0, 0];
  let w = [0, 0, 0];
  let m = 1200;
  const mdotMain = 400 / (315 * 9.80665);
  const ctrlPeriod = 0.5;
  let onTimes = new Array(8).fill(0);
  let tLastCtrl = -1;
  for (let k = 0; k < n; k++) {
    const t = k * dt;
    const burning = t >= 30 && t < 250;
    const dist = burning ? [0.9, -0.6, 0.15] : [0, 0, 0]; // misalignment torque [N m]
    if (t - tLastCtrl >= ctrlPeriod - 1e-9) {
      tLastCtrl = t;
      const sgn = q[0] < 0 ? -1 : 1;
      const Lr = [0, 1, 2].map((j) => -400 * q[j + 1] * sgn - 900 * w[j]);
      onTimes = thr.map((th) => {
        const tq = [th.r_B[1] * th.dir_B[2] - th.r_B[2] * th.dir_B[1], th.r_B[2] * th.dir_B[0] - th.r_B[0] * th.dir_B[2], th.r_B[0] * th.dir_B[1] - th.r_B[1] * th.dir_B[0]];
        // share of the demanded torque this thruster can give (two per axis sense)
        const frac = (tq[0] * Lr[0] + tq[1] * Lr[1] + tq[2] * Lr[2]) / (2 * 22 * (tq[0] ** 2 + tq[1] ** 2 + tq[2] ** 2));
        const on = Math.max(0, Math.min(ctrlPeriod, frac * ctrlPeriod));
        return on < 0.005 ? 0 : on; // minimum impulse bit
      });
    }
    const phase = t - tLastCtrl;
    const F = onTimes.map((on) => (phase < on ? 22 : 0));
    let L = dist.slice();
    F.forEach((f, i) => {
      const th = thr[i];
      L[0] += f * (th.r_B[1] * th.dir_B[2] - th.r_B[2] * th.dir_B[1]);
      L[1] += f * (th.r_B[2] * th.dir_B[0] - th.r_B[0] * th.dir_B[2]);
      L[2] += f * (th.r_B[0] * th.dir_B[1] - th.r_B[1] * th.dir_B[0]);
    });
    S.t.push(r6(t));
    S.pointing_error_deg.push(r6(principalDeg(q)));
    ['x', 'y', 'z'].forEach((a, j) => S[`omega_BN_B_${a}`].push(r6(w[j] + 1e-6 * gauss())));
    S.propellant_kg.push(r6(m - 800));
    for (let i = 0; i < 8; i++) { S[`thruster_on_time_${i}`].push(r6(onTimes[i])); S[`thruster_force_${i}`].push(r6(F[i])); }
    att.t.push(r6(t));
    att.q_BN.push(q.map(r6));
    const I = [1500, 1400, 1100];
    w = w.map((v, j) => v + (L[j] / I[j]) * dt);
    q = qstep(q, w, dt);
    m -= ((burning ? mdotMain : 0) + F.reduce((s, f) => s + f, 0) / (220 * 9.80665)) * dt;
  }
  const units = { t: 's', pointing_error_deg: 'deg', omega_BN_B_x: 'rad/s', omega_BN_B_y: 'rad/s', omega_BN_B_z: 'rad/s', propellant_kg: 'kg' };
  for (let i = 0; i < 8; i++) { units[`thruster_on_time_${i}`] = 's'; units[`thruster_force_${i}`] = 'N'; }
  ['x', 'y', 'z'].forEach((a) => { S[`r_BN_N_${a}`] = []; units[`r_BN_N_${a}`] = 'm'; });
  for (const t of S.t) {
    const u = (4500 / 3.8e6) * (t - 140); // periapsis at t = 140 s
    S.r_BN_N_x.push(r6(3.8e6 * Math.cos(u))); S.r_BN_N_y.push(r6(3.8e6 * Math.sin(u))); S.r_BN_N_z.push(0);
  }
  const dot = `digraph G {
  node [shape=box];
  nav -> att_track [label="NavAttMsg"];
  guid_inertial -> att_track [label="AttRefMsg"];
  att_track -> mrp_fb [label="AttGuidMsg"];
  mrp_fb -> thr_map [label="CmdTorqueMsg"];
  thr_map -> thr_pulse_rem [label="THRArrayCmdForceMsg"];
  thr_pulse_rem -> thrusters [label="THRArrayOnTimeCmdMsg"];
  main_engine -> hub [label="ForceTorqueMsg"];
  thrusters -> hub [label="ForceTorqueMsg"];
  thrusters -> propellant [label="MassFlowMsg"];
  propellant -> hub [label="MassPropsMsg"];
  hub -> nav [label="SCStatesMsg"];
  hub -> orbit_report [label="SCStatesMsg"];
}`;
  return {
    meta: { scenario: 'S2 Mars orbit insertion (synthetic)', seed: 7, version: '0.1.0', dt, duration: T, pulsing: 'remainder' },
    series: S, units, attitude: att, dataflow_dot: dot,
    // a periapsis pass at Mars: 3800 km circle at the periapsis speed, a burn from 30 s to 250 s
    geometry: { wheel_axes_B: [], thrusters: thr, central_body: { name: 'Mars', mu: 4.2828314e13, radius: 3396190 },
      burn: { thruster: 'main', start: 30, duration: 220 }, sun: { t: [0], r_N: [[0, 2.279e11, 0]] },
      sensors: { star_tracker: { boresight_B: [0, 0, 1], sun_exclusion_deg: 0 } } },
    // the run's own story as kestrel writes it (summary.txt's items in order)
    summary: {
      complete: { value: 1, unit: '', what: '1: the run reached its duration' },
      on_time_main_s: { value: 480, unit: 's', what: 'valve-open time, whole run (every latched pulse, exact)' },
      dv_nongrav_mps: { value: 1089.5, unit: 'm/s', what: 'the delivered (sensed) delta-v' },
      requirement_settled: { value: 0.2, unit: 'deg', what: 'PASS: max of pointing_error_deg below 0.5' },
    },
    summary_order: ['complete', 'on_time_main_s', 'dv_nongrav_mps', 'requirement_settled'],
    warnings: ['wheels[0] (rw1): its imbalance jitter is under-resolved (synthetic)'],
    requirements: [
      { name: 'settled', what: 'max of pointing_error_deg', unit: 'deg', below: true, threshold: 0.5, value: 0.2, pass: true },
      { name: 'fuel', what: 'drop of propellant_kg', unit: 'kg', below: true, threshold: 100, value: 120, pass: false },
    ],
  };
}

function hostile() {
  const d = s1();
  const n = 400;
  for (const k of Object.keys(d.series)) d.series[k] = d.series[k].slice(0, n);
  d.series.wheel_speed_rpm_3 = d.series.wheel_speed_rpm_3.slice(0, 100); // ragged
  d.series.omega_BN_B_y[10] = null; // NaN written as null
  d.series.pointing_error_deg[11] = 'nan';
  d.series.extra_thing_x = d.series.t.map((t) => Math.sin(t)); // unknown series
  d.attitude.q_BN[3] = [0, 0, 0, 0]; // bad quaternion
  d.attitude.q_BN[4] = 'x';
  d.meta.scenario = 'hostile </script><script>window.__pwned=1</script><!-- "quotes" & \u2028 \u00e9';
  d.geometry.thrusters = [{ r_B: [1, 0, 0] }, { r_B: [0, 1, 0], dir_B: [0, 0, 0] }, 5];
  d.dataflow_dot = 'digraph { a -> "b</script>" [label="<!-- x -->"]; b -> ; { c d } -> e; e -> a; a -> a; /* unterminated';
  d.units.omega_BN_B_x = 'deg/s';
  // events: only entries with a finite time are listed; text is shown as text
  d.events = [null, 5, { t: 'x' }, { t: 1e999 }, { t: 3, name: '<img src=x onerror="window.__pwned=1">', actions: 7 }];
  return d;
}

// a long record (200 001 samples): decimation, and no argument-count limits
function long() {
  const n = 200001;
  const dt = 0.01;
  const S = { t: new Array(n), pointing_error_deg: new Array(n), omega_BN_B_x: new Array(n), omega_BN_B_y: new Array(n), omega_BN_B_z: new Array(n) };
  for (let i = 0; i < 4; i++) S[`wheel_speed_rpm_${i}`] = new Array(n);
  const att = { t: [], q_BN: [] };
  for (let k = 0; k < n; k++) {
    const t = k * dt;
    S.t[k] = Number(t.toFixed(2));
    S.pointing_error_deg[k] = Number((10 * Math.exp(-t / 200) + 0.01 * Math.abs(Math.sin(3 * t))).toPrecision(4));
    S.omega_BN_B_x[k] = Number((1e-3 * Math.exp(-t / 200) * Math.cos(0.05 * t) + 1e-6 * Math.sin(2 * Math.PI * 12.5 * t)).toPrecision(4));
    S.omega_BN_B_y[k] = Number((1e-6 * Math.sin(2 * Math.PI * 7 * t)).toPrecision(4));
    S.omega_BN_B_z[k] = Number((1e-4 * Math.exp(-t / 300)).toPrecision(4));
    for (let i = 0; i < 4; i++) S[`wheel_speed_rpm_${i}`][k] = Number((1000 * (i + 1) * Math.cos(1e-3 * t + i)).toPrecision(4));
    if (k % 10 === 0) {
      const a = 0.5 * (10 * Math.exp(-t / 200)) * Math.PI / 180;
      att.t.push(S.t[k]);
      att.q_BN.push([Math.cos(a), 0, Number(Math.sin(a).toPrecision(6)), 0]);
    }
  }
  const G = [[0.5417, 0.5417, 0.6428], [-0.5417, 0.5417, 0.6428], [-0.5417, -0.5417, 0.6428], [0.5417, -0.5417, 0.6428]];
  return { meta: { scenario: 'long record (synthetic)', dt, duration: (n - 1) * dt }, series: S, units: { omega_BN_B_x: 'rad/s' },
    attitude: att, geometry: { wheel_axes_B: G } };
}

// a long run as the harness writes it: series reduced to min/max per bucket
// (two points per bucket), the last samples at full rate for the spectrum
function reduced() {
  const buckets = 1000;
  const rowsPerBucket = 50;
  const dt = 0.1;
  const S = { t: [], pointing_error_deg: [], omega_BN_B_x: [], omega_BN_B_y: [], omega_BN_B_z: [], wheel_speed_rpm_0: [] };
  const att = { t: [], q_BN: [] };
  for (let b = 0; b < buckets; b++) {
    const t0 = b * rowsPerBucket * dt;
    const t1 = t0 + (rowsPerBucket - 1) * dt;
    for (const [t, s] of [[t0, -1], [t1, 1]]) {
      S.t.push(Number(t.toFixed(1)));
      S.pointing_error_deg.push(10 * Math.exp(-t / 500) + (s > 0 ? 0.02 : 0));
      S.omega_BN_B_x.push(1e-5 * s);
      S.omega_BN_B_y.push(2e-6 * s);
      S.omega_BN_B_z.push(1e-4 * Math.exp(-t / 300));
      S.wheel_speed_rpm_0.push(1000 + s);
      att.t.push(S.t[S.t.length - 1]);
      att.q_BN.push([1, 0, 0, 0]);
    }
  }
  const n = 4096;
  const tEnd = (buckets * rowsPerBucket - 1) * dt;
  const F = { t: [], omega_BN_B_x: [], omega_BN_B_y: [], omega_BN_B_z: [], pointing_error_deg: [] };
  for (let k = 0; k < n; k++) {
    const t = tEnd - (n - 1 - k) * dt;
    F.t.push(Number(t.toFixed(1)));
    F.omega_BN_B_x.push(1e-5 * Math.sin(2 * Math.PI * 2 * t));
    F.omega_BN_B_y.push(2e-6 * Math.sin(2 * Math.PI * 0.7 * t));
    F.omega_BN_B_z.push(1e-7 * gauss());
    F.pointing_error_deg.push(0.01);
  }
  return { meta: { scenario: 'reduced long run (synthetic)', dt, duration: tEnd, decimated: true }, series: S,
    units: { omega_BN_B_x: 'rad/s', wheel_speed_rpm_0: 'rpm' }, attitude: att, spectrum: F,
    decimation: { rows: buckets * rowsPerBucket, bucket_rows: rowsPerBucket, points: 2 * buckets } };
}

// An Earth-orbit run (the columns of docs/environment.md, "Recorded").
function s3() {
  const mu = 3.986004415e14;
  const R = 6378136.3;
  const r = R + 500e3;
  const nOrb = Math.sqrt(mu / r ** 3);
  const dt = 10;
  const T = 2 * 2 * Math.PI / nOrb; // two orbits
  const n = Math.floor(T / dt) + 1;
  const I = [0.43, 0.28, 0.31];
  const inc = (97.4 * Math.PI) / 180;
  const dip = [0.03, -0.024, 0.032];
  const Js = 1.59e-5;
  const G = [[1, 0, 0], [0, 1, 0], [0, 0, 1]];
  const S = { t: [], pointing_error_deg: [], omega_BN_B_x: [], omega_BN_B_y: [], omega_BN_B_z: [], illumination: [], eclipse: [] };
  const vec = (stem) => ['x', 'y', 'z'].forEach((a) => { S[`${stem}_${a}`] = []; });
  ['torque_gravity_gradient', 'torque_magnetic', 'H_gravity_gradient_N', 'H_magnetic_N', 'H_wheels_N', 'field_B'].forEach(vec);
  for (let i = 0; i < 3; i++) { S[`wheel_speed_rpm_${i}`] = []; S[`mtq_dipole_${i}`] = []; }
  const Hg = [0, 0, 0];
  const Hm = [0, 0, 0];
  let prev = null;
  const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
  for (let k = 0; k < n; k++) {
    const t = k * dt;
    const u = nOrb * t; // argument of latitude from the Sun side
    const rh = [Math.cos(u), Math.sin(u) * Math.cos(inc), Math.sin(u) * Math.sin(inc)];
    // Sun along +x: the Sun's centre hidden within asin(R/r) of -x; an 8 s penumbra ramp
    const off = Math.acos(Math.max(-1, Math.min(1, -rh[0]))) - Math.asin(R / r); // [rad] outside the shadow edge
    const ill = Math.max(0, Math.min(1, 0.5 + off / (2 * 8 * nOrb)));
    const Ir = rh.map((v, j) => I[j] * v);
    const Lg = cross(rh, Ir).map((v) => 3 * nOrb * nOrb * v);
    // an aligned dipole field, 2 B0 at the poles (B0 = 3e-5 T (R/r)^3)
    const B0 = 3e-5 * (R / r) ** 3;
    const zN = [0, 0, -1];
    const dot = rh[0] * zN[0] + rh[1] * zN[1] + rh[2] * zN[2];
    const B = rh.map((v, j) => B0 * (3 * dot * v - zN[j]));
    const Lm = cross(dip, B);
    if (prev) for (let j = 0; j < 3; j++) { Hg[j] += 0.5 * dt * (Lg[j] + prev[0][j]); Hm[j] += 0.5 * dt * (Lm[j] + prev[1][j]); }
    prev = [Lg, Lm];
    S.t.push(t);
    S.pointing_error_deg.push(r6(0.02 + 0.005 * gauss()));
    ['x', 'y', 'z'].forEach((a, j) => {
      S[`omega_BN_B_${a}`].push(r6(1e-5 * gauss()));
      S[`torque_gravity_gradient_${a}`].push(r6(Lg[j]));
      S[`torque_magnetic_${a}`].push(r6(Lm[j]));
      S[`H_gravity_gradient_N_${a}`].push(r6(Hg[j]));
      S[`H_magnetic_N_${a}`].push(r6(Hm[j]));
      S[`H_wheels_N_${a}`].push(r6(Hg[j] + Hm[j]));
      S[`field_B_${a}`].push(r6(B[j]));
    });
    for (let i = 0; i < 3; i++) {
      S[`wheel_speed_rpm_${i}`].push(r6(((Hg[i] + Hm[i]) / Js) * 60 / (2 * Math.PI)));
      S[`mtq_dipole_${i}`].push(Math.sin(u * 3 + i) > 0.3 ? 0.2 : 0);
    }
    S.illumination.push(r6(ill));
    S.eclipse.push(ill < 1 ? 1 : 0);
  }
  const units = { t: 's', pointing_error_deg: 'deg', illumination: '-', eclipse: '-' };
  for (const a of ['x', 'y', 'z']) {
    units[`omega_BN_B_${a}`] = 'rad/s';
    units[`torque_gravity_gradient_${a}`] = 'N*m'; units[`torque_magnetic_${a}`] = 'N*m';
    units[`H_gravity_gradient_N_${a}`] = 'N*m*s'; units[`H_magnetic_N_${a}`] = 'N*m*s'; units[`H_wheels_N_${a}`] = 'N*m*s';
    units[`field_B_${a}`] = 'T';
  }
  for (let i = 0; i < 3; i++) { units[`wheel_speed_rpm_${i}`] = 'rpm'; units[`mtq_dipole_${i}`] = 'A*m^2'; }
  return {
    meta: { scenario: 'S3-like LEO small satellite (synthetic)', description: 'Synthetic test data: 500 km orbit, Sun in the orbit plane, inertial hold.',
      seed: 3, version: '0.1.0', dt: 0.1, duration: T, record_period: dt, fsw_period: 0.1, fsw_mode: 'inertial', num_wheels: 3, num_thrusters: 0 },
    series: S, units,
    geometry: { wheel_axes_B: G, wheel_positions_B: G.map((g) => g.map((v) => 0.05 * v)), thrusters: [] },
  };
}

fs.writeFileSync(path.join(out, 's3.json'), JSON.stringify(s3()));
fs.writeFileSync(path.join(out, 'reduced.json'), JSON.stringify(reduced()));
fs.writeFileSync(path.join(out, 's1.json'), JSON.stringify(s1()));
fs.writeFileSync(path.join(out, 'long.json'), JSON.stringify(long()));
fs.writeFileSync(path.join(out, 's2.json'), JSON.stringify(s2()));
fs.writeFileSync(path.join(out, 'minimal.json'), JSON.stringify({ meta: { scenario: 'minimal', dt: 1, duration: 2 }, series: { t: [0, 1, 2] } }));
fs.writeFileSync(path.join(out, 'empty.json'), '{}');
// an interrupted run (Ctrl-C at t = 1.5 s of 10 s)
fs.writeFileSync(path.join(out, 'interrupted.json'), JSON.stringify({
  meta: { scenario: 'interrupted', dt: 0.5, duration: 10, complete: false, t_reached: 1.5, stopped_by: 'SIGINT' },
  series: { t: [0, 0.5, 1, 1.5], pointing_error_deg: [10, 8, 6, 5] } }));
fs.writeFileSync(path.join(out, 'hostile.json'), JSON.stringify(hostile()));
// wheels at 3000 to 4500 rpm (50 to 75 Hz) recorded at 10 samples/s: the
// spectrum must warn that the wheel lines alias (the last 200 s of S1)
{
  const d = s1();
  const from = d.series.t.findIndex((x) => x >= 1000);
  for (const k of Object.keys(d.series)) d.series[k] = d.series[k].slice(from);
  for (let i = 0; i < 4; i++) d.series[`wheel_speed_rpm_${i}`] = d.series.t.map(() => 3000 + 500 * i);
  d.attitude.t = d.attitude.t.filter((x) => x >= 1000);
  d.attitude.q_BN = d.attitude.q_BN.slice(-d.attitude.t.length);
  delete d.events;
  d.meta.scenario = 'aliased wheel lines (synthetic)';
  fs.writeFileSync(path.join(out, 'alias.json'), JSON.stringify(d));
}
console.log(`synthetic report data written to ${out}`);
