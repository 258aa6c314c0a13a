// Time-series plots with uPlot: one card per quantity present in the data,
// cursors and x-zoom synchronised across cards.
import uPlot from 'uplot';
import { alignSeries, indexedKeys, isNumArray, el, finiteMinMax } from './data.js';
import { ENV_SOURCES, eclipseIntervals, magnitude, sumMagnitude } from './environment.js';
import { tickLabels, plotOffset, constantValue, enumOf, enumLabel, displayUnit, deviceName } from './plotmath.js';
import { pointingTitle } from './pointing.js';

export const PALETTE = ['#1f77b4', '#d62728', '#2ca02c', '#ff7f0e', '#9467bd', '#8c564b', '#e377c2', '#17becf',
  '#7f7f7f', '#bcbd22', '#393b79', '#ad494a', '#637939', '#e6550d', '#6b6ecf', '#843c39'];
export const AXIS_COLORS = ['#d62728', '#2ca02c', '#1f77b4'];

const MAX_POINTS = 40000;

// Min/max bucketing to at most ~MAX_POINTS x values, keeping peaks.
export function decimate(t, ys) {
  const n = t.length;
  if (n <= MAX_POINTS) return [t, ys];
  const b = Math.ceil((2 * n) / MAX_POINTS);
  const tx = [];
  const out = ys.map(() => []);
  for (let s = 0; s < n; s += b) {
    const e = Math.min(n, s + b);
    const m = (s + e) >> 1;
    tx.push(t[s], t[m]);
    ys.forEach((y, k) => {
      let lo = -1;
      let hi = -1;
      for (let i = s; i < e; i++) {
        const v = y[i];
        if (v === null) continue;
        if (lo < 0 || v < y[lo]) lo = i;
        if (hi < 0 || v > y[hi]) hi = i;
      }
      if (lo < 0) out[k].push(null, null);
      else if (lo <= hi) out[k].push(y[lo], y[hi]);
      else out[k].push(y[hi], y[lo]);
    });
  }
  return [tx, out];
}

const plots = [];

// The replay's time, drawn as a vertical line on every time plot; a click
// (not a drag) on a plot moves the replay to that time.
let markerTime = null;
let markerPending = false;
export function setMarkerTime(t) {
  markerTime = t;
  if (markerPending) return;
  markerPending = true;
  requestAnimationFrame(() => {
    markerPending = false;
    for (const u of plots) u.redraw(false, false);
  });
}

// Applied scenario events: a solid vertical line on every time plot.
let eventTimes = [];
export function setEventTimes(ts) {
  eventTimes = ts.filter((x) => Number.isFinite(x));
}

function drawEvents(u) {
  if (!eventTimes.length || !u.scales.x) return;
  const { ctx, bbox } = u;
  ctx.save();
  ctx.strokeStyle = 'rgba(200, 30, 30, 0.8)';
  ctx.lineWidth = Math.max(1, window.devicePixelRatio || 1);
  for (const te of eventTimes) {
    if (!(te >= u.scales.x.min && te <= u.scales.x.max)) continue;
    const x = Math.round(u.valToPos(te, 'x', true));
    ctx.beginPath();
    ctx.moveTo(x, bbox.top);
    ctx.lineTo(x, bbox.top + bbox.height);
    ctx.stroke();
  }
  ctx.restore();
}

// Eclipse intervals of an Earth-orbit run (illumination < 1): shaded bands
// under the curves of every time plot.
let shadeIntervals = [];
function drawShade(u) {
  if (!shadeIntervals.length || !u.scales.x) return;
  const { ctx, bbox } = u;
  ctx.save();
  ctx.fillStyle = 'rgba(70, 70, 110, 0.13)';
  for (const iv of shadeIntervals) {
    if (iv.t1 < u.scales.x.min || iv.t0 > u.scales.x.max) continue;
    const x0 = Math.max(bbox.left, u.valToPos(iv.t0, 'x', true));
    const x1 = Math.min(bbox.left + bbox.width, u.valToPos(iv.t1, 'x', true));
    if (x1 > x0) ctx.fillRect(x0, bbox.top, x1 - x0, bbox.height);
  }
  ctx.restore();
}

