//! Contour lines of a field on a map grid by marching squares.
//!
//! A grid node is *above* the level when `f >= level`. Every cell edge whose two nodes
//! lie on different sides holds one contour vertex, placed by linear interpolation along
//! that edge: `t = (level - f0) / (f1 - f0)`, `x = x0 + t (x1 - x0)` (the other coordinate
//! is the grid line itself). A cell with two such edges gets one segment. A saddle cell
//! (four such edges, diagonal corners alike) is resolved by the cell-centre mean
//! `(f0 + f1 + f2 + f3) / 4`: when it is above the level the above corners are joined
//! through the centre, otherwise the below corners are; the rule only uses the cell's own
//! values, so neighbouring cells always agree on their shared edges. Segments are then
//! joined through their shared edges into polylines; a polyline that returns to its first
//! edge is closed (its last point repeats its first). Cells with a non-finite corner are
//! skipped, so a contour can end at them.
//!
//! Points are `[ks, cs]` in N/m and N s/m. Fields use the map layout: row-major, Cs rows,
//! Ks columns (see [`Grid::index`]).

use super::grid::Grid;
use crate::error::{Result, RideError};
use crate::math;
use serde::{Deserialize, Serialize};
use std::collections::HashMap;

/// One connected piece of a contour line.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Polyline {
    /// Vertices `[ks, cs]`, N/m and N s/m; a closed polyline repeats its first point last.
    pub points: Vec<[f64; 2]>,
    /// True when the line closes on itself (inside the grid).
    pub closed: bool,
}

/// All contour lines of one level.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Contour {
    /// The level, in the field's unit.
    pub level: f64,
    /// Its polylines (none when the level is outside the field's range).
    pub polylines: Vec<Polyline>,
}

/// Contour lines of `field` on `grid` at each of `levels`.
pub fn contours(grid: &Grid, field: &[f64], levels: &[f64]) -> Result<Vec<Contour>> {
    levels.iter().map(|&l| contour(grid, field, l)).collect()
}

/// Contour lines of `field` (map layout, `grid.len()` values) at `level`.
pub fn contour(grid: &Grid, field: &[f64], level: f64) -> Result<Contour> {
    grid.validate()?;
    if field.len() != grid.len() {
        return Err(RideError::field(
            "field",
            format!(
                "has {} values, the {} x {} grid needs {}",
                field.len(),
                grid.ks.n,
                grid.cs.n,
                grid.len()
            ),
        ));
    }
    if !level.is_finite() {
        return Err(RideError::field("level", "must be a finite number"));
    }
    let ms = Marching::new(grid, field, level);
    let segments = ms.segments();
    Ok(Contour {
        level,
        polylines: ms.join(&segments),
    })
}

/// At most `target` round levels strictly inside `(min, max)`: the multiples of the
/// smallest step `m 10^e`, `m` in {1, 2, 2.5, 5}, that gives no more than `target` of them.
/// Empty when the range is empty or not finite.
pub(crate) fn nice_levels(min: f64, max: f64, target: usize) -> Vec<f64> {
    if target == 0 || !(min.is_finite() && max.is_finite()) || max <= min {
        return Vec::new();
    }
    let e0 = math::log10((max - min) / target as f64).floor() as i32 - 1;
    for e in e0..e0 + 4 {
        for m in [1.0, 2.0, 2.5, 5.0] {
            // k m 10^e, rounded once (a negative power of ten is not exact).
            let value = |k: f64| {
                if e >= 0 {
                    k * m * 10f64.powi(e)
                } else {
                    k * m / 10f64.powi(-e)
                }
            };
            let mut k = (min / value(1.0)).floor();
            let mut out = Vec::new();
            loop {
                let v = value(k);
                if v >= max || out.len() > target {
                    break;
                }
                if v > min {
                    out.push(v);
                }
                k += 1.0;
            }
            if out.len() <= target {
                return out;
            }
        }
    }
    Vec::new()
}

/// [`nice_levels`] over the finite range of `field`.
pub fn auto_levels(field: &[f64], target: usize) -> Vec<f64> {
    let (lo, hi) = field
        .iter()
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(v), hi.max(v))
        });
    nice_levels(lo, hi, target)
}

