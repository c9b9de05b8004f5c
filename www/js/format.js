// Number formatting and axis ticks shared by the readout and the maps.

/** `v` with `sig` significant digits, fixed notation, no digit grouping. */
export function fmt(v, sig = 4) {
  if (v === null || v === undefined || Number.isNaN(v)) return '–';
  if (!Number.isFinite(v)) return v > 0 ? '∞' : '−∞';
  if (v === 0) return '0';
  const mag = Math.floor(Math.log10(Math.abs(v)));
  const dec = Math.max(0, Math.min(12, sig - 1 - mag));
  return minus(v.toFixed(dec));
}

/** A value for an input box: up to `dec` decimals, trailing zeros dropped. */
export function fmtInput(v, dec = 3) {
  if (!Number.isFinite(v)) return '';
  return String(Number(v.toFixed(dec)));
}

/** A signed percentage change, e.g. "+3.2 %" or "−12.5 %". */
export function fmtPct(frac, dec = 1) {
  if (!Number.isFinite(frac)) return '–';
  const p = frac * 100;
  const s = Math.abs(p) < 0.5 * 10 ** -dec ? (0).toFixed(dec) : p.toFixed(dec);
  return (p > 0 && Number(s) !== 0 ? '+' : '') + minus(s) + ' %';
}

/** Typographic minus sign. */
function minus(s) {
  return s.replace(/^-/, '−');
}

/** Tick label: the shortest decimal that shows the step. */
export function fmtTick(v, step) {
  let dec = 0;
  while (dec < 10 && Math.abs(Math.round(step * 10 ** dec) - step * 10 ** dec) > 1e-6) dec++;
  return minus((Math.abs(v) < step * 1e-9 ? 0 : v).toFixed(dec));
}

/** A small positive quantity such as a relative error, e.g. "3e-12" or "0.0042". */
export function fmtSmall(v) {
  if (!Number.isFinite(v)) return '–';
  if (v === 0) return '0';
  if (Math.abs(v) >= 1e-3) return fmt(v, 2);
  const [m, e] = v.toExponential(0).split('e');
  return `${m}e${e.replace('+', '')}`;
}

/** About `n` "nice" ticks (1, 2, 2.5 or 5 times a power of ten) covering [lo, hi]. */
export function niceTicks(lo, hi, n = 5) {
  if (!(Number.isFinite(lo) && Number.isFinite(hi)) || hi <= lo) return { ticks: [lo], step: 1 };
  const raw = (hi - lo) / Math.max(1, n);
  const p = 10 ** Math.floor(Math.log10(raw));
  const m = raw / p;
  const step = (m < 1.5 ? 1 : m < 2.25 ? 2 : m < 3.5 ? 2.5 : m < 7.5 ? 5 : 10) * p;
  const ticks = [];
  const first = Math.ceil(lo / step - 1e-9);
  for (let k = first; k * step <= hi + step * 1e-9; k++) ticks.push(k * step);
  return { ticks, step };
}

/**
 * Parses what a user typed into a number box. Accepts a decimal comma. Returns
 * `{value}` or `{error}` with a message for the field.
 */
export function parseNumber(text) {
  const t = String(text ?? '').trim();
  if (t === '') return { error: 'enter a number' };
  const norm = /^[+-]?\d+,\d*$/.test(t) ? t.replace(',', '.') : t;
  if (!/^[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?$/.test(norm)) return { error: `'${t}' is not a number` };
  const v = Number(norm);
  if (!Number.isFinite(v)) return { error: `'${t}' is not a finite number` };
  return { value: v };
}
