//! Where a surrogate may be wrong: an estimate `sigma_k(x)` of the relative error
//! `|S_k(x) / F_k(x) - 1|` of each criterion `k` over the design box, for every surrogate.
//!
//! - [`UncertaintyMethod::Model`]: the surrogate's own predictive standard deviation (the GP
//!   correction `gp-mul`, [`super::gp`]).
//! - [`UncertaintyMethod::Loo`], for any surrogate: leave-one-out cross-validation errors
//!   spread over the box. Each sample `i` is left out in turn, the surrogate refitted to the
//!   others and its relative error there recorded,
//!   `e_ik = S^(-i)_k(x_i) / F_ik - 1` ([`loo_errors`]). A unit-variance simple-Kriging
//!   standard deviation of the sample layout,
//!
//!   ```text
//!   s(x)^2 = 1 - r(x)^T R^-1 r(x),   R_ij = exp(-theta |x_i - x_j|^2) + nu delta_ij,  r_i(x) = exp(-theta |x - x_i|^2)
//!   ```
//!
//!   (normalised coordinates), is the shape: zero at the samples (up to the nugget `nu`) and
//!   rising towards 1 away from them. Its leave-one-out value `s_-i(x_i)^2 = 1 / (R^-1)_ii`
//!   (the conditional variance of a Gaussian vector's component given the others) calibrates
//!   the part of each error beyond the fit's own residual `r_ik = S_k(x_i) / F_ik - 1` (zero
//!   for an interpolating surrogate), `z_ik^2 = max(e_ik^2 - r_ik^2, 0) / s_-i(x_i)^2`, and
//!
//!   ```text
//!   sigma_k(x)^2 = rho_k(x)^2 + s(x)^2 c_k(x)^2,
//!   rho_k(x)^2 = sum_i w_i r_ik^2 / sum_i w_i,   c_k(x)^2 = sum_i w_i z_ik^2 / sum_i w_i,   w_i = 1 / |x - x_i|^2
//!   ```
//!
//!   spreads residuals and calibration by inverse-distance weighting (at a sample,
//!   `sigma_k = |r_ik|`, the error the fit is known to have there: zero for an
//!   interpolator, the noise floor of a least-squares fit such as VBA).
//!   `theta` maximises the leave-one-out pseudo-likelihood of the errors under
//!   `e'_ik ~ N(0, c_k^2 s_-i(x_i)^2)` (`e'_ik^2 = max(e_ik^2 - r_ik^2, 0)`) with the global
//!   `c_k^2 = mean_i z_ik^2`, i.e. minimises
//!   `sum_k [sum_i ln s_-i(x_i) + (n / 2) ln c_k^2]` over `log10 theta = 0, 0.25, .., 3`;
//!   that sum does not change when `s` is scaled, so `theta` is picked by how well the
//!   *pattern* of the layout's leave-one-out variances matches the errors.
//!
//! [`check`] measures how well an estimate predicts the true error on a HiFi validation grid
//! (Pearson and Spearman correlation of `sigma_k` against `|S_k / F_k - 1|`).

use super::fit::LmOptions;
use super::kriging::correlation_matrix;
use super::metrics::{pearson, spearman, ByCriterion};
use super::validation::ValidationSet;
use super::{Sample, Setting, Surrogate, SurrogateSpec};
use crate::design::DesignBox;
use crate::error::{parse_choice, Result, RideError};
use crate::evaluate::{Criteria, Evaluator};
use crate::math;
use nalgebra::{Cholesky, DVector, Dyn};
use serde::{Deserialize, Serialize};
use strum::{EnumIter, EnumProperty, IntoStaticStr, VariantNames};

/// Candidate `log10 theta` of the leave-one-out shape: `0, 0.25, .., 3`.
const LOG10_THETA_STEPS: usize = 13;
/// Squared normalised distance under which a point counts as a sample (IDW weights).
const AT_SAMPLE: f64 = 1e-24;
/// Smallest mean squared calibrated error in the pseudo-likelihood (exact LOO has 0).
const Z2_FLOOR: f64 = 1e-300;

