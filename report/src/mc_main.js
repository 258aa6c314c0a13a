// Kestrel Monte Carlo report: entry point of the second bundle (build.cjs).
// Reads the campaign data (mc_report_data.json, docs/report.md "Monte Carlo
// report") from <script id="kestrel-data" type="application/json"> and builds
// each section; a section that fails shows its error and the others still
// render.  Every string from the data is set as text, never as HTML.
import 'uplot/dist/uPlot.min.css';
import './report.css';
import './mc.css';
import { el, fmt } from './data.js';
import { resizePlots } from './plots.js';
import { normalizeMc, status as runStatus } from './mcdata.js';
import { addEnvelopeCard } from './mcplots.js';
import { buildHistograms, buildScatter, buildTable } from './mcviews.js';
import { section as sectionOf, embeddedData, finishPage, whenLoaded } from './page.js';

const status = { ready: false, errors: [], plots: 0, runLines: 0, histograms: 0 };
window.kestrelReport = status;

const section = (id, fn) => sectionOf(status, id, fn);

function header(D) {
  const m = D.meta;
  document.getElementById('title-scenario').textContent = m.scenario ? `\u2014 ${m.scenario}` : '';
  if (m.scenario) document.title = `Kestrel Monte Carlo: ${m.scenario}`;
  const metaRoot = document.getElementById('meta');
  const kv = (k, v) => metaRoot.appendChild(el('span', { class: 'kv', id: 'mc-meta-' + k.replace(/\W+/g, '_') }, el('b', { text: k + ' ' }), v));
  if (m.scenario !== undefined) kv('scenario', m.scenario);
  if (m.master_seed !== undefined) kv('master seed', String(m.master_seed));
  if (m.runs !== undefined) kv('runs', String(m.runs));
  if (m.failed !== undefined) kv('failed', String(m.failed));
  if (m.invalid !== undefined) kv('invalid draws', String(m.invalid));
  if (m.wall_seconds !== undefined) kv('wall time', `${fmt(m.wall_seconds)} s`);
  if (m.kestrel_version !== undefined) kv('version', m.kestrel_version);
}

function criteria(root, D) {
  if (!D.criteria.length) {
    root.appendChild(el('p', { class: 'absent', text: 'No pass/fail criteria in the data.' }));
    return;
  }
  const rows = D.criteria.map((c) => el('tr', null,
    el('td', { text: c.name }), el('td', { text: c.metric }), el('td', { text: c.op }),
    el('td', { class: 'num', text: c.threshold === null ? '\u2013' : fmt(c.threshold, 6) + (c.unit ? ` ${c.unit}` : '') }),
    el('td', { text: c.what })));
  root.appendChild(el('table', { class: 'summary', id: 'mc-criteria' },
    el('thead', null, el('tr', null, ...['criterion', 'metric', 'pass when', 'threshold', 'what'].map((h) => el('th', { text: h })))),
    el('tbody', null, ...rows)));
  // what the table holds, as a check of the header's counts
  const n = { pass: 0, fail: 0, invalid: 0 };
  for (const r of D.table) n[runStatus(r)]++;
  root.appendChild(el('p', { class: 'note', id: 'mc-counts', text: `In the table: ${D.table.length} runs, ${n.fail} failing, ${n.invalid} invalid draws, ${n.pass} passing.` }));
}

