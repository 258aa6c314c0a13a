// Access to report_data.json: tolerant of anything missing or malformed.

export function isNumArray(a) {
  return Array.isArray(a) && a.length > 0;
}

// Numeric view of a series aligned with t (length n): numbers stay, anything
// else (null, NaN written as null, strings) becomes null (a gap in a plot).
export function alignSeries(a, n) {
  const out = new Array(n);
  for (let i = 0; i < n; i++) {
    const v = Array.isArray(a) && i < a.length ? a[i] : null;
    out[i] = typeof v === 'number' && Number.isFinite(v) ? v : null;
  }
  return out;
}

// Keys "<prefix><k>" with integer k, sorted by k.
export function indexedKeys(series, prefix) {
  const re = new RegExp('^' + prefix.replace(/[.*+?^${}()|[\]\\]/g, '\\$&') + '(\\d+)$');
  const ks = [];
  for (const k of Object.keys(series || {})) {
    const m = re.exec(k);
    if (m && isNumArray(series[k])) ks.push([Number(m[1]), k]);
  }
  ks.sort((a, b) => a[0] - b[0]);
  return ks.map(([i, k]) => ({ index: i, key: k }));
}

export function normalize(raw) {
  const d = raw && typeof raw === 'object' ? raw : {};
  const meta = d.meta && typeof d.meta === 'object' ? d.meta : {};
  const series = d.series && typeof d.series === 'object' ? d.series : {};
  const units = d.units && typeof d.units === 'object' ? d.units : {};
  const t = isNumArray(series.t) ? alignSeries(series.t, series.t.length) : [];
  const attitude = d.attitude && typeof d.attitude === 'object' ? d.attitude : {};
  const geometry = d.geometry && typeof d.geometry === 'object' ? d.geometry : {};
  const dot = typeof d.dataflow_dot === 'string' ? d.dataflow_dot : '';
  // long runs: the series are reduced for display (min/max per bucket) and
  // the last samples are kept at full rate for the jitter spectrum
  const spectrum = d.spectrum && typeof d.spectrum === 'object' && isNumArray(d.spectrum.t) ? d.spectrum : null;
  const decimation = d.decimation && typeof d.decimation === 'object' ? d.decimation : null;
  // applied scenario events (docs/events.md): {name, tick, t, actions}
  const events = Array.isArray(d.events)
    ? d.events.filter((e) => e && typeof e === 'object' && typeof e.t === 'number' && Number.isFinite(e.t))
    : [];
  // the run's own summary (summary.txt's items, in its order), its warnings
  // and its requirement lines
  const summary = d.summary && typeof d.summary === 'object' ? d.summary : {};
  const summaryOrder = Array.isArray(d.summary_order)
    ? d.summary_order.filter((k) => typeof k === 'string')
    : Object.keys(summary);
  const warnings = Array.isArray(d.warnings) ? d.warnings.filter((w) => typeof w === 'string') : [];
  const requirements = Array.isArray(d.requirements)
    ? d.requirements.filter((r) => r && typeof r === 'object' && typeof r.name === 'string')
    : [];
  return { meta, series, units, t, attitude, geometry, dot, spectrum, decimation, events, summary, summaryOrder, warnings, requirements };
}

export function finiteMinMax(a) {
  let lo = Infinity;
  let hi = -Infinity;
  for (const v of a) {
    if (typeof v === 'number' && Number.isFinite(v)) {
      if (v < lo) lo = v;
      if (v > hi) hi = v;
    }
  }
  return lo <= hi ? [lo, hi] : null;
}

// Index of the last sample with t[i] <= x (0 if before the start).
export function sampleIndex(t, x) {
  let lo = 0;
  let hi = t.length - 1;
  if (hi < 0) return -1;
  if (!(x >= t[0])) return 0;
  if (x >= t[hi]) return hi;
  while (hi - lo > 1) {
    const mid = (lo + hi) >> 1;
    if (t[mid] <= x) lo = mid;
    else hi = mid;
  }
  return lo;
}

export function fmt(v, digits = 4) {
  if (v === null || v === undefined || (typeof v === 'number' && !Number.isFinite(v))) return '\u2013';
  if (typeof v !== 'number') return String(v);
  if (v === 0) return '0';
  const a = Math.abs(v);
  if (a >= 1e5 || a < 1e-3) return v.toExponential(digits - 1);
  return Number(v.toPrecision(digits)).toString();
}

export function el(tag, attrs, ...children) {
  const e = document.createElement(tag);
  if (attrs) {
    for (const [k, v] of Object.entries(attrs)) {
      if (k === 'class') e.className = v;
      else if (k === 'text') e.textContent = v;
      else if (k.startsWith('on') && typeof v === 'function') e.addEventListener(k.slice(2), v);
      else e.setAttribute(k, v);
    }
  }
  for (const c of children) {
    if (c === null || c === undefined) continue;
    e.appendChild(typeof c === 'string' ? document.createTextNode(c) : c);
  }
  return e;
}
