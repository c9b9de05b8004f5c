// Colour maps as 256-entry RGB lookup tables.

function lut(stops) {
  const out = new Uint8ClampedArray(256 * 3);
  for (let k = 0; k < 256; k++) {
    const t = k / 255;
    let s = 0;
    while (s < stops.length - 2 && t > stops[s + 1][0]) s++;
    const [t0, c0] = stops[s];
    const [t1, c1] = stops[s + 1];
    const u = Math.min(1, Math.max(0, (t - t0) / (t1 - t0)));
    for (let c = 0; c < 3; c++) out[3 * k + c] = Math.round(c0[c] + u * (c1[c] - c0[c]));
  }
  return out;
}

/** Viridis (perceptually uniform, colour-blind safe), sampled from matplotlib. */
export const VIRIDIS = lut([
  [0.0, [68, 1, 84]],
  [0.125, [72, 40, 120]],
  [0.25, [62, 73, 137]],
  [0.375, [49, 104, 142]],
  [0.5, [38, 130, 142]],
  [0.625, [31, 158, 137]],
  [0.75, [53, 183, 121]],
  [0.875, [110, 206, 88]],
  [1.0, [253, 231, 37]],
]);

/** Diverging blue (better, below the datum) to red (worse), white at zero. */
export const DIVERGING = lut([
  [0.0, [33, 102, 172]],
  [0.25, [103, 169, 207]],
  [0.5, [247, 247, 247]],
  [0.75, [239, 138, 98]],
  [1.0, [178, 24, 43]],
]);

/** Writes the colour of `t` in [0, 1] into `rgba` at byte offset `o`. */
export function paint(table, t, rgba, o) {
  const k = Number.isFinite(t) ? Math.round(Math.min(1, Math.max(0, t)) * 255) : -1;
  if (k < 0) {
    rgba[o] = rgba[o + 1] = rgba[o + 2] = 200;
  } else {
    rgba[o] = table[3 * k];
    rgba[o + 1] = table[3 * k + 1];
    rgba[o + 2] = table[3 * k + 2];
  }
  rgba[o + 3] = 255;
}
