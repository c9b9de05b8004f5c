//! STM, the space transformation method: map a dense grid of a 2-variable design
//! space into the objective plane, keep the feasible non-dominated points, then refine
//! them locally so the front follows the true one instead of the grid's staircase.
//!
//! Refinement works on a lattice `2^L` times finer than the grid (`L` levels). At level
//! `l = 1..L` the lattice step is `s_l = 2^(L - l)` fine cells (half the previous step),
//! and every current front point is surrounded by a 5 x 5 patch `x + (a, b) s_l`,
//! `a, b = -2..2` (points already evaluated are not evaluated again). Last, every front
//! point next to an infeasible lattice neighbour is moved onto the feasible boundary by
//! bisection along that axis, so a front lying on a constraint (such as SWS = limit)
//! is traced exactly rather than at the nearest feasible lattice row.

use super::problem::{check_bounds, feasible_front, non_dominated, Problem, Solution};
use crate::budget;
use crate::error::{Result, RideError};
use serde::{Deserialize, Serialize};
use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};

/// Bisection steps onto the feasible boundary: the bracket shrinks to `2^-20` of a fine cell.
const BISECTION_STEPS: usize = 20;

/// STM settings.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct StmParams {
    /// Grid points per design variable (`grid x grid` designs), 2..=2001.
    pub grid: usize,
    /// Local refinement levels `L`, each halving the lattice step, <= 10; 0 keeps the
    /// plain grid (no patches, no boundary bisection).
    pub levels: usize,
}

impl Default for StmParams {
    fn default() -> Self {
        StmParams {
            grid: 201,
            levels: 3,
        }
    }
}

impl StmParams {
    /// Checks the settings; errors name the field.
    pub(crate) fn validate(&self) -> Result<()> {
        if !(2..=2001).contains(&self.grid) {
            return Err(RideError::field(
                "grid",
                "needs 2 to 2001 points per variable",
            ));
        }
        if self.levels > 10 {
            return Err(RideError::field("levels", "at most 10 refinement levels"));
        }
        let side = budget::lattice_side(self.grid, self.levels);
        if side > budget::MAX_LATTICE_SIDE {
            return Err(RideError::field(
                "levels",
                format!(
                    "--grid {} with {} levels refines to a lattice of {} steps a side; at most {} (a front of a few points a step): lower --levels or --grid",
                    self.grid,
                    self.levels,
                    budget::group(side),
                    budget::group(budget::MAX_LATTICE_SIDE)
                ),
            ));
        }
        self.check_runs(1)
    }

    /// Refuses STM over `cases` cases whose estimated runs ([`budget::stm_runs`] each)
    /// exceed the command's bound; errors name `grid`.
    pub(crate) fn check_runs(&self, cases: usize) -> Result<()> {
        let runs = budget::stm_runs(self.grid, self.levels).saturating_mul(cases as u64);
        let what = if cases > 1 {
            format!(
                "STM on a {0} x {0} grid with {1} levels over {cases} cases",
                self.grid, self.levels
            )
        } else {
            format!(
                "STM on a {0} x {0} grid with {1} levels",
                self.grid, self.levels
            )
        };
        budget::check(runs, "grid", &what, "--grid or --levels")
    }
}

/// Runs STM on a 2-variable `problem`; returns the feasible non-dominated designs
/// found, sorted by increasing `f1`; errors with [`Problem::infeasible`] when the
/// grid holds no feasible design.
pub fn stm<P: Problem>(problem: &P, params: &StmParams) -> Result<Vec<Solution<P::Info>>> {
    params.validate()?;
    let bounds = problem.bounds();
    check_bounds(&bounds)?;
    if bounds.len() != 2 {
        return Err(RideError::field(
            "bounds",
            format!(
                "STM maps a 2-variable design space, got {} variables",
                bounds.len()
            ),
        ));
    }
    let cell = 1i64 << params.levels;
    let mut map = Lattice::new(
        [bounds[0], bounds[1]],
        (params.grid as i64 - 1) * cell,
        params.grid.pow(2),
    );

    for i in 0..params.grid as i64 {
        for j in 0..params.grid as i64 {
            map.visit(problem, [i * cell, j * cell])?;
        }
    }
    let mut front = map.front(0..map.points.len());
    if front.is_empty() {
        return Err(problem.infeasible());
    }
    for level in 1..=params.levels {
        let step = cell >> level;
        let new = map.points.len();
        for &k in &front {
            let [i, j] = map.keys[k];
            for a in -2..=2 {
                for b in -2..=2 {
                    map.visit(problem, [i + a * step, j + b * step])?;
                }
            }
        }
        // ND(all) = ND(ND(old) + new): only the old front and the new points compete.
        front = map.front(front.into_iter().chain(new..map.points.len()));
    }

    let mut pool: Vec<Solution<P::Info>> = front.iter().map(|&k| map.points[k].clone()).collect();
    if params.levels > 0 {
        for &k in &front {
            let [i, j] = map.keys[k];
            for [di, dj] in [[1, 0], [-1, 0], [0, 1], [0, -1]] {
                if let Some(q) = map.visit(problem, [i + di, j + dj])? {
                    if !map.points[q].eval.feasible() {
                        pool.push(bisect(problem, &map.points[k], &map.points[q])?);
                    }
                }
            }
        }
    }
    Ok(feasible_front(&pool))
}

