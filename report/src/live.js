// Kestrel live view: entry point of the live page's bundle (docs/live.md).
// Served by `kestrel run SCENARIO --live`; talks to the same server only:
//   GET  /api/info            the scenario, recorded columns, devices and their actions, geometry
//   GET  /api/stream          server-sent events: each message the frames published since the last
//                             one (the last recorded row each), run state, gains in force, the command
//                             log, drop counters
//   GET  /api/frames?since=N  the same, asked for: the fallback when the stream is refused
//   POST /api/command         {op: pause|resume|step|rate|event|save, ...}
// every request with the access token of the page's URL (X-Kestrel-Token).
// Offline like the report: uPlot and three.js are bundled, nothing is fetched
// from elsewhere.
import 'uplot/dist/uPlot.min.css';
import './report.css';
import './live.css';
import uPlot from 'uplot';
import { el, fmt } from './data.js';
import { PALETTE, AXIS_COLORS, fmtTick } from './plots.js';
import { buildReplay } from './replay3d.js';

const token = new URLSearchParams(window.location.search).get('token') || '';
const status = { ready: false, errors: [], frames: 0, missed: 0, t: NaN, state: 'starting', info: null, replay: '',
  transport: 'none', messages: 0, gains: null, seq: 0, dupes: 0 };
window.kestrelLive = status;

const KEEP = 3000; // points kept per plot
const POLL_MS = 100; // the fallback (no stream)

function api(path, body) {
  const opt = { headers: { 'X-Kestrel-Token': token }, cache: 'no-store' };
  if (body !== undefined) {
    opt.method = 'POST';
    opt.headers['Content-Type'] = 'application/json';
    opt.body = JSON.stringify(body);
  }
  return fetch(path, opt).then(async (r) => {
    let j = null;
    try { j = await r.json(); } catch (e) { j = { error: `HTTP ${r.status}` }; }
    return { status: r.status, ok: r.ok, body: j };
  });
}

function message(text, bad) {
  const m = document.getElementById('message');
  m.textContent = text;
  m.className = bad ? 'message bad' : 'message';
}

async function command(body) {
  try {
    const r = await api('/api/command', body);
    if (!r.ok) message(`refused: ${r.body && r.body.error ? r.body.error : 'HTTP ' + r.status}`, true);
    else message(`queued #${r.body.id}: ${r.body.command} (enters at the next tick boundary)`, false);
    return r;
  } catch (e) {
    message(`the server does not answer: ${e.message}`, true);
    return null;
  }
}

// ---- plots --------------------------------------------------------------------
const plots = [];
function makePlot(grid, id, title, unit, names, cols, opts = {}) {
  if (!cols.length || cols.some((c) => c < 0)) return;
  const card = el('div', { class: 'card', id: 'plot-' + id });
  card.appendChild(el('h3', { text: title + (unit ? ` [${unit}]` : '') }));
  const holder = el('div', { class: 'plot' });
  card.appendChild(holder);
  grid.appendChild(card);
  const width = Math.max(280, Math.floor(card.getBoundingClientRect().width) - 24);
  const u = new uPlot({
    width, height: 200,
    scales: { x: { time: false }, y: opts.log ? { distr: 3 } : { auto: true } },
    legend: { live: true },
    axes: [{ label: 't [s]', size: 36 }, { label: unit || '', size: 64, values: (s, ticks) => ticks.map((v) => fmtTick(v)) }],
    series: [{ label: 't [s]' }, ...names.map((n, k) => ({
      label: n, stroke: (opts.colors || PALETTE)[k % (opts.colors || PALETTE).length], width: 1.25,
      paths: opts.stepped ? uPlot.paths.stepped({ align: 1 }) : undefined,
      value: (s, v) => (v === null || v === undefined ? '\u2013' : fmtTick(v)),
    }))],
  }, [[], ...names.map(() => [])], holder);
  plots.push({ u, cols, data: [[], ...names.map(() => [])], log: !!opts.log, scale: opts.scale || 1 });
}

