//! Response models over the normalised design square `(u, v)`, the building blocks of the
//! response-based corrections ([`super::rba`]) and the data-fit baselines ([`super::datafit`]):
//!
//! - polynomials of degree 1 or 2, `p(u, v) = c^T m(u, v)` with the monomials
//!   `m = [1, u, v, u^2, u v, v^2]` (first 3 for degree 1), fitted by least squares with
//!   the Moore-Penrose pseudo-inverse of the (row-weighted) Vandermonde matrix (SVD);
//! - radial basis functions with a polynomial tail,
//!   `s(u, v) = sum_j w_j phi(|x - x_j|) + t^T m(u, v)`, interpolating the data: the Gram
//!   system `[Phi P; P^T 0] [w; t] = [y; 0]` is solved for each candidate shape parameter and
//!   the one with the least leave-one-out error is kept (Rippa's formula
//!   `e_k = w_k / (M^-1)_kk`, exact for the augmented system).

use super::Parameter;
use crate::error::{Result, RideError};
use crate::math;
use nalgebra::{DMatrix, DVector};
use serde::{Deserialize, Serialize};

/// Radial basis kernel `phi(r)`, `r` the distance in normalised coordinates, `e` the shape.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Kernel {
    /// Gaussian `phi = exp(-(e r)^2)`, constant tail.
    Gauss,
    /// Multiquadric `phi = sqrt(1 + (e r)^2)`, constant tail.
    Multiquadric,
    /// Thin-plate spline `phi = r^2 ln r`, linear tail, no shape parameter.
    ThinPlate,
}

/// Shape parameters `e` tried for the Gaussian and multiquadric kernels, per unit length.
const SHAPES: [f64; 7] = [0.25, 0.5, 1.0, 2.0, 4.0, 8.0, 16.0];

/// Singular values below this fraction of the largest count as zero (rank test).
const RANK_TOL: f64 = 1e-10;

/// Largest 1-norm condition number `|M|_1 |M^-1|_1` of an RBF system whose solution and
/// leave-one-out errors are trusted; flatter (worse conditioned) shapes are skipped.
const MAX_CONDITION: f64 = 1e10;

impl Kernel {
    /// All kernels with their name suffixes.
    pub const ALL: [(Kernel, &'static str); 3] = [
        (Kernel::Gauss, "gauss"),
        (Kernel::Multiquadric, "mq"),
        (Kernel::ThinPlate, "tps"),
    ];

    /// Name suffix: "gauss", "mq" or "tps".
    pub(crate) fn suffix(self) -> &'static str {
        Kernel::ALL
            .iter()
            .find(|(k, _)| *k == self)
            .map_or("", |(_, s)| s)
    }

    /// `phi(r)` with shape `e` (ignored by the thin-plate spline).
    fn phi(self, r: f64, e: f64) -> f64 {
        match self {
            Kernel::Gauss => math::exp(-(e * r).powi(2)),
            Kernel::Multiquadric => (1.0 + (e * r).powi(2)).sqrt(),
            Kernel::ThinPlate if r > 0.0 => r * r * math::ln(r),
            Kernel::ThinPlate => 0.0,
        }
    }

    /// Degree of the polynomial tail that makes the interpolation problem well posed.
    fn tail_degree(self) -> usize {
        match self {
            Kernel::ThinPlate => 1,
            Kernel::Gauss | Kernel::Multiquadric => 0,
        }
    }

    /// Candidate shape parameters (`None`: the kernel has none).
    fn shapes(self) -> Vec<Option<f64>> {
        match self {
            Kernel::ThinPlate => vec![None],
            Kernel::Gauss | Kernel::Multiquadric => SHAPES.iter().map(|&e| Some(e)).collect(),
        }
    }
}

/// Which response model: a polynomial of degree 1 or 2, or an RBF model.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ResponseKind {
    /// Polynomial of degree 1 or 2 in `(u, v)`.
    Poly(usize),
    /// Radial basis function interpolant.
    Rbf(Kernel),
}

