// Monte Carlo report: one card per channel with the retained runs overlaid
// (passing runs thin and translucent under the envelopes, failing runs red
// on top of everything) and the percentile envelopes over all runs (bands
// between symmetric levels, lines for the others).  uPlot draws the axes,
// the envelopes and the legend; the runs are drawn by hooks on its canvas.
// Cursor and x-zoom are synchronised with the other cards (plots.js).
import uPlot from 'uplot';
import { alignSeries, el, finiteMinMax } from './data.js';
import { fmtTick, rateDisplay, trackPlot, untrackPlot, syncX, widthOf } from './plots.js';
import { bandPairs } from './mcdata.js';

export const PASS_COLOR = 'rgba(31, 95, 191, 0.35)';
export const FAIL_COLOR = '#d62728';
const BAND_FILLS = ['rgba(120, 120, 120, 0.16)', 'rgba(90, 90, 90, 0.22)', 'rgba(60, 60, 60, 0.28)'];

function drawRuns(u, runs, t, log, clip) {
  const { ctx, bbox } = u;
  const [i0, i1] = u.series[0].idxs && u.series[0].idxs.length === 2 ? u.series[0].idxs : [0, t.length - 1];
  const a = Math.max(0, i0 - 1);
  const b = Math.min(t.length - 1, i1 + 1);
  ctx.save();
  if (clip) {
    ctx.beginPath();
    ctx.rect(bbox.left, bbox.top, bbox.width, bbox.height);
    ctx.clip();
  }
  const dpr = window.devicePixelRatio || 1;
  ctx.setLineDash([]); // uPlot leaves the dash of the last series it stroked
  ctx.lineJoin = 'round';
  for (const r of runs) {
    ctx.strokeStyle = r.pass ? PASS_COLOR : FAIL_COLOR;
    ctx.lineWidth = (r.pass ? 1 : 1.6) * dpr;
    ctx.beginPath();
    let pen = false;
    for (let i = a; i <= b; i++) {
      const y = r.y[i];
      if (y === null || t[i] === null || (log && !(y > 0))) { pen = false; continue; }
      const px = u.valToPos(t[i], 'x', true);
      const py = u.valToPos(y, 'y', true);
      if (pen) ctx.lineTo(px, py);
      else { ctx.moveTo(px, py); pen = true; }
    }
    ctx.stroke();
  }
  ctx.restore();
}

// y range over the visible window of the runs and the envelopes
function yRange(u, all, t, log) {
  const [i0, i1] = u.series[0].idxs && u.series[0].idxs.length === 2 ? u.series[0].idxs : [0, t.length - 1];
  let lo = Infinity;
  let hi = -Infinity;
  for (const y of all) {
    for (let i = Math.max(0, i0); i <= i1 && i < y.length; i++) {
      const v = y[i];
      if (v === null || (log && !(v > 0))) continue;
      if (v < lo) lo = v;
      if (v > hi) hi = v;
    }
  }
  if (!(lo <= hi)) return log ? [0.1, 1] : [-1, 1];
  if (log) return [10 ** Math.floor(Math.log10(lo)), 10 ** Math.ceil(Math.log10(hi) + 1e-9)];
  const pad = hi > lo ? 0.05 * (hi - lo) : Math.abs(hi) * 0.1 || 1;
  return [lo - pad, hi + pad];
}

