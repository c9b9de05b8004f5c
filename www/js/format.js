// Number formatting shared by the readout, the panels and the number inputs (chart ticks
// are the core's: plotters draws every axis).

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
/**
 * The road of state `s` in words: "class B at 20 m/s, correlated tracks", or on a measured
 * road (the road menu's, `roadProfile` "<file>#<hash>") "the measured road slab.csv at 20 m/s".
 */
export function roadWords(s) {
  if (s.roadProfile) return `the measured road ${s.roadProfile.replace(/#[0-9a-f]+$/, '')} at ${fmtInput(s.speed, 3)} m/s`;
  return `class ${s.class} at ${fmtInput(s.speed, 3)} m/s, ${s.tracks} tracks`;
}

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

/** A small positive quantity such as a relative error, e.g. "3e-12" or "0.0042". */
export function fmtSmall(v) {
  if (!Number.isFinite(v)) return '–';
  if (v === 0) return '0';
  if (Math.abs(v) >= 1e-3) return fmt(v, 2);
  const [m, e] = v.toExponential(0).split('e');
  return `${m}e${e.replace('+', '')}`;
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

/**
 * A core message in the page's units: spring rates in N/m as kN/m and damper rates in
 * N s/m as kNs/m (numbers and ranges such as `1000..2e+6 N/m`), as `ridelab::domain::page_units`.
 */
export function inPageUnits(text) {
  const kilo = (nums) => nums.split('..').map((n) => String(+(Number(n) / 1000).toPrecision(6))).join('..');
  return String(text)
    .replace(/(-?[\d.]+(?:e[+-]?\d+)?(?:\.\.-?[\d.]+(?:e[+-]?\d+)?)?) N s\/m/g, (m, n) => `${kilo(n)} kNs/m`)
    .replace(/(-?[\d.]+(?:e[+-]?\d+)?(?:\.\.-?[\d.]+(?:e[+-]?\d+)?)?) N\/m/g, (m, n) => `${kilo(n)} kN/m`);
}