function pushPlots(t, row) {
  for (const p of plots) {
    p.data[0].push(t);
    p.cols.forEach((c, k) => {
      let v = row[c];
      if (v !== null && v !== undefined) v *= p.scale;
      if (p.log && !(v > 0)) v = null;
      p.data[k + 1].push(v === undefined ? null : v);
    });
    if (p.data[0].length > KEEP) for (const a of p.data) a.splice(0, a.length - KEEP);
  }
}

// ---- the page -------------------------------------------------------------------
let info = null;
let col = {};
let last = 0;
const recent = []; // {t, wall, paused} for the real-time factor
let replay = null;
let lastDraw = -1e9;

function idx(name) { return name in col ? col[name] : -1; }
function indexed(prefix, n) { const a = []; for (let i = 0; i < n; i++) a.push(idx(prefix + i)); return a; }

function buildPage() {
  document.getElementById('title-scenario').textContent = info.scenario;
  document.getElementById('description').textContent = info.description || '';
  col = {};
  info.columns.forEach((c, i) => { col[c] = i; });
  const nw = info.wheels.length;
  const nt = info.geometry.thrusters.length;
  const grid = document.getElementById('plots');
  const wn = info.wheels.map((w) => w.name);
  const tn = info.geometry.thrusters.map((t) => t.name);
  makePlot(grid, 'pointing', 'Pointing error', 'deg', ['pointing error'], [idx('pointing_error_deg')], { log: true });
  makePlot(grid, 'rates', 'Body rates omega_BN', 'deg/s', ['x', 'y', 'z'],
    [idx('omega_BN_B_x'), idx('omega_BN_B_y'), idx('omega_BN_B_z')], { colors: AXIS_COLORS, scale: 180 / Math.PI });
  if (nw) {
    makePlot(grid, 'wheel-speed', 'Wheel speeds', 'rpm', wn, indexed('wheel_speed_rpm_', nw));
    makePlot(grid, 'wheel-torque', 'Wheel motor torques', 'N m', wn, indexed('wheel_torque_', nw));
  }
  if (nt) {
    const f = indexed('thruster_force_', nt);
    if (f.every((c) => c >= 0)) makePlot(grid, 'thr-force', 'Thruster forces', 'N', tn, f, { stepped: true });
    else makePlot(grid, 'thr-on', 'Thruster on-times', 's', tn, indexed('thruster_on_time_', nt), { stepped: true });
  }
  const rateBox = document.getElementById('rate-x');
  rateBox.value = info.rate > 0 ? String(info.rate) : '1';
  try {
    replay = buildReplay(document.getElementById('replay'), {
      t: [], series: {}, attitude: {}, geometry: info.geometry,
    }, status, { live: true, maxRpm: Math.max(1, ...info.wheels.map((w) => (w.Omega_max > 0 ? w.Omega_max * 30 / Math.PI : 0))) });
  } catch (e) {
    status.errors.push('3D: ' + e.message);
    document.getElementById('replay').appendChild(el('p', { class: 'error', text: '3D view: ' + e.message }));
  }
}

function buildDevices() {
  const root = document.getElementById('devices');
  const table = el('table', { class: 'summary devices' });
  for (const d of info.devices) {
    const cell = el('td');
    for (const a of d.actions) {
      if (a.value === 'none') {
        const b = el('button', { text: a.action, title: a.what, 'data-device': d.name, 'data-action': a.action });
        b.addEventListener('click', () => command({ op: 'event', device: d.name, action: a.action }));
        cell.appendChild(b);
      } else {
        // a gain's box starts at the gain in force (and follows it: showGains)
        const gain = d.kind === 'flight software' && /^gain_[KP]$/.test(a.action) ? a.action.slice(5) : '';
        const init = gain && info.gains ? String(info.gains[gain]) : a.value === 'finite' ? '0' : '1';
        const box = el('input', { type: 'number', step: 'any', value: init, title: `${a.what} [${a.unit}]`,
          'data-device': d.name, 'data-value-for': a.action, class: 'value' });
        if (gain) box.dataset.gain = gain;
        const b = el('button', { text: `${a.action} [${a.unit}]`, title: a.what, 'data-device': d.name, 'data-action': a.action });
        b.addEventListener('click', () => command({ op: 'event', device: d.name, action: a.action, value: Number(box.value) }));
        cell.appendChild(el('span', { class: 'valued' }, b, box));
      }
    }
    table.appendChild(el('tr', null, el('th', { text: `${d.name} (${d.kind})` }), cell));
  }
  root.appendChild(table);
}

