// What the time plots show, as pure functions (no DOM, no uPlot), tested on
// their own (test/report/js/plotmath.test.mjs): tick labels that never
// repeat, the offset a nearly constant series is plotted from, which series
// are constant (folded into one table), the names of enumerated values
// (FswStatus, modes, flags), one display unit per quantity, and the names the
// scenario gives its devices.

// Labels for the ticks of one axis, all distinct when the ticks are: the
// fewest decimals (or mantissa digits, in scientific notation for large and
// small magnitudes) that tell every tick from its neighbours and write its
// value (to a millionth of the step).  A tick within
// a millionth of a step of zero is "0".
export function tickLabels(ticks) {
  const v = ticks.map((x) => (typeof x === 'number' && Number.isFinite(x) ? x : null));
  const fin = v.filter((x) => x !== null);
  if (!fin.length) return v.map(() => '');
  const sorted = [...new Set(fin)].sort((a, b) => a - b);
  let step = Infinity;
  for (let i = 1; i < sorted.length; i++) step = Math.min(step, sorted[i] - sorted[i - 1]);
  const m = Math.max(...fin.map(Math.abs));
  if (!Number.isFinite(step)) step = m || 1;
  const zero = (x) => Math.abs(x) <= step * 1e-6;
  const sci = m >= 1e5 || m < 1e-3;
  const strip = (s) => s.replace(/(\.\d*?)0+(?=$|e)/, '$1').replace(/\.(?=$|e)/, '').replace(/^-(0(?:e.*)?)$/, '$1');
  const fmt = (x, d) => {
    if (x === null) return '';
    if (zero(x)) return '0';
    return strip(sci ? x.toExponential(d).replace('e+', 'e') : x.toFixed(d));
  };
  // first guess: as many digits as the step needs, then more until distinct
  let d = sci ? Math.max(0, Math.ceil(Math.log10(m / step) - 1e-9)) : Math.max(0, -Math.floor(Math.log10(step) + 1e-9));
  for (; d <= (sci ? 16 : 20); d++) {
    const labels = v.map((x) => fmt(x, d));
    const seen = new Map();
    let ok = true;
    v.forEach((x, i) => {
      if (x === null) return;
      const prev = seen.get(labels[i]);
      if (prev !== undefined && prev !== x) ok = false;
      // and each label is the tick's value (0.25 is not "0.3")
      if (!(Math.abs(Number(labels[i]) - x) <= 1e-6 * step)) ok = false;
      seen.set(labels[i], x);
    });
    if (ok) return labels;
  }
  return v.map((x) => (x === null ? '' : String(x)));
}

// A series whose variation is small against its value (span below 1e-3 of
// its magnitude) is plotted as the difference from a round offset, so the
// axis reads "+2e-9" and the title the offset: a conserved quantity shows
// the size of its variation instead of a line across the whole plot.
// Returns the offset, or 0 when the series reads well as it is (or is constant).
export function plotOffset(min, max) {
  if (!Number.isFinite(min) || !Number.isFinite(max)) return 0;
  const mid = 0.5 * (min + max);
  const span = max - min;
  // a constant series reads as it is (a flat line at its value)
  if (mid === 0 || span === 0 || !(span < 1e-3 * Math.abs(mid))) return 0;
  const k = Math.floor(Math.log10(span)) + 1; // the offset keeps the digits above the span
  const p = Math.pow(10, k);
  const off = Math.round(mid / p) * p;
  return Number(off.toPrecision(Math.min(17, Math.max(1, Math.ceil(Math.log10(Math.abs(off) / p)) + 1))));
}

// The value of a constant series: every finite sample equal, or spread by
// at most 1e-12 of their magnitude (rounding); null when it varies or has
// no finite sample.  { value, spread }.
export function constantValue(y) {
  let lo = Infinity;
  let hi = -Infinity;
  let n = 0;
  for (const x of y) {
    if (typeof x !== 'number' || !Number.isFinite(x)) continue;
    n++;
    if (x < lo) lo = x;
    if (x > hi) hi = x;
  }
  if (!n) return null;
  const spread = hi - lo;
  if (spread > 1e-12 * Math.max(Math.abs(lo), Math.abs(hi))) return null;
  return { value: spread === 0 ? lo : 0.5 * (lo + hi), spread };
}