/// How the uncertainty of a surrogate is estimated.
#[derive(
    Debug,
    Clone,
    Copy,
    PartialEq,
    Eq,
    Serialize,
    Deserialize,
    EnumIter,
    EnumProperty,
    IntoStaticStr,
    VariantNames,
)]
#[serde(rename_all = "kebab-case")]
#[strum(serialize_all = "kebab-case")]
#[strum()]
pub enum UncertaintyMethod {
    /// The surrogate's own predictive standard deviation (`gp-mul`).
    Model,
    /// Leave-one-out errors spread over the box (every surrogate).
    Loo,
}

impl std::str::FromStr for UncertaintyMethod {
    type Err = RideError;
    fn from_str(s: &str) -> Result<UncertaintyMethod> {
        UncertaintyMethod::parse(s)
    }
}

impl UncertaintyMethod {
    /// The method used unless asked otherwise: the model's own where it has one, else LOO.
    pub fn default_for(spec: &SurrogateSpec) -> UncertaintyMethod {
        match spec.approach {
            super::Approach::Gp => UncertaintyMethod::Model,
            _ => UncertaintyMethod::Loo,
        }
    }

    /// Parses `model` or `loo` (any case; errors name `uncertainty`).
    pub fn parse(s: &str) -> Result<UncertaintyMethod> {
        parse_choice("uncertainty", s)
    }

    /// `"model"` or `"loo"`.
    pub fn name(self) -> &'static str {
        self.into()
    }

    /// One line on how the estimate is computed (for reports and the page).
    pub fn description(self) -> &'static str {
        match self {
            UncertaintyMethod::Model => {
                "the surrogate's own predictive standard deviation (Kriging variance of ln(HiFi / LoFi))"
            }
            UncertaintyMethod::Loo => {
                "leave-one-out relative errors, calibrated by the samples' simple-Kriging leave-one-out deviation and spread over the box by inverse-distance weighting, times the Kriging deviation of the sample layout"
            }
        }
    }
}

/// The relative leave-one-out errors `e_ik = S^(-i)_k(x_i) / F_ik - 1` of `spec` on
/// `samples`: refits without each sample in turn (`n` fits). Errors (naming `plan`) when
/// the surrogate cannot be fitted to `n - 1` of the samples.
pub(crate) fn loo_errors(
    spec: &SurrogateSpec,
    setting: &Setting,
    samples: &[Sample],
    options: &LmOptions,
) -> Result<Vec<[f64; 3]>> {
    (0..samples.len())
        .map(|i| {
            let rest: Vec<Sample> = samples
                .iter()
                .enumerate()
                .filter(|(j, _)| *j != i)
                .map(|(_, s)| *s)
                .collect();
            let model = spec.fit(setting, &rest, options).map_err(|e| {
                RideError::field(
                    "plan",
                    format!(
                        "leave-one-out needs {} to fit {} of the {} samples: {e}",
                        spec.name(),
                        rest.len(),
                        samples.len()
                    ),
                )
            })?;
            let (s, p) = (samples[i], model.evaluate(samples[i].ks, samples[i].cs)?);
            let (p, f) = (p.to_array(), s.hifi.to_array());
            Ok(std::array::from_fn(|k| p[k] / f[k] - 1.0))
        })
        .collect()
}

/// The leave-one-out uncertainty field (module doc) of one set of samples.
#[derive(Debug, Clone)]
pub(crate) struct LooField {
    design_box: DesignBox,
    /// Normalised sample positions.
    x: Vec<[f64; 2]>,
    theta: f64,
    chol: Cholesky<f64, Dyn>,
    /// Calibrated squared errors `z_ik^2`.
    z2: Vec<[f64; 3]>,
    /// Squared residuals `r_ik^2` of the fit at the samples.
    r2: Vec<[f64; 3]>,
}

