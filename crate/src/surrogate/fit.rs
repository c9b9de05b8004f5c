//! Fitting a tuned LoFi (VBA, PBA): nonlinear least squares on relative errors,
//!
//! ```text
//! min_a  C(a) = 1/2 sum_i sum_{k in K} r_ik(a)^2,   r_ik = (S_k(x_i; a) - F_ik) / F_ik
//! ```
//!
//! over the samples `i` and the criteria `K` of the fit (all three in the shared scheme, one
//! in the per-criterion scheme), by Levenberg-Marquardt (the `levenberg-marquardt` crate, a
//! MINPACK port on the same nalgebra) from several seeded starts; the Jacobian is taken by
//! central differences. A tuning that leaves the LoFi invalid anywhere in the design box
//! (for VBA a transformed Ks or Cs <= 0) gets a large constant residual, so Levenberg-Marquardt
//! rejects the step and shrinks its trust region.

use super::{Sample, Scheme, SurrogateLoFi};
use crate::car::QuarterCar;
use crate::error::{Result, RideError};
use crate::evaluate::Criteria;
use levenberg_marquardt::{LeastSquaresProblem, LevenbergMarquardt};
use nalgebra::storage::Owned;
use nalgebra::{DMatrix, DVector, Dyn};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};
use std::cell::Cell;

/// Residual given to every sample and criterion of an inadmissible tuning.
const PENALTY: f64 = 1e3;
/// Relative central-difference step, about the cube root of the machine epsilon.
const FD_STEP: f64 = 6e-6;
/// Draws allowed to find an admissible random start.
const START_DRAWS: usize = 100;

/// A parametric tuning of the LoFi quarter car, `a -> p(a)` or `x -> tau(x, a)`.
pub trait Tuning: Send + Sync {
    /// Parameter names, e.g. `["ks.a0", "ks.a1", ...]`.
    fn names(&self) -> Vec<String>;

    /// The neutral tuning that leaves the LoFi as it is (first start).
    fn neutral(&self) -> Vec<f64>;

    /// Half-widths of the box around [`Tuning::neutral`] the random starts are drawn from.
    fn spread(&self) -> Vec<f64>;

    /// Whether `a` keeps the tuned quarter car valid over the whole design box.
    fn admissible(&self, a: &[f64]) -> bool;

    /// The tuned quarter car at design `(ks N/m, cs N s/m)`.
    fn quarter(&self, a: &[f64], ks: f64, cs: f64) -> Result<QuarterCar>;
}

/// Settings of the Levenberg-Marquardt fit.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct LmOptions {
    /// Number of starts: the neutral tuning, then random ones around it (>= 1).
    pub starts: usize,
    /// Seed of the random starts.
    pub seed: u64,
    /// Each run stops after `patience (n_params + 1)` residual evaluations (>= 1).
    pub patience: usize,
}

impl Default for LmOptions {
    /// Four starts, seed 1, patience 100 (MINPACK's default budget).
    fn default() -> Self {
        LmOptions {
            starts: 4,
            seed: 1,
            patience: 100,
        }
    }
}

impl LmOptions {
    /// Checks `starts >= 1` and `patience >= 1`.
    pub fn check(&self) -> Result<()> {
        if self.starts == 0 {
            return Err(RideError::field("starts", "need at least one start"));
        }
        if self.patience == 0 {
            return Err(RideError::field("patience", "must be >= 1"));
        }
        Ok(())
    }
}

/// How one fit went.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FitDiagnostics {
    /// Criteria the fit covers: "all" (shared) or "bacc", "dtl", "sws".
    pub criteria: String,
    /// "levenberg-marquardt", "least squares (SVD pseudo-inverse)" or "rbf interpolation".
    pub method: String,
    /// Final cost `1/2 sum r_ik^2` of the relative errors at the samples, -.
    pub cost: f64,
    /// Iterations (Jacobians) of the winning start (0 for direct fits).
    pub iterations: usize,
    /// Residual evaluations of the winning start (0 for direct fits).
    pub evaluations: usize,
    /// Starts tried (1 for direct fits).
    pub starts: usize,
    /// Index of the start that won (0: the neutral tuning).
    pub best_start: usize,
    /// Whether the winning run met a convergence test (always true for direct fits).
    pub converged: bool,
    /// Why the winning run stopped, or a note on the direct fit.
    pub termination: String,
}