function drawMarker(u) {
  if (markerTime === null || !u.scales.x || !(markerTime >= u.scales.x.min && markerTime <= u.scales.x.max)) return;
  const x = Math.round(u.valToPos(markerTime, 'x', true));
  const { ctx, bbox } = u;
  ctx.save();
  ctx.strokeStyle = 'rgba(230, 120, 20, 0.9)';
  ctx.lineWidth = Math.max(1, window.devicePixelRatio || 1);
  ctx.setLineDash([4, 3]);
  ctx.beginPath();
  ctx.moveTo(x, bbox.top);
  ctx.lineTo(x, bbox.top + bbox.height);
  ctx.stroke();
  ctx.restore();
}

function clickToTime(u) {
  let down = null;
  u.over.addEventListener('mousedown', (e) => { down = [e.clientX, e.clientY]; });
  u.over.addEventListener('mouseup', (e) => {
    if (!down || Math.hypot(e.clientX - down[0], e.clientY - down[1]) > 3) return;
    const t = u.posToVal(e.clientX - u.over.getBoundingClientRect().left, 'x');
    if (Number.isFinite(t)) window.dispatchEvent(new CustomEvent('kestrel:time', { detail: t }));
  });
}

// A plot made outside addTimePlot (the Monte Carlo page's envelope plots)
// joins the x-zoom synchronisation and the resizing; its setScale hook calls
// syncX.
export function trackPlot(u) { plots.push(u); }
export function untrackPlot(u) {
  const i = plots.indexOf(u);
  if (i >= 0) plots.splice(i, 1);
}

export function syncX(u) {
  const min = u.scales.x.min;
  const max = u.scales.x.max;
  for (const p of plots) {
    if (p !== u && p.scales.x && (p.scales.x.min !== min || p.scales.x.max !== max)) p.setScale('x', { min, max });
  }
}

export function widthOf(container) {
  return Math.max(280, Math.floor(container.getBoundingClientRect().width) - 24);
}

// Labels of a value axis: distinct however small the step (plotmath.js);
// an enumerated series (spec.enumKey) is labelled with its names at whole
// values; a log axis keeps one mantissa digit per decade.
function axisValues(spec, log) {
  if (spec.enumKey) {
    const names = enumOf(spec.enumKey) || {};
    return (self, ticks) => ticks.map((v) => (Number.isInteger(v) ? (names[v] !== undefined ? names[v] : String(v)) : ''));
  }
  if (log) return (self, ticks) => ticks.map((v) => fmtTick(v));
  return (self, ticks) => tickLabels(ticks);
}