// the gain boxes show the gains in force (the server's, after each applied
// gain command); a box being edited is left alone
function showGains(g) {
  if (!g) return;
  const changed = !status.gains || status.gains.K !== g.K || status.gains.P !== g.P;
  status.gains = g;
  if (!changed) return;
  for (const box of document.querySelectorAll('input[data-gain]')) {
    if (document.activeElement !== box) box.value = String(g[box.dataset.gain]);
  }
}

function setText(id, text, cls) {
  const e = document.getElementById(id);
  if (!e) return;
  e.textContent = text;
  if (cls !== undefined) e.className = cls;
}

function valid(v) { return v !== null && v !== undefined && Number.isFinite(v); }

function showStatus(row) {
  const rows = [];
  const add = (k, v, good) => rows.push(el('tr', null, el('th', { text: k }),
    el('td', { text: v, class: good === undefined ? '' : good ? 'good' : 'bad' })));
  add('FSW mode', info.fsw_mode);
  const st = row[idx('fsw_status')];
  // fsw_status.h: 0 ok, > 0 a warning (1 singular mapping, 2 a limit applied, 3 call period), < 0 an error
  const word = (v) => (v === 0 ? 'ok' : v > 0 ? ['', 'singular', 'saturated', 'rate'][v] || 'warning' : 'error');
  if (idx('fsw_status') >= 0) add('FSW status', valid(st) ? `${word(st)} (${st})` : '\u2013', st >= 0);
  const so = row[idx('fsw_safe_output')];
  if (idx('fsw_safe_output') >= 0) add('FSW safe output', so ? 'yes' : 'no', !so);
  const stages = info.columns.filter((c) => c.startsWith('fsw_stage_'));
  const badStages = stages.filter((c) => row[col[c]] !== 0 && row[col[c]] !== null);
  if (stages.length) add('FSW stages', badStages.length ? badStages.map((c) => `${c.slice(10)} ${word(row[col[c]])} (${row[col[c]]})`).join(', ') : 'all ok',
    !badStages.some((c) => row[col[c]] < 0));
  if (idx('meas_att_valid') >= 0) add('star tracker attitude', row[idx('meas_att_valid')] ? 'valid' : 'invalid', !!row[idx('meas_att_valid')]);
  if (idx('meas_omega_BN_B_x') >= 0) {
    const g = ['x', 'y', 'z'].every((a) => valid(row[idx('meas_omega_BN_B_' + a)]));
    add('gyro rates', g ? 'valid' : 'invalid (NaN)', g);
  }
  info.wheels.forEach((w, i) => {
    const c = idx('meas_wheel_speed_rpm_' + i);
    if (c >= 0) add(`tachometer ${w.name}`, valid(row[c]) ? 'valid' : 'invalid (NaN)', valid(row[c]));
  });
  if (idx('sun_valid') >= 0) add('Sun heading', row[idx('sun_valid')] ? 'valid' : 'invalid', !!row[idx('sun_valid')]);
  if (idx('css_num_lit') >= 0) add('coarse sun sensors lit', String(row[idx('css_num_lit')]));
  const nt = info.geometry.thrusters.length;
  if (nt) {
    const on = indexed('thruster_on_time_', nt).filter((c) => c >= 0 && row[c] > 0).length;
    add('thrusters firing', `${on} of ${nt}`);
  }
  const tb = document.getElementById('status-table');
  tb.replaceChildren(...rows);
}

