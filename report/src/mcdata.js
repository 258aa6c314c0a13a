// Monte Carlo report: access to mc_report_data.json (docs/report.md, "Monte
// Carlo report") and the pure computations of the page (no DOM, no uPlot:
// unit-tested by test/report/js/mcdata.test.mjs).  Tolerant of anything
// missing or malformed: what is not of the documented type is dropped.

const obj = (v) => (v && typeof v === 'object' && !Array.isArray(v) ? v : {});
const arr = (v) => (Array.isArray(v) ? v : []);
const str = (v) => (typeof v === 'string' ? v : '');
export const num = (v) => (typeof v === 'number' && Number.isFinite(v) ? v : null);

// Numbers (or null) aligned with a list of n names.
function numsOf(a, n) {
  const out = new Array(n);
  for (let i = 0; i < n; i++) out[i] = Array.isArray(a) ? num(a[i]) : null;
  return out;
}

const named = (list) => arr(list).filter((x) => x && typeof x === 'object' && typeof x.name === 'string')
  .map((x) => ({ name: x.name, unit: str(x.unit) }));

export function normalizeMc(raw) {
  const d = obj(raw);
  const drawn = named(d.drawn);
  const metrics = named(d.metrics);
  const criteria = arr(d.criteria).filter((c) => c && typeof c === 'object').map((c) => ({
    name: str(c.name), metric: str(c.metric), op: str(c.op), threshold: num(c.threshold), unit: str(c.unit), what: str(c.what),
  }));
  const table = arr(d.table).filter((r) => r && typeof r === 'object').map((r, k) => ({
    index: Number.isInteger(r.index) ? r.index : k,
    seed: typeof r.seed === 'string' || typeof r.seed === 'number' ? String(r.seed) : '',
    pass: r.pass === true,
    invalid: r.invalid === true,
    reason: str(r.reason),
    drawn: numsOf(r.drawn, drawn.length),
    metrics: numsOf(r.metrics, metrics.length),
    report: safeLink(r.report),
  }));
  const s = obj(d.series);
  const t = arr(s.t).map(num);
  const channels = arr(s.channels).filter((c) => c && typeof c === 'object' && typeof c.name === 'string')
    .map((c) => ({ name: c.name, unit: str(c.unit), columns: arr(c.columns).filter((x) => typeof x === 'string') }))
    .filter((c) => c.columns.length > 0);
  const p = obj(s.percentiles);
  const levels = arr(p.levels).map(num);
  const pcols = obj(p.columns);
  const runs = arr(s.runs).filter((r) => r && typeof r === 'object' && Number.isInteger(r.index))
    .map((r) => ({ index: r.index, pass: r.pass === true, columns: obj(r.columns) }));
  const meta = {};
  for (const k of ['scenario', 'kestrel_version']) if (typeof d[k] === 'string') meta[k] = d[k];
  for (const k of ['master_seed', 'runs', 'failed', 'invalid', 'wall_seconds']) {
    if (num(d[k]) !== null) meta[k] = d[k];
    else if (typeof d[k] === 'string' && /^\d+$/.test(d[k])) meta[k] = d[k]; // a 64-bit seed as text
  }
  // what drives each criterion's failures (docs/monte-carlo.md)
  const drivers = arr(d.drivers).filter((c) => c && typeof c === 'object' && typeof c.criterion === 'string').map((c) => ({
    criterion: c.criterion, runs: num(c.runs), failed: num(c.failed), rankedBy: str(c.ranked_by),
    failing: arr(c.failing).filter((i) => Number.isInteger(i)),
    ranked: arr(c.ranked).filter((r) => r && typeof r === 'object' && typeof r.drawn === 'string').map((r) => ({
      drawn: r.drawn, unit: str(r.unit), n: num(r.n), auc: num(r.auc), delta: num(r.delta), p: num(r.p), rho: num(r.rho),
    })),
  }));
  return { kind: str(d.kind), schema: num(d.schema), meta, criteria, drawn, metrics, table, drivers,
    series: { t, channels, levels, pcols, runs } };
}

// pass / fail / invalid of a table row (an invalid draw never ran: its pass is meaningless)
export function status(row) {
  if (row.invalid) return 'invalid';
  return row.pass ? 'pass' : 'fail';
}
const RANK = { fail: 0, invalid: 1, pass: 2 };

function seedCmp(a, b) {
  const da = /^\d+$/.test(a);
  const db = /^\d+$/.test(b);
  if (da && db) return a.length - b.length || (a < b ? -1 : a > b ? 1 : 0); // decimal, no leading zeros
  if (da !== db) return da ? -1 : 1;
  return a < b ? -1 : a > b ? 1 : 0;
}