impl LooField {
    /// The field of the leave-one-out `errors` (from [`loo_errors`]) and the fit's
    /// `residuals` at `samples` (relative, as the errors). Errors (naming `plan`) for fewer
    /// than 2 samples, unequal lengths, non-finite values or coincident samples.
    pub fn new(
        design_box: &DesignBox,
        samples: &[Sample],
        errors: &[[f64; 3]],
        residuals: &[[f64; 3]],
    ) -> Result<Self> {
        let n = samples.len();
        if n < 2 || errors.len() != n || residuals.len() != n {
            return Err(RideError::field(
                "plan",
                format!(
                    "a leave-one-out field needs at least 2 samples with one error and residual each, got {n}, {} and {}",
                    errors.len(),
                    residuals.len()
                ),
            ));
        }
        if !errors
            .iter()
            .chain(residuals)
            .flatten()
            .all(|e| e.is_finite())
        {
            return Err(RideError::field(
                "plan",
                "leave-one-out errors must be finite",
            ));
        }
        let x: Vec<[f64; 2]> = samples
            .iter()
            .map(|s| {
                let (u, v) = design_box.normalize(s.ks, s.cs);
                [u, v]
            })
            .collect();
        let r2: Vec<[f64; 3]> = residuals.iter().map(|r| r.map(|v| v * v)).collect();
        let beyond: Vec<[f64; 3]> = errors
            .iter()
            .zip(&r2)
            .map(|(e, r2)| std::array::from_fn(|k| (e[k] * e[k] - r2[k]).max(0.0)))
            .collect();
        let n = n as f64;
        // (ln L, theta, the correlation matrix's factor, its solves), the best so far.
        type Best = (f64, f64, Cholesky<f64, Dyn>, Vec<[f64; 3]>);
        let mut best: Option<Best> = None;
        for step in 0..LOG10_THETA_STEPS {
            let theta = math::powf(10f64, 3.0 * step as f64 / (LOG10_THETA_STEPS - 1) as f64);
            let Some(chol) = correlation_matrix([theta; 2], &x).cholesky() else {
                continue;
            };
            let inv = chol.inverse();
            // s_-i(x_i)^2 = 1 / (R^-1)_ii
            let s2: Vec<f64> = (0..x.len()).map(|i| 1.0 / inv[(i, i)]).collect();
            if !s2.iter().all(|v| v.is_finite() && *v > 0.0) {
                continue;
            }
            let z2: Vec<[f64; 3]> = beyond
                .iter()
                .zip(&s2)
                .map(|(e2, s2)| e2.map(|v| v / s2))
                .collect();
            let ln_s: f64 = s2.iter().map(|v| 0.5 * math::ln(*v)).sum();
            let nlpl: f64 = (0..3)
                .map(|k| {
                    let c2 = z2.iter().map(|z| z[k]).sum::<f64>() / n;
                    ln_s + 0.5 * n * math::ln(c2.max(Z2_FLOOR))
                })
                .sum();
            if nlpl.is_finite() && best.as_ref().is_none_or(|b| nlpl < b.0) {
                best = Some((nlpl, theta, chol, z2));
            }
        }
        let (_, theta, chol, z2) = best.ok_or_else(|| {
            RideError::field(
                "plan",
                "the samples' Kriging system is singular for every correlation length (coincident samples?)",
            )
        })?;
        Ok(LooField {
            design_box: *design_box,
            x,
            theta,
            chol,
            z2,
            r2,
        })
    }

    /// The shape `s(x)` at normalised `(u, v)`: the unit-variance simple-Kriging deviation.
    pub fn shape(&self, u: f64, v: f64) -> f64 {
        let r = DVector::from_iterator(
            self.x.len(),
            self.x
                .iter()
                .map(|xi| super::kriging::correlation([self.theta; 2], [u, v], *xi)),
        );
        (1.0 - r.dot(&self.chol.solve(&r))).max(0.0).sqrt()
    }