impl ResponseKind {
    /// Rejects polynomial degrees other than 1 and 2 (error names `approach`).
    pub fn check(self) -> Result<()> {
        match self {
            ResponseKind::Poly(d) if !(1..=2).contains(&d) => Err(RideError::field(
                "approach",
                format!("polynomial degree must be 1 or 2, got {d}"),
            )),
            _ => Ok(()),
        }
    }

    /// Fewest samples that determine the model: the number of polynomial coefficients, or
    /// one more than the RBF tail has (so that leave-one-out leaves a well-posed problem).
    pub(crate) fn min_samples(self) -> usize {
        match self {
            ResponseKind::Poly(d) => terms(d),
            ResponseKind::Rbf(k) => terms(k.tail_degree()) + 1,
        }
    }

    /// Name part: "poly1", "poly2", "rbf-gauss", ...
    pub fn name(self) -> String {
        match self {
            ResponseKind::Poly(d) => format!("poly{d}"),
            ResponseKind::Rbf(k) => format!("rbf-{}", k.suffix()),
        }
    }
}

/// Number of monomials of degree `<= d` in two variables, `(d + 1)(d + 2)/2`.
pub fn terms(d: usize) -> usize {
    (d + 1) * (d + 2) / 2
}

/// The monomials `[1, u, v, u^2, u v, v^2]`; a degree-`d` model uses the first `terms(d)`.
fn monomials(u: f64, v: f64) -> [f64; 6] {
    [1.0, u, v, u * u, u * v, v * v]
}

/// Names of the monomials, for parameter reports.
const MONOMIAL_NAMES: [&str; 6] = ["1", "u", "v", "uu", "uv", "vv"];

/// A fitted response model over `(u, v)`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub(crate) enum Response {
    /// `p(u, v) = c^T m(u, v)`.
    Poly {
        /// Coefficients of `[1, u, v, u^2, u v, v^2]` (first `terms(degree)`).
        coefficients: Vec<f64>,
    },
    /// `s(u, v) = sum_j w_j phi(|x - x_j|) + t^T m(u, v)`.
    Rbf {
        /// Kernel.
        kernel: Kernel,
        /// Shape parameter chosen by leave-one-out (none for the thin-plate spline).
        shape: Option<f64>,
        /// Centres `x_j = [u_j, v_j]` (the samples).
        centres: Vec<[f64; 2]>,
        /// Weights `w_j`.
        weights: Vec<f64>,
        /// Tail coefficients `t` of `[1]` or `[1, u, v]`.
        tail: Vec<f64>,
    },
}

impl Response {
    /// The model's value at `(u, v)`.
    pub fn value(&self, u: f64, v: f64) -> f64 {
        let m = monomials(u, v);
        match self {
            Response::Poly { coefficients } => coefficients.iter().zip(m).map(|(c, x)| c * x).sum(),
            Response::Rbf {
                kernel,
                shape,
                centres,
                weights,
                tail,
            } => {
                let e = shape.unwrap_or(1.0);
                let radial: f64 = centres
                    .iter()
                    .zip(weights)
                    .map(|(c, w)| w * kernel.phi(distance(u - c[0], v - c[1]), e))
                    .sum();
                radial + tail.iter().zip(m).map(|(t, x)| t * x).sum::<f64>()
            }
        }
    }

    /// The model's parameters named with `prefix`: `c_1, c_u, ...` or `shape, w_0, ...,
    /// t_1, ...`.
    pub fn parameters(&self, prefix: &str) -> Vec<Parameter> {
        let named = |name: String, value: f64| Parameter {
            name: format!("{prefix}{name}"),
            value,
        };
        match self {
            Response::Poly { coefficients } => coefficients
                .iter()
                .zip(MONOMIAL_NAMES)
                .map(|(&c, n)| named(format!("c_{n}"), c))
                .collect(),
            Response::Rbf {
                shape,
                weights,
                tail,
                ..
            } => shape
                .map(|e| named("shape".into(), e))
                .into_iter()
                .chain(
                    weights
                        .iter()
                        .enumerate()
                        .map(|(j, &w)| named(format!("w_{j}"), w)),
                )
                .chain(
                    tail.iter()
                        .zip(MONOMIAL_NAMES)
                        .map(|(&t, n)| named(format!("t_{n}"), t)),
                )
                .collect(),
        }
    }
}

