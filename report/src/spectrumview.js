// Jitter spectrum card: Welch ASD of the body rates over a chosen window.
import uPlot from 'uplot';
import { alignSeries, isNumArray, indexedKeys, el, fmt } from './data.js';
import { uniformWindow, welch, rms, wheelAliasing, recordDivisorFor } from './spectrum.js';
import { deviceName } from './plotmath.js';
import { AXIS_COLORS, rateDisplay, fmtTick } from './plots.js';

// Jitter is a property of the hold: the window starts after the last sample
// with a pointing error above SETTLED_DEG (the whole run if there is none);
// without a pointing error, or if fewer than 256 samples would remain, it
// is the second half of the run.
const SETTLED_DEG = 1.0;
const ok0 = (res) => res.find((r) => r.s) || null;
export function defaultWindowStart(t, pe) {
  const n = t.length;
  const half = t[0] + 0.5 * (t[n - 1] - t[0]);
  if (!isNumArray(pe)) return half;
  let last = -1;
  for (let i = 0; i < Math.min(n, pe.length); i++) if (typeof pe[i] === 'number' && pe[i] > SETTLED_DEG) last = i;
  if (last < 0) return t[0];
  if (n - 1 - last < 256) return half;
  return t[last + 1];
}

export function buildSpectrum(root, D) {
  const { series, units } = D;
  // full-rate samples: the spectrum block of a reduced run, else the series
  const full = D.spectrum || series;
  const t = D.spectrum ? alignSeries(D.spectrum.t, D.spectrum.t.length) : D.t;
  const keys = ['x', 'y', 'z'].map((a) => `omega_BN_B_${a}`).filter((k) => isNumArray(full[k]));
  if (!keys.length || t.length < 16) {
    root.appendChild(el('p', { class: 'absent', text: 'No body-rate series in this run: no spectrum.' }));
    return;
  }
  const [ys, unit] = rateDisplay(keys.map((k) => alignSeries(full[k], t.length)), typeof units[keys[0]] === 'string' ? units[keys[0]] : 'rad/s');
  const tEnd = t[t.length - 1];
  const t0Default = defaultWindowStart(t, full.pointing_error_deg);
  const card = el('div', { class: 'card wide', id: 'spectrum-card' });
  if (D.spectrum) {
    card.appendChild(el('p', { class: 'note', id: 'spectrum-full-rate',
      text: `Full-rate samples of the last ${t.length} records (t = ${fmt(t[0])} to ${fmt(tEnd)} s); ` +
            'the time plots show this run reduced to the minimum and maximum of each bucket' +
            (D.decimation && D.decimation.bucket_rows ? ` of ${D.decimation.bucket_rows} records` : '') +
            '. The whole run at full rate is in results.h5.' }));
  }
  const from = el('input', { type: 'number', step: 'any', value: String(Number(t0Default.toPrecision(6))), id: 'spec-from' });
  const to = el('input', { type: 'number', step: 'any', value: String(Number(tEnd.toPrecision(6))), id: 'spec-to' });
  const go = el('button', { text: 'recompute' });
  card.appendChild(el('div', { class: 'controls' },
    el('label', null, 'window from t = ', from, ' s'), el('label', null, ' to ', to, ' s '), go));
  const holder = el('div', { class: 'plot' });
  card.appendChild(holder);
  const info = el('p', { class: 'note' });
  card.appendChild(info);
  const warn = el('p', { class: 'warning', id: 'spectrum-alias-warning', hidden: '' });
  card.insertBefore(warn, holder);
  root.appendChild(card);
  let u = null;
  const compute = () => {
    const a = Number(from.value);
    const b = Number(to.value);
    const res = ys.map((y) => {
      const w = uniformWindow(t, y, Number.isFinite(a) ? a : -Infinity, Number.isFinite(b) ? b : Infinity);
      return { w, s: welch(w.y, w.dt) };
    });
    // mean wheel speed over the window: the imbalance lines sit at |rpm|/60 Hz
    const wheelLines = [];
    const tw = D.t;  // wheel speeds: from the (possibly reduced) series
    for (const { index, key } of indexedKeys(series, 'wheel_speed_rpm_')) {
      const w = alignSeries(series[key], tw.length);
      let sum = 0;
      let cnt = 0;
      for (let i = 0; i < tw.length; i++) {
        if (w[i] !== null && tw[i] >= (Number.isFinite(a) ? a : -Infinity) && tw[i] <= (Number.isFinite(b) ? b : Infinity)) { sum += Math.abs(w[i]); cnt++; }
      }
      if (cnt) wheelLines.push({ name: deviceName(key, D.geometry) || 'w' + index, f: sum / cnt / 60 });
    }
    // above the Nyquist frequency a wheel's line shows folded (aliased) back
    const fsWin = ok0(res) ? 1 / ok0(res).w.dt : NaN;
    aliasWarning(warn, wheelLines, fsWin, D.meta);
    for (const wl of wheelLines) {
      if (Number.isFinite(fsWin) && wl.f > fsWin / 2) {
        wl.f = Math.abs(wl.f - fsWin * Math.round(wl.f / fsWin));
        wl.name += ' (alias)';
        wl.alias = true;
      }
    }
    if (u) { u.destroy(); u = null; }
    const ok = res.filter((r) => r.s);
    if (!ok.length) {
      holder.textContent = 'Too few samples in the window for a spectrum (at least 16 needed).';
      info.textContent = '';
      return;
    }
    holder.textContent = '';
    const f = Array.from(ok[0].s.f).slice(1);
    const data = [f, ...res.map((r) => (r.s ? Array.from(r.s.asd).slice(1).map((v) => (v > 0 ? v : null)) : f.map(() => null)))];
    u = new uPlot({
      width: Math.max(280, Math.floor(card.getBoundingClientRect().width) - 24),
      height: 260,
      scales: { x: { time: false, distr: 3 }, y: { distr: 3 } },
      axes: [{ label: 'frequency [Hz]', size: 40 }, { label: `ASD [${unit}/\u221aHz]`, size: 70, values: (s, ticks) => ticks.map(fmtTick) }],
      series: [
        { label: 'f [Hz]', value: (s, v) => (v == null ? '\u2013' : fmtTick(v)) },
        ...keys.map((k, i) => ({ label: '\u03c9_' + k.slice(-1), stroke: AXIS_COLORS['xyz'.indexOf(k.slice(-1))], width: 1.25, value: (s, v) => (v == null ? '\u2013' : fmtTick(v)) })),
      ],
      hooks: { draw: [(self) => {
        const { ctx, bbox } = self;
        ctx.save();
        ctx.strokeStyle = 'rgba(120, 120, 140, 0.7)';
        ctx.fillStyle = 'rgba(80, 80, 100, 0.9)';
        ctx.font = `${Math.round(10 * (window.devicePixelRatio || 1))}px sans-serif`;
        ctx.setLineDash([3, 3]);
        const dpr = window.devicePixelRatio || 1;
        wheelLines.forEach((wl, i) => {
          if (!(wl.f >= self.scales.x.min && wl.f <= self.scales.x.max)) return;
          const x = Math.round(self.valToPos(wl.f, 'x', true));
          ctx.beginPath();
          ctx.moveTo(x, bbox.top);
          ctx.lineTo(x, bbox.top + bbox.height);
          ctx.stroke();
          ctx.fillText(wl.name, x + 3, bbox.top + (12 + 12 * (i % 4)) * dpr); // staggered: lines can be close
        });
        ctx.restore();
      }] },
    }, data, holder);
    const r0 = ok[0];
    const aliased = wheelLines.some((wl) => wl.alias);
    info.textContent = (wheelLines.length ? 'Dashed lines: mean wheel speeds over the window (|rpm|/60 Hz, where static and dynamic imbalance act)' +
      (aliased ? '; wheels faster than the Nyquist frequency are marked where they fold to (alias): record the rates faster to resolve them' : '') + '. ' : '') + `Default window: from the end of the last excursion above ${SETTLED_DEG} deg pointing error (the hold). Welch: Hann window, ${r0.s.nseg}-sample segments, 50 % overlap, ${r0.s.segments} averages, ` +
      `fs = ${fmt(1 / r0.w.dt)} Hz. RMS over the window (mean removed): ` +
      res.map((r, i) => `\u03c9_${keys[i].slice(-1)} ${r.w.y.length ? fmt(rms(r.w.y)) : '\u2013'} ${unit}`).join(', ') + '.';
  };
  go.addEventListener('click', compute);
  compute();
}

