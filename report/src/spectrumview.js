// Jitter spectrum card: Welch ASD of the body rates over a chosen window.
import uPlot from 'uplot';
import { alignSeries, isNumArray, el, fmt } from './data.js';
import { uniformWindow, welch, rms } from './spectrum.js';
import { AXIS_COLORS, rateDisplay, fmtTick } from './plots.js';

export function buildSpectrum(root, D) {
  const { series, units, t } = D;
  const keys = ['x', 'y', 'z'].map((a) => `omega_BN_B_${a}`).filter((k) => isNumArray(series[k]));
  if (!keys.length || t.length < 16) {
    root.appendChild(el('p', { class: 'absent', text: 'No body-rate series in this run: no spectrum.' }));
    return;
  }
  const [ys, unit] = rateDisplay(keys.map((k) => alignSeries(series[k], t.length)), typeof units[keys[0]] === 'string' ? units[keys[0]] : 'rad/s');
  const tEnd = t[t.length - 1];
  const t0Default = t[0] + 0.5 * (tEnd - t[0]);
  const card = el('div', { class: 'card wide', id: 'spectrum-card' });
  const from = el('input', { type: 'number', step: 'any', value: String(Number(t0Default.toPrecision(6))), id: 'spec-from' });
  const to = el('input', { type: 'number', step: 'any', value: String(Number(tEnd.toPrecision(6))), id: 'spec-to' });
  const go = el('button', { text: 'recompute' });
  card.appendChild(el('div', { class: 'controls' },
    el('label', null, 'window from t = ', from, ' s'), el('label', null, ' to ', to, ' s '), go));
  const holder = el('div', { class: 'plot' });
  card.appendChild(holder);
  const info = el('p', { class: 'note' });
  card.appendChild(info);
  root.appendChild(card);
  let u = null;
  const compute = () => {
    const a = Number(from.value);
    const b = Number(to.value);
    const res = ys.map((y) => {
      const w = uniformWindow(t, y, Number.isFinite(a) ? a : -Infinity, Number.isFinite(b) ? b : Infinity);
      return { w, s: welch(w.y, w.dt) };
    });
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
    }, data, holder);
    const r0 = ok[0];
    info.textContent = `Welch: Hann window, ${r0.s.nseg}-sample segments, 50 % overlap, ${r0.s.segments} averages, ` +
      `fs = ${fmt(1 / r0.w.dt)} Hz. RMS over the window (mean removed): ` +
      res.map((r, i) => `\u03c9_${keys[i].slice(-1)} ${r.w.y.length ? fmt(rms(r.w.y)) : '\u2013'} ${unit}`).join(', ') + '.';
  };
  go.addEventListener('click', compute);
  compute();
}
