// Kestrel run report: entry point of the bundle.  Reads the run data from the
// <script id="kestrel-data" type="application/json"> element and builds each
// section; a section that fails shows its error and the others still render.
import 'uplot/dist/uPlot.min.css';
import './report.css';
import { normalize, el, fmt, finiteMinMax, isNumArray, indexedKeys, alignSeries } from './data.js';
import { eclipseIntervals } from './environment.js';
import { buildTimePlots, resizePlots, setEventTimes } from './plots.js';
import { buildSpectrum } from './spectrumview.js';
import { buildReplay } from './replay3d.js';
import { buildDataflow } from './dataflowview.js';
import { section as sectionOf, embeddedData, finishPage, whenLoaded } from './page.js';

const status = { ready: false, errors: [], plots: 0 };
window.kestrelReport = status;

const section = (id, fn) => sectionOf(status, id, fn);

// The run's own summary, as summary.txt says it (one source: the run writes
// both files from the same items), its warnings and its requirement lines.
function runStory(root, D) {
  if (D.warnings.length) {
    root.appendChild(el('div', { class: 'warnings', id: 'run-warnings' },
      el('b', { text: `The run printed ${D.warnings.length} warning${D.warnings.length === 1 ? '' : 's'}:` }),
      el('ul', null, ...D.warnings.map((w) => el('li', { text: w })))));
  }
  if (D.requirements.length) {
    const nfail = D.requirements.filter((r) => !r.pass).length;
    root.appendChild(el('h3', { text: `Requirements: ${nfail ? `${nfail} of ${D.requirements.length} FAIL` : `all ${D.requirements.length} PASS`}` }));
    const unit = (r) => (r.unit && r.unit !== '-' ? ` ${r.unit}` : '');
    root.appendChild(el('table', { class: 'summary', id: 'requirements-table' },
      el('tr', null, ...['requirement', 'measured', 'required', 'result'].map((h) => el('th', { text: h }))),
      ...D.requirements.map((r) => el('tr', { class: r.pass ? 'pass' : 'fail' },
        el('td', null, el('b', { text: String(r.name ?? '') }), ` (${r.what ?? ''})`),
        el('td', { text: fmt(r.value) + unit(r) }),
        el('td', { text: `${r.below ? '<' : '>'} ${fmt(r.threshold)}${unit(r)}` }),
        el('td', { class: 'verdict', text: r.pass ? 'PASS' : 'FAIL' })))));
    root.appendChild(el('p', { class: 'note', text: 'The scenario\'s monte_carlo.criteria evaluated on this run\'s recorded rows, every row (docs/monte-carlo.md).' }));
  }
  const reqKeys = new Set(D.requirements.map((r) => `requirement_${r.name}`));
  const keys = D.summaryOrder.filter((k) => D.summary[k] && !reqKeys.has(k));
  if (!keys.length) return;
  root.appendChild(el('h3', { text: 'Run summary (summary.txt)' }));
  root.appendChild(el('table', { class: 'summary', id: 'run-summary' }, el('tbody', null,
    ...keys.map((k) => {
      const it = D.summary[k];
      const v = typeof it.value === 'number' ? fmt(it.value, 7) : '\u2013';
      return el('tr', null, el('th', { text: k }), el('td', { class: 'num', text: v + (it.unit && it.unit !== '-' ? ` ${it.unit}` : '') }),
        el('td', { class: 'what', text: String(it.what ?? '') }));
    }))));
}