impl FitDiagnostics {
    /// Diagnostics of a direct (non-iterative) fit.
    pub(crate) fn direct(criteria: String, method: &str, note: String, cost: f64) -> Self {
        FitDiagnostics {
            criteria,
            method: method.into(),
            cost,
            iterations: 0,
            evaluations: 0,
            starts: 1,
            best_start: 0,
            converged: true,
            termination: note,
        }
    }
}

/// The least-squares problem of one fit, as the `levenberg-marquardt` crate sees it.
struct Problem<'a, T> {
    tuning: &'a T,
    lofi: &'a SurrogateLoFi,
    samples: &'a [Sample],
    criteria: &'a [usize],
    a: DVector<f64>,
    jacobians: Cell<usize>,
}

impl<T: Tuning> Problem<'_, T> {
    /// Residuals `r_ik(a)`, or the penalty where `a` is inadmissible.
    fn residuals_at(&self, a: &[f64]) -> DVector<f64> {
        let m = self.samples.len() * self.criteria.len();
        match self.try_residuals(a) {
            Some(r) => r,
            None => DVector::from_element(m, PENALTY),
        }
    }

    fn try_residuals(&self, a: &[f64]) -> Option<DVector<f64>> {
        if !self.tuning.admissible(a) {
            return None;
        }
        let mut r = Vec::with_capacity(self.samples.len() * self.criteria.len());
        for s in self.samples {
            let q = self.tuning.quarter(a, s.ks, s.cs).ok()?;
            let p = self.lofi.quarter_criteria(&q).ok()?.to_array();
            let f = s.hifi.to_array();
            r.extend(self.criteria.iter().map(|&k| (p[k] - f[k]) / f[k]));
        }
        r.iter()
            .all(|x| x.is_finite())
            .then(|| DVector::from_vec(r))
    }
}

impl<T: Tuning> LeastSquaresProblem<f64, Dyn, Dyn> for Problem<'_, T> {
    type ResidualStorage = Owned<f64, Dyn>;
    type JacobianStorage = Owned<f64, Dyn, Dyn>;
    type ParameterStorage = Owned<f64, Dyn>;

    fn set_params(&mut self, a: &DVector<f64>) {
        self.a.copy_from(a);
    }

    fn params(&self) -> DVector<f64> {
        self.a.clone()
    }

    fn residuals(&self) -> Option<DVector<f64>> {
        Some(self.residuals_at(self.a.as_slice()))
    }

    /// Central differences `(r(a + h e_j) - r(a - h e_j)) / 2h`, `h = FD_STEP max(|a_j|, 1)`.
    fn jacobian(&self) -> Option<DMatrix<f64>> {
        self.jacobians.set(self.jacobians.get() + 1);
        let n = self.a.len();
        let m = self.samples.len() * self.criteria.len();
        let mut jac = DMatrix::zeros(m, n);
        let mut a = self.a.clone();
        for j in 0..n {
            let h = FD_STEP * self.a[j].abs().max(1.0);
            a[j] = self.a[j] + h;
            let up = self.residuals_at(a.as_slice());
            a[j] = self.a[j] - h;
            let down = self.residuals_at(a.as_slice());
            a[j] = self.a[j];
            jac.set_column(j, &((up - down) / (2.0 * h)));
        }
        Some(jac)
    }
}

/// The tuning of one fit and how it went.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Fitted {
    /// Tuning parameters `a`.
    pub params: Vec<f64>,
    /// How the fit went.
    pub diagnostics: FitDiagnostics,
}

