// Colour maps as 256-entry RGB lookup tables, taken from the core (`colourTable`,
// crate/src/chart/colour.rs), so a map image on screen has the colours of the core's
// colour bar and of the exported charts.

/** The colour maps the page uses: absolute values (two palettes) and % changes. */
const TABLES = ['viridis', 'cividis', 'diverging'];

/** `{viridis, cividis, diverging}`: each a Uint8Array of 768 bytes, from `colourTable(name)`. */
export function loadTables(colourTable) {
  return Object.fromEntries(TABLES.map((name) => [name, colourTable(name)]));
}

/** The index in `pixels(table)` of light grey. */
export const GREY = 256;

/** `pixels(table)` by table: each is built once. */
const PIXELS = new WeakMap();

/**
 * The RGBA pixels of a colour table, one 32-bit word each (the bytes r, g, b, 255 in
 * memory order, so a word copied into an `ImageData`'s buffer is that colour on any
 * byte order): 256 colours, then light grey at `GREY` for a value that is not finite.
 * A map image is written a word per cell instead of four bytes through a call.
 */
export function pixels(table) {
  let words = PIXELS.get(table);
  if (!words) {
    words = new Uint32Array(257);
    const bytes = new Uint8Array(words.buffer);
    for (let k = 0; k < 256; k++) bytes.set([table[3 * k], table[3 * k + 1], table[3 * k + 2], 255], 4 * k);
    bytes.set([200, 200, 200, 255], 4 * GREY);
    PIXELS.set(table, words);
  }
  return words;
}

/** The index in `pixels(table)` of `t` in [0, 1] (clamped; `GREY` when not finite). */
export function colourIndex(t) {
  return Number.isFinite(t) ? Math.round(Math.min(1, Math.max(0, t)) * 255) : GREY;
}