// ch: {name, unit, columns}; S: normalized series {t, levels, pcols, runs}
export function addEnvelopeCard(grid, ch, S, status) {
  const t = S.t;
  const n = t.length;
  const id = 'mc-plot-' + ch.name.replace(/[^A-Za-z0-9_-]/g, '_');
  const card = el('div', { class: 'card', id });
  const h3 = el('h3', { text: ch.name + (ch.unit ? ` [${ch.unit}]` : '') });
  card.appendChild(h3);
  let col = ch.columns[0];
  if (ch.columns.length > 1) {
    const sel = el('select', { class: 'column', title: 'component shown' },
      ...ch.columns.map((c) => el('option', { value: c, text: c })));
    sel.addEventListener('change', () => { col = sel.value; build(); });
    h3.appendChild(sel);
  }
  const holder = el('div', { class: 'plot' });
  card.appendChild(holder);
  const note = el('p', { class: 'note' });
  card.appendChild(note);
  grid.appendChild(card);

  const { bands, lines } = bandPairs(S.levels);
  let log = null; // decided from the first column's data
  let u = null;
  let logBtn = null;

  function build() {
    if (u) { untrackPlot(u); u.destroy(); u = null; }
    // runs holding this column, passing first so that failing ones are drawn last
    const runs = S.runs.filter((r) => Array.isArray(r.columns[col]))
      .map((r) => ({ index: r.index, pass: r.pass, y: alignSeries(r.columns[col], n) }))
      .sort((a, b) => (a.pass === b.pass ? 0 : a.pass ? -1 : 1));
    const pct = Array.isArray(S.pcols[col]) ? S.pcols[col] : [];
    const levelIdx = S.levels.map((l, k) => k).filter((k) => S.levels[k] !== null && Array.isArray(pct[k]));
    let pys = levelIdx.map((k) => alignSeries(pct[k], n));
    let ys = runs.map((r) => r.y);
    let unit = ch.unit;
    if (/^rad\s*\/\s*s$/i.test(unit)) {
      [pys, unit] = rateDisplay(pys, unit);
      [ys] = rateDisplay(ys, ch.unit);
      ys.forEach((y, k) => { runs[k].y = y; });
    }
    h3.firstChild.textContent = ch.name + (unit ? ` [${unit}]` : '');
    if (log === null) {
      // log axis for a positive quantity spanning more than two decades (pointing error)
      const mm = finiteMinMax([].concat(...ys, ...pys));
      log = !!(mm && mm[0] >= 0 && mm[1] > 0 && mm[1] / Math.max(mm[0], 1e-12) > 100 && /pointing/i.test(ch.name));
    }
    const pos = new Map(levelIdx.map((k, j) => [k, j + 1])); // level index -> uPlot series index
    const series = [
      { label: 't [s]', value: (self, v) => (v === null || v === undefined ? '\u2013' : v.toFixed(2)) },
      ...levelIdx.map((k) => {
        const isLine = lines.includes(k);
        return {
          label: `p${S.levels[k]}`,
          stroke: isLine ? '#1d2433' : 'rgba(60, 60, 60, 0.55)',
          width: isLine ? 1.6 : 0.8,
          dash: isLine ? undefined : [4, 3],
          spanGaps: false,
          points: { show: false },
          value: (self, v) => (v === null || v === undefined ? '\u2013' : fmtTick(v)),
        };
      }),
    ];
    const uBands = bands.filter(([lo, hi]) => pos.has(lo) && pos.has(hi))
      .map(([lo, hi], k) => ({ series: [pos.get(hi), pos.get(lo)], fill: BAND_FILLS[Math.min(BAND_FILLS.length - 1, k)] }));
    const fails = runs.filter((r) => !r.pass);
    const passes = runs.filter((r) => r.pass);
    const all = ys.concat(pys);
    const logNow = log;
    const data = [t, ...pys.map((y) => (logNow ? y.map((v) => (v !== null && v > 0 ? v : null)) : y))];
    if (data.length === 1) data.push(new Array(n).fill(null)); // no envelope: an empty series keeps uPlot happy
    if (series.length === 1) series.push({ label: 'no envelope', show: false });
    const opts = {
      width: widthOf(card),
      height: 240,
      cursor: { sync: { key: 'kestrel-t', setSeries: false }, drag: { x: true, y: false }, points: { show: false } },
      scales: { x: { time: false }, y: logNow ? { distr: 3, range: (self) => yRange(self, all, t, true) } : { range: (self) => yRange(self, all, t, false) } },
      legend: { live: true },
      bands: uBands,
      axes: [
        { label: 't [s]', size: 40 },
        { label: unit || '', size: 64, values: (self, ticks) => ticks.map((v) => fmtTick(v)) },
      ],
      series,
      hooks: {
        setScale: [(self, key) => { if (key === 'x') syncX(self); }],
        drawClear: [(self) => drawRuns(self, passes, t, logNow, true)],
        draw: [(self) => drawRuns(self, fails, t, logNow, true)],
      },
    };
    u = new uPlot(opts, data, holder);
    trackPlot(u);
    const lv = levelIdx.map((k) => S.levels[k]);
    note.textContent = `${runs.length} retained runs (${fails.length} failing, red, drawn on top)` +
      (lv.length ? `; percentiles ${lv.join(', ')} over all runs (shaded between symmetric levels)` : '; no percentile envelope in the data') + '.';
    status.runLines += runs.length;
  }

  build();
  if (log) {
    logBtn = el('button', { class: 'toggle', text: 'linear scale' });
    logBtn.addEventListener('click', () => {
      log = !log;
      logBtn.textContent = log ? 'linear scale' : 'log scale';
      build();
    });
    h3.appendChild(logBtn);
  }
  return card;
}
