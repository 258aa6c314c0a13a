// Monte Carlo report: histograms of the metrics, the scatter of a metric
// against a drawn value (small SVG drawings) and the sortable table of runs.
import { el, fmt } from './data.js';
import { fmtTick } from './plots.js';
import { histogram, niceTicks, rowComparator, status, num } from './mcdata.js';
import { FAIL_COLOR } from './mcplots.js';

const SVGNS = 'http://www.w3.org/2000/svg';
const PASS_FILL = '#5b8fd6';

function s(tag, attrs, ...children) {
  const e = document.createElementNS(SVGNS, tag);
  for (const [k, v] of Object.entries(attrs || {})) {
    if (k === 'text') e.textContent = v;
    else e.setAttribute(k, String(v));
  }
  for (const c of children) if (c) e.appendChild(c);
  return e;
}

const W = 520;
const H = 230;
const M = { l: 56, r: 12, t: 12, b: 40 };

// a linear axis frame: returns the value -> pixel maps and draws the ticks
function frame(svg, xr, yr, xlabel, ylabel) {
  const X = (v) => M.l + ((v - xr[0]) / (xr[1] - xr[0] || 1)) * (W - M.l - M.r);
  const Y = (v) => H - M.b - ((v - yr[0]) / (yr[1] - yr[0] || 1)) * (H - M.t - M.b);
  const g = s('g', { class: 'axes' });
  g.appendChild(s('rect', { x: M.l, y: M.t, width: W - M.l - M.r, height: H - M.t - M.b, class: 'frame' }));
  for (const v of niceTicks(xr[0], xr[1], 6)) {
    g.appendChild(s('line', { x1: X(v), x2: X(v), y1: H - M.b, y2: H - M.b + 4, class: 'tick' }));
    g.appendChild(s('text', { x: X(v), y: H - M.b + 15, 'text-anchor': 'middle', text: fmtTick(v) }));
  }
  for (const v of niceTicks(yr[0], yr[1], 4)) {
    g.appendChild(s('line', { x1: M.l - 4, x2: W - M.r, y1: Y(v), y2: Y(v), class: 'grid' }));
    g.appendChild(s('text', { x: M.l - 6, y: Y(v) + 4, 'text-anchor': 'end', text: fmtTick(v) }));
  }
  g.appendChild(s('text', { x: (M.l + W - M.r) / 2, y: H - 6, 'text-anchor': 'middle', class: 'label', text: xlabel }));
  g.appendChild(s('text', { x: 12, y: (M.t + H - M.b) / 2, 'text-anchor': 'middle', class: 'label',
    transform: `rotate(-90 12 ${(M.t + H - M.b) / 2})`, text: ylabel }));
  svg.appendChild(g);
  return { X, Y };
}

function thresholdLine(svg, X, Y, xr, yr, v, vertical) {
  const a = vertical ? { x1: X(v), x2: X(v), y1: Y(yr[0]), y2: Y(yr[1]) } : { x1: X(xr[0]), x2: X(xr[1]), y1: Y(v), y2: Y(v) };
  svg.appendChild(s('line', { ...a, class: 'threshold' }));
  // the label on the side of the line with more room
  const right = X(v) < (M.l + W - M.r) / 2;
  svg.appendChild(s('text', vertical ? { x: X(v) + (right ? 3 : -3), y: M.t + 11, 'text-anchor': right ? 'start' : 'end', class: 'threshold-label', text: `threshold ${fmtTick(v)}` }
    : { x: X(xr[1]) - 3, y: Y(v) - 4, 'text-anchor': 'end', class: 'threshold-label', text: `threshold ${fmtTick(v)}` }));
}

const withUnit = (x) => x.name + (x.unit ? ` [${x.unit}]` : '');

// the criteria thresholds per metric name
export function thresholdsOf(D) {
  const m = new Map();
  for (const c of D.criteria) if (c.metric && c.threshold !== null && !m.has(c.metric)) m.set(c.metric, c.threshold);
  return m;
}

