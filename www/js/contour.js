// Marching squares over a grid of cell-centre values.

/**
 * Line segments where the grid crosses `level`: a flat array `[x0, y0, x1, y1, ...]`
 * in grid coordinates (cell centre i at x = i, row j at y = j). `get(i, j)` reads a value.
 */
export function contourSegments(get, nx, ny, level) {
  const seg = [];
  const lerp = (a, b) => (level - a) / (b - a);
  for (let j = 0; j < ny - 1; j++) {
    for (let i = 0; i < nx - 1; i++) {
      const a = get(i, j); // bottom-left
      const b = get(i + 1, j); // bottom-right
      const c = get(i + 1, j + 1); // top-right
      const d = get(i, j + 1); // top-left
      const code = (a > level ? 1 : 0) | (b > level ? 2 : 0) | (c > level ? 4 : 0) | (d > level ? 8 : 0);
      if (code === 0 || code === 15) continue;
      // Edge crossing points: bottom, right, top, left.
      const B = () => [i + lerp(a, b), j];
      const R = () => [i + 1, j + lerp(b, c)];
      const T = () => [i + lerp(d, c), j + 1];
      const L = () => [i, j + lerp(a, d)];
      const push = (p, q) => seg.push(p[0], p[1], q[0], q[1]);
      switch (code) {
        case 1: case 14: push(L(), B()); break;
        case 2: case 13: push(B(), R()); break;
        case 3: case 12: push(L(), R()); break;
        case 4: case 11: push(R(), T()); break;
        case 6: case 9: push(B(), T()); break;
        case 7: case 8: push(L(), T()); break;
        case 5: case 10: {
          const centre = (a + b + c + d) / 4 > level;
          if ((code === 5) === centre) {
            push(L(), T());
            push(B(), R());
          } else {
            push(L(), B());
            push(R(), T());
          }
          break;
        }
        default: break;
      }
    }
  }
  return seg;
}
