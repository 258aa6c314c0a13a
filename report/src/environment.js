// Earth-orbit runs (docs/environment.md, "Recorded"): the eclipse intervals
// from `illumination`, and the quantities the environment plots show, as
// pure functions of the recorded series (no DOM, no uPlot).

export const ENV_SOURCES = [
  ['gravity_gradient', 'gravity gradient'],
  ['solar_pressure', 'solar pressure'],
  ['drag', 'drag'],
  ['magnetic', 'magnetic'],
];

// Intervals [t0, t1] in which illumination < 1 (penumbra or umbra), with
// their least illumination.  Each interval runs from the first shadowed
// sample to the first sunlit sample after it (or the last sample).
export function eclipseIntervals(t, illum) {
  const out = [];
  let start = -1;
  let least = 1;
  const n = Math.min(t.length, illum.length);
  for (let i = 0; i < n; i++) {
    const v = illum[i];
    if (typeof v !== 'number' || typeof t[i] !== 'number') continue;
    if (v < 1) {
      if (start < 0) { start = i; least = v; } else least = Math.min(least, v);
    } else if (start >= 0) {
      out.push({ t0: t[start], t1: t[i], min: least });
      start = -1;
    }
  }
  if (start >= 0) out.push({ t0: t[start], t1: t[n - 1], min: least });
  return out;
}

// |(x, y, z)| per sample of the series <stem>_x/_y/_z (null where one is missing).
export function magnitude(series, stem, n) {
  const c = ['x', 'y', 'z'].map((a) => series[`${stem}_${a}`]);
  if (!c.every((a) => Array.isArray(a))) return null;
  const out = new Array(n);
  for (let i = 0; i < n; i++) {
    const v = c.map((a) => a[i]);
    out[i] = v.every((x) => typeof x === 'number' && Number.isFinite(x)) ? Math.hypot(v[0], v[1], v[2]) : null;
  }
  return out;
}

// |sum of the vectors <stem>_x/_y/_z over stems, minus their first sample
// when `fromStart`|, per sample.
export function sumMagnitude(series, stems, n, fromStart = false) {
  const cols = stems.map((s) => ['x', 'y', 'z'].map((a) => series[`${s}_${a}`]));
  if (!cols.length || !cols.every((c) => c.every((a) => Array.isArray(a)))) return null;
  const at = (i) => {
    const v = [0, 0, 0];
    for (const c of cols) for (let j = 0; j < 3; j++) {
      const x = c[j][i];
      if (typeof x !== 'number' || !Number.isFinite(x)) return null;
      v[j] += x;
    }
    return v;
  };
  const v0 = fromStart ? at(0) : [0, 0, 0];
  const out = new Array(n);
  for (let i = 0; i < n; i++) {
    const v = at(i);
    out[i] = v && v0 ? Math.hypot(v[0] - v0[0], v[1] - v0[1], v[2] - v0[2]) : null;
  }
  return out;
}