// spec: { id, title, unit, names: [], ys: [[...]], colors?, log?, stepped?, note?, enumKey? }
// The unit is shown as displayUnit() spells it (values scaled to it); a
// series that varies little against its value is drawn from an offset,
// named in the title (the legend shows the full values).
export function addTimePlot(grid, t, spec) {
  const du = displayUnit(spec.unit);
  const scaled = du.scale === 1 ? spec.ys : spec.ys.map((y) => y.map((v) => (v === null ? null : v * du.scale)));
  // each series' own offset (plotOffset): one shared by every series goes
  // into the title, different ones into the legend names
  const offs = scaled.map((y) => {
    const mm = spec.log || spec.enumKey ? null : finiteMinMax(y);
    return mm ? plotOffset(mm[0], mm[1]) : 0;
  });
  const shared = offs.length && offs.every((o) => o !== 0 && o === offs[0]) ? offs[0] : 0;
  const shifted = scaled.map((y, k) => (offs[k] ? y.map((v) => (v === null ? null : v - offs[k])) : y));
  const minus = (o) => (o < 0 ? ` + ${String(-o)}` : ` \u2212 ${String(o)}`);
  const names = spec.names.map((nm, k) => (offs[k] && !shared ? nm + minus(offs[k]) : nm));
  const card = el('div', { class: 'card', id: 'plot-' + spec.id });
  const offText = shared ? minus(shared) : '';
  card.appendChild(el('h3', { text: spec.title + offText + (du.unit ? ` [${du.unit}]` : '') }));
  const holder = el('div', { class: 'plot' });
  card.appendChild(holder);
  if (offs.some((o) => o !== 0)) {
    const u = du.unit ? ' ' + du.unit : '';
    const parts = offs.map((o, k) => {
      if (!o) return '';
      const mm = finiteMinMax(scaled[k]);
      return `${spec.names[k]} from ${String(o)}${u} (varies by ${fmtTick(mm[1] - mm[0])}${u}, ${fmtTick((mm[1] - mm[0]) / Math.abs(o))} of its value)`;
    }).filter(Boolean);
    card.appendChild(el('p', { class: 'note offset-note', text: `Nearly constant, so drawn as the difference from an offset: ${parts.join('; ')}.` }));
  }
  if (spec.note) card.appendChild(el('p', { class: 'note', text: spec.note }));
  grid.appendChild(card);

  let log = !!spec.log;
  let u = null;
  const enumNames = spec.enumKey ? enumOf(spec.enumKey) : null;
  const legend = (v, k) => {
    if (v === null || v === undefined) return '\u2013';
    if (enumNames) return enumLabel(spec.enumKey, v) || fmtTick(v);
    return offs[k] ? String(Number((v + offs[k]).toPrecision(12))) : fmtTick(v);
  };
  const build = () => {
    if (u) { plots.splice(plots.indexOf(u), 1); u.destroy(); }
    let ys = shifted;
    if (log) {
      // log axis: non-positive values become gaps
      ys = ys.map((y) => y.map((v) => (v !== null && v > 0 ? v : null)));
    }
    const [tx, yd] = decimate(t, ys);
    const stepped = spec.stepped || spec.enumKey ? uPlot.paths.stepped({ align: 1 }) : undefined;
    const opts = {
      width: widthOf(card),
      height: 220,
      cursor: { sync: { key: 'kestrel-t', setSeries: false }, drag: { x: true, y: false } },
      scales: { x: { time: false }, y: log ? { distr: 3 } : { auto: true } },
      legend: { live: true },
      axes: [
        { label: 't [s]', size: 40, values: (self, ticks) => tickLabels(ticks) },
        { label: du.unit || '', size: spec.enumKey ? 110 : 64, values: axisValues(spec, log) },
      ],
      series: [
        { label: 't [s]', value: (self, v) => (v === null || v === undefined ? '\u2013' : v.toFixed(2)) },
        ...names.map((name, k) => ({
          label: name,
          stroke: (spec.colors || PALETTE)[k % (spec.colors || PALETTE).length],
          width: 1.25,
          spanGaps: false,
          paths: stepped,
          value: (self, v) => legend(v, k),
        })),
      ],
      hooks: { setScale: [(self, key) => { if (key === 'x') syncX(self); }], drawClear: [drawShade], draw: [drawEvents, drawMarker] },
    };
    u = new uPlot(opts, [tx, ...yd], holder);
    clickToTime(u);
    plots.push(u);
  };
  if (spec.log !== undefined) {
    const btn = el('button', { class: 'toggle', text: log ? 'linear scale' : 'log scale' });
    btn.addEventListener('click', () => {
      log = !log;
      btn.textContent = log ? 'linear scale' : 'log scale';
      build();
    });
    card.querySelector('h3').appendChild(btn);
  }
  build();
  return card;
}