/// One least-squares row `g c^T m(u, v) ~ t` of a polynomial fit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Row {
    /// Normalised Ks.
    pub u: f64,
    /// Normalised Cs.
    pub v: f64,
    /// Row weight `g`.
    pub g: f64,
    /// Target `t`.
    pub t: f64,
}

/// Least squares `min_c sum_i (g_i c^T m(u_i, v_i) - t_i)^2` for a degree-`d` polynomial,
/// `c = A^+ t` with `A_ij = g_i m_j(u_i, v_i)` and `A^+` the pseudo-inverse (SVD). Errors
/// (naming `plan`) when `A` is rank deficient: the points do not determine the polynomial.
/// Returns the model and a note on the rank and condition of `A`.
fn fit_poly(d: usize, rows: &[Row]) -> Result<(Response, String)> {
    ResponseKind::Poly(d).check()?;
    let m = terms(d);
    let a = DMatrix::from_fn(rows.len(), m, |i, j| {
        rows[i].g * monomials(rows[i].u, rows[i].v)[j]
    });
    let t = DVector::from_iterator(rows.len(), rows.iter().map(|r| r.t));
    let svd = a.svd(true, true);
    let s_max = svd.singular_values.max();
    let s_min = svd.singular_values.min();
    let full_rank = s_min > RANK_TOL * s_max; // false for NaN too
    if rows.len() < m || !full_rank {
        return Err(RideError::field(
            "plan",
            format!(
                "the sample points do not determine a degree-{d} polynomial ({m} coefficients)"
            ),
        ));
    }
    let c = svd
        .solve(&t, 0.0)
        .map_err(|e| RideError::Numerical(format!("pseudo-inverse: {e}")))?;
    Ok((
        Response::Poly {
            coefficients: c.iter().copied().collect(),
        },
        format!("full rank {m}, condition number {:.3e}", s_max / s_min),
    ))
}

/// The RBF interpolant of `y` at the centres `x` with the `kernel`, its shape parameter
/// chosen among the candidates by the least root-mean-square leave-one-out error; shapes whose
/// system has a condition number above [`MAX_CONDITION`] are skipped (their solution and
/// leave-one-out errors are rounding noise). Errors (naming `plan`) with too few points or
/// when no candidate gives a well-conditioned system.
/// Returns the model and a note on the chosen shape and its leave-one-out error.
fn fit_rbf(kernel: Kernel, x: &[[f64; 2]], y: &[f64]) -> Result<(Response, String)> {
    let n = x.len();
    let q = terms(kernel.tail_degree());
    if n < q + 1 {
        return Err(RideError::field(
            "plan",
            format!(
                "an RBF model with a {q}-term tail needs at least {} samples",
                q + 1
            ),
        ));
    }
    let mut best: Option<(f64, Option<f64>, DVector<f64>)> = None;
    for shape in kernel.shapes() {
        let m = gram(kernel, shape, x);
        let norm1 = |a: &DMatrix<f64>| {
            a.column_iter()
                .map(|c| c.iter().map(|v| v.abs()).sum::<f64>())
                .fold(0.0, f64::max)
        };
        let Some(inv) = m.clone().try_inverse() else {
            continue;
        };
        let conditioned = norm1(&m) * norm1(&inv) <= MAX_CONDITION; // false for NaN too
        if !conditioned {
            continue;
        }
        let rhs = DVector::from_fn(n + q, |i, _| if i < n { y[i] } else { 0.0 });
        let sol = &inv * rhs;
        let loo = ((0..n).map(|k| (sol[k] / inv[(k, k)]).powi(2)).sum::<f64>() / n as f64).sqrt();
        if loo.is_finite()
            && sol.iter().all(|s| s.is_finite())
            && best.as_ref().is_none_or(|b| loo < b.0)
        {
            best = Some((loo, shape, sol));
        }
    }
    let (loo, shape, sol) = best.ok_or_else(|| {
        RideError::field(
            "plan",
            format!("the RBF system is singular or has a condition number above {MAX_CONDITION:e} for every shape parameter"),
        )
    })?;
    let note = match shape {
        Some(e) => format!("shape {e} by leave-one-out, LOO rms error {loo:.3e}"),
        None => format!("no shape parameter, LOO rms error {loo:.3e}"),
    };
    Ok((rbf_model(kernel, shape, x, &sol), note))
}

