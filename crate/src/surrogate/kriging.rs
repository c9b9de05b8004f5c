//! Ordinary Kriging (Gaussian-process regression with a constant mean) over the normalised
//! design square `x = (u, v)`, the building block of the GP correction of the LoFi
//! ([`super::gp`]) and of the leave-one-out uncertainty field ([`super::uncertainty`]):
//!
//! ```text
//! y(x) = mu + Z(x),   Z ~ GP(0, sigma^2 R),   R(x, x') = exp(-theta_u (u - u')^2 - theta_v (v - v')^2)
//! ```
//!
//! For `n` samples `(x_i, y_i)` with correlation matrix `R_ij = R(x_i, x_j) + nu delta_ij`
//! (a nugget `nu` = [`NUGGET`] keeps the Cholesky factorisation `R = L L^T` stable), the
//! generalised least-squares mean and the maximum-likelihood variance are
//!
//! ```text
//! mu = 1^T R^-1 y / 1^T R^-1 1,   sigma^2 = (y - mu 1)^T R^-1 (y - mu 1) / n,
//! ```
//!
//! the concentrated log-likelihood (constants dropped) is
//! `ln L(theta) = -(n/2) ln sigma^2 - (1/2) ln det R`, and at a new point with correlations
//! `r_i = R(x, x_i)` the predictor and its mean squared error are
//!
//! ```text
//! y^(x)   = mu + r^T R^-1 (y - mu 1)
//! s^2(x)  = sigma^2 [1 - r^T R^-1 r + (1 - 1^T R^-1 r)^2 / (1^T R^-1 1)]
//! ```
//!
//! (DACE, Lophaven, Nielsen and Sondergaard 2002; the `(1 - 1^T R^-1 r)^2` term counts the
//! uncertainty of the estimated mean). `s^2` is zero at the samples up to the nugget's floor
//! `sigma^2 nu` and grows towards `sigma^2 (1 + 1 / 1^T R^-1 1)` far from them.
//!
//! `theta` is chosen by maximum likelihood: a log grid over `10^-2 .. 10^3` per axis
//! (correlation lengths `1 / sqrt(theta)` from 0.03 to 10 box widths), then a compass search
//! in `log10 theta` from the best grid point. Everything is deterministic.
//! nalgebra's Cholesky factorisation does the linear algebra.

use crate::error::{Result, RideError};
use crate::math;
use nalgebra::{Cholesky, DMatrix, DVector, Dyn};
use serde::{Deserialize, Serialize};

/// Nugget `nu` added to the diagonal of the correlation matrix (relative to `sigma^2`).
pub(crate) const NUGGET: f64 = 1e-10;

/// Range of `log10 theta` searched by maximum likelihood, per axis.
const LOG10_THETA: (f64, f64) = (-2.0, 3.0);

/// Points per axis of the maximum-likelihood log grid (half a decade apart).
const GRID_POINTS: usize = 11;

/// First and last step (decades) of the compass search after the grid.
const COMPASS_STEPS: (f64, f64) = (0.25, 0.005);

/// Smallest `sigma^2` used in the likelihood (constant data has `sigma^2 = 0`).
const SIGMA2_FLOOR: f64 = 1e-300;

/// The correlation `exp(-theta_u (a_u - b_u)^2 - theta_v (a_v - b_v)^2)`.
pub(crate) fn correlation(theta: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let (du, dv) = (a[0] - b[0], a[1] - b[1]);
    math::exp(-theta[0] * du * du - theta[1] * dv * dv)
}

/// The correlation matrix `R_ij = R(x_i, x_j) + nu delta_ij` of the points `x`.
pub(crate) fn correlation_matrix(theta: [f64; 2], x: &[[f64; 2]]) -> DMatrix<f64> {
    let n = x.len();
    DMatrix::from_fn(n, n, |i, j| {
        correlation(theta, x[i], x[j]) + if i == j { NUGGET } else { 0.0 }
    })
}

/// A fitted ordinary Kriging model.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub(crate) struct Kriging {
    x: Vec<[f64; 2]>,
    theta: [f64; 2],
    mu: f64,
    sigma2: f64,
    /// `R^-1 (y - mu 1)`.
    alpha: DVector<f64>,
    chol: Cholesky<f64, Dyn>,
    /// `R^-1 1`.
    r_inv_one: DVector<f64>,
    /// `1^T R^-1 1`.
    one_r_inv_one: f64,
    ln_likelihood: f64,
}

