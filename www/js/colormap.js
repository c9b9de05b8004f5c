// Colour maps as 256-entry RGB lookup tables, taken from the core (`colourTable`,
// crate/src/chart/colour.rs), so a map image on screen has the colours of the core's
// colour bar and of the exported charts.

/** The colour maps the page uses: absolute values (two palettes) and % changes. */
const TABLES = ['viridis', 'cividis', 'diverging'];

/** `{viridis, cividis, diverging}`: each a Uint8Array of 768 bytes, from `colourTable(name)`. */
export function loadTables(colourTable) {
  return Object.fromEntries(TABLES.map((name) => [name, colourTable(name)]));
}

/** Writes the colour of `t` in [0, 1] into `rgba` at byte offset `o` (light grey when `t` is not finite). */
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