// the last save (from this page, another or a script): the checkpoint's
// name, tick, time and size once it is written, or why it was refused
function showSaved(cmds) {
  const c = cmds.filter((x) => x.command === 'save state').pop();
  if (!c) return;
  if (c.status === 'queued') setText('saved', `#${c.id} saving at the next tick boundary\u2026`, 'saved');
  else if (c.status === 'applied' && c.file) {
    setText('saved', `saved ${c.file.name}: tick ${c.tick}, t = ${fmt(c.t, 8)} s, ${fmt(c.file.bytes / 1000, 4)} kB`, 'saved');
  } else setText('saved', `not saved: ${c.detail}`, 'saved bad');
}

function showCommands(cmds) {
  showSaved(cmds);
  const tb = document.getElementById('commands');
  tb.replaceChildren(...cmds.slice().reverse().map((c) => el('tr', { class: 'cmd-' + c.status, 'data-id': String(c.id) },
    el('td', { text: '#' + c.id }), el('td', { text: c.command }), el('td', { text: c.status }),
    el('td', { text: c.status === 'queued' ? '' : `t = ${fmt(c.t, 8)} s (tick ${c.tick})` }),
    el('td', { text: c.detail }))));
}

function rtf() {
  // over the frames of the last 2 s of wall time, not across a pause
  if (recent.length < 2) return NaN;
  const b = recent[recent.length - 1];
  let a = null;
  for (let i = recent.length - 2; i >= 0; i--) {
    if (recent[i].paused || b.wall - recent[i].wall > 2) break;
    a = recent[i];
  }
  if (!a || b.wall <= a.wall) return NaN;
  return (b.t - a.t) / (b.wall - a.wall);
}

function onFrames(j) {
  status.state = j.state;
  setText('state', j.state === 'waiting' ? 'waiting for a page' : j.state, 'state ' + j.state);
  showGains(j.gains);
  status.missed += j.missed;
  for (const f of j.frames) {
    if (f.seq <= status.seq) { status.dupes++; continue; } // never drawn twice (a reconnection's overlap)
    status.seq = f.seq;
    const row = f.row;
    const t = row[0];
    status.frames++;
    status.t = t;
    status.tick = f.tick;
    recent.push({ t, wall: f.wall, paused: f.paused });
    if (recent.length > 400) recent.splice(0, recent.length - 400);
    pushPlots(t, row);
  }
  last = j.last;
  const lastFrame = j.frames.length ? j.frames[j.frames.length - 1] : null;
  if (lastFrame) {
    const row = lastFrame.row;
    setText('simtime', `t = ${fmt(row[0], 6)} s of ${fmt(info.duration)} s (next tick ${lastFrame.tick})`);
    const pe = row[idx('pointing_error_deg')];
    setText('pe', valid(pe) ? `${fmt(pe)} deg` : '\u2013');
    showStatus(row);
    // plots redrawn at most 5 times a second (the page shares the machine with the run)
    const now = performance.now();
    if (now - lastDraw >= 200 || j.state !== 'running') {
      lastDraw = now;
      for (const p of plots) p.u.setData(p.data);
    }
    if (replay && replay.show) {
      const q = [0, 1, 2, 3].map((i) => row[idx('q_BN_' + i)]);
      const speeds = info.wheels.map((_, i) => row[idx('wheel_speed_rpm_' + i)]);
      const nt = info.geometry.thrusters.length;
      const lv = [];
      for (let i = 0; i < nt; i++) {
        const f = idx('thruster_force_' + i);
        const F = f >= 0 ? row[f] : row[idx('thruster_on_time_' + i)] > 0 ? 1 : 0;
        lv.push(F);
      }
      replay.show(row[0], q, speeds, lv);
    }
  }
  const r = rtf();
  setText('rtf', Number.isFinite(r) ? `${fmt(r, 4)}\u00d7 real time` : j.state === 'paused' ? 'paused' : '\u2013');
  const paced = j.rate > 0 ? `paced at ${fmt(j.rate)}\u00d7` : 'as fast as it can';
  setText('pacing', paced);
  setText('frames', `${status.frames} frames ${status.transport === 'push' ? 'pushed' : 'polled'}; missed ${status.missed} (page slow), dropped ${j.dropped_busy + j.dropped_unread} on the server`);
  showCommands(j.commands);
  if (j.state === 'ended') {
    const end = document.getElementById('end');
    if (!end.dataset.done) {
      end.dataset.done = '1';
      end.hidden = false;
      end.appendChild(el('p', { text: `The run ended: ${j.end || ''}.` }));
      if (j.report) {
        const a = el('a', { href: `${j.report}?token=${encodeURIComponent(token)}`, id: 'report-link', target: '_blank', text: 'Open the run report' });
        end.appendChild(el('p', null, a));
      }
      for (const b of document.querySelectorAll('#controls button, #devices button')) b.disabled = true;
    }
  }
  status.ready = true;
}