/// The augmented Gram matrix `M = [Phi P; P^T 0]`, `Phi_ij = phi(|x_i - x_j|)`,
/// `P_ij = m_j(x_i)` over the tail's monomials.
fn gram(kernel: Kernel, shape: Option<f64>, x: &[[f64; 2]]) -> DMatrix<f64> {
    let (n, q) = (x.len(), terms(kernel.tail_degree()));
    let e = shape.unwrap_or(1.0);
    DMatrix::from_fn(n + q, n + q, |i, j| match (i < n, j < n) {
        (true, true) => kernel.phi(distance(x[i][0] - x[j][0], x[i][1] - x[j][1]), e),
        (true, false) => monomials(x[i][0], x[i][1])[j - n],
        (false, true) => monomials(x[j][0], x[j][1])[i - n],
        (false, false) => 0.0,
    })
}

/// The model from the solution `[w; t]` of the Gram system.
fn rbf_model(kernel: Kernel, shape: Option<f64>, x: &[[f64; 2]], sol: &DVector<f64>) -> Response {
    let n = x.len();
    Response::Rbf {
        kernel,
        shape,
        centres: x.to_vec(),
        weights: sol.rows(0, n).iter().copied().collect(),
        tail: sol.rows(n, sol.len() - n).iter().copied().collect(),
    }
}

/// One sample of a model `S_k = a_k + b_k c(u, v)`: the normalised design, offsets `a`,
/// gains `b` and HiFi values `F` of the three criteria.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct AffineSample {
    /// Normalised Ks.
    pub u: f64,
    /// Normalised Cs.
    pub v: f64,
    /// Offsets `a_k` (the LoFi for an additive correction, else 0).
    pub a: [f64; 3],
    /// Gains `b_k` (the LoFi for a multiplicative correction, else 1).
    pub b: [f64; 3],
    /// HiFi criteria `F_k`.
    pub f: [f64; 3],
}

/// Fits the response `c` of `S_k = a_k + b_k c(u, v)` to the HiFi values, one response per
/// group of criteria. A polynomial minimises the relative errors `(S_k - F_k) / F_k`, i.e.
/// rows `(b_k / F_k) c(u, v) ~ (F_k - a_k) / F_k` over the samples and the group's criteria;
/// an RBF model interpolates `c_i = (F_k - a_k) / b_k` (one criterion per group). Returns each
/// response with its fit note.
pub(crate) fn fit_affine(
    kind: ResponseKind,
    groups: &[&[usize]],
    samples: &[AffineSample],
) -> Result<Vec<(Response, String)>> {
    groups
        .iter()
        .map(|group| match (kind, group) {
            (ResponseKind::Poly(d), _) => {
                let rows: Vec<Row> = samples
                    .iter()
                    .flat_map(|s| {
                        group.iter().map(move |&k| Row {
                            u: s.u,
                            v: s.v,
                            g: s.b[k] / s.f[k],
                            t: (s.f[k] - s.a[k]) / s.f[k],
                        })
                    })
                    .collect();
                fit_poly(d, &rows)
            }
            (ResponseKind::Rbf(kernel), &&[k]) => {
                let x: Vec<[f64; 2]> = samples.iter().map(|s| [s.u, s.v]).collect();
                let y: Vec<f64> = samples.iter().map(|s| (s.f[k] - s.a[k]) / s.b[k]).collect();
                fit_rbf(kernel, &x, &y)
            }
            (ResponseKind::Rbf(_), _) => Err(RideError::field(
                "scheme",
                "an RBF model interpolates one criterion; use the per-criterion scheme",
            )),
        })
        .collect()
}