impl Kriging {
    /// Fits the model to `y` at `x` with `theta` chosen by maximum likelihood (module doc).
    /// Errors (naming `plan`) for fewer than 2 points, different lengths, non-finite data,
    /// or when no `theta` gives a positive-definite correlation matrix.
    pub fn fit(x: &[[f64; 2]], y: &[f64]) -> Result<Kriging> {
        check_data(x, y)?;
        let (lo, hi) = LOG10_THETA;
        let level = |i: usize| lo + (hi - lo) * i as f64 / (GRID_POINTS - 1) as f64;
        let mut best: Option<([f64; 2], Kriging)> = None;
        let consider = |t: [f64; 2], best: &mut Option<([f64; 2], Kriging)>| {
            if let Some(k) =
                Kriging::fit_with(x, y, [math::powf(10f64, t[0]), math::powf(10f64, t[1])])
            {
                if best
                    .as_ref()
                    .is_none_or(|b| k.ln_likelihood > b.1.ln_likelihood)
                {
                    *best = Some((t, k));
                }
            }
        };
        for i in 0..GRID_POINTS {
            for j in 0..GRID_POINTS {
                consider([level(i), level(j)], &mut best);
            }
        }
        let mut t = match &best {
            Some(b) => b.0,
            None => {
                return Err(RideError::field(
                    "plan",
                    "no correlation length gives a positive-definite Kriging system",
                ))
            }
        };
        let mut step = COMPASS_STEPS.0;
        while step >= COMPASS_STEPS.1 {
            let here = best
                .as_ref()
                .map_or(f64::NEG_INFINITY, |b| b.1.ln_likelihood);
            for d in [[step, 0.0], [-step, 0.0], [0.0, step], [0.0, -step]] {
                let next = [(t[0] + d[0]).clamp(lo, hi), (t[1] + d[1]).clamp(lo, hi)];
                consider(next, &mut best);
            }
            match &best {
                Some(b) if b.1.ln_likelihood > here => t = b.0,
                _ => step *= 0.5,
            }
        }
        best.map(|b| b.1).ok_or_else(|| {
            RideError::Numerical("Kriging: the likelihood search lost its start".into())
        })
    }

    /// The model with a fixed `theta`; `None` when `R` is not positive definite or the fit
    /// is not finite. The caller has checked the data.
    fn fit_with(x: &[[f64; 2]], y: &[f64], theta: [f64; 2]) -> Option<Kriging> {
        let n = x.len();
        let chol = correlation_matrix(theta, x).cholesky()?;
        let one = DVector::from_element(n, 1.0);
        let r_inv_one = chol.solve(&one);
        let one_r_inv_one = r_inv_one.sum();
        let y = DVector::from_column_slice(y);
        let mu = r_inv_one.dot(&y) / one_r_inv_one;
        let resid = y.add_scalar(-mu);
        let alpha = chol.solve(&resid);
        let sigma2 = (resid.dot(&alpha) / n as f64).max(0.0);
        let ln_det: f64 = chol
            .l_dirty()
            .diagonal()
            .iter()
            .map(|d| 2.0 * math::ln(*d))
            .sum();
        let ln_likelihood = -0.5 * n as f64 * math::ln(sigma2.max(SIGMA2_FLOOR)) - 0.5 * ln_det;
        let finite = mu.is_finite()
            && one_r_inv_one > 0.0
            && ln_likelihood.is_finite()
            && alpha.iter().all(|a| a.is_finite());
        finite.then(|| Kriging {
            x: x.to_vec(),
            theta,
            mu,
            sigma2,
            alpha,
            chol,
            r_inv_one,
            one_r_inv_one,
            ln_likelihood,
        })
    }

    /// The predictor `y^(x)` at `x = (u, v)` (no linear solve: the fast path).
    pub fn mean(&self, u: f64, v: f64) -> f64 {
        self.mu
            + self
                .x
                .iter()
                .zip(self.alpha.iter())
                .map(|(xi, a)| a * correlation(self.theta, [u, v], *xi))
                .sum::<f64>()
    }

