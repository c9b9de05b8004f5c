// The class front's markers (issue #30, js/classfront.js): each student's design as a
// magenta disc with a white rim and its rank beside it in bold type on a white halo, on
// the three maps (at Ks, Cs) and on the objective plane (at its criteria by the plane's
// model). Magenta is in neither colour map (viridis, cividis) nor the plane's series.

import { scenarioKey } from './store.js';

/** The class markers' fill. */
export const CLASS_COLOUR = '#d6008f';

/**
 * Paints `rows` (`[{rank, ...}]`, best first) on context `g` (CSS px): `at(row)` gives
 * `[x, y]` or null (not drawn); `r` the marker radius, `lw` the line-width factor, `fs`
 * the label's type size (px). The best ranks are painted last, so they stay on top.
 */
export function paintClass(g, rows, at, { r, lw, fs }) {
  if (!rows || !rows.length) return;
  const placed = [];
  for (const row of [...rows].reverse()) {
    const p = at(row);
    if (!p || !p.every(Number.isFinite)) continue;
    placed.push([row, p]);
    g.beginPath();
    g.arc(p[0], p[1], r, 0, 2 * Math.PI);
    g.fillStyle = CLASS_COLOUR;
    g.fill();
    g.lineWidth = 1.8 * lw;
    g.strokeStyle = '#fff';
    g.stroke();
  }
  // The labels after every disc, so no disc covers a label.
  g.save();
  g.font = `700 ${Math.round(fs)}px system-ui, sans-serif`;
  g.textBaseline = 'middle';
  g.lineJoin = 'round';
  for (const [row, p] of placed) {
    if (row.rank == null) continue;
    const text = String(row.rank);
    g.lineWidth = 3.5 * lw;
    g.strokeStyle = '#fff';
    g.strokeText(text, p[0] + r + 1.5, p[1]);
    g.fillStyle = '#000';
    g.fillText(text, p[0] + r + 1.5, p[1]);
  }
  g.restore();
}

/** The class's designs to mark (`[{rank, label, ks, cs, plane}]`), or null (none, or for another scenario). */
export function classMarks(st) {
  const cf = st.classFront;
  return cf && cf.key === scenarioKey(st.state) && cf.rows.length ? cf.rows : null;
}