export function fmtTick(v) {
  if (v === null || v === undefined || !Number.isFinite(v)) return '';
  if (v === 0) return '0';
  const a = Math.abs(v);
  if (a >= 1e5 || a < 1e-3) return v.toExponential(1);
  return Number(v.toPrecision(4)).toString();
}

// The texts of every value-axis tick label drawn on the page's time plots
// (for the browser tests: none may repeat within an axis).
export function axisTickTexts() {
  return plots.map((u) => ({
    id: (u.root.closest('.card') || {}).id || '',
    axes: u.axes.map((a) => (a._values || []).filter((v) => v !== null && v !== undefined && v !== '').map(String)),
  }));
}

if (typeof window !== 'undefined') window.kestrelAxisTicks = axisTickTexts;

export function resizePlots() {
  for (const u of plots) {
    const card = u.root.closest('.card');
    if (card) u.setSize({ width: widthOf(card), height: u.height });
  }
}

// rad/s -> deg/s for display (deg/s is how rates are read); returns [ys, unit].
export function rateDisplay(ys, unit) {
  if (!unit || /^rad\s*\/\s*s$/i.test(unit)) {
    return [ys.map((y) => y.map((v) => (v === null ? null : (v * 180) / Math.PI))), 'deg/s'];
  }
  return [ys, unit];
}

// Builds every time-series card; returns the keys used (others are shown
// as generic cards) and what is absent.
export function buildTimePlots(grid, D, otherGrid = grid) {
  const { series, units, t } = D;
  const n = t.length;
  const used = new Set(['t']);
  const absent = [];
  const take = (k) => { used.add(k); return alignSeries(series[k], n); };
  const unitOf = (k, def) => (typeof units[k] === 'string' ? units[k] : def);

  if (isNumArray(series.pointing_error_deg)) {
    const y = take('pointing_error_deg');
    const mm = finiteMinMax(y);
    addTimePlot(grid, t, {
      id: 'pointing', title: pointingTitle(D), unit: unitOf('pointing_error_deg', 'deg'),
      names: ['error'], ys: [y], log: !!(mm && mm[1] > 0 && mm[1] / Math.max(mm[0], 1e-12) > 100),
    });
  } else absent.push('pointing error');

  const rk = ['x', 'y', 'z'].map((a) => `omega_BN_B_${a}`).filter((k) => isNumArray(series[k]));
  if (rk.length) {
    const [ys, unit] = rateDisplay(rk.map(take), unitOf(rk[0], 'rad/s'));
    addTimePlot(grid, t, { id: 'rates', title: 'Body rates \u03c9_BN in B', unit, names: rk.map((k) => k.slice(-1)), ys, colors: rk.map((k) => AXIS_COLORS['xyz'.indexOf(k.slice(-1))]) });
  } else absent.push('body rates');

  const groups = [
    ['wheel_speed_rpm_', 'wheels', 'Wheel speeds', 'rpm', 'wheel ', false],
    ['wheel_torque_', 'wheeltorque', 'Wheel motor torques', 'N m', 'wheel ', false],
    ['thruster_on_time_', 'ontime', 'Thruster on-times', 's', 'thr ', true],
    ['thruster_force_', 'force', 'Thruster forces', 'N', 'thr ', true],
  ];
  const geom = D.geometry || {};
  const devName = (key, fallback) => deviceName(key, geom) || fallback;
  for (const [prefix, id, title, unit, nm, stepped] of groups) {
    const ks = indexedKeys(series, prefix);
    if (!ks.length) { absent.push(title.toLowerCase()); continue; }
    addTimePlot(grid, t, {
      id, title, unit: unitOf(ks[0].key, unit), stepped,
      names: ks.map(({ index, key }) => devName(key, nm + index)), ys: ks.map(({ key }) => take(key)),
    });
  }

  const env = buildEnvironmentPlots(grid, D, take, unitOf, devName);

  if (isNumArray(series.propellant_kg)) {
    addTimePlot(grid, t, { id: 'propellant', title: 'Propellant', unit: unitOf('propellant_kg', 'kg'), names: ['propellant'], ys: [take('propellant_kg')] });
  } else absent.push('propellant');

  // anything else the harness recorded, grouped by name stem (the FSW's
  // stage statuses in one group); a series constant over the whole run is
  // a row of the constants table instead of a flat plot (a vector is
  // plotted whole when one of its components varies)
  const rest = new Map();
  const constants = env.constants;
  for (const k of Object.keys(series).sort()) {
    if (used.has(k) || !isNumArray(series[k]) || typeof series[k][0] === 'object') continue;
    const stem = k.startsWith('fsw_stage_') ? 'fsw_stage' : k.replace(/_(\d+|[xyz])$/, '');
    if (!rest.has(stem)) rest.set(stem, []);
    rest.get(stem).push(k);
  }
  let others = 0;
  for (const [stem, all] of rest) {
    const vector = all.every((k) => /_[xyz]$/.test(k));
    const ys = new Map(all.map((k) => [k, take(k)]));
    const cv = new Map(all.map((k) => [k, constantValue(ys.get(k))]));
    const ks = vector && all.some((k) => !cv.get(k)) ? all : all.filter((k) => !cv.get(k));
    for (const k of all) if (!ks.includes(k) && cv.get(k)) constants.push({ key: k, label: constantLabel(k, geom), unit: unitOf(k, ''), ...cv.get(k) });
    if (!ks.length) continue;
    const names = all.length > 1 ? ks.map((k) => devName(k, stem === 'fsw_stage' ? k.slice('fsw_stage_'.length) : k.slice(stem.length + 1))) : ks;
    const enumKey = ks.every((k) => enumOf(k)) ? ks[0] : undefined;
    const title = stem === 'fsw_stage' ? 'FSW stage statuses (fsw_stage_*)' : stem;
    addTimePlot(otherGrid, t, { id: 'x-' + stem.replace(/[^A-Za-z0-9_-]/g, '_'), title, unit: unitOf(ks[0], ''), names, ys: ks.map((k) => ys.get(k)), enumKey });
    others++;
  }
  if (constants.length) grid.after(constantsTable(constants));
  return { absent, others, eclipses: env.eclipses, constants: constants.length };
}