    /// `sigma_k(x)` at `(ks, cs)` for `[bacc, dtl, sws]` (module doc), -.
    pub fn relative_std(&self, ks: f64, cs: f64) -> [f64; 3] {
        let (u, v) = self.design_box.normalize(ks, cs);
        let s2 = self.shape(u, v).powi(2);
        let combine =
            |r2: [f64; 3], z2: [f64; 3]| std::array::from_fn(|k| (r2[k] + s2 * z2[k]).sqrt());
        let (mut r2, mut z2, mut den) = ([0.0; 3], [0.0; 3], 0.0);
        for ((xi, zi), ri) in self.x.iter().zip(&self.z2).zip(&self.r2) {
            let d2 = (u - xi[0]).powi(2) + (v - xi[1]).powi(2);
            if d2 < AT_SAMPLE {
                return combine(*ri, *zi);
            }
            let w = 1.0 / d2;
            den += w;
            for k in 0..3 {
                r2[k] += w * ri[k];
                z2[k] += w * zi[k];
            }
        }
        combine(r2.map(|v| v / den), z2.map(|v| v / den))
    }
}

/// A fitted surrogate with its uncertainty estimate.
pub struct Uncertain {
    /// The fitted surrogate.
    pub model: Box<dyn Surrogate>,
    /// How the uncertainty is estimated.
    pub method: UncertaintyMethod,
    /// The leave-one-out errors and field ([`UncertaintyMethod::Loo`]).
    loo: Option<(Vec<[f64; 3]>, LooField)>,
}

impl Uncertain {
    /// Fits `spec` to `samples` and sets up the `method` estimate (for LOO: `n` more fits).
    /// Errors name `plan` (too few samples) or `uncertainty` (a surrogate without its own
    /// variance asked for [`UncertaintyMethod::Model`]).
    pub fn fit(
        spec: &SurrogateSpec,
        setting: &Setting,
        samples: &[Sample],
        options: &LmOptions,
        method: UncertaintyMethod,
    ) -> Result<Uncertain> {
        let model = spec.fit(setting, samples, options)?;
        let loo = match method {
            UncertaintyMethod::Model => {
                let (ks, cs) = (samples[0].ks, samples[0].cs);
                if model.relative_std(ks, cs)?.is_none() {
                    return Err(RideError::field(
                        "uncertainty",
                        format!(
                            "{} has no predictive variance of its own; use loo",
                            spec.name()
                        ),
                    ));
                }
                None
            }
            UncertaintyMethod::Loo => {
                let errors = loo_errors(spec, setting, samples, options)?;
                let residuals = samples
                    .iter()
                    .map(|s| {
                        let (p, f) = (model.evaluate(s.ks, s.cs)?.to_array(), s.hifi.to_array());
                        Ok(std::array::from_fn(|k| p[k] / f[k] - 1.0))
                    })
                    .collect::<Result<Vec<[f64; 3]>>>()?;
                let field = LooField::new(&setting.design_box, samples, &errors, &residuals)?;
                Some((errors, field))
            }
        };
        Ok(Uncertain {
            model: Box::new(model),
            method,
            loo,
        })
    }

    /// The estimated relative error (1 sigma) of `[bacc, dtl, sws]` at `(ks, cs)`, -.
    pub fn relative_std(&self, ks: f64, cs: f64) -> Result<[f64; 3]> {
        crate::car::check_design(ks, cs)?;
        match &self.loo {
            Some((_, field)) => Ok(field.relative_std(ks, cs)),
            None => self.model.relative_std(ks, cs)?.ok_or_else(|| {
                RideError::Numerical("the surrogate lost its predictive variance".into())
            }),
        }
    }

    /// The prediction and its relative uncertainty at `(ks, cs)`.
    pub fn predict(&self, ks: f64, cs: f64) -> Result<(Criteria, [f64; 3])> {
        Ok((self.model.evaluate(ks, cs)?, self.relative_std(ks, cs)?))
    }
}