/// Edge ids: horizontal edge `(i, j)-(i+1, j)` is `j (nk - 1) + i`; vertical edge
/// `(i, j)-(i, j+1)` is `nh + j nk + i` with `nh = (nk - 1) nc`.
struct Marching<'a> {
    field: &'a [f64],
    level: f64,
    xs: Vec<f64>,
    ys: Vec<f64>,
    nk: usize,
    nc: usize,
    nh: usize,
}

impl<'a> Marching<'a> {
    fn new(grid: &Grid, field: &'a [f64], level: f64) -> Self {
        let (nk, nc) = (grid.ks.n, grid.cs.n);
        Marching {
            field,
            level,
            xs: grid.ks.values(),
            ys: grid.cs.values(),
            nk,
            nc,
            nh: (nk - 1) * nc,
        }
    }

    fn f(&self, i: usize, j: usize) -> f64 {
        self.field[j * self.nk + i]
    }

    fn h(&self, i: usize, j: usize) -> usize {
        j * (self.nk - 1) + i
    }

    fn v(&self, i: usize, j: usize) -> usize {
        self.nh + j * self.nk + i
    }

    /// Segments as pairs of edge ids, cell by cell in row-major order.
    fn segments(&self) -> Vec<[usize; 2]> {
        let mut out = Vec::new();
        for j in 0..self.nc - 1 {
            for i in 0..self.nk - 1 {
                let f = [
                    self.f(i, j),
                    self.f(i + 1, j),
                    self.f(i + 1, j + 1),
                    self.f(i, j + 1),
                ];
                if f.iter().any(|v| !v.is_finite()) {
                    continue;
                }
                let a = f.map(|v| v >= self.level);
                // Edges: 0 bottom (c0-c1), 1 right (c1-c2), 2 top (c3-c2), 3 left (c0-c3).
                let ids = [
                    self.h(i, j),
                    self.v(i + 1, j),
                    self.h(i, j + 1),
                    self.v(i, j),
                ];
                let cut = [a[0] != a[1], a[1] != a[2], a[3] != a[2], a[0] != a[3]];
                let crossing: Vec<usize> = (0..4).filter(|&e| cut[e]).collect();
                match crossing.len() {
                    2 => out.push([ids[crossing[0]], ids[crossing[1]]]),
                    4 => {
                        let centre = (f[0] + f[1] + f[2] + f[3]) / 4.0 >= self.level;
                        if centre == a[0] {
                            // c0 and c2 joined through the centre: cut off c1 and c3.
                            out.push([ids[0], ids[1]]);
                            out.push([ids[2], ids[3]]);
                        } else {
                            // c1 and c3 joined: cut off c0 and c2.
                            out.push([ids[3], ids[0]]);
                            out.push([ids[1], ids[2]]);
                        }
                    }
                    _ => {}
                }
            }
        }
        out
    }

    /// The contour vertex on edge `id`, `[ks, cs]`.
    fn point(&self, id: usize) -> [f64; 2] {
        let (i0, j0, i1, j1) = if id < self.nh {
            let (i, j) = (id % (self.nk - 1), id / (self.nk - 1));
            (i, j, i + 1, j)
        } else {
            let k = id - self.nh;
            let (i, j) = (k % self.nk, k / self.nk);
            (i, j, i, j + 1)
        };
        let (f0, f1) = (self.f(i0, j0), self.f(i1, j1));
        let t = (self.level - f0) / (f1 - f0);
        [
            self.xs[i0] + t * (self.xs[i1] - self.xs[i0]),
            self.ys[j0] + t * (self.ys[j1] - self.ys[j0]),
        ]
    }