    /// The predictor and its mean squared error `(y^(x), s^2(x))` at `x = (u, v)`.
    pub fn predict(&self, u: f64, v: f64) -> (f64, f64) {
        let r = DVector::from_iterator(
            self.x.len(),
            self.x.iter().map(|xi| correlation(self.theta, [u, v], *xi)),
        );
        let mean = self.mu + r.dot(&self.alpha);
        let r_inv_r = self.chol.solve(&r);
        let gap = 1.0 - self.r_inv_one.dot(&r);
        let mse = self.sigma2 * (1.0 - r.dot(&r_inv_r) + gap * gap / self.one_r_inv_one);
        (mean, mse.max(0.0))
    }

    /// The correlation parameters `[theta_u, theta_v]`, per squared normalised unit.
    pub(crate) fn theta(&self) -> [f64; 2] {
        self.theta
    }

    /// The estimated constant mean `mu`.
    pub fn mu(&self) -> f64 {
        self.mu
    }

    /// The estimated process variance `sigma^2`.
    pub(crate) fn sigma2(&self) -> f64 {
        self.sigma2
    }

    /// The concentrated log-likelihood `-(n/2) ln sigma^2 - (1/2) ln det R`.
    pub(crate) fn ln_likelihood(&self) -> f64 {
        self.ln_likelihood
    }
}