/// How well an uncertainty estimate predicts the true error on a validation grid.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct UncertaintyCheck {
    /// The method.
    pub method: UncertaintyMethod,
    /// How it is computed, in words.
    pub description: String,
    /// Pearson correlation of `sigma_k` with `|S_k / F_k - 1|` over the grid (`None`: no
    /// spread in one of them).
    pub pearson: ByCriterion<Option<f64>>,
    /// Spearman (rank) correlation of the same.
    pub spearman: ByCriterion<Option<f64>>,
    /// Mean estimate over the grid, %.
    pub estimated_mean_percent: ByCriterion<f64>,
    /// Mean true error over the grid, %.
    pub true_mean_percent: ByCriterion<f64>,
    /// `sigma_k` at each validation point (the map beside the error map, same order), %.
    pub map_percent: ByCriterion<Vec<f64>>,
}

/// How well an estimate predicts the size of the true error at the same points.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub(crate) struct ErrorCorrelation {
    /// Pearson's `r` of `sigma_i` against `|e_i|` (`None`: fewer than 2 points, a
    /// non-finite value, or no spread in one of them).
    pub pearson: Option<f64>,
    /// Spearman's rank correlation of the same (ties share their mean rank).
    pub spearman: Option<f64>,
}

/// The correlation of the estimates `sigma` with the sizes `|e_i|` of the true errors
/// `error` (same points, same units; the sign of an error is dropped):
///
/// ```text
/// r = sum_i (sigma_i - mean sigma) (|e_i| - mean |e|) / sqrt(sum_i (sigma_i - mean sigma)^2 sum_i (|e_i| - mean |e|)^2)
/// ```
///
/// and Spearman's rank correlation (Pearson's of the ranks). Both `None` for slices of
/// unequal length.
fn error_correlation(sigma: &[f64], error: &[f64]) -> ErrorCorrelation {
    let size: Vec<f64> = error.iter().map(|e| e.abs()).collect();
    ErrorCorrelation {
        pearson: pearson(sigma, &size),
        spearman: spearman(sigma, &size),
    }
}

/// Compares `est` with the true errors on `validation` (module doc).
pub fn check(est: &Uncertain, validation: &ValidationSet) -> Result<UncertaintyCheck> {
    let mut sigma: [Vec<f64>; 3] = Default::default();
    let mut truth: [Vec<f64>; 3] = Default::default();
    for (&(ks, cs), f) in validation.points.iter().zip(&validation.hifi) {
        let (p, s) = est.predict(ks, cs)?;
        let (p, f) = (p.to_array(), f.to_array());
        for k in 0..3 {
            sigma[k].push(100.0 * s[k]);
            truth[k].push(100.0 * (p[k] / f[k] - 1.0).abs());
        }
    }
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len().max(1) as f64;
    let r: [ErrorCorrelation; 3] = std::array::from_fn(|k| error_correlation(&sigma[k], &truth[k]));
    Ok(UncertaintyCheck {
        method: est.method,
        description: est.method.description().into(),
        pearson: ByCriterion::from_fn(|k| r[k].pearson),
        spearman: ByCriterion::from_fn(|k| r[k].spearman),
        estimated_mean_percent: ByCriterion::from_fn(|k| mean(&sigma[k])),
        true_mean_percent: ByCriterion::from_fn(|k| mean(&truth[k])),
        map_percent: ByCriterion::from_fn(|k| std::mem::take(&mut sigma[k])),
    })
}

/// One uncertainty estimate of a surrogate report: checked on the validation grid, or
/// why it could not be made.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "status", rename_all = "lowercase")]
pub enum UncertaintyOutcome {
    /// Estimated and checked (boxed: the check is much larger than the skip).
    Estimated(Box<UncertaintyCheck>),
    /// Not estimated (leave-one-out on too few samples), and why.
    Skipped {
        /// The method.
        method: UncertaintyMethod,
        /// The reason.
        reason: String,
    },
}