    /// Joins segments through shared edges; open lines first (from their ends), then
    /// closed loops, each started at the first unused segment in cell order.
    fn join(&self, segments: &[[usize; 2]]) -> Vec<Polyline> {
        const NONE: usize = usize::MAX;
        let mut at: HashMap<usize, [usize; 2]> = HashMap::with_capacity(2 * segments.len());
        for (s, seg) in segments.iter().enumerate() {
            for &e in seg {
                let slot = at.entry(e).or_insert([NONE, NONE]);
                if slot[0] == NONE {
                    slot[0] = s;
                } else {
                    slot[1] = s;
                }
            }
        }
        let degree = |e: usize| at[&e].iter().filter(|&&s| s != NONE).count();
        let mut used = vec![false; segments.len()];
        let mut lines = Vec::new();
        let mut walk = |start: usize, from: usize, used: &mut Vec<bool>| {
            let mut edges = vec![from];
            let (mut seg, mut edge) = (start, from);
            loop {
                used[seg] = true;
                let next = if segments[seg][0] == edge {
                    segments[seg][1]
                } else {
                    segments[seg][0]
                };
                edges.push(next);
                let slots = at[&next];
                match slots.iter().find(|&&s| s != NONE && s != seg && !used[s]) {
                    Some(&s) => {
                        seg = s;
                        edge = next;
                    }
                    None => break,
                }
            }
            let closed = edges.len() > 2 && edges.first() == edges.last();
            let mut points: Vec<[f64; 2]> = Vec::with_capacity(edges.len());
            for &e in &edges {
                let p = self.point(e);
                if points.last() != Some(&p) {
                    points.push(p);
                }
            }
            if points.len() >= 2 {
                lines.push(Polyline { points, closed });
            }
        };
        for s in 0..segments.len() {
            if used[s] {
                continue;
            }
            if let Some(&end) = segments[s].iter().find(|&&e| degree(e) == 1) {
                walk(s, end, &mut used);
            }
        }
        for s in 0..segments.len() {
            if !used[s] {
                walk(s, segments[s][0], &mut used);
            }
        }
        lines
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn field_of(grid: &Grid, f: impl Fn(f64, f64) -> f64) -> Vec<f64> {
        (0..grid.len())
            .map(|k| {
                let (i, j) = grid.indices(k);
                let (x, y) = grid.point(i, j);
                f(x, y)
            })
            .collect()
    }

    /// Largest |linear interpolation of the field along the vertex's edge - level|; fails
    /// when a vertex is not on a grid edge.
    fn worst_on_edges(grid: &Grid, field: &[f64], c: &Contour) -> f64 {
        let (xs, ys) = (grid.ks.values(), grid.cs.values());
        let f = |i: usize, j: usize| field[grid.index(i, j)];
        let mut worst = 0.0f64;
        for line in &c.polylines {
            for &[x, y] in &line.points {
                let interp = if let Some(j) = ys.iter().position(|&v| v == y) {
                    let i = (0..xs.len() - 1)
                        .find(|&i| xs[i] <= x && x <= xs[i + 1])
                        .expect("x inside the grid");
                    let t = (x - xs[i]) / (xs[i + 1] - xs[i]);
                    f(i, j) + t * (f(i + 1, j) - f(i, j))
                } else if let Some(i) = xs.iter().position(|&v| v == x) {
                    let j = (0..ys.len() - 1)
                        .find(|&j| ys[j] <= y && y <= ys[j + 1])
                        .expect("y inside the grid");
                    let t = (y - ys[j]) / (ys[j + 1] - ys[j]);
                    f(i, j) + t * (f(i, j + 1) - f(i, j))
                } else {
                    panic!("vertex ({x}, {y}) is not on a grid line");
                };
                worst = worst.max((interp - c.level).abs());
            }
        }
        worst
    }

    fn on_boundary(grid: &Grid, p: [f64; 2]) -> bool {
        p[0] == grid.ks.min || p[0] == grid.ks.max || p[1] == grid.cs.min || p[1] == grid.cs.max
    }

    #[test]
    fn plane_contours_are_exact_straight_lines() {
        let grid = Grid::parse("10000:40000:31", "500:4000:29").unwrap();
        let plane = |ks: f64, cs: f64| ks / 1e4 + cs / 1e3;
        let field = field_of(&grid, plane);
        let levels = auto_levels(&field, 10);
        assert_eq!(levels, vec![2.0, 3.0, 4.0, 5.0, 6.0, 7.0]);
        let mut worst = 0.0f64;
        for c in contours(&grid, &field, &[1.51, 3.0, 4.37, 7.99])
            .unwrap()
            .into_iter()
            .chain(contours(&grid, &field, &levels).unwrap())
        {
            worst = worst.max(worst_on_edges(&grid, &field, &c));
            assert_eq!(c.polylines.len(), 1, "level {}", c.level);
            let line = &c.polylines[0];
            assert!(!line.closed);
            assert!(on_boundary(&grid, line.points[0]));
            assert!(on_boundary(&grid, *line.points.last().unwrap()));
            for &[x, y] in &line.points {
                // The field is linear: interpolation is exact up to rounding.
                assert!((plane(x, y) - c.level).abs() < 1e-12, "{x} {y} {}", c.level);
            }
        }
        assert!(worst < 1e-12, "{worst}");
        println!("plane: worst |interpolated - level| on edges {worst:e}");
        // Outside the range: nothing.
        assert!(contour(&grid, &field, 100.0).unwrap().polylines.is_empty());
    }

    #[test]
    fn circle_contour_is_closed_and_near_the_true_circle() {
        let grid = Grid::parse("10000:40000:61", "500:4000:51").unwrap();
        // Normalised coordinates u, v in [-1, 1]; f = radius.
        let uv = |ks: f64, cs: f64| ((ks - 25_000.0) / 15_000.0, (cs - 2_250.0) / 1_750.0);
        let r = |ks: f64, cs: f64| {
            let (u, v) = uv(ks, cs);
            u.hypot(v)
        };
        let field = field_of(&grid, r);
        let h = (2.0 / 60.0f64).max(2.0 / 50.0);
        for level in [0.3, 0.61, 0.9] {
            let c = contour(&grid, &field, level).unwrap();
            assert!(worst_on_edges(&grid, &field, &c) < 1e-12);
            assert_eq!(c.polylines.len(), 1, "level {level}");
            let line = &c.polylines[0];
            assert!(line.closed);
            assert_eq!(line.points.first(), line.points.last());
            let far = line
                .points
                .iter()
                .map(|p| (r(p[0], p[1]) - level).abs())
                .fold(0.0, f64::max);
            // Linear interpolation of a radius field: error far below one grid step.
            assert!(far < 0.05 * h, "level {level}: {far} vs h {h}");
            println!(
                "circle r = {level}: {} points, worst |r - level| {far:e} (grid step {h}), edge residual {:e}",
                line.points.len(),
                worst_on_edges(&grid, &field, &c)
            );
            // Goes all the way round.
            let turn: f64 = line
                .points
                .windows(2)
                .map(|w| {
                    let (a, b) = (uv(w[0][0], w[0][1]), uv(w[1][0], w[1][1]));
                    let d = b.1.atan2(b.0) - a.1.atan2(a.0);
                    (d + std::f64::consts::PI).rem_euclid(2.0 * std::f64::consts::PI)
                        - std::f64::consts::PI
                })
                .sum();
            assert!(
                (turn.abs() - 2.0 * std::f64::consts::PI).abs() < 1e-9,
                "{turn}"
            );
        }
        // A circle cut by the grid's edge: open, ends on the boundary.
        let c = contour(&grid, &field, 1.2).unwrap();
        assert_eq!(c.polylines.len(), 4);
        for line in &c.polylines {
            assert!(!line.closed);
            assert!(on_boundary(&grid, line.points[0]));
            assert!(on_boundary(&grid, *line.points.last().unwrap()));
        }
    }

    #[test]
    fn saddles_follow_the_cell_centre() {
        let grid = Grid::parse("1:2:2", "1:2:2").unwrap();
        // Corners c0 (1,1), c1 (2,1), c2 (2,2), c3 (1,2), stored row-major.
        let cut = |field: [f64; 4], level: f64| {
            let row_major = [field[0], field[1], field[3], field[2]];
            let c = contour(&grid, &row_major, level).unwrap();
            assert!(worst_on_edges(&grid, &row_major, &c) < 1e-12);
            let mut ends: Vec<[[f64; 2]; 2]> = c
                .polylines
                .iter()
                .map(|l| {
                    assert!(!l.closed);
                    let mut e = [l.points[0], l.points[1]];
                    e.sort_by(|a, b| a.partial_cmp(b).unwrap());
                    e
                })
                .collect();
            ends.sort_by(|a, b| a.partial_cmp(b).unwrap());
            ends
        };
        // Centre mean 0.5 >= 0.5: the high corners c0, c2 are joined; c1, c3 cut off.
        assert_eq!(
            cut([1.0, 0.0, 1.0, 0.0], 0.5),
            vec![[[1.0, 1.5], [1.5, 2.0]], [[1.5, 1.0], [2.0, 1.5]]]
        );
        // Centre mean 0.40625 < 0.5: the low corners c1, c3 are joined; c0, c2 cut off.
        assert_eq!(
            cut([1.0, 0.0, 0.625, 0.0], 0.5),
            vec![
                [[1.0, 1.5], [1.5, 1.0]],
                [[1.0 + 0.8, 2.0], [2.0, 1.0 + 0.8]]
            ]
        );
        // A checkerboard of saddles: polylines never share a vertex.
        let g = Grid::parse("1:6:6", "1:5:5").unwrap();
        let field: Vec<f64> = (0..g.len())
            .map(|k| {
                let (i, j) = g.indices(k);
                if (i + j) % 2 == 0 {
                    1.0
                } else {
                    -1.0
                }
            })
            .collect();
        let c = contour(&g, &field, 0.0).unwrap();
        // Closed lines repeat their first point last: count it once.
        let mut all: Vec<[f64; 2]> = c
            .polylines
            .iter()
            .flat_map(|l| l.points[..l.points.len() - usize::from(l.closed)].to_vec())
            .collect();
        let n = all.len();
        all.sort_by(|a, b| a.partial_cmp(b).unwrap());
        all.dedup();
        assert_eq!(all.len(), n);
        // Every crossing edge of the 6 x 5 grid is used once: 5*5 + 6*4 = 49 vertices.
        assert_eq!(n, 49);
    }

    #[test]
    fn nice_levels_are_round() {
        assert_eq!(
            nice_levels(0.13, 0.97, 8),
            vec![0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9]
        );
        assert_eq!(nice_levels(0.0, 1.0, 4), vec![0.2, 0.4, 0.6, 0.8]);
        assert_eq!(nice_levels(0.0, 1.0, 3), vec![0.25, 0.5, 0.75]);
        assert_eq!(
            nice_levels(312.0, 1480.0, 10),
            vec![400.0, 600.0, 800.0, 1000.0, 1200.0, 1400.0]
        );
        assert_eq!(
            nice_levels(0.0041, 0.0123, 5),
            vec![0.006, 0.008, 0.01, 0.012]
        );
        assert_eq!(nice_levels(-3.0, 3.0, 3), vec![-2.0, 0.0, 2.0]);
        assert!(nice_levels(1.0, 1.0, 5).is_empty());
        assert!(nice_levels(f64::NAN, 1.0, 5).is_empty());
        assert!(nice_levels(0.0, 1.0, 0).is_empty());
        for (lo, hi, n) in [(0.7, 2.9, 10), (1e-3, 9.9e-3, 7), (12.0, 5e4, 9)] {
            let l = nice_levels(lo, hi, n);
            assert!(!l.is_empty() && l.len() <= n, "{l:?}");
            assert!(l.windows(2).all(|w| w[0] < w[1]) && l[0] > lo && *l.last().unwrap() < hi);
        }
    }

    #[test]
    fn bad_inputs_name_the_field() {
        let grid = Grid::parse("1:2:2", "1:2:2").unwrap();
        let e = contour(&grid, &[1.0; 3], 0.5).unwrap_err().to_string();
        assert!(e.starts_with("field: has 3 values"), "{e}");
        let e = contour(&grid, &[1.0; 4], f64::NAN).unwrap_err().to_string();
        assert!(e.starts_with("level: "), "{e}");
        // Non-finite values: those cells are skipped.
        let c = contour(&grid, &[0.0, 1.0, f64::NAN, 1.0], 0.5).unwrap();
        assert!(c.polylines.is_empty());
    }
}