// Earth-orbit runs, each card only when its columns exist: illumination
// (and the eclipse bands on every plot), the disturbance torque of each
// source, the momentum each source has given against the wheels', the field
// in B and the magnetorquer dipoles.  The torque and momentum cards show
// magnitudes; their components stay among the other recorded series.
function buildEnvironmentPlots(grid, D, take, unitOf, devName) {
  const { series, t } = D;
  const n = t.length;
  let eclipses = 0;
  if (isNumArray(series.illumination)) {
    const iv = eclipseIntervals(t, alignSeries(series.illumination, n));
    shadeIntervals = iv;
    eclipses = iv.length;
    if (isNumArray(series.eclipse)) take('eclipse');
    addTimePlot(grid, t, {
      id: 'illumination', title: 'Illumination: visible fraction of the Sun\'s disk', unit: unitOf('illumination', '-'),
      names: ['illumination'], ys: [take('illumination')],
      note: `Shaded on every plot: the Earth's shadow (illumination < 1), ${iv.length} interval${iv.length === 1 ? '' : 's'}.`,
    });
  }
  const present = ENV_SOURCES.filter(([s]) => isNumArray(series[`torque_${s}_x`]));
  if (present.length) {
    addTimePlot(grid, t, {
      id: 'disturbance', title: 'Disturbance torques about the mass centre, by source |L_C|', unit: unitOf(`torque_${present[0][0]}_x`, 'N m'),
      names: present.map(([, label]) => label), ys: present.map(([s]) => magnitude(series, `torque_${s}`, n)), log: true,
    });
  }
  const hs = ENV_SOURCES.filter(([s]) => isNumArray(series[`H_${s}_N_x`]));
  if (hs.length) {
    const names = hs.map(([, label]) => label);
    const ys = hs.map(([s]) => magnitude(series, `H_${s}_N`, n));
    if (hs.length > 1) { names.push('sum of sources'); ys.push(sumMagnitude(series, hs.map(([s]) => `H_${s}_N`), n)); }
    if (isNumArray(series.H_wheels_N_x)) { names.push('wheels (change)'); ys.push(sumMagnitude(series, ['H_wheels_N'], n, true)); }
    addTimePlot(grid, t, {
      id: 'envmomentum', title: 'Angular momentum given by each source, against the wheels\' |H| (N)', unit: unitOf(`H_${hs[0][0]}_N_x`, 'N m s'),
      names, ys, note: 'Each source: |\u222b [NB] L_C dt| since t = 0. The wheels take up the sum unless something dumps it.',
    });
  }
  const fk = ['x', 'y', 'z'].map((a) => `field_B_${a}`).filter((k) => isNumArray(series[k]));
  if (fk.length) {
    addTimePlot(grid, t, { id: 'field', title: 'Geomagnetic field in B', unit: unitOf(fk[0], 'T'), names: fk.map((k) => k.slice(-1)),
      ys: fk.map(take), colors: fk.map((k) => AXIS_COLORS['xyz'.indexOf(k.slice(-1))]) });
  }
  // the rods' dipoles: a table row each when none of them moves
  const constants = [];
  const mk = indexedKeys(series, 'mtq_dipole_');
  const mys = mk.map(({ key }) => take(key));
  const mcv = mys.map(constantValue);
  if (mk.length && mcv.every(Boolean)) {
    mk.forEach(({ key }, i) => constants.push({ key, label: constantLabel(key, D.geometry), unit: unitOf(key, 'A m^2'), ...mcv[i] }));
  } else if (mk.length) {
    addTimePlot(grid, t, { id: 'mtqdipole', title: 'Magnetorquer dipoles', unit: unitOf(mk[0].key, 'A m^2'), stepped: true,
      names: mk.map(({ index, key }) => devName(key, `rod ${index}`)), ys: mys });
  }
  return { eclipses, constants };
}