/// Every estimate `spec` offers on `samples` (LOO, and the model's own where it has one),
/// each checked on `validation`; an estimate that cannot be made is a skipped entry.
pub(crate) fn estimates(
    spec: &SurrogateSpec,
    setting: &Setting,
    samples: &[Sample],
    options: &LmOptions,
    validation: &ValidationSet,
) -> Result<Vec<UncertaintyOutcome>> {
    let mut methods = vec![UncertaintyMethod::Loo];
    if UncertaintyMethod::default_for(spec) == UncertaintyMethod::Model {
        methods.insert(0, UncertaintyMethod::Model);
    }
    methods
        .into_iter()
        .map(
            |method| match Uncertain::fit(spec, setting, samples, options, method) {
                Ok(est) => Ok(UncertaintyOutcome::Estimated(Box::new(check(
                    &est, validation,
                )?))),
                Err(e) => Ok(UncertaintyOutcome::Skipped {
                    method,
                    reason: e.to_string(),
                }),
            },
        )
        .collect()
}

#[cfg(test)]
mod tests {
    use super::super::kriging::NUGGET;
    use super::*;
    use crate::car::Car;
    use crate::doe::audze_eglais;
    use crate::road::Road;
    use crate::surrogate::sample_plan;
    use crate::HiFi;

    fn setup(n: usize) -> (Setting, HiFi, Vec<Sample>) {
        let (car, road, b) = (Car::datum(), Road::default(), DesignBox::default());
        let setting = Setting::new(&car, &road, &b).unwrap();
        let hifi = HiFi::new(&car, &road).unwrap();
        let samples = sample_plan(&hifi, &audze_eglais(n, 1).unwrap(), &b).unwrap();
        (setting, hifi, samples)
    }

    /// LOO of a linear least-squares fit has the closed form `r_i / (1 - h_ii)` (residual
    /// over one minus the leverage); `data-lin` fits each criterion by rows
    /// `(1 / F_i) c^T m(x_i) ~ 1`, so its relative LOO error is that of row `i`.
    #[test]
    fn loo_errors_match_the_hat_matrix() {
        let (setting, _, samples) = setup(9);
        let spec = SurrogateSpec::parse("data-lin").unwrap();
        let loo = loo_errors(&spec, &setting, &samples, &LmOptions::default()).unwrap();
        for k in 0..3 {
            let a = nalgebra::DMatrix::from_fn(samples.len(), 3, |i, j| {
                let (u, v) = setting.design_box.normalize(samples[i].ks, samples[i].cs);
                [1.0, u, v][j] / samples[i].hifi.to_array()[k]
            });
            let t = DVector::from_element(samples.len(), 1.0);
            let ata_inv = (a.transpose() * &a).try_inverse().unwrap();
            let h = &a * &ata_inv * a.transpose();
            let r = &a * (&ata_inv * a.transpose() * &t) - &t;
            for i in 0..samples.len() {
                let want = r[i] / (1.0 - h[(i, i)]);
                assert!(
                    (loo[i][k] - want).abs() < 1e-9 * want.abs().max(1e-6),
                    "{k} {i}: {} vs {want}",
                    loo[i][k]
                );
            }
        }
    }

    /// The shape's leave-one-out variance `1 / (R^-1)_ii` against an explicit fit without
    /// sample `i`: `(1 + nu) - r^T R_-i^-1 r`.
    #[test]
    fn shape_loo_variance_matches_explicit_refits() {
        let (setting, _, samples) = setup(7);
        let x: Vec<[f64; 2]> = samples
            .iter()
            .map(|s| {
                let (u, v) = setting.design_box.normalize(s.ks, s.cs);
                [u, v]
            })
            .collect();
        let theta = 8.0;
        let inv = correlation_matrix([theta; 2], &x)
            .cholesky()
            .unwrap()
            .inverse();
        for i in 0..x.len() {
            let rest: Vec<[f64; 2]> = x
                .iter()
                .enumerate()
                .filter(|(j, _)| *j != i)
                .map(|(_, p)| *p)
                .collect();
            let r = DVector::from_iterator(
                rest.len(),
                rest.iter()
                    .map(|p| super::super::kriging::correlation([theta; 2], x[i], *p)),
            );
            let sub = correlation_matrix([theta; 2], &rest).lu();
            let explicit = 1.0 + NUGGET - r.dot(&sub.solve(&r).unwrap());
            assert!(
                (1.0 / inv[(i, i)] - explicit).abs() < 1e-9,
                "{i}: {} vs {explicit}",
                1.0 / inv[(i, i)]
            );
        }
    }