// The telemetry is pushed (GET /api/stream, server-sent events); the page
// polls /api/frames only when the stream is refused or never opens.
async function loadInfo() {
  for (;;) {
    try {
      const i = await api('/api/info');
      if (i.ok) {
        info = i.body; status.info = info; buildPage(); buildDevices();
        if (info.save_refused) setText('saved', `save state: not possible in this run: ${info.save_refused}`, 'saved bad');
        return;
      }
      if (i.status === 403) { message(`the server refused: ${i.body && i.body.error}`, true); return; }
    } catch (e) {
      message(`the server does not answer: ${e.message}`, true);
    }
    await new Promise((r) => setTimeout(r, POLL_MS));
  }
}

function listen() {
  if (typeof EventSource === 'undefined') { status.transport = 'poll'; poll(); return; }
  const es = new EventSource(`/api/stream?token=${encodeURIComponent(token)}`);
  status.transport = 'push';
  es.onmessage = (ev) => {
    status.messages++;
    const j = JSON.parse(ev.data);
    if (j.last < last) return; // an older message after a reconnection
    onFrames(j);
    if (j.state === 'ended') es.close();
  };
  es.onerror = () => {
    if (status.state === 'ended') { es.close(); return; }
    if (status.messages === 0) { // refused (at most two streams) or never opened: poll instead
      es.close();
      status.transport = 'poll';
      poll();
    }
    // otherwise the browser reconnects by itself, resuming after the last frame (Last-Event-ID)
  };
}

async function poll() {
  try {
    const r = await api(`/api/frames?since=${last}`);
    if (r.ok) {
      if (info) onFrames(r.body);
    } else {
      message(`the server refused: ${r.body && r.body.error}`, true);
    }
  } catch (e) {
    if (status.state === 'ended') { setText('state', 'ended (server closed)', 'state ended'); return; }
    message(`the server does not answer: ${e.message}`, true);
  }
  if (status.state !== 'ended') setTimeout(poll, POLL_MS);
}

function wireControls() {
  document.getElementById('pause').addEventListener('click', () => command({ op: 'pause' }));
  document.getElementById('resume').addEventListener('click', () => command({ op: 'resume' }));
  document.getElementById('step').addEventListener('click', () => command({ op: 'step', ticks: Math.max(1, Math.round(Number(document.getElementById('step-n').value) || 1)) }));
  document.getElementById('rate').addEventListener('click', () => command({ op: 'rate', value: Number(document.getElementById('rate-x').value) }));
  document.getElementById('save').addEventListener('click', async () => {
    const r = await command({ op: 'save' });
    if (r && !r.ok) setText('saved', `not saved: ${r.body && r.body.error ? r.body.error : 'HTTP ' + r.status}`, 'saved bad');
  });
}

wireControls();
window.addEventListener('error', (e) => status.errors.push(String(e.message)));
loadInfo().then(() => { if (info) listen(); });