/// Name of the fitting method of `kind`, for diagnostics.
pub fn method(kind: ResponseKind) -> &'static str {
    match kind {
        ResponseKind::Poly(_) => "least squares (SVD pseudo-inverse)",
        ResponseKind::Rbf(_) => "rbf interpolation",
    }
}

/// Euclidean length of `(du, dv)` in the normalised design square. Not `f64::hypot`:
/// its overflow-safe libm routine made a surrogate map several times slower in wasm, and
/// normalised coordinates (|du|, |dv| <= about 1) cannot overflow.
fn distance(du: f64, dv: f64) -> f64 {
    (du * du + dv * dv).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn polynomial_recovers_exact_quadratic() {
        let f = |u: f64, v: f64| 1.0 - 2.0 * u + 0.5 * v + 3.0 * u * u - u * v + 0.25 * v * v;
        let rows: Vec<Row> = (0..3)
            .flat_map(|i| (0..3).map(move |j| (i as f64 / 2.0, j as f64 / 2.0)))
            .map(|(u, v)| Row {
                u,
                v,
                g: 2.0,
                t: 2.0 * f(u, v),
            })
            .collect();
        let (p, _) = fit_poly(2, &rows).unwrap();
        assert!((p.value(0.3, 0.7) - f(0.3, 0.7)).abs() < 1e-12);
        let Response::Poly { coefficients } = &p else {
            unreachable!()
        };
        assert!((coefficients[4] + 1.0).abs() < 1e-12);
        // Five points cannot determine six coefficients; nor can collinear points.
        assert!(fit_poly(2, &rows[..5]).is_err());
        let line: Vec<Row> = rows.iter().filter(|r| r.u == r.v).copied().collect();
        assert!(fit_poly(1, &line)
            .unwrap_err()
            .to_string()
            .starts_with("plan"));
    }

    #[test]
    fn rbf_interpolates_and_loo_matches_refits() {
        let x: [[f64; 2]; 6] = [
            [0.0, 0.2],
            [0.3, 1.0],
            [0.6, 0.0],
            [1.0, 0.7],
            [0.5, 0.5],
            [0.9, 0.1],
        ];
        let y: Vec<f64> = x.iter().map(|p| (3.0 * p[0]).sin() + p[1] * p[1]).collect();
        for (kernel, _) in Kernel::ALL {
            let (s, _) = fit_rbf(kernel, &x, &y).unwrap();
            for (p, yi) in x.iter().zip(&y) {
                assert!((s.value(p[0], p[1]) - yi).abs() < 1e-9, "{kernel:?}");
            }
            // Rippa's formula against explicit refits without point k, at the chosen shape.
            let Response::Rbf { shape, .. } = &s else {
                unreachable!()
            };
            let (_, note) = fit_rbf(kernel, &x, &y).unwrap();
            let mut sq = 0.0;
            for k in 0..x.len() {
                let (xs, ys): (Vec<_>, Vec<_>) = x
                    .iter()
                    .zip(&y)
                    .enumerate()
                    .filter(|(i, _)| *i != k)
                    .map(|(_, (p, v))| (*p, *v))
                    .unzip();
                let fixed = refit_at(kernel, *shape, &xs, &ys);
                sq += (y[k] - fixed.value(x[k][0], x[k][1])).powi(2);
            }
            let loo = (sq / x.len() as f64).sqrt();
            let reported: f64 = note.rsplit(' ').next().unwrap().parse().unwrap();
            assert!(
                (reported / loo - 1.0).abs() < 1e-3,
                "{kernel:?}: {reported} vs {loo}"
            );
        }
        assert!(fit_rbf(Kernel::ThinPlate, &x[..3], &y[..3]).is_err());
    }

    /// The interpolant with a fixed shape (no selection), for the leave-one-out check.
    fn refit_at(kernel: Kernel, shape: Option<f64>, x: &[[f64; 2]], y: &[f64]) -> Response {
        let q = terms(kernel.tail_degree());
        let rhs = DVector::from_fn(x.len() + q, |i, _| y.get(i).copied().unwrap_or(0.0));
        let sol = gram(kernel, shape, x).lu().solve(&rhs).unwrap();
        rbf_model(kernel, shape, x, &sol)
    }
}