    /// Both estimates are at their noise floor at the samples (zero for the interpolating
    /// RBF and GP corrections, VBA's least-squares residual for VBA) and grow away from
    /// them: the mean over a 41 x 41 grid rises with the distance to the nearest sample.
    #[test]
    fn at_the_noise_floor_at_the_samples_and_growing_away() {
        let (setting, _, samples) = setup(10);
        for (name, method, interpolates) in [
            ("rba-mul-rbf-mq", UncertaintyMethod::Loo, true),
            ("vba-qts", UncertaintyMethod::Loo, false),
            ("gp-mul", UncertaintyMethod::Model, true),
            ("gp-mul", UncertaintyMethod::Loo, true),
        ] {
            let spec = SurrogateSpec::parse(name).unwrap();
            let est =
                Uncertain::fit(&spec, &setting, &samples, &LmOptions::default(), method).unwrap();
            let b = setting.design_box;
            let mut bands = [(0.0, 0usize); 3];
            let mut peak: f64 = 0.0;
            for i in 0..=40 {
                for j in 0..=40 {
                    let (u, v) = (i as f64 / 40.0, j as f64 / 40.0);
                    let (ks, cs) = b.scale(u, v);
                    let s = est.relative_std(ks, cs).unwrap();
                    let d = samples
                        .iter()
                        .map(|p| {
                            let (pu, pv) = b.normalize(p.ks, p.cs);
                            (u - pu).hypot(v - pv)
                        })
                        .fold(f64::INFINITY, f64::min);
                    let band = match d {
                        d if d < 0.05 => 0,
                        d if d < 0.1 => 1,
                        _ => 2,
                    };
                    let m = s.iter().copied().fold(0.0, f64::max);
                    peak = peak.max(m);
                    bands[band].0 += m;
                    bands[band].1 += 1;
                }
            }
            let mean: Vec<f64> = bands.iter().map(|(s, n)| s / *n as f64).collect();
            assert!(
                mean[0] < mean[1] && mean[1] < mean[2],
                "{name} {method:?}: {mean:?}"
            );
            for p in &samples {
                let s = est.relative_std(p.ks, p.cs).unwrap();
                let (m, f) = (est.model.evaluate(p.ks, p.cs).unwrap(), p.hifi);
                for k in 0..3 {
                    let residual = (m.to_array()[k] / f.to_array()[k] - 1.0).abs();
                    if interpolates {
                        assert!(residual < 1e-7, "{name}: {residual}");
                    }
                    // the floor: the residual plus the nugget's sqrt(1e-10) share
                    assert!(
                        (s[k] - residual).abs() <= 1e-4 * peak,
                        "{name} {method:?} {k}: {} vs residual {residual}, peak {peak}",
                        s[k]
                    );
                }
            }
        }
        let spec = SurrogateSpec::parse("vba-qts").unwrap();
        let e = Uncertain::fit(
            &spec,
            &setting,
            &samples,
            &LmOptions::default(),
            UncertaintyMethod::Model,
        );
        assert!(e.err().unwrap().to_string().starts_with("uncertainty"));
        assert!(UncertaintyMethod::parse("x")
            .unwrap_err()
            .to_string()
            .starts_with("uncertainty"));
    }