/// Rejects fewer than 2 points, unequal lengths and non-finite data (errors name `plan`).
fn check_data(x: &[[f64; 2]], y: &[f64]) -> Result<()> {
    if x.len() < 2 || x.len() != y.len() {
        return Err(RideError::field(
            "plan",
            format!(
                "Kriging needs at least 2 points with one value each, got {} points and {} values",
                x.len(),
                y.len()
            ),
        ));
    }
    let finite = x.iter().flatten().chain(y).all(|v| v.is_finite());
    if !finite {
        return Err(RideError::field("plan", "Kriging data must be finite"));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two points on the line `v = 0.5`: the closed forms of the module doc with
    /// `R = [[1, rho], [rho, 1]]` (nugget neglected, 1e-8 tolerance): `mu = (y1 + y2) / 2`,
    /// `sigma^2 = d^2 / (1 - rho)` with `d = (y2 - y1) / 2`,
    /// `y^ = mu + d (r2 - r1) / (1 - rho)`, and
    /// `s^2 = sigma^2 [1 - (r1^2 + r2^2 - 2 rho r1 r2) / (1 - rho^2) + (1 - (r1 + r2) / (1 + rho))^2 (1 + rho) / 2]`.
    #[test]
    fn two_points_match_the_closed_form() {
        let x = [[0.2, 0.5], [0.7, 0.5]];
        let y = [1.0, 3.0];
        let theta = [3.0, 5.0];
        let k = Kriging::fit_with(&x, &y, theta).unwrap();
        let rho = (-3.0f64 * 0.25).exp();
        let d = 1.0;
        assert!((k.mu() - 2.0).abs() < 1e-8, "{}", k.mu());
        let s2 = d * d / (1.0 - rho);
        assert!(
            (k.sigma2() / s2 - 1.0).abs() < 1e-8,
            "{} vs {s2}",
            k.sigma2()
        );
        for p in [[0.4, 0.5], [0.4, 0.8], [0.95, 0.1], [0.2, 0.5]] {
            let r1 = correlation(theta, p, x[0]);
            let r2 = correlation(theta, p, x[1]);
            let mean = 2.0 + d * (r2 - r1) / (1.0 - rho);
            let mse = s2
                * (1.0 - (r1 * r1 + r2 * r2 - 2.0 * rho * r1 * r2) / (1.0 - rho * rho)
                    + (1.0 - (r1 + r2) / (1.0 + rho)).powi(2) * (1.0 + rho) / 2.0);
            let (m, v) = k.predict(p[0], p[1]);
            assert!((m - mean).abs() < 1e-8, "{p:?}: {m} vs {mean}");
            assert!((v - mse).abs() < 1e-8 * s2, "{p:?}: {v} vs {mse}");
            assert!((k.mean(p[0], p[1]) - m).abs() < 1e-12);
        }
    }

    fn toy() -> (Vec<[f64; 2]>, Vec<f64>) {
        let x: Vec<[f64; 2]> = (0..12)
            .map(|i| {
                let t = i as f64 / 11.0;
                [t, (7.0 * t).fract()]
            })
            .collect();
        let y = x
            .iter()
            .map(|p| (2.0 * p[0]).sin() + 0.5 * (3.0 * p[1]).cos())
            .collect();
        (x, y)
    }

    /// The concentrated likelihood plus its dropped constants equals the Gaussian
    /// log-density of the data (LU inverse and determinant, not the Cholesky path).
    #[test]
    fn likelihood_is_the_gaussian_density() {
        let (x, y) = toy();
        let theta = [2.0, 8.0];
        let k = Kriging::fit_with(&x, &y, theta).unwrap();
        let n = x.len() as f64;
        let r = correlation_matrix(theta, &x);
        let lu = r.clone().lu();
        let inv = lu.try_inverse().unwrap();
        let e = DVector::from_iterator(x.len(), y.iter().map(|v| v - k.mu()));
        let s2 = k.sigma2();
        let density = -0.5 * n * (2.0 * std::f64::consts::PI * s2).ln()
            - 0.5 * r.determinant().ln()
            - 0.5 * (e.transpose() * &inv * &e)[0] / s2;
        let expected = k.ln_likelihood() - 0.5 * n * (2.0 * std::f64::consts::PI).ln() - 0.5 * n;
        assert!((density - expected).abs() < 1e-6, "{density} vs {expected}");
        // the GLS mean
        let one = DVector::from_element(x.len(), 1.0);
        let yv = DVector::from_column_slice(&y);
        let mu = (one.transpose() * &inv * &yv)[0] / (one.transpose() * &inv * &one)[0];
        assert!((mu - k.mu()).abs() < 1e-6);
    }

    #[test]
    fn maximum_likelihood_beats_a_fine_grid() {
        let (x, y) = toy();
        let k = Kriging::fit(&x, &y).unwrap();
        let n = 41;
        let (lo, hi) = LOG10_THETA;
        let mut grid_best = f64::NEG_INFINITY;
        for i in 0..n {
            for j in 0..n {
                let t = |i: usize| 10f64.powf(lo + (hi - lo) * i as f64 / (n - 1) as f64);
                if let Some(g) = Kriging::fit_with(&x, &y, [t(i), t(j)]) {
                    grid_best = grid_best.max(g.ln_likelihood());
                }
            }
        }
        assert!(
            k.ln_likelihood() >= grid_best - 1e-6,
            "{} vs grid {grid_best}",
            k.ln_likelihood()
        );
    }

    #[test]
    fn interpolates_with_zero_variance_at_the_samples() {
        let (x, y) = toy();
        let k = Kriging::fit(&x, &y).unwrap();
        let far = (0..=20)
            .flat_map(|i| (0..=20).map(move |j| (i as f64 / 20.0, j as f64 / 20.0)))
            .map(|(u, v)| k.predict(u, v).1)
            .fold(0.0, f64::max);
        assert!(far > 0.0);
        for (p, yi) in x.iter().zip(&y) {
            let (m, v) = k.predict(p[0], p[1]);
            assert!((m - yi).abs() < 1e-6, "{m} vs {yi}");
            assert!(v <= 1e-6 * far, "{v} vs {far}");
        }
    }

    #[test]
    fn bad_data_names_the_plan() {
        assert!(Kriging::fit(&[[0.0, 0.0]], &[1.0])
            .unwrap_err()
            .to_string()
            .starts_with("plan"));
        assert!(Kriging::fit(&[[0.0, 0.0], [1.0, 1.0]], &[1.0, f64::NAN])
            .unwrap_err()
            .to_string()
            .starts_with("plan"));
        // Constant data: a flat predictor with zero variance.
        let k = Kriging::fit(&[[0.0, 0.0], [1.0, 1.0], [0.5, 0.2]], &[2.0; 3]).unwrap();
        let (m, v) = k.predict(0.3, 0.9);
        assert!((m - 2.0).abs() < 1e-9 && v < 1e-12, "{m} {v}");
    }
}