/// Fits `tuning` to the criteria `criteria` of `samples` on `lofi`'s road (see the module doc):
/// Levenberg-Marquardt from the neutral tuning and `options.starts - 1` seeded random starts,
/// keeping the admissible result of least cost. Errors (naming `plan`) when no start ends
/// admissible with a finite cost.
fn least_squares<T: Tuning>(
    tuning: &T,
    lofi: &SurrogateLoFi,
    samples: &[Sample],
    criteria: &[usize],
    label: String,
    options: &LmOptions,
) -> Result<Fitted> {
    options.check()?;
    let lm = LevenbergMarquardt::new().with_patience(options.patience);
    let mut rng = ChaCha8Rng::seed_from_u64(options.seed);
    let (neutral, spread) = (tuning.neutral(), tuning.spread());
    let mut best: Option<(f64, Vec<f64>, FitDiagnostics)> = None;
    for start in 0..options.starts {
        let a0 = if start == 0 {
            Some(neutral.clone())
        } else {
            (0..START_DRAWS)
                .map(|_| {
                    neutral
                        .iter()
                        .zip(&spread)
                        .map(|(n, s)| n + s * rng.random_range(-1.0..=1.0))
                        .collect::<Vec<f64>>()
                })
                .find(|a| tuning.admissible(a))
        };
        let Some(a0) = a0 else { continue };
        let problem = Problem {
            tuning,
            lofi,
            samples,
            criteria,
            a: DVector::from_vec(a0),
            jacobians: Cell::new(0),
        };
        let (problem, report) = lm.minimize(problem);
        let a: Vec<f64> = problem.a.iter().copied().collect();
        let Some(r) = problem.try_residuals(&a) else {
            continue;
        };
        let cost = 0.5 * r.norm_squared();
        if best.as_ref().is_none_or(|b| cost < b.0) {
            let diagnostics = FitDiagnostics {
                criteria: label.clone(),
                method: "levenberg-marquardt".into(),
                cost,
                iterations: problem.jacobians.get(),
                evaluations: report.number_of_evaluations,
                starts: options.starts,
                best_start: start,
                converged: report.termination.was_successful(),
                termination: format!("{:?}", report.termination),
            };
            best = Some((cost, a, diagnostics));
        }
    }
    let (_, params, diagnostics) = best.ok_or_else(|| {
        RideError::field(
            "plan",
            format!(
                "the fit failed: no start of {} ended with a valid tuned LoFi",
                options.starts
            ),
        )
    })?;
    Ok(Fitted {
        params,
        diagnostics,
    })
}

/// Fits `tuning` in `scheme`: one fit over all criteria, or one per criterion.
pub(crate) fn fit_scheme<T: Tuning>(
    tuning: &T,
    lofi: &SurrogateLoFi,
    samples: &[Sample],
    scheme: Scheme,
    options: &LmOptions,
) -> Result<Vec<Fitted>> {
    scheme
        .groups()
        .iter()
        .enumerate()
        .map(|(g, criteria)| {
            least_squares(tuning, lofi, samples, criteria, scheme.label(g), options)
        })
        .collect()
}

/// Checks that `samples` can determine `p` tuning parameters per fit in `scheme`: at least
/// as many residuals per fit as parameters, and at least `levels` distinct Ks and Cs values.
/// Errors name `plan`; `what` names the surrogate in the message.
pub(crate) fn check_tuning(
    p: usize,
    levels: [usize; 2],
    samples: &[Sample],
    scheme: Scheme,
    what: &str,
) -> Result<()> {
    super::check_samples(samples)?;
    let per_fit = scheme.groups()[0].len();
    let needed = p.div_ceil(per_fit);
    super::require_samples(samples, needed, &format!("{what} ({p} parameters per fit)"))?;
    let have = super::distinct_levels(samples);
    for (d, name) in ["Ks", "Cs"].iter().enumerate() {
        if have[d] < levels[d] {
            return Err(RideError::field(
                "plan",
                format!(
                    "{what} needs at least {} distinct {name} levels, the plan has {}",
                    levels[d], have[d]
                ),
            ));
        }
    }
    Ok(())
}

/// Criteria of the tuned quarter car at `(ks, cs)` for tuning `a`.
pub(crate) fn tuned_criteria<T: Tuning>(
    tuning: &T,
    lofi: &SurrogateLoFi,
    a: &[f64],
    ks: f64,
    cs: f64,
) -> Result<Criteria> {
    lofi.quarter_criteria(&tuning.quarter(a, ks, cs)?)
}