// FswStatus (fsw_c/include/fsw/fsw_status.h): every stage and the cycle.
export const FSW_STATUS_NAMES = {
  0: 'FSW_OK', 1: 'FSW_W_SINGULAR', 2: 'FSW_W_SAT', 3: 'FSW_W_RATE', '-1': 'FSW_E_NULL_ARG', '-2': 'FSW_E_CONFIG',
  '-3': 'FSW_E_CAPACITY', '-4': 'FSW_E_SINGULAR', '-5': 'FSW_E_BAD_INPUT', '-6': 'FSW_E_TIME', '-7': 'FSW_E_UNSUPPORTED',
  '-8': 'FSW_E_NOT_INIT',
};
const MODE_NAMES = { 0: 'sun-safe', 1: 'inertial', 2: 'detumble', 3: 'nadir' }; // FswAcsMode
const POLICY_NAMES = { 0: 'none', 1: 'thrusters', 2: 'magnetorquers' };    // FswAcsMomentumPolicy
const PHASE_NAMES = { 0: 'idle', 1: 'pulse', 2: 'coast' };                  // thr_momentum phase
const FLAG_NAMES = { 0: 'no', 1: 'yes' };

// The enumeration a recorded series holds, by its name; null for a number.
export function enumOf(key) {
  if (key === 'fsw_status' || key.startsWith('fsw_stage_')) return FSW_STATUS_NAMES;
  if (key === 'fsw_mode') return MODE_NAMES;
  if (key === 'fsw_policy') return POLICY_NAMES;
  if (key === 'fsw_dump_phase') return PHASE_NAMES;
  if (/(^|_)valid$/.test(key) || /^fsw_rw_(failed|latched)_\d+$/.test(key) || ['fsw_safe_output', 'eclipse', 'fsw_detumbled'].includes(key)) {
    return FLAG_NAMES;
  }
  return null;
}

// "FSW_W_SAT (2)" for an enumerated series' value, "" for a plain number.
export function enumLabel(key, value) {
  const names = enumOf(key);
  if (!names || !Number.isInteger(value)) return '';
  const name = names[value];
  return name === undefined ? `unknown (${value})` : `${name} (${value})`;
}

// One display unit per quantity across the page: the harness's spellings
// ("N*m", "kg*m^2/s", "N*m*s") become one ("N m", "N m s"), angular rates are
// shown in deg/s (as the body rates and the spectrum are), "-" is no unit.
// Returns { unit, scale }: display value = scale * recorded value.
export function displayUnit(unit) {
  if (typeof unit !== 'string') return { unit: '', scale: 1 };
  const u = unit.trim().replace(/\s*\*\s*/g, ' ').replace(/\s+/g, ' ');
  if (u === '-' || u === '') return { unit: '', scale: 1 };
  if (/^rad ?\/ ?s$/i.test(u)) return { unit: 'deg/s', scale: 180 / Math.PI };
  if (/^(N m|Nm)$/.test(u)) return { unit: 'N m', scale: 1 };
  if (/^(N m s|Nms|kg m\^2 ?\/ ?s)$/.test(u)) return { unit: 'N m s', scale: 1 };
  return { unit: u, scale: 1 };
}

// The name the scenario gives device `index` of a series' family, from
// geometry (wheel_names, thrusters[].name, magnetorquer_names); null if none.
export function deviceName(key, geometry) {
  const g = geometry && typeof geometry === 'object' ? geometry : {};
  const m = /^(.*?)_?(\d+)$/.exec(key);
  if (!m) return null;
  const stem = m[1];
  const i = Number(m[2]);
  const pick = (a) => (Array.isArray(a) && typeof a[i] === 'string' && a[i] ? a[i] : null);
  if (/thruster/.test(stem)) return pick((Array.isArray(g.thrusters) ? g.thrusters : []).map((t) => (t && t.name) || null));
  if (/wheel|(^|_)rw(_|$)/.test(stem)) return pick(g.wheel_names);
  if (/mtq/.test(stem)) return pick(g.magnetorquer_names);
  return null;
}