// The value of a row in a column: {kind: 'index'|'seed'|'status'|'reason'|'drawn'|'metric', i}
export function cellValue(row, col) {
  switch (col.kind) {
    case 'index': return row.index;
    case 'seed': return row.seed;
    case 'status': return RANK[status(row)];
    case 'reason': return row.reason;
    case 'drawn': return row.drawn[col.i];
    case 'metric': return row.metrics[col.i];
    default: return null;
  }
}

// Comparator for sorting by a column, ascending (dir 1) or descending (-1).
// Missing values (null, '') sort last either way; ties keep the default
// order (failing first, then by run index).
export function rowComparator(col, dir = 1) {
  return (a, b) => {
    if (col) {
      const va = cellValue(a, col);
      const vb = cellValue(b, col);
      const ma = va === null || va === '';
      const mb = vb === null || vb === '';
      if (ma !== mb) return ma ? 1 : -1;
      if (!ma) {
        let c;
        if (col.kind === 'seed') c = seedCmp(va, vb);
        else if (typeof va === 'number') c = va - vb;
        else c = va < vb ? -1 : va > vb ? 1 : 0;
        if (c !== 0) return dir * c;
      }
    }
    return RANK[status(a)] - RANK[status(b)] || a.index - b.index;
  };
}

// Histogram of the finite values of rows: `bins` equal bins (default: the
// square-root rule, 5 to 40) over [min, max] of the values, widened to take
// in `mark` (a criterion threshold) so that it can be drawn.  Each bin counts
// passing and failing runs apart (the last bin is closed).
export function histogram(values, failing, mark = null, bins = 0) {
  const v = [];
  const f = [];
  values.forEach((x, i) => { if (num(x) !== null) { v.push(x); f.push(!!failing[i]); } });
  if (!v.length) return null;
  let lo = Math.min(...v);
  let hi = Math.max(...v);
  if (num(mark) !== null) { lo = Math.min(lo, mark); hi = Math.max(hi, mark); }
  if (hi === lo) { const h = lo === 0 ? 0.5 : Math.abs(lo) * 0.05; lo -= h; hi += h; }
  const n = bins > 0 ? bins : Math.max(5, Math.min(40, Math.ceil(Math.sqrt(v.length))));
  const w = (hi - lo) / n;
  const edges = Array.from({ length: n + 1 }, (_, k) => (k === n ? hi : lo + k * w));
  const pass = new Array(n).fill(0);
  const fail = new Array(n).fill(0);
  v.forEach((x, i) => {
    const k = Math.min(n - 1, Math.max(0, Math.floor((x - lo) / w)));
    (f[i] ? fail : pass)[k]++;
  });
  return { edges, pass, fail, n: v.length };
}

// Percentile levels to draw: pairs (lo, hi) symmetric about the middle of
// the sorted levels become shaded bands (outer pairs lighter), a level
// without a partner (the median of 0/5/50/95/100) is a line.  Returns
// indexes into `levels`.
export function bandPairs(levels) {
  const idx = levels.map((l, i) => [l, i]).filter(([l]) => l !== null).sort((a, b) => a[0] - b[0]).map(([, i]) => i);
  const bands = [];
  const lines = [];
  let a = 0;
  let b = idx.length - 1;
  while (a < b && levels[idx[a]] < levels[idx[b]]) { bands.push([idx[a], idx[b]]); a++; b--; }
  for (let k = a; k <= b; k++) lines.push(idx[k]);
  return { bands, lines };
}

// A per-run report link as written by `kestrel mc`: a relative path only
// (no scheme such as javascript: or http:, no absolute or protocol-relative
// path, no control characters); anything else is dropped.
export function safeLink(s) {
  if (typeof s !== 'string' || !s || s.length > 4096) return null;
  if (/[\u0000-\u001f\u007f\\]/.test(s)) return null;
  if (/^[a-zA-Z][a-zA-Z0-9+.-]*:/.test(s) || s.startsWith('/')) return null;
  return s;
}

// About n round tick values covering [lo, hi].
export function niceTicks(lo, hi, n = 5) {
  if (!(hi > lo)) return [lo];
  const raw = (hi - lo) / Math.max(1, n);
  const p = 10 ** Math.floor(Math.log10(raw));
  const step = [1, 2, 2.5, 5, 10].map((m) => m * p).find((s) => s >= raw) || 10 * p;
  const out = [];
  for (let v = Math.ceil(lo / step - 1e-9) * step; v <= hi + step * 1e-9; v += step) out.push(Math.abs(v) < step * 1e-9 ? 0 : v);
  return out;
}
