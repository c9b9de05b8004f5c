//! The bi-objective problem both optimisers solve, and the 2-D Pareto filter they share.
//!
//! A problem maps a point `x` of a box to two objectives `f = [f1, f2]` (both minimised)
//! and a total constraint violation `v >= 0` (`v = 0` when feasible), plus whatever the
//! caller wants kept with each point (the suspension problem keeps all three criteria).

use crate::error::{Result, RideError};
use std::cmp::Ordering;

/// One evaluated point: objectives, violation and the problem's extra record.
#[derive(Debug, Clone, PartialEq)]
pub struct Eval<I> {
    /// The two objectives, both minimised.
    pub f: [f64; 2],
    /// Total constraint violation, `sum max(0, g_j)`; 0 when feasible.
    pub violation: f64,
    /// What the problem keeps with the point (for example the ride criteria).
    pub info: I,
}

impl<I> Eval<I> {
    /// True when no constraint is broken.
    pub(crate) fn feasible(&self) -> bool {
        self.violation <= 0.0
    }
}

/// A design point together with its evaluation.
#[derive(Debug, Clone, PartialEq)]
pub struct Solution<I> {
    /// Design variables, inside [`Problem::bounds`].
    pub x: Vec<f64>,
    /// Its objectives, violation and extra record.
    pub eval: Eval<I>,
}

/// A bi-objective, box-bounded, possibly constrained minimisation problem.
pub trait Problem {
    /// What is kept with every evaluated point.
    type Info: Clone;

    /// Lower and upper bound of each design variable.
    fn bounds(&self) -> Vec<(f64, f64)>;

    /// Objectives and violation at `x` (`x.len() == bounds().len()`, inside the bounds).
    fn evaluate(&self, x: &[f64]) -> Result<Eval<Self::Info>>;

    /// The error to report when an optimiser finds no feasible point; problems that
    /// know which constraint binds should name it.
    fn infeasible(&self) -> RideError {
        RideError::Numerical("no feasible point found".into())
    }
}

/// Checks that every bound is finite and increasing; errors name `bounds[i]`.
pub(crate) fn check_bounds(bounds: &[(f64, f64)]) -> Result<()> {
    if bounds.is_empty() {
        return Err(RideError::field(
            "bounds",
            "the problem has no design variables",
        ));
    }
    for (i, &(lo, hi)) in bounds.iter().enumerate() {
        if !(lo.is_finite() && hi.is_finite() && lo < hi) {
            return Err(RideError::field(
                format!("bounds[{i}]"),
                format!("needs finite lo < hi, got {lo}..{hi}"),
            ));
        }
    }
    Ok(())
}

/// Pareto dominance for minimisation: `a` is no worse in both objectives and better in one.
pub(crate) fn dominates(a: [f64; 2], b: [f64; 2]) -> bool {
    a[0] <= b[0] && a[1] <= b[1] && (a[0] < b[0] || a[1] < b[1])
}

/// Indices of the non-dominated points of `f`, sorted by increasing `f1`
/// (so decreasing `f2`). Duplicates and weakly dominated points are dropped;
/// O(N log N) sort-and-sweep.
pub fn non_dominated(f: &[[f64; 2]]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..f.len()).collect();
    order.sort_by(|&a, &b| lexical(f[a], f[b]));
    let mut keep = Vec::new();
    let mut best_f2 = f64::INFINITY;
    for i in order {
        if f[i][1] < best_f2 {
            best_f2 = f[i][1];
            keep.push(i);
        }
    }
    keep
}

/// Lexical order on `(f1, f2)` with `f64::total_cmp`, so sorting is deterministic.
pub(crate) fn lexical(a: [f64; 2], b: [f64; 2]) -> Ordering {
    a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1]))
}

/// The feasible, non-dominated members of `pool`, sorted by increasing `f1`.
pub(crate) fn feasible_front<I: Clone>(pool: &[Solution<I>]) -> Vec<Solution<I>> {
    let feasible: Vec<&Solution<I>> = pool.iter().filter(|s| s.eval.feasible()).collect();
    let f: Vec<[f64; 2]> = feasible.iter().map(|s| s.eval.f).collect();
    non_dominated(&f)
        .into_iter()
        .map(|i| feasible[i].clone())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn filter_keeps_the_staircase_and_drops_duplicates() {
        let f = [
            [2.0, 2.0],
            [1.0, 3.0],
            [2.0, 2.0],
            [3.0, 1.0],
            [2.5, 2.5],
            [1.0, 4.0],
        ];
        assert_eq!(non_dominated(&f), vec![1, 0, 3]);
        assert!(dominates([1.0, 1.0], [1.0, 2.0]));
        assert!(!dominates([1.0, 1.0], [1.0, 1.0]));
    }

    #[test]
    fn bad_bounds_name_the_variable() {
        let e = check_bounds(&[(0.0, 1.0), (2.0, 1.0)]).unwrap_err();
        assert!(e.to_string().starts_with("bounds[1]"), "{e}");
    }
}
