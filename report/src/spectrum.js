// Jitter spectrum: Welch's averaged periodogram (Hann window, 50 % overlap,
// per-segment mean removed), one-sided, returned as an amplitude spectral
// density sqrt(PSD) in <unit>/sqrt(Hz).  Pure functions, tested with node.

// In-place iterative radix-2 FFT of (re, im); n must be a power of two.
export function fft(re, im) {
  const n = re.length;
  for (let i = 1, j = 0; i < n; i++) {
    let bit = n >> 1;
    for (; j & bit; bit >>= 1) j ^= bit;
    j ^= bit;
    if (i < j) {
      let t = re[i]; re[i] = re[j]; re[j] = t;
      t = im[i]; im[i] = im[j]; im[j] = t;
    }
  }
  for (let len = 2; len <= n; len <<= 1) {
    const ang = (-2 * Math.PI) / len;
    const wr = Math.cos(ang);
    const wi = Math.sin(ang);
    for (let i = 0; i < n; i += len) {
      let cr = 1;
      let ci = 0;
      for (let k = 0; k < len / 2; k++) {
        const a = i + k;
        const b = a + len / 2;
        const xr = re[b] * cr - im[b] * ci;
        const xi = re[b] * ci + im[b] * cr;
        re[b] = re[a] - xr; im[b] = im[a] - xi;
        re[a] += xr; im[a] += xi;
        const ncr = cr * wr - ci * wi;
        ci = cr * wi + ci * wr;
        cr = ncr;
      }
    }
  }
}

export function median(a) {
  if (a.length === 0) return NaN;
  const s = Float64Array.from(a).sort();
  const m = s.length >> 1;
  return s.length % 2 ? s[m] : 0.5 * (s[m - 1] + s[m]);
}

// Samples (t, y) in [t0, t1] on a uniform grid: as they are when t is uniform
// (and y has no gaps), else linearly interpolated at the median step.
export function uniformWindow(t, y, t0 = -Infinity, t1 = Infinity) {
  const ts = [];
  const ys = [];
  for (let i = 0; i < t.length && i < y.length; i++) {
    const ti = t[i];
    const yi = y[i];
    if (typeof ti !== 'number' || !Number.isFinite(ti) || ti < t0 || ti > t1) continue;
    if (typeof yi !== 'number' || !Number.isFinite(yi)) continue;
    if (ts.length && ti <= ts[ts.length - 1]) continue; // non-increasing: skip
    ts.push(ti);
    ys.push(yi);
  }
  if (ts.length < 2) return { dt: NaN, y: Float64Array.from(ys) };
  const d = [];
  for (let i = 1; i < ts.length; i++) d.push(ts[i] - ts[i - 1]);
  const dt = median(d);
  let uniform = true;
  for (const di of d) if (Math.abs(di - dt) > 1e-6 * dt) { uniform = false; break; }
  if (uniform) return { dt, y: Float64Array.from(ys) };
  const n = Math.floor((ts[ts.length - 1] - ts[0]) / dt) + 1;
  const out = new Float64Array(n);
  let j = 0;
  for (let i = 0; i < n; i++) {
    const x = ts[0] + i * dt;
    while (j < ts.length - 2 && ts[j + 1] < x) j++;
    const f = (x - ts[j]) / (ts[j + 1] - ts[j]);
    out[i] = ys[j] + Math.min(1, Math.max(0, f)) * (ys[j + 1] - ys[j]);
  }
  return { dt, y: out };
}

export function segmentLength(n, maxLen = 8192) {
  // about 8 averaged segments (15 with the overlap) when the record allows
  let L = 16;
  while (L * 2 <= Math.min(maxLen, Math.max(16, Math.floor(n / 4)))) L *= 2;
  while (L > n && L > 1) L >>= 1;
  return L;
}

// Welch ASD of a uniformly sampled record y with step dt.
// Returns { f: Float64Array, asd: Float64Array, segments, nseg } or null.
export function welch(y, dt, segLen) {
  const n = y.length;
  if (!(dt > 0) || n < 16) return null;
  const L = segLen || segmentLength(n);
  const fs = 1 / dt;
  const w = new Float64Array(L);
  let s2 = 0;
  for (let i = 0; i < L; i++) {
    w[i] = 0.5 - 0.5 * Math.cos((2 * Math.PI * i) / L); // periodic Hann
    s2 += w[i] * w[i];
  }
  const hop = L >> 1;
  const nf = (L >> 1) + 1;
  const psd = new Float64Array(nf);
  const re = new Float64Array(L);
  const im = new Float64Array(L);
  let segments = 0;
  for (let start = 0; start + L <= n; start += hop) {
    let mean = 0;
    for (let i = 0; i < L; i++) mean += y[start + i];
    mean /= L;
    for (let i = 0; i < L; i++) {
      re[i] = (y[start + i] - mean) * w[i];
      im[i] = 0;
    }
    fft(re, im);
    for (let k = 0; k < nf; k++) psd[k] += re[k] * re[k] + im[k] * im[k];
    segments++;
  }
  const f = new Float64Array(nf);
  const asd = new Float64Array(nf);
  for (let k = 0; k < nf; k++) {
    const oneSided = k === 0 || (k === nf - 1 && L % 2 === 0) ? 1 : 2;
    const p = (oneSided * psd[k]) / (segments * fs * s2);
    f[k] = (k * fs) / L;
    asd[k] = Math.sqrt(p);
  }
  return { f, asd, segments, nseg: L };
}

// RMS of y (after removing the mean) = sqrt(integral of PSD): for checks.
export function rms(y) {
  let m = 0;
  for (const v of y) m += v;
  m /= y.length;
  let s = 0;
  for (const v of y) s += (v - m) * (v - m);
  return Math.sqrt(s / y.length);
}

// Wheel lines against the recording rate.  A wheel spinning at f Hz
// (|rpm| / 60: static and dynamic imbalance act once a revolution) puts a
// line at f and its harmonics k f; sampled at fs, a line above the Nyquist
// frequency fs / 2 shows folded back to |k f - fs round(k f / fs)|.
// lines: [{ name, f }]; returns { nyquist, aliased: [{ name, k, f, folded }],
// fMax } for the harmonics 1 .. harmonics.
export function wheelAliasing(lines, fs, harmonics = 1) {
  const nyquist = fs / 2;
  const aliased = [];
  let fMax = 0;
  for (const { name, f } of lines) {
    if (!(f > 0)) continue;
    fMax = Math.max(fMax, f);
    for (let k = 1; k <= harmonics; k++) {
      const fk = k * f;
      if (fk > nyquist) aliased.push({ name, k, f: fk, folded: Math.abs(fk - fs * Math.round(fk / fs)) });
    }
  }
  return { nyquist, aliased, fMax };
}

// The largest recording divisor (ticks of dt per recorded sample, the
// scenario key rates.record_divisor) whose rate puts fMax below the Nyquist
// frequency with a margin: 1 / (divisor dt) >= 2.5 fMax.  0 when even every
// tick (divisor 1) is too slow: rates.dt itself must shrink.
export function recordDivisorFor(fMax, dt) {
  if (!(fMax > 0) || !(dt > 0)) return 0;
  const d = Math.floor(1 / (2.5 * fMax * dt) + 1e-9);
  return d >= 1 ? d : 0;
}