// "wheel_speed_rpm_1 (rw2)": the recorded name, with the device's own.
function constantLabel(key, geometry) {
  const d = deviceName(key, geometry);
  return d ? `${key} (${d})` : key;
}

// One compact table of every series that holds one value over the whole
// run: status codes and flags with their names, the stages and actuators
// this scenario does not use.
function constantsTable(rows) {
  const block = el('div', { class: 'card wide', id: 'constants' });
  block.appendChild(el('h3', { text: `Constant over the whole run (${rows.length} series)` }));
  block.appendChild(el('p', { class: 'note', text: 'Each of these series holds one value from the first sample to the last, so it is listed ' +
    'here instead of drawn as a flat line. Status codes are FswStatus values (FSW_OK 0, warnings positive, errors negative); flags are 0 no, 1 yes.' }));
  const tr = (...cells) => el('tr', null, ...cells);
  const body = rows.map((r) => {
    const du = displayUnit(r.unit);
    const v = r.value * du.scale;
    const name = enumLabel(r.key, r.value);
    return tr(el('td', { text: r.label }), el('td', { class: 'num', text: name || String(Number(v.toPrecision(12))) }),
      el('td', { text: du.unit }), el('td', { class: 'note', text: r.spread > 0 ? `within ${fmtTick(r.spread * du.scale)} (rounding)` : '' }));
  });
  block.appendChild(el('table', { id: 'constants-table', class: 'constants' },
    el('thead', null, tr(el('th', { text: 'series' }), el('th', { text: 'value' }), el('th', { text: 'unit' }), el('th', { text: '' }))),
    el('tbody', null, ...body)));
  return block;
}
