// Marching squares over a grid of cell-centre values.

// For each of the 16 corner codes (bit 0 bottom-left, 1 bottom-right, 2 top-right,
// 3 top-left above the level), the crossed edges to join, in pairs:
// 0 bottom, 1 right, 2 top, 3 left. The saddles 5 and 10 are resolved at run time.
const EDGES = [
  [], [3, 0], [0, 1], [3, 1], [1, 2], null, [0, 2], [3, 2],
  [3, 2], [0, 2], null, [1, 2], [3, 1], [0, 1], [3, 0], [],
];

/**
 * Line segments where the grid crosses `level`: a flat array `[x0, y0, x1, y1, ...]`
 * in grid coordinates (cell centre i at x = i, row j at y = j). The grid is
 * `v[offset + j nx + i]`.
 */
export function contourSegments(v, offset, nx, ny, level) {
  const seg = [];
  const px = [0, 0, 0, 0];
  const py = [0, 0, 0, 0];
  for (let j = 0; j < ny - 1; j++) {
    const row = offset + j * nx;
    for (let i = 0; i < nx - 1; i++) {
      const a = v[row + i]; // bottom-left
      const b = v[row + i + 1]; // bottom-right
      const c = v[row + nx + i + 1]; // top-right
      const d = v[row + nx + i]; // top-left
      const code = (a > level ? 1 : 0) | (b > level ? 2 : 0) | (c > level ? 4 : 0) | (d > level ? 8 : 0);
      if (code === 0 || code === 15) continue;
      // Crossing points on the four edges (only the crossed ones are used).
      px[0] = i + (level - a) / (b - a);
      py[0] = j;
      px[1] = i + 1;
      py[1] = j + (level - b) / (c - b);
      px[2] = i + (level - d) / (c - d);
      py[2] = j + 1;
      px[3] = i;
      py[3] = j + (level - a) / (d - a);
      let e = EDGES[code];
      if (e === null) {
        const centreHigh = (a + b + c + d) / 4 > level;
        // Code 5 (a, c high): a high centre joins them, cutting off b and d.
        e = (code === 5) === centreHigh ? [3, 2, 0, 1] : [3, 0, 1, 2];
      }
      for (let k = 0; k < e.length; k += 2) seg.push(px[e[k]], py[e[k]], px[e[k + 1]], py[e[k + 1]]);
    }
  }
  return seg;
}