export function buildHistograms(root, D) {
  const rows = D.table.filter((r) => !r.invalid);
  const th = thresholdsOf(D);
  let drawn = 0;
  D.metrics.forEach((m, i) => {
    const card = el('div', { class: 'card hist', id: 'mc-hist-' + i });
    card.appendChild(el('h3', { text: withUnit(m) }));
    root.appendChild(card);
    const mark = th.has(m.name) ? th.get(m.name) : null;
    const h = histogram(rows.map((r) => r.metrics[i]), rows.map((r) => status(r) === 'fail'), mark);
    if (!h) { card.appendChild(el('p', { class: 'absent', text: 'No finite values.' })); return; }
    const svg = s('svg', { viewBox: `0 0 ${W} ${H}`, class: 'mc-svg', role: 'img' });
    const top = Math.max(...h.pass.map((p, k) => p + h.fail[k]));
    const xr = [h.edges[0], h.edges[h.edges.length - 1]];
    const yr = [0, Math.max(1, top) * 1.08];
    const { X, Y } = frame(svg, xr, yr, withUnit(m), 'runs');
    for (let k = 0; k < h.pass.length; k++) {
      const x0 = X(h.edges[k]) + 0.5;
      const w = Math.max(0.5, X(h.edges[k + 1]) - X(h.edges[k]) - 1);
      const tip = `${fmt(h.edges[k])} \u2026 ${fmt(h.edges[k + 1])}: ${h.pass[k]} passing, ${h.fail[k]} failing`;
      if (h.pass[k]) svg.appendChild(s('rect', { x: x0, y: Y(h.pass[k]), width: w, height: Y(0) - Y(h.pass[k]), fill: PASS_FILL, class: 'bar pass' }, s('title', { text: tip })));
      if (h.fail[k]) svg.appendChild(s('rect', { x: x0, y: Y(h.pass[k] + h.fail[k]), width: w, height: Y(h.pass[k]) - Y(h.pass[k] + h.fail[k]), fill: FAIL_COLOR, class: 'bar fail' }, s('title', { text: tip })));
    }
    if (mark !== null) thresholdLine(svg, X, Y, xr, yr, mark, true);
    card.appendChild(svg);
    card.appendChild(el('p', { class: 'note', text: `${h.n} runs with a value; failing runs stacked in red` + (mark !== null ? '; dashed: the criterion threshold.' : '.') }));
    drawn++;
  });
  if (!D.metrics.length) root.appendChild(el('p', { class: 'absent', text: 'No metrics in the data.' }));
  return drawn;
}

export function buildScatter(root, D, onPick) {
  if (!D.metrics.length || !D.drawn.length) {
    root.appendChild(el('p', { class: 'absent', text: 'The scatter needs at least one metric and one drawn value.' }));
    return;
  }
  const th = thresholdsOf(D);
  const selY = el('select', { id: 'mc-scatter-metric' }, ...D.metrics.map((m, i) => el('option', { value: String(i), text: withUnit(m) })));
  const selX = el('select', { id: 'mc-scatter-drawn' }, ...D.drawn.map((d, i) => el('option', { value: String(i), text: withUnit(d) })));
  root.appendChild(el('div', { class: 'controls' }, el('label', null, 'metric ', selY), el('label', null, 'against drawn value ', selX)));
  const card = el('div', { class: 'card' });
  root.appendChild(card);
  const note = el('p', { class: 'note' });
  const draw = () => {
    const mi = Number(selY.value);
    const di = Number(selX.value);
    card.textContent = '';
    const pts = D.table.filter((r) => !r.invalid && num(r.metrics[mi]) !== null && num(r.drawn[di]) !== null)
      .map((r) => ({ r, x: r.drawn[di], y: r.metrics[mi], fail: status(r) === 'fail' }));
    const svg = s('svg', { viewBox: `0 0 ${W} ${H}`, class: 'mc-svg', id: 'mc-scatter-svg', 'data-metric': mi, 'data-drawn': di, role: 'img' });
    const mark = th.has(D.metrics[mi].name) ? th.get(D.metrics[mi].name) : null;
    const xs = pts.map((p) => p.x);
    const ys = pts.map((p) => p.y).concat(mark !== null ? [mark] : []);
    const range = (v) => {
      if (!v.length) return [0, 1];
      let lo = Math.min(...v);
      let hi = Math.max(...v);
      if (hi === lo) { const h = lo === 0 ? 0.5 : Math.abs(lo) * 0.05; lo -= h; hi += h; }
      const pad = 0.04 * (hi - lo);
      return [lo - pad, hi + pad];
    };
    const xr = range(xs);
    const yr = range(ys);
    const { X, Y } = frame(svg, xr, yr, withUnit(D.drawn[di]), withUnit(D.metrics[mi]));
    if (mark !== null) thresholdLine(svg, X, Y, xr, yr, mark, false);
    // passing first, failing on top
    for (const p of pts.filter((q) => !q.fail).concat(pts.filter((q) => q.fail))) {
      const c = s('circle', { cx: X(p.x), cy: Y(p.y), r: p.fail ? 3.6 : 2.6, class: p.fail ? 'pt fail' : 'pt pass', 'data-run': p.r.index },
        s('title', { text: `run ${p.r.index} (${status(p.r)}): ${fmt(p.x)}, ${fmt(p.y)}` }));
      c.addEventListener('click', () => onPick(p.r.index));
      svg.appendChild(c);
    }
    card.appendChild(svg);
    note.textContent = `${pts.length} runs (failing in red); a click on a point shows its row in the table.`;
    card.appendChild(note);
  };
  selY.addEventListener('change', draw);
  selX.addEventListener('change', draw);
  draw();
}

