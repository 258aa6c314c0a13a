// Unit tests of the report's jitter spectrum (report/src/spectrum.js).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { fft, welch, uniformWindow, segmentLength, rms } from '../../../report/src/spectrum.js';

test('fft of a unit impulse is flat, of a cosine two lines', () => {
  const re = new Float64Array(8); const im = new Float64Array(8);
  re[0] = 1;
  fft(re, im);
  for (let k = 0; k < 8; k++) { assert.ok(Math.abs(re[k] - 1) < 1e-12); assert.ok(Math.abs(im[k]) < 1e-12); }
  const n = 64; const r = new Float64Array(n); const i2 = new Float64Array(n);
  for (let k = 0; k < n; k++) r[k] = Math.cos((2 * Math.PI * 5 * k) / n);
  fft(r, i2);
  assert.ok(Math.abs(r[5] - n / 2) < 1e-9 && Math.abs(r[n - 5] - n / 2) < 1e-9);
  assert.ok(Math.abs(r[6]) < 1e-9);
});

test('welch finds a sinusoid at its frequency and keeps Parseval', () => {
  const dt = 0.01; const n = 20000; const f0 = 7.3; const A = 2e-3;
  const y = new Float64Array(n);
  for (let k = 0; k < n; k++) y[k] = A * Math.sin(2 * Math.PI * f0 * k * dt) + 1.0; // offset removed per segment
  const s = welch(y, dt);
  assert.ok(s && s.segments >= 8);
  let kmax = 1;
  for (let k = 1; k < s.asd.length; k++) if (s.asd[k] > s.asd[kmax]) kmax = k;
  assert.ok(Math.abs(s.f[kmax] - f0) <= s.f[1], `peak at ${s.f[kmax]} Hz`);
  // integral of the PSD = variance of the signal (within the window's leakage)
  const df = s.f[1] - s.f[0];
  let v = 0;
  for (let k = 0; k < s.asd.length; k++) v += s.asd[k] * s.asd[k] * df;
  const want = (A * A) / 2;
  assert.ok(Math.abs(v - want) / want < 0.02, `variance ${v} vs ${want}`);
  assert.ok(Math.abs(rms(y) - A / Math.SQRT2) < 1e-5);
});

test('white noise has a flat density at sigma*sqrt(2/fs)', () => {
  let seed = 1;
  const rnd = () => { seed = (seed * 1103515245 + 12345) % 2147483648; return seed / 2147483648; };
  const dt = 0.1; const n = 65536; const sigma = 1e-4;
  const y = new Float64Array(n);
  for (let k = 0; k < n; k++) y[k] = sigma * Math.sqrt(-2 * Math.log(rnd() + 1e-15)) * Math.cos(2 * Math.PI * rnd());
  const s = welch(y, dt);
  let m = 0; let c = 0;
  for (let k = 2; k < s.asd.length - 1; k++) { m += s.asd[k] * s.asd[k]; c++; }
  const psd = m / c;
  const want = (2 * sigma * sigma) * dt;
  assert.ok(Math.abs(psd - want) / want < 0.05, `psd ${psd} vs ${want}`);
});

test('uniformWindow keeps uniform data, resamples irregular data, drops gaps', () => {
  const t = [0, 1, 2, 3, 4, 5];
  const u = uniformWindow(t, [0, 1, 2, 3, 4, 5], 1, 4);
  assert.equal(u.dt, 1);
  assert.deepEqual(Array.from(u.y), [1, 2, 3, 4]);
  const w = uniformWindow([0, 1, 3, 4], [0, 10, 30, 40]);
  assert.equal(w.dt, 1);
  assert.deepEqual(Array.from(w.y), [0, 10, 20, 30, 40]);
  const g = uniformWindow([0, 1, 2], [0, null, 'x']);
  assert.equal(g.y.length, 1);
  assert.equal(welch(new Float64Array(5), 0.1), null);
  assert.equal(welch(new Float64Array(100), 0), null);
  assert.ok(segmentLength(100000) === 8192 && segmentLength(64) === 16);
});

test('wheel lines above the Nyquist frequency of the recording fold back, and the divisor that resolves them', async () => {
  const { wheelAliasing, recordDivisorFor } = await import('../../../report/src/spectrum.js');
  // 3000 rpm = 50 Hz recorded at 10 Hz: Nyquist 5 Hz, 50 Hz folds to 0 Hz;
  // 1000 rpm = 16.67 Hz folds to |16.67 - 20| = 3.33 Hz; 120 rpm = 2 Hz is resolved
  const r = wheelAliasing([{ name: 'rw1', f: 50 }, { name: 'rw2', f: 1000 / 60 }, { name: 'rw3', f: 2 }], 10);
  assert.equal(r.nyquist, 5);
  assert.deepEqual(r.aliased.map((a) => a.name), ['rw1', 'rw2']);
  assert.ok(Math.abs(r.aliased[0].folded) < 1e-9);
  assert.ok(Math.abs(r.aliased[1].folded - 10 / 3) < 1e-9);
  assert.equal(r.fMax, 50);
  // the second harmonic of rw3 (4 Hz) is still below 5 Hz; of a 3 Hz wheel (6 Hz) not
  assert.equal(wheelAliasing([{ name: 'w', f: 2 }], 10, 2).aliased.length, 0);
  assert.deepEqual(wheelAliasing([{ name: 'w', f: 3 }], 10, 2).aliased.map((a) => [a.k, a.f, a.folded]), [[2, 6, 4]]);
  // dt = 0.01 s: 50 Hz needs 125 samples/s or more: divisor floor(100 / 125) = 0 -> dt must shrink;
  // 16.67 Hz needs 41.7 samples/s: divisor 2 (50 samples/s)
  assert.equal(recordDivisorFor(50, 0.01), 0);
  assert.equal(recordDivisorFor(1000 / 60, 0.01), 2);
  assert.equal(recordDivisorFor(2, 0.01), 20);
  assert.equal(recordDivisorFor(0, 0.01), 0);
});
