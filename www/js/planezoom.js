// The objective plane's axes (issue #30): fitted to what it shows, the fronts (STM,
// NSGA-II, the adaptive loop's, the HiFi's), the pick and its re-check, with room to the
// upper right for the feasible designs as far as there are any; the datum and the design
// are not in the fit (js/plane.js pins them to the edge with an arrow when outside).
// Zoom and pan are fractions of the fitted axes, `[x0, x1, y0, y1]` (`[0, 1, 0, 1]` the
// fitted axes themselves), so a link's `pz=` means the same on its own scenario and in
// both axis modes. Plain functions; js/plane.js binds them to the wheel, drag and keys.

/** The most and least a zoom may span, as a fraction of the fitted axes. */
const MIN_SPAN = 0.002;
const MAX_SPAN = 20;

/** `[lo, hi]` of the finite numbers `vs` (`[Infinity, -Infinity]` for none). */
export function extent(vs) {
  let lo = Infinity;
  let hi = -Infinity;
  for (const v of vs) {
    if (!Number.isFinite(v)) continue;
    if (v < lo) lo = v;
    if (v > hi) hi = v;
  }
  return [lo, hi];
}

/**
 * One axis fitted to the front values `fv` and the feasible designs' values `cv`: 6 % of
 * the front's span below it, and above it up to 45 % more, as far as feasible designs go.
 */
function fitAxis(fv, cv) {
  let [lo, hi] = extent(fv);
  if (!(hi >= lo)) [lo, hi] = extent(cv);
  if (!(hi >= lo)) return [0, 1];
  const d = hi - lo || Math.abs(lo) * 0.05 || 1;
  const [, chi] = extent(cv);
  const top = Number.isFinite(chi) ? Math.min(hi + 0.45 * d, Math.max(hi + 0.06 * d, chi + 0.02 * d)) : hi + 0.06 * d;
  return [lo - 0.06 * d, top];
}

/**
 * The fitted axes `{x: [lo, hi], y: [lo, hi]}` of the plane's points: `fronts` (`[[x, y]]`
 * of every front, the pick and its re-check) and `cloud` (`[[x, y]]` of the feasible designs).
 */
export function fitAxes(fronts, cloud) {
  return {
    x: fitAxis(fronts.map((p) => p[0]), cloud.map((p) => p[0])),
    y: fitAxis(fronts.map((p) => p[1]), cloud.map((p) => p[1])),
  };
}

/** The axes shown: the fitted axes `fit` under zoom `z` (`[x0, x1, y0, y1]` fractions, or null). */
export function zoomedAxes(fit, z) {
  if (!z) return fit;
  const at = ([lo, hi], a, b) => [lo + a * (hi - lo), lo + b * (hi - lo)];
  return { x: at(fit.x, z[0], z[1]), y: at(fit.y, z[2], z[3]) };
}

/** A zoom kept within MIN_SPAN..MAX_SPAN of the fitted axes each way, or null for the fitted axes. */
function bounded(z) {
  const out = [...z];
  for (const k of [0, 2]) {
    const c = (out[k] + out[k + 1]) / 2;
    const h = Math.min(MAX_SPAN, Math.max(MIN_SPAN, out[k + 1] - out[k])) / 2;
    [out[k], out[k + 1]] = [c - h, c + h];
  }
  const r = out.map((v) => Math.round(v * 1e4) / 1e4);
  return r[0] === 0 && r[1] === 1 && r[2] === 0 && r[3] === 1 ? null : r;
}

/**
 * Zoom `z` (null: the fitted axes) scaled by `f` (< 1 zooms in) about the point at
 * fractions `(u, v)` of the axes shown (0..1 from the lower left), which stays put.
 */
export function zoomAbout(z, f, u = 0.5, v = 0.5) {
  const [x0, x1, y0, y1] = z || [0, 1, 0, 1];
  const cx = x0 + u * (x1 - x0);
  const cy = y0 + v * (y1 - y0);
  return bounded([cx - (cx - x0) * f, cx + (x1 - cx) * f, cy - (cy - y0) * f, cy + (y1 - cy) * f]);
}

/** Zoom `z` moved by `(du, dv)` fractions of the axes shown (positive: the view moves right, up). */
export function panBy(z, du, dv) {
  const [x0, x1, y0, y1] = z || [0, 1, 0, 1];
  const dx = du * (x1 - x0);
  const dy = dv * (y1 - y0);
  return bounded([x0 + dx, x1 + dx, y0 + dy, y1 + dy]);
}

/** The zoom a key asks for (`+`/`=` in, `-` out, arrows pan a tenth, `0` the fitted axes), or undefined for another key. */
export function zoomForKey(z, key) {
  if (key === '+' || key === '=') return zoomAbout(z, 1 / 1.25);
  if (key === '-' || key === '_') return zoomAbout(z, 1.25);
  if (key === '0') return null;
  const pan = { ArrowLeft: [-0.1, 0], ArrowRight: [0.1, 0], ArrowUp: [0, 0.1], ArrowDown: [0, -0.1] }[key];
  return pan ? panBy(z, ...pan) : undefined;
}