// The table of runs: one header per column, a click sorts by it (again:
// reverses); the default order is failing first, then invalid draws, then
// passing runs, each by run index.
export function buildTable(root, D) {
  const cols = [
    { kind: 'index', title: 'run' },
    { kind: 'seed', title: 'seed' },
    { kind: 'status', title: 'result' },
    { kind: 'reason', title: 'reason' },
    ...D.drawn.map((d, i) => ({ kind: 'drawn', i, title: withUnit(d), cls: 'drawn' })),
    ...D.metrics.map((m, i) => ({ kind: 'metric', i, title: withUnit(m), cls: 'metric' })),
  ];
  const hasReports = D.table.some((r) => r.report);
  const tr = D.table.map((r) => {
    const st = status(r);
    const cells = cols.map((c) => {
      if (c.kind === 'status') return el('td', { class: 'st ' + st, text: st === 'fail' ? 'FAIL' : st });
      if (c.kind === 'index' || c.kind === 'seed' || c.kind === 'reason') return el('td', { class: c.kind, text: String(r[c.kind]) });
      return el('td', { class: 'num', text: fmt(c.kind === 'drawn' ? r.drawn[c.i] : r.metrics[c.i]) });
    });
    if (hasReports) cells.push(el('td', null, r.report ? el('a', { href: r.report, text: 'report' }) : null));
    const row = el('tr', { class: st, id: 'mc-run-' + r.index, 'data-run': r.index }, ...cells);
    return { r, row };
  });
  const head = el('tr', null);
  const tbody = el('tbody');
  let sortCol = -1;
  let dir = 1;
  const ths = cols.map((c, k) => {
    const th = el('th', { class: 'sortable', title: 'sort by this column (again: reverse)', text: c.title });
    th.addEventListener('click', () => {
      dir = sortCol === k ? -dir : 1;
      sortCol = k;
      ths.forEach((h, j) => h.setAttribute('aria-sort', j === k ? (dir > 0 ? 'ascending' : 'descending') : 'none'));
      apply(rowComparator(cols[k], dir));
    });
    head.appendChild(th);
    return th;
  });
  if (hasReports) head.appendChild(el('th', { text: 'run report' }));
  const apply = (cmp) => {
    tr.sort((a, b) => cmp(a.r, b.r));
    const frag = document.createDocumentFragment();
    for (const { row } of tr) frag.appendChild(row);
    tbody.appendChild(frag);
  };
  apply(rowComparator(null));
  root.appendChild(el('div', { class: 'table-scroll' }, el('table', { id: 'mc-runs', class: 'runs' }, el('thead', null, head), tbody)));
  if (!D.table.length) root.appendChild(el('p', { class: 'absent', text: 'No runs in the data.' }));
}