    /// `error_correlation` by hand: `sigma = [0, 1, 2, 5]`, errors `[1, -1, -3, 4]`, so
    /// `|e| = [1, 1, 3, 4]`. Deviations from the means 2 and 2.25: `(-2, -1, 0, 3)` and
    /// `(-1.25, -1.25, 0.75, 1.75)`; `Sxy = 2.5 + 1.25 + 0 + 5.25 = 9`, `Sxx = 14`,
    /// `Syy = 6.75`, `r = 9 / sqrt(94.5)`. Ranks `(1, 2, 3, 4)` and `(1.5, 1.5, 3, 4)`:
    /// `Sxy = 4.5`, `Sxx = 5`, `Syy = 4.5`, `rho = 4.5 / sqrt(22.5) = sqrt(0.9)`. An
    /// estimate exactly proportional to `|e|` correlates 1 by both, whatever the signs.
    #[test]
    fn error_correlation_by_hand() {
        let c = error_correlation(&[0.0, 1.0, 2.0, 5.0], &[1.0, -1.0, -3.0, 4.0]);
        assert!(
            (c.pearson.unwrap() - 9.0 / 94.5f64.sqrt()).abs() < 1e-12,
            "{c:?}"
        );
        assert!((c.spearman.unwrap() - 0.9f64.sqrt()).abs() < 1e-12, "{c:?}");
        let e = [0.3, -1.7, 2.2, -0.05, 4.0, -3.1];
        let sigma: Vec<f64> = e.iter().map(|v: &f64| 2.5 * v.abs()).collect();
        let c = error_correlation(&sigma, &e);
        assert!((c.pearson.unwrap() - 1.0).abs() < 1e-12, "{c:?}");
        assert!((c.spearman.unwrap() - 1.0).abs() < 1e-12, "{c:?}");
        // No spread in the estimate, or unequal lengths: no correlation.
        assert_eq!(error_correlation(&[1.0; 6], &e).pearson, None);
        assert_eq!(error_correlation(&[1.0, 2.0], &e).spearman, None);
    }

    /// How well each estimate predicts the true error on the 20 x 20 HiFi validation grid,
    /// default scenario, 10-point Audze-Eglais plan. Observed (Pearson / Spearman for
    /// BAcc, DTL, SWS):
    /// rba-mul-rbf-mq LOO 0.71 / 0.53, 0.79 / 0.69, 0.46 / 0.56;
    /// vba-qts LOO 0.74 / 0.74, 0.88 / 0.88, 0.88 / 0.85;
    /// gp-mul LOO 0.86 / 0.61, 0.60 / 0.50, 0.90 / 0.73;
    /// gp-mul's own variance 0.63 / 0.48, 0.17 / 0.24, 0.81 / 0.72.
    /// Asserted: every LOO correlation >= 0.4; the GP's own >= 0.4 for BAcc and SWS and
    /// > 0.1 for DTL (its weak spot: the DTL correction is nearly flat, so its length scales
    /// say little about where the error is); each mean estimate within a factor 4 of the
    /// mean true error (observed 0.36 to 2.1).
    #[test]
    fn estimates_track_the_true_error() {
        let (setting, hifi, samples) = setup(10);
        let validation = ValidationSet::new(&hifi, &setting.design_box, 20).unwrap();
        for (name, method) in [
            ("rba-mul-rbf-mq", UncertaintyMethod::Loo),
            ("vba-qts", UncertaintyMethod::Loo),
            ("gp-mul", UncertaintyMethod::Loo),
            ("gp-mul", UncertaintyMethod::Model),
        ] {
            let spec = SurrogateSpec::parse(name).unwrap();
            let est =
                Uncertain::fit(&spec, &setting, &samples, &LmOptions::default(), method).unwrap();
            let c = check(&est, &validation).unwrap();
            eprintln!(
                "{name} {method:?}: pearson {:?} spearman {:?} mean estimate {:?} % mean true {:?} %",
                c.pearson, c.spearman, c.estimated_mean_percent, c.true_mean_percent
            );
            assert_eq!(c.map_percent.bacc.len(), 400);
            for k in 0..3 {
                let bound = match (method, k) {
                    (UncertaintyMethod::Model, 1) => 0.1,
                    _ => 0.4,
                };
                let (p, r) = (
                    c.pearson.to_array()[k].unwrap(),
                    c.spearman.to_array()[k].unwrap(),
                );
                assert!(p >= bound && r >= bound, "{name} {method:?} {k}: {p} {r}");
                let ratio =
                    c.estimated_mean_percent.to_array()[k] / c.true_mean_percent.to_array()[k];
                assert!(
                    (0.25..=4.0).contains(&ratio),
                    "{name} {method:?} {k}: {ratio}"
                );
            }
        }
    }
}