// The warning above the spectrum when the recording rate cannot show the
// wheel lines: which wheels fold, where to, and the scenario key that fixes
// it (rates.record_divisor, or rates.dt when even every tick is too slow).
function aliasWarning(warn, wheelLines, fs, meta) {
  const r = Number.isFinite(fs) ? wheelAliasing(wheelLines, fs) : { aliased: [] };
  warn.hidden = !r.aliased.length;
  if (!r.aliased.length) { warn.textContent = ''; return; }
  const dt = typeof meta.dt === 'number' && meta.dt > 0 ? meta.dt : NaN;
  const div = recordDivisorFor(r.fMax, dt);
  const list = r.aliased.map((a) => `${a.name} at ${fmt(a.f)} Hz (${fmt(a.f * 60)} rpm) shows at ${fmt(a.folded)} Hz`).join('; ');
  const need = `at least ${fmt(2 * r.fMax)} samples/s, better ${fmt(2.5 * r.fMax)}`;
  let fix;
  if (div > 0) fix = `set rates.record_divisor: ${div} in the scenario (or --set rates.record_divisor=${div}): one record every ${fmt(div * dt)} s, ${fmt(1 / (div * dt))} samples/s`;
  else if (Number.isFinite(dt)) fix = `every tick (rates.dt = ${fmt(dt)} s, record_divisor 1) is still too slow: make rates.dt at most ${fmt(1 / (2.5 * r.fMax))} s with rates.record_divisor: 1`;
  else fix = 'record the body rates faster (rates.record_divisor, rates.dt)';
  warn.textContent = `Aliased wheel lines: the body rates are recorded at ${fmt(fs)} samples/s (Nyquist frequency ${fmt(fs / 2)} Hz), ` +
    `too slow for the wheel speeds: ${list}. The marked lines are where they fold to, not where the jitter is. ` +
    `To resolve wheel jitter up to ${fmt(r.fMax)} Hz, record ${need}: ${fix}.`;
}
