// Keyboard steps of the design: the sliders and a focused map move Ks and Cs on a grid
// through the datum design, so a step from the datum lands on round offsets of it and the
// datum itself is always one of the positions.

/** One step (arrow key) and one coarse step (Page Up / Down, Shift + arrow): N/m, N s/m. */
export const STEPS = {
  ks: { fine: 100, coarse: 1000 },
  cs: { fine: 10, coarse: 100 },
};

/**
 * `value` moved by `n` steps of `step` on the grid through `datum` (an off-grid value
 * goes to the next grid point that way first), within `[lo, hi]`.
 */
function stepValue(value, datum, step, n, lo, hi) {
  const u = (value - datum) / step;
  const eps = 1e-9;
  const k = n > 0 ? Math.floor(u + eps) + n : Math.ceil(u - eps) + n;
  const v = Math.round((datum + k * step) * 1e6) / 1e6;
  return Math.min(hi, Math.max(lo, v));
}

/**
 * The design after key `ev` (a KeyboardEvent) on a design control, or null when the key
 * is not one of them: arrows one step (left/right Ks, up/down Cs; on a one-axis slider
 * `axis` both move that axis), Page Up / Down and Shift + arrows coarse, Home / End the
 * box ends. `design`, `datum`: `{ks, cs}`; `box`: the design box (N/m, N s/m).
 */
export function keyStep(ev, design, datum, box, axis = null) {
  const coarse = ev.shiftKey ? 'coarse' : 'fine';
  const moves = {
    ArrowRight: [axis || 'ks', 1, coarse],
    ArrowLeft: [axis || 'ks', -1, coarse],
    ArrowUp: [axis || 'cs', 1, coarse],
    ArrowDown: [axis || 'cs', -1, coarse],
    PageUp: [axis || 'cs', 1, 'coarse'],
    PageDown: [axis || 'cs', -1, 'coarse'],
  };
  const range = { ks: [box.ks_min, box.ks_max], cs: [box.cs_min, box.cs_max] };
  if (axis && (ev.key === 'Home' || ev.key === 'End')) {
    return { ...design, [axis]: range[axis][ev.key === 'Home' ? 0 : 1] };
  }
  const m = moves[ev.key];
  if (!m) return null;
  const [k, n, size] = m;
  const [lo, hi] = range[k];
  return { ...design, [k]: stepValue(design[k], datum[k], STEPS[k][size], n, lo, hi) };
}