/// Multiplicative (Fibonacci) hashing of lattice indices: the keys are distinct small
/// integers, so the std hasher's protection against chosen keys only costs time.
#[derive(Default)]
struct LatticeHasher(u64);

impl Hasher for LatticeHasher {
    fn finish(&self) -> u64 {
        self.0
    }
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.write_u64(u64::from(b));
        }
    }
    fn write_u64(&mut self, v: u64) {
        self.0 = (self.0.rotate_left(5) ^ v).wrapping_mul(0x9E37_79B9_7F4A_7C15);
    }
}

/// Evaluated points of the fine lattice `x_k = lo_k + (hi_k - lo_k) i_k / n`, `i_k = 0..n`,
/// each evaluated once.
struct Lattice<I> {
    bounds: [(f64, f64); 2],
    n: i64,
    index: HashMap<u64, usize, BuildHasherDefault<LatticeHasher>>,
    keys: Vec<[i64; 2]>,
    points: Vec<Solution<I>>,
}

impl<I: Clone> Lattice<I> {
    /// An empty lattice with room for `capacity` points.
    fn new(bounds: [(f64, f64); 2], n: i64, capacity: usize) -> Self {
        Lattice {
            bounds,
            n,
            index: HashMap::with_capacity_and_hasher(capacity, Default::default()),
            keys: Vec::with_capacity(capacity),
            points: Vec::with_capacity(capacity),
        }
    }

    /// Evaluates lattice point `key` unless done already; `None` outside the box.
    fn visit<P: Problem<Info = I>>(&mut self, problem: &P, key: [i64; 2]) -> Result<Option<usize>> {
        if key.iter().any(|&i| i < 0 || i > self.n) {
            return Ok(None);
        }
        let flat = (key[0] * (self.n + 1) + key[1]) as u64;
        if let Some(&k) = self.index.get(&flat) {
            return Ok(Some(k));
        }
        let x: Vec<f64> = (0..2)
            .map(|d| {
                let (lo, hi) = self.bounds[d];
                lo + (hi - lo) * key[d] as f64 / self.n as f64
            })
            .collect();
        let eval = problem.evaluate(&x)?;
        self.index.insert(flat, self.points.len());
        self.keys.push(key);
        self.points.push(Solution { x, eval });
        Ok(Some(self.points.len() - 1))
    }

    /// Indices of the feasible non-dominated points among `candidates`.
    fn front(&self, candidates: impl Iterator<Item = usize>) -> Vec<usize> {
        let feasible: Vec<usize> = candidates
            .filter(|&k| self.points[k].eval.feasible())
            .collect();
        let f: Vec<[f64; 2]> = feasible.iter().map(|&k| self.points[k].eval.f).collect();
        non_dominated(&f).into_iter().map(|i| feasible[i]).collect()
    }
}

/// The feasible end of the bracket after bisecting the segment from the feasible
/// `inside` to the infeasible `outside` for the feasibility boundary.
fn bisect<P: Problem>(
    problem: &P,
    inside: &Solution<P::Info>,
    outside: &Solution<P::Info>,
) -> Result<Solution<P::Info>> {
    let (mut lo, mut hi) = (0.0, 1.0);
    let mut best = inside.clone();
    for _ in 0..BISECTION_STEPS {
        let t = 0.5 * (lo + hi);
        let x: Vec<f64> = inside
            .x
            .iter()
            .zip(&outside.x)
            .map(|(a, b)| a + t * (b - a))
            .collect();
        let eval = problem.evaluate(&x)?;
        if eval.feasible() {
            lo = t;
            best = Solution { x, eval };
        } else {
            hi = t;
        }
    }
    Ok(best)
}

#[cfg(test)]
mod tests {
    use super::super::hypervolume::{hypervolume, reference_point};
    use super::super::test_problems::{Bnh, Zdt1};
    use super::*;

    #[test]
    fn bnh_front_from_the_grid_matches_the_analytic_one() {
        let truth = Bnh::true_front(100_001);
        let r = reference_point(&truth, 0.1);
        let front = stm(
            &Bnh,
            &StmParams {
                grid: 101,
                levels: 2,
            },
        )
        .unwrap();
        let f: Vec<[f64; 2]> = front.iter().map(|s| s.eval.f).collect();
        let ratio = hypervolume(&f, r) / hypervolume(&truth, r);
        println!("BNH by STM: {} points, HV ratio {ratio:.6}", front.len());
        assert!(ratio >= 0.999, "{ratio}");
    }

    #[test]
    fn bad_settings_name_the_field() {
        let e = stm(&Bnh, &StmParams { grid: 1, levels: 0 }).unwrap_err();
        assert!(e.to_string().starts_with("grid"), "{e}");
        let e = stm(
            &Bnh,
            &StmParams {
                grid: 11,
                levels: 11,
            },
        )
        .unwrap_err();
        assert!(e.to_string().starts_with("levels"), "{e}");
        let e = stm(&Zdt1 { n: 3 }, &StmParams::default()).unwrap_err();
        assert!(e.to_string().starts_with("bounds"), "{e}");
    }
}