// Per criterion: the runs that failed it and the dispersions ranked by how
// strongly they separate failing from passing runs (rank statistics).
function drivers(root, D) {
  if (!D.drivers.length) {
    root.appendChild(el('p', { class: 'absent', text: 'No criteria: nothing to explain.' }));
    return;
  }
  root.appendChild(el('p', { class: 'note', text: 'For each criterion, each drawn value x: AUC = P(x of a failing run > x of a passing run) '
    + '(Mann-Whitney, ties count 1/2); \u03b4 = 2 AUC \u2212 1 ranks the dispersions (+1: failures drew larger values, \u22121: smaller, 0: no separation); '
    + 'p: chance of a separation this strong if x did not matter; \u03c1: Spearman correlation of x with the criterion\'s metric '
    + '(it ranks when nothing or everything failed). docs/monte-carlo.md, "What drives the failures".' }));
  for (const c of D.drivers) {
    const card = el('div', { class: 'card drivers', id: 'mc-drivers-' + c.criterion.replace(/\W+/g, '_') });
    const top = c.ranked[0];
    let verdict;
    if (!c.failed) verdict = `${c.criterion}: no run failed it (${c.runs} runs).`;
    else {
      verdict = `${c.criterion}: ${c.failed} of ${c.runs} runs failed`;
      if (c.rankedBy === 'delta' && top && top.delta !== null) {
        verdict += `; driven most by ${top.drawn} (\u03b4 = ${fmt(top.delta, 3)}: failing runs drew ${top.delta > 0 ? 'larger' : 'smaller'} values`
          + `${top.p !== null ? `, p = ${fmt(top.p, 2)}` : ''})`;
      }
      verdict += '.';
    }
    card.appendChild(el('h3', { class: 'verdict', text: verdict }));
    if (c.failing.length) {
      const more = c.failed > c.failing.length ? ` \u2026 (${c.failed - c.failing.length} more)` : '';
      card.appendChild(el('p', { class: 'failing-runs', text: `Failing runs: ${c.failing.map((i) => '#' + i).join(', ')}${more}` }));
    }
    const rows = c.ranked.map((r, k) => el('tr', { class: k === 0 && c.failed ? 'top' : '' },
      el('td', { class: 'num', text: String(k + 1) }), el('td', { text: r.drawn + (r.unit ? ` [${r.unit}]` : '') }),
      el('td', { class: 'num', text: fmt(r.delta, 3) }), el('td', { class: 'num', text: fmt(r.auc, 3) }),
      el('td', { class: 'num', text: fmt(r.p, 2) }), el('td', { class: 'num', text: fmt(r.rho, 3) })));
    card.appendChild(el('table', { class: 'summary drivers-table' },
      el('thead', null, el('tr', null, ...['rank', 'drawn value', '\u03b4', 'AUC', 'p', '\u03c1 (metric)'].map((h) => el('th', { text: h })))),
      el('tbody', null, ...rows)));
    root.appendChild(card);
  }
}

function main() {
  const raw = embeddedData(status, 'criteria', 'campaign data');
  const D = normalizeMc(raw);
  section('meta', () => header(D));
  section('criteria', (root) => criteria(root, D));
  section('mc-drivers', (root) => drivers(root, D));
  section('mc-series', (root) => {
    const S = D.series;
    if (!S.t.length || !S.channels.length) {
      root.appendChild(el('p', { class: 'absent', text: 'No time series in the data.' }));
      return;
    }
    const shown = new Set(S.runs.map((r) => r.index)).size;
    document.getElementById('series-note').textContent = `${shown} retained runs of ${D.meta.runs ?? D.table.length}, ` +
      'passing in translucent blue, failing in red on top; the envelopes are over all runs. Drag to zoom in time (all cards follow), double-click to reset.';
    for (const ch of S.channels) section('mc-series', (r) => addEnvelopeCard(r, ch, S, status));
    status.plots = root.querySelectorAll('.uplot').length;
  });
  section('mc-hist', (root) => { status.histograms = buildHistograms(root, D); });
  section('mc-scatter', (root) => buildScatter(root, D, (index) => {
    const row = document.getElementById('mc-run-' + index);
    if (!row) return;
    for (const r of document.querySelectorAll('#mc-runs tr.picked')) r.classList.remove('picked');
    row.classList.add('picked');
    row.scrollIntoView({ block: 'center' });
  }));
  section('mc-table', (root) => buildTable(root, D));
  finishPage(status, resizePlots);
}

whenLoaded(main);