// Figures of the recorded series that the summary does not carry: the
// decimated series keep each bucket's extremes, so maxima stay exact.
function seriesFigures(root, D, absent) {
  const { series, t } = D;
  const rows = [];
  const add = (k, v) => rows.push(el('tr', null, el('th', { text: k }), el('td', { text: v })));
  if (t.length) add('samples', `${t.length} (t = ${fmt(t[0])} \u2026 ${fmt(t[t.length - 1])} s)`);
  if (isNumArray(series.pointing_error_deg)) {
    const y = series.pointing_error_deg;
    const mmAll = finiteMinMax(y);
    if (mmAll) add('max pointing error', `${fmt(mmAll[1])} deg`);
  }
  const wk = indexedKeys(series, 'wheel_speed_rpm_');
  if (wk.length) {
    let mx = 0;
    for (const { key } of wk) { const mm = finiteMinMax(series[key]); if (mm) mx = Math.max(mx, Math.abs(mm[0]), Math.abs(mm[1])); }
    add('wheels', `${wk.length}, peak |speed| ${fmt(mx)} rpm`);
  }
  if (isNumArray(series.illumination)) {
    const iv = eclipseIntervals(t, alignSeries(series.illumination, t.length));
    const tot = iv.reduce((acc, x) => acc + (x.t1 - x.t0), 0);
    add('Earth\'s shadow', `${iv.length} interval${iv.length === 1 ? '' : 's'}, ${fmt(tot)} s (illumination < 1)`);
  }
  if (absent.length) add('not in this run', absent.join(', '));
  if (!rows.length) return;
  root.appendChild(el('h3', { text: 'From the recorded series' }));
  root.appendChild(el('table', { class: 'summary', id: 'series-figures' }, el('tbody', null, ...rows)));
}

function summary(root, D, absent) {
  runStory(root, D);
  seriesFigures(root, D, absent);
}

function main() {
  const raw = embeddedData(status, 'summary', 'run data');
  const D = normalize(raw);
  const m = D.meta;
  document.getElementById('title-scenario').textContent = m.scenario ? `\u2014 ${m.scenario}` : '';
  if (m.scenario) document.title = `Kestrel report: ${m.scenario}`;
  const metaRoot = document.getElementById('meta');
  for (const [k, unit] of [['scenario', ''], ['seed', ''], ['version', ''], ['dt', ' s'], ['duration', ' s']]) {
    if (m[k] !== undefined && m[k] !== null) metaRoot.appendChild(el('span', { class: 'kv' }, el('b', { text: k + ' ' }), String(m[k]) + unit));
  }
  if (typeof m.description === 'string' && m.description.trim()) document.getElementById('description').textContent = m.description.trim();
  if (m.complete === false) {
    // an interrupted or failed run: its plots end where it stopped
    const why = typeof m.stopped_by === 'string' && m.stopped_by ? ` (${m.stopped_by})` : '';
    const at = typeof m.t_reached === 'number' ? ` at t = ${m.t_reached} s` : '';
    const of = typeof m.duration === 'number' ? ` of ${m.duration} s` : '';
    metaRoot.after(el('p', { class: 'incomplete', id: 'incomplete', text: `Incomplete run: stopped${why}${at}${of}. The plots end where the run stopped.` }));
  }
  for (const [k, v] of Object.entries(m)) {
    if (['scenario', 'seed', 'version', 'dt', 'duration', 'description', 'stopped_by'].includes(k) || (typeof v === 'object' && v !== null)) continue;
    metaRoot.appendChild(el('span', { class: 'kv' }, el('b', { text: k + ' ' }), String(v)));
  }
  let absent = [];
  section('events', (root) => {
    if (!D.events.length) return;
    document.getElementById('sec-events').hidden = false;
    setEventTimes(D.events.map((e) => e.t));
    root.appendChild(el('p', { text: 'Scenario events applied during the run (docs/events.md); each is a red vertical line on every time plot.' }));
    const rows = D.events.map((e) => el('tr', null, el('td', { text: fmt(e.t) }), el('td', { text: String(e.tick ?? '') }),
      el('td', { text: String(e.name ?? '') }), el('td', { text: String(e.actions ?? '') })));
    root.appendChild(el('table', { id: 'events-table' },
      el('tr', null, el('th', { text: 't [s]' }), el('th', { text: 'tick' }), el('th', { text: 'event' }), el('th', { text: 'actions' })),
      ...rows));
  });
  section('plots', (root) => {
    if (!D.t.length) {
      root.appendChild(el('p', { class: 'absent', text: 'No time series in this run.' }));
      return;
    }
    const res = buildTimePlots(root, D, document.getElementById('plots-other'));
    absent = res.absent;
    status.eclipses = res.eclipses;
    if (res.others) document.getElementById('others-title').hidden = false;
    status.plots = root.querySelectorAll('.uplot').length;
  });
  section('summary', (root) => summary(root, D, absent));
  section('spectrum', (root) => buildSpectrum(root, D));
  section('replay', (root) => buildReplay(root, D, status));
  section('dataflow', (root) => buildDataflow(root, D, status));
  finishPage(status, resizePlots);
}

whenLoaded(main);
