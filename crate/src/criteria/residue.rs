//! The residue route: the exact variances of [`super::criteria_exact`] for a family of
//! models over the front design `(ks, cs)`, from the poles and residues of the transfer
//! functions in polynomial form, in a few microseconds a point.
//!
//! **Family.** `M q'' + C(cs) q' + K(ks) q = Kr r + Cr r'` with `K = K0 + ks dK`,
//! `C = C0 + cs dK` and `dK` of rank one (both front corners of the symmetric half car
//! move with one deflection). In coordinates `p = T^-1 q` whose `j`-th entry is that
//! deflection, `Q(s) = T^T (M s^2 + C s + K) T = Q0(s) + kappa(s) dK_jj e_j e_j^T` with
//! `kappa(s) = ks + cs s`, so every determinant and cofactor is affine in `kappa`:
//!
//! ```text
//! D(s)     = det Q(s)                = det Q0(s) + kappa(s) dK_jj det Q0_jj(s)
//! N_go(s)  = x_o(s)^T adj Q(s) y_g(s) = alpha_go(s) + kappa(s) beta_go(s)
//! alpha_go = x_o^T adj(Q0) y_g,        beta_go = dK_jj x_o,-j^T adj(Q0_jj) y_g,-j
//! ```
//!
//! (`Q0_jj`: `Q0` without row and column `j`; `x_o(s) = T^T (Yq + s Yv + s^2 Ya)` the output
//! row, `y_g(s) = T^T (Kr_g + s Cr_g)` the input of wheel group `g`). These polynomials are
//! built once, without subtracting one determinant from another; a point then costs the
//! `2n + 1` coefficients of `D`, its roots, and Horner sums.
//!
//! **Residues.** With `T_g(s) = N_g(s) / D(s) + Yr_g` and `lambda_k` the (simple) roots of
//! `D`, the road-velocity transfer is `T_g(s) / s = sum_k rho_gk / (s - lambda_k) + G_g / s`,
//! `rho_gk = N_g(lambda_k) / (lambda_k D'(lambda_k))`, `G_g = N_g(0) / D(0) + Yr_g`, and the
//! variance is the modal route's closed form ([`super::criteria_modal`]):
//!
//! ```text
//! var = W sum_{g >= l} m_gl [ Re sum_km rho_gk rho_lm e^{lambda_m D_gl} / -(lambda_k + lambda_m)
//!                              - 2 G_g 1(g != l) Re sum_k rho_lk (e^{lambda_k D_gl} - 1) / lambda_k ]
//!     + W sum_gl G_g G_l min(tau_g, tau_l)
//! ```
//!
//! (`D_gl = tau_g - tau_l >= 0`, `m_gl = 2` for `g != l`, else 1). Complex roots come in
//! exact conjugate pairs, so every sum runs over one root of each pair (real part, doubled).
//! `D'(lambda_k) = d_2n prod_{i != k} (lambda_k - lambda_i)` from the roots, which makes the
//! partial fractions exact for the polynomial whose roots they are.
//!
//! **Roots.** The Aberth-Ehrlich iteration on the four upper-half-plane roots, started
//! from the roots at a reference design (computed once by QR), usually 2 to 6 iterations;
//! where it does not converge (a pair of roots turning real) the companion matrix by
//! Francis QR ([`super::poly::roots`]). Both are deterministic functions of `(ks, cs)`,
//! so a map equals its point evaluations bit for bit.
//!
//! **Error bound.** Each result carries a first-order bound on the relative error of its
//! variances, `bound = E / var`, where `E` sums, over every product in the sums, the
//! product's sensitivity times the error of each factor:
//!
//! - a residue: `4 (2n + 2) u |sum_i |n_i| |lambda|^i| / |lambda D'(lambda)|` (rounding of
//!   the numerator, `u = 2^-53`; the absolute coefficients bound any cancellation between
//!   `alpha` and `kappa beta` too) plus `eps_k |rho_k|`, the root error's effect:
//!   `eps_k = (2n + 2) dl_k / |lambda_k| + 2 (2n - 1) dl_max / gap_k`, where
//!   `dl_k = (|D(lambda_k)| + u sum_i d_i |lambda_k|^i) / |D'(lambda_k)|` is the first-order
//!   error of the root and `gap_k` its distance to the nearest other root;
//! - `S_km` and `e^{lambda_m D}`: `8 (2n + 2) u` of rounding plus `dl_max / sigma_min +
//!   dl_max tau_max` from the roots (`|lambda_k + lambda_m| >= 2 sigma_min`);
//! - the static gains: `4 u` of their magnitude.
//!
//! Magnitudes are taken as `|re| + |im|` (at most `sqrt 2` over). Nearly repeated roots
//! (residues of opposite signs cancelling, or roots not resolved: `dl_k >= gap_k / 100`)
//! make the bound large or the route decline; the caller then uses an exact route. The
//! route also declines when no root finder converges or a root is not in the left half
//! plane. The bound is first order (products of two errors are dropped); on the test
//! matrix it exceeds the observed error by one to three orders of magnitude.

use super::exact::check_stationary;
use super::poly::{adjugate, l1, minor_det, recip, roots, value_and_slope, Poly, PolyMatrix};
use super::poly::{Roots, MAX_N, MAX_ROOTS};
use crate::error::{Result, RideError};
use crate::evaluate::Criteria;
use crate::math;
use crate::model::{LinearModel, N_OUT};
use crate::road::Road;
use nalgebra::DMatrix;
use num_complex::Complex64 as C64;

mod quarter;
mod roads;
mod shaped;
pub(crate) use quarter::quarter_shaped;
pub(crate) use roads::ResidueRoads;
pub(crate) use shaped::{PoleZeroFilter, ShapedResidueRoute};

/// Most generalised coordinates of a family (the symmetric half car has 4).
pub(crate) const MAX_DOF: usize = MAX_N;
/// Coefficients of `D` and of every numerator (degree `2n` at most).
const NC: usize = MAX_ROOTS + 1;
/// Most wheel groups (distinct delays) of one source.
const MAX_GROUPS: usize = 2;
/// Most independent sources (left and right tracks).
const MAX_SOURCES: usize = 2;

/// A wheel group of one source in polynomial form.
#[derive(Debug, Clone, PartialEq)]
struct Group {
    /// Delay behind the front axle, s.
    tau: f64,
    /// Road-displacement feed-through of each output.
    yr: [f64; N_OUT],
    /// `alpha_go`, ascending powers of `s`.
    alpha: [[f64; NC]; N_OUT],
    /// `beta_go`, ascending powers of `s` (degree `2n - 1` at most).
    beta: [[f64; NC]; N_OUT],
}

/// A model family over the front design, prepared for the residue route (module doc).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct ResidueFamily {
    /// Degree `2n` of `D`.
    deg: usize,
    /// `det Q0(s)`, ascending powers.
    d0: [f64; NC],
    /// `dK_jj det Q0_jj(s)`, ascending powers (degree `2n - 1` at most).
    e: [f64; NC],
    /// Wheel groups of each independent source, sorted by delay.
    sources: Vec<Vec<Group>>,
    /// Two-sided intensity `W` of each source's road velocity, m^2/s.
    intensity: f64,
    /// Size of the road feed-through, for the stationarity check.
    scale: f64,
    /// Roots of `D` at the reference design and their first-order change with the
    /// design: the Aberth iteration's start (`None` when some roots are real there).
    start: Option<Start>,
}

/// Roots `lambda0` of `D` at a reference design `(ks0, cs0)` and `c = -e(lambda0) /
/// D'(lambda0)`, so that `lambda0 + c (ks - ks0 + lambda0 (cs - cs0))` predicts the roots
/// at `(ks, cs)` to first order (`dD/dks = e(s)`, `dD/dcs = s e(s)`).
#[derive(Debug, Clone, PartialEq)]
struct Start {
    at: (f64, f64),
    roots: Roots,
    slope: [C64; MAX_ROOTS],
}

impl Start {
    /// The predicted roots at `(ks, cs)`.
    fn predict(&self, ks: f64, cs: f64) -> Roots {
        let mut r = self.roots;
        let (dk, dc) = (ks - self.at.0, cs - self.at.1);
        for k in 0..r.n {
            let z = r.z[k] + self.slope[k] * (r.z[k] * dc + dk);
            // Keep the guess a complex pair (Aberth works on the upper half plane).
            r.z[k] = C64::new(z.re, z.im.max(0.5 * r.z[k].im));
        }
        r
    }
}

/// Variances of one point by the residue route, or why the route declined.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Residue {
    /// Variances `[BAcc, DTL, SWS]` (m^2/s^4, N^2, m^2) and the bound on their relative error.
    Variances {
        /// The variances.
        var: [f64; N_OUT],
        /// First-order bound of the relative error of each variance (module doc).
        bound: f64,
    },
    /// The route cannot certify this point; the caller must use an exact route.
    Declined(Decline),
}

/// Why the residue route declined a point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Decline {
    /// No root finder converged, or two roots lie closer than 100 times their error
    /// (the first-order error analysis does not hold).
    Unresolved,
    /// `D` has a coefficient `<= 0` or a root with `Re >= 0`: not asymptotically stable
    /// as computed (the exact route gives the verdict).
    NotStable,
    /// A variance came out non-positive or not finite.
    BadVariance,
    /// The error bound (relative, of the variances) exceeds [`RESIDUE_TOLERANCE`].
    Bound(f64),
}

/// Largest error bound (relative, of each variance) the route accepts. The RMS error is
/// half of it; the criteria are wanted exact to `1e-8`.
pub const RESIDUE_TOLERANCE: f64 = 1e-9;

/// The criteria from one or more families at the same design: `var = sum_p w_p var_p`
/// (the symmetric half alone with correlated tracks; both halves of a mirror-symmetric
/// car with weights 1/2 with independent tracks, see [`crate::model::antisymmetric_half`]).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct ResidueRoute {
    parts: Vec<(ResidueFamily, f64)>,
}

/// The criteria of one point by the residue route, or why it declined.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Certified {
    /// RMS criteria and the bound on the relative error of their variances
    /// (at most [`RESIDUE_TOLERANCE`]).
    Exact {
        /// The RMS criteria.
        criteria: Criteria,
        /// Bound on the relative error of the variances.
        bound: f64,
    },
    /// The caller must use an exact route.
    Declined(Decline),
}

impl ResidueRoute {
    /// The route over `parts` (family, weight); fails on no part or a weight that is
    /// not finite and positive.
    pub(crate) fn new(parts: Vec<(ResidueFamily, f64)>) -> Result<ResidueRoute> {
        if parts.is_empty() || parts.iter().any(|(_, w)| !w.is_finite() || *w <= 0.0) {
            return Err(RideError::Numerical(
                "residue route: needs families with positive weights".into(),
            ));
        }
        Ok(ResidueRoute { parts })
    }

    /// The RMS criteria at `(ks, cs)` (N/m, N s/m) with their error bound, or why the
    /// route declines; errors as [`ResidueFamily::variances`].
    pub(crate) fn criteria(&self, ks: f64, cs: f64) -> Result<Certified> {
        let mut var = [0.0; N_OUT];
        let mut err = [0.0; N_OUT];
        for (family, weight) in &self.parts {
            match family.variances(ks, cs)? {
                Residue::Variances { var: v, bound } => {
                    add_part(&mut var, &mut err, *weight, &v, bound)
                }
                Residue::Declined(why) => return Ok(Certified::Declined(why)),
            }
        }
        Ok(certify(&var, &err))
    }
}

/// Adds a part's variances `v` with weight `weight` and its bound to the route's sums.
fn add_part(
    var: &mut [f64; N_OUT],
    err: &mut [f64; N_OUT],
    weight: f64,
    v: &[f64; N_OUT],
    bound: f64,
) {
    for o in 0..N_OUT {
        var[o] += weight * v[o];
        err[o] += weight * v[o] * bound;
    }
}

/// The RMS criteria of the summed variances `var` with errors `err`, or the bound that
/// exceeds [`RESIDUE_TOLERANCE`].
fn certify(var: &[f64; N_OUT], err: &[f64; N_OUT]) -> Certified {
    let bound = (0..N_OUT).map(|o| err[o] / var[o]).fold(0.0, f64::max);
    if bound.is_nan() || bound > RESIDUE_TOLERANCE {
        return Certified::Declined(Decline::Bound(bound));
    }
    Certified::Exact {
        criteria: Criteria::from_array(var.map(f64::sqrt)),
        bound,
    }
}

impl ResidueFamily {
    /// Prepares the family `K = K0 + ks dk`, `C = C0 + cs dc` of `base` (whose own front
    /// spring and damper are zero) on `road`; `reference` is a typical design `(ks, cs)`
    /// (the car's own), whose roots start every point's root finder.
    ///
    /// Fails when the family is not of this form (2 to [`MAX_DOF`] coordinates, `dk = dc`
    /// of rank one and positive), when an output feeds through the white road velocity,
    /// or on more than 2 wheel delays.
    pub(crate) fn new(
        base: &LinearModel,
        dk: &DMatrix<f64>,
        dc: &DMatrix<f64>,
        road: &Road,
        reference: (f64, f64),
    ) -> Result<ResidueFamily> {
        road.validate()?;
        let n = base.n();
        let unsuited = |why: &str| RideError::Numerical(format!("residue route: {why}"));
        if !(2..=MAX_DOF).contains(&n) || dk.shape() != (n, n) || dc.shape() != (n, n) {
            return Err(unsuited("the family needs 2 to 4 coordinates"));
        }
        // dK = dK_jj u u^T with u_j = 1, and dC = dK.
        let j = (0..n)
            .max_by(|&a, &b| dk[(a, a)].total_cmp(&dk[(b, b)]))
            .unwrap_or(0);
        let djj = dk[(j, j)];
        let size = dk.amax();
        if !djj.is_finite() || djj <= 0.0 {
            return Err(unsuited("the design term is not positive"));
        }
        let u: Vec<f64> = (0..n).map(|i| dk[(i, j)] / djj).collect();
        for r in 0..n {
            for c in 0..n {
                let rank_one = (dk[(r, c)] - djj * u[r] * u[c]).abs() <= 1e-9 * size;
                let same = (dk[(r, c)] - dc[(r, c)]).abs() <= 1e-9 * size;
                if !(rank_one && same) {
                    return Err(unsuited("the design term is not one spring and damper"));
                }
            }
        }
        // q = T p: T = I except row j, T_ji = -u_i (i != j); then u^T T = e_j^T.
        let mut t = DMatrix::<f64>::identity(n, n);
        for i in (0..n).filter(|&i| i != j) {
            t[(j, i)] = -u[i];
        }
        let tt = t.transpose();
        let (m, c, k) = (&tt * &base.m * &t, &tt * &base.c * &t, &tt * &base.k * &t);
        let mut q0: PolyMatrix = [[Poly::zero(); MAX_N]; MAX_N];
        for r in 0..n {
            for s in 0..n {
                q0[r][s] = Poly::new(&[k[(r, s)], c[(r, s)], m[(r, s)]]);
            }
        }
        // Q0 without row and column j, re-indexed.
        let keep: Vec<usize> = (0..n).filter(|&i| i != j).collect();
        let mut q0j: PolyMatrix = [[Poly::zero(); MAX_N]; MAX_N];
        for (r, &kr) in keep.iter().enumerate() {
            for (s, &ks) in keep.iter().enumerate() {
                q0j[r][s] = q0[kr][ks];
            }
        }
        let adj0 = adjugate(&q0, n);
        let adj0j = adjugate(&q0j, n - 1);
        let all: Vec<usize> = (0..n).collect();
        let deg = 2 * n;
        let d0 = fixed(&minor_det(&q0, &all, &all), deg);
        let e = fixed(
            &minor_det(&q0j, &all[..n - 1], &all[..n - 1]).scaled(djj),
            deg - 1,
        );
        // x^T adj y for vectors of polynomials.
        let bilinear = |adj: &PolyMatrix, x: &[Poly], y: &[Poly]| -> Poly {
            let mut acc = Poly::zero();
            for (r, xr) in x.iter().enumerate() {
                let mut z = Poly::zero();
                for (s, ys) in y.iter().enumerate() {
                    z = z.add_scaled(&adj[r][s].mul(ys), 1.0);
                }
                acc = acc.add_scaled(&xr.mul(&z), 1.0);
            }
            acc
        };
        // T^T v, and v without entry j.
        let transformed = |v: &[Poly]| -> Vec<Poly> {
            (0..n)
                .map(|r| (0..n).fold(Poly::zero(), |acc, s| acc.add_scaled(&v[s], tt[(r, s)])))
                .collect()
        };
        let drop_j = |v: &[Poly]| -> Vec<Poly> { keep.iter().map(|&i| v[i]).collect() };
        let rows: Vec<Vec<Poly>> = base
            .outputs
            .iter()
            .map(|o| {
                let x: Vec<Poly> = (0..n)
                    .map(|i| Poly::new(&[o.q[i], o.v[i], o.a[i]]))
                    .collect();
                transformed(&x)
            })
            .collect();
        let feed = base.outputs.iter().map(|o| o.r.amax()).fold(1.0, f64::max);
        // The white road velocity reaches an output through Ya M^-1 Cr (the exact
        // route's check, in the model's own coordinates).
        if base.state_space()?.dw.amax() > 1e-12 * feed {
            return Err(RideError::Numerical(
                "an output feeds through the white road velocity: its RMS is unbounded".into(),
            ));
        }
        let exc = base.excitation(road);
        if exc.sources.len() > MAX_SOURCES {
            return Err(unsuited("more than 2 independent tracks"));
        }
        let mut sources = Vec::with_capacity(exc.sources.len());
        for src in &exc.sources {
            // Wheels of one source with equal delays act as one group: delay, Kr and Cr
            // columns, road feed-through.
            type Raw = (f64, Vec<f64>, Vec<f64>, [f64; N_OUT]);
            let mut raw: Vec<Raw> = Vec::new();
            for &(w, tau) in &src.channels {
                let kr: Vec<f64> = (0..n).map(|i| base.kr[(i, w)]).collect();
                let cr: Vec<f64> = (0..n).map(|i| base.cr[(i, w)]).collect();
                let yr: [f64; N_OUT] = std::array::from_fn(|o| base.outputs[o].r[w]);
                match raw
                    .iter_mut()
                    .find(|g| (g.0 - tau).abs() <= 1e-12 * (1.0 + tau))
                {
                    Some(g) => {
                        for i in 0..n {
                            g.1[i] += kr[i];
                            g.2[i] += cr[i];
                        }
                        for o in 0..N_OUT {
                            g.3[o] += yr[o];
                        }
                    }
                    None => raw.push((tau, kr, cr, yr)),
                }
            }
            crate::order::sort_by_f64_key(&mut raw, |r| r.0);
            if raw.len() > MAX_GROUPS {
                return Err(unsuited("more than 2 wheel delays"));
            }
            let mut groups = Vec::with_capacity(raw.len());
            for (tau, kr, cr, yr) in raw {
                let input: Vec<Poly> = (0..n).map(|i| Poly::new(&[kr[i], cr[i]])).collect();
                let y = transformed(&input);
                let mut alpha = [[0.0; NC]; N_OUT];
                let mut beta = [[0.0; NC]; N_OUT];
                for o in 0..N_OUT {
                    // Its s^(2n+1) term is det(M) Ya M^-1 Cr, zero (checked above): what
                    // the products leave there is rounding, dropped.
                    let a = bilinear(&adj0, &rows[o], &y);
                    alpha[o] = fixed(&a, deg);
                    let b = bilinear(&adj0j, &drop_j(&rows[o]), &drop_j(&y));
                    beta[o] = fixed(&b.scaled(djj), deg - 1);
                }
                groups.push(Group {
                    tau,
                    yr,
                    alpha,
                    beta,
                });
            }
            sources.push(groups);
        }
        let mut family = ResidueFamily {
            deg,
            d0,
            e,
            sources,
            intensity: exc.intensity,
            scale: feed,
            start: None,
        };
        let d = family.characteristic(reference.0, reference.1);
        family.start = roots(&d[..=deg], None)
            .filter(|r| r.n == deg / 2 && r.pair[..r.n].iter().all(|&p| p))
            .map(|r| {
                let mut slope = [C64::new(0.0, 0.0); MAX_ROOTS];
                for k in 0..r.n {
                    let (_, dp) = value_and_slope(&d[..=deg], r.z[k]);
                    let (e, _) = value_and_slope(&family.e[..deg], r.z[k]);
                    slope[k] = -e * recip(dp);
                }
                Start {
                    at: reference,
                    roots: r,
                    slope,
                }
            });
        Ok(family)
    }

    /// Coefficients of `D(s) = det Q0(s) + (ks + cs s) dK_jj det Q0_jj(s)`.
    fn characteristic(&self, ks: f64, cs: f64) -> [f64; NC] {
        let mut d = [0.0; NC];
        for i in 0..=self.deg {
            d[i] = self.d0[i] + ks * self.e[i] + if i > 0 { cs * self.e[i - 1] } else { 0.0 };
        }
        d
    }

    /// The variances at front spring rate `ks` (N/m) and damper rate `cs` (N s/m), with
    /// their error bound, or the reason the route declines. Errors only on a road warp
    /// (non-stationary response), as the exact routes do.
    pub(crate) fn variances(&self, ks: f64, cs: f64) -> Result<Residue> {
        /// This family's own road.
        struct Own;
        impl OnPoint for Own {
            type Out = Residue;
            fn on<const NP: usize>(self, family: &ResidueFamily, point: &Point<NP>) -> Residue {
                family.accumulate(point, &family.delay_terms(point))
            }
        }
        Ok(match self.at(ks, cs, Own)? {
            Ok(residue) => residue,
            Err(why) => Residue::Declined(why),
        })
    }

    /// The road-independent part of the point `(ks, cs)` ([`Point`]) handed to `then`,
    /// or why the route declines there; errors on a road warp.
    fn at<V: OnPoint>(
        &self,
        ks: f64,
        cs: f64,
        then: V,
    ) -> Result<std::result::Result<V::Out, Decline>> {
        let deg = self.deg;
        let d = self.characteristic(ks, cs);
        if d[..=deg].iter().any(|&v| !v.is_finite() || v <= 0.0) {
            return Ok(Err(Decline::NotStable));
        }
        let guess = self.start.as_ref().map(|s| s.predict(ks, cs));
        let Some(found) = roots(&d[..=deg], guess.as_ref()) else {
            return Ok(Err(Decline::Unresolved));
        };
        if found.z[..found.n]
            .iter()
            .any(|l| l.re.is_nan() || l.re >= 0.0)
        {
            return Ok(Err(Decline::NotStable));
        }
        // Fixed-size loops over the kept roots: 4 when every root is in a pair (up to
        // 4 pairs), all 8 otherwise; unused places are zero.
        if found.n <= 4 {
            let point = self.point::<4>(ks, cs, &d, &found)?;
            Ok(point.map(|p| then.on(self, &p)))
        } else {
            let point = self.point::<MAX_ROOTS>(ks, cs, &d, &found)?;
            Ok(point.map(|p| then.on(self, &p)))
        }
    }

    /// The poles, the `S` table and each source's residues and static gains at
    /// `(ks, cs)` over `NP >= found.n` places for the roots (module doc); errors on a
    /// road warp (static gains of a source not summing to zero).
    fn point<const NP: usize>(
        &self,
        ks: f64,
        cs: f64,
        d: &[f64; NC],
        found: &Roots,
    ) -> Result<std::result::Result<Point<NP>, Decline>> {
        let deg = self.deg;
        let Some(p) = Poles::<NP>::new(&d[..=deg], found) else {
            return Ok(Err(Decline::Unresolved));
        };
        let table = STable::<NP>::new(&p);
        // Rounding of a residue (numerator, product, inverse), and of a term of the sums
        // with the roots' backward error turned into a relative error of D on the axis.
        let unit = f64::EPSILON / 2.0;
        let g_eval = 4.0 * (deg + 2) as f64 * unit;
        let g_sum = 8.0 * (deg + 2) as f64 * unit + 4.0 * p.backward * p.mu;
        let mut sources = [SourceResidues::<NP>::zero(); MAX_SOURCES];
        for (groups, res) in self.sources.iter().zip(sources.iter_mut()) {
            let ng = groups.len();
            // Residues rho[g][o] on the kept roots, their error bounds, static gains and
            // their errors.
            for (g, grp) in groups.iter().enumerate() {
                for o in 0..N_OUT {
                    // N = alpha + (ks + cs s) beta; `na` bounds its terms' magnitudes.
                    let (mut nc, mut na) = ([0.0; NC], [0.0; NC]);
                    for i in 0..NC {
                        let b = if i > 0 { cs * grp.beta[o][i - 1] } else { 0.0 };
                        let (x, y) = (grp.alpha[o][i], ks * grp.beta[o][i]);
                        nc[i] = x + y + b;
                        na[i] = x.abs() + y.abs() + b.abs();
                    }
                    let (mut re, mut im, mut bound) = ([0.0; NP], [0.0; NP], [0.0; NP]);
                    for i in 0..NC {
                        for k in 0..NP {
                            re[k] += nc[i] * p.pw.re[i][k];
                            im[k] += nc[i] * p.pw.im[i][k];
                            bound[k] += na[i] * p.pw_abs[i][k];
                        }
                    }
                    let r = &mut res.rho[g][o];
                    for k in 0..NP {
                        r.re[k] = re[k] * p.ild.re[k] - im[k] * p.ild.im[k];
                        r.im[k] = re[k] * p.ild.im[k] + im[k] * p.ild.re[k];
                        res.drho[g][o][k] = g_eval * bound[k] * p.ild_l1[k];
                    }
                    res.gain[g][o] = nc[0] / d[0] + grp.yr[o];
                    res.dgain[g][o] = 4.0 * unit * (na[0] / d[0] + grp.yr[o].abs());
                }
            }
            check_stationary(res.gain[..ng].iter().copied(), self.scale)?;
        }
        Ok(Ok(Point {
            poles: p,
            table,
            g_sum,
            sources,
        }))
    }

    /// The terms of the sums that depend on the wheel delays (module doc: the residue
    /// and box-exponential terms `t`, with their first-order errors `e`), per source,
    /// output and group, at this family's delays; without the intensity `W`.
    fn delay_terms<const NP: usize>(&self, point: &Point<NP>) -> DelayTerms {
        let (p, table, g_sum) = (&point.poles, &point.table, point.g_sum);
        let mut terms = [[[(0.0, 0.0); MAX_GROUPS]; N_OUT]; MAX_SOURCES];
        for ((groups, res), out) in self.sources.iter().zip(&point.sources).zip(&mut terms) {
            let ng = groups.len();
            let (rho, drho, gain, dgain) = (&res.rho, &res.drho, &res.gain, &res.dgain);
            // ex[g][l] = exp(lambda (tau_g - tau_l)) for l < g.
            let mut ex = [[Cv::<NP>::zero(); MAX_GROUPS]; MAX_GROUPS];
            for g in 0..ng {
                for l in 0..g {
                    let dt = groups[g].tau - groups[l].tau;
                    for k in 0..NP {
                        let (sin, cos) = math::sin_cos(p.lam.im[k] * dt);
                        let mag = math::exp(p.lam.re[k] * dt);
                        ex[g][l].re[k] = mag * cos;
                        ex[g][l].im[k] = mag * sin;
                    }
                }
            }
            for o in 0..N_OUT {
                for g in 0..ng {
                    // sum_{l <= g} m_gl sum_km rho_gk S_km rho_lm e^{lambda_m D_gl}
                    //   = sum_km rho_gk S_km z_m,  z = rho_g + 2 sum_{l < g} rho_l e^{lambda D_gl}.
                    let rg = &rho[g][o];
                    let (mut z, mut dz) = (*rg, drho[g][o]);
                    for l in 0..g {
                        let (rl, e) = (&rho[l][o], &ex[g][l]);
                        for k in 0..NP {
                            z.re[k] += 2.0 * (rl.re[k] * e.re[k] - rl.im[k] * e.im[k]);
                            z.im[k] += 2.0 * (rl.re[k] * e.im[k] + rl.im[k] * e.re[k]);
                            dz[k] += 2.0 * drho[l][o][k] * (e.re[k].abs() + e.im[k].abs());
                        }
                    }
                    let u = table.apply(&z);
                    let (lz, lr) = (z.l1(), rg.l1());
                    // First-order error: d rho_g |S z| + |S^T rho_g| dz + rounding of the
                    // terms |rho_g| |S| |z|.
                    let (mut t, mut e) = (0.0, 0.0);
                    for k in 0..NP {
                        let (mut sz, mut sr) = (0.0, 0.0);
                        for m in 0..NP {
                            sz += table.abs[k][m] * lz[m];
                            sr += table.abs[k][m] * lr[m];
                        }
                        let lu = u.re[k].abs() + u.im[k].abs();
                        t += p.weight[k] * (rg.re[k] * u.re[k] - rg.im[k] * u.im[k]);
                        e += p.weight[k] * (drho[g][o][k] * lu + dz[k] * sr + g_sum * lr[k] * sz);
                    }
                    // Box-exponential terms -2 G_g sum_k rho_lk (e^{lambda_k D_gl} - 1) / lambda_k.
                    for l in 0..g {
                        let (rl, ee) = (&rho[l][o], &ex[g][l]);
                        let (mut bx, mut dbx) = (0.0, 0.0);
                        for k in 0..NP {
                            let (er, ei) = (ee.re[k] - 1.0, ee.im[k]);
                            let fr = er * p.ilam.re[k] - ei * p.ilam.im[k];
                            let fi = er * p.ilam.im[k] + ei * p.ilam.re[k];
                            bx += p.weight[k] * (rl.re[k] * fr - rl.im[k] * fi);
                            let lrl = rl.re[k].abs() + rl.im[k].abs();
                            dbx +=
                                p.weight[k] * (drho[l][o][k] + g_sum * lrl) * (fr.abs() + fi.abs());
                        }
                        t -= 2.0 * gain[g][o] * bx;
                        e += 2.0 * (gain[g][o].abs() * dbx + dgain[g][o] * bx.abs());
                    }
                    out[o][g] = (t, e);
                }
            }
        }
        terms
    }

    /// The variances and their bound from the delay terms `terms` (of this family's
    /// delays) with this family's intensity `W` and the box-box terms
    /// `W G_g G_l min(tau_g, tau_l)`.
    fn accumulate<const NP: usize>(&self, point: &Point<NP>, terms: &DelayTerms) -> Residue {
        let (w, g_sum) = (self.intensity, point.g_sum);
        let mut var = [0.0; N_OUT];
        let mut err = [0.0; N_OUT];
        for ((groups, res), ts) in self.sources.iter().zip(&point.sources).zip(terms) {
            let ng = groups.len();
            let (gain, dgain) = (&res.gain, &res.dgain);
            for o in 0..N_OUT {
                for &(t, e) in &ts[o][..ng] {
                    var[o] += w * t;
                    err[o] += w * e;
                }
            }
            for g in 0..ng {
                for l in 0..ng {
                    let tmin = groups[g].tau.min(groups[l].tau);
                    for o in 0..N_OUT {
                        let (a, b) = (gain[g][o], gain[l][o]);
                        var[o] += w * a * b * tmin;
                        err[o] += w
                            * tmin
                            * (dgain[g][o] * b.abs()
                                + a.abs() * dgain[l][o]
                                + g_sum * (a * b).abs());
                    }
                }
            }
        }
        if var.iter().any(|v| !v.is_finite() || *v <= 0.0) {
            return Residue::Declined(Decline::BadVariance);
        }
        let bound = (0..N_OUT).map(|o| err[o] / var[o]).fold(0.0, f64::max);
        Residue::Variances { var, bound }
    }
}

/// What is done with the road-independent part of a point ([`Point`]): the sums on one
/// family's road, or on the roads of several families of one model ([`roads`]).
trait OnPoint {
    /// The result.
    type Out;
    /// Uses `point`, computed by `family`.
    fn on<const NP: usize>(self, family: &ResidueFamily, point: &Point<NP>) -> Self::Out;
}

/// Per source, output and group, a residue term of the sums and its first-order error
/// (without the intensity).
type DelayTerms = [[[(f64, f64); MAX_GROUPS]; N_OUT]; MAX_SOURCES];

/// What the sums at one design need that does not depend on the road (the wheel delays
/// and the intensity): the poles and the `S` table of `D`, and each source's residues.
struct Point<const NP: usize> {
    poles: Poles<NP>,
    table: STable<NP>,
    /// Relative rounding of a term of the sums, with the roots' backward error.
    g_sum: f64,
    sources: [SourceResidues<NP>; MAX_SOURCES],
}

/// One source's residues `rho[g][o]` on the kept roots, their error bounds, the static
/// gains `G[g][o]` and their errors (module doc).
#[derive(Clone, Copy)]
struct SourceResidues<const NP: usize> {
    rho: [[Cv<NP>; N_OUT]; MAX_GROUPS],
    drho: [[[f64; NP]; N_OUT]; MAX_GROUPS],
    gain: [[f64; N_OUT]; MAX_GROUPS],
    dgain: [[f64; N_OUT]; MAX_GROUPS],
}

impl<const NP: usize> SourceResidues<NP> {
    fn zero() -> Self {
        SourceResidues {
            rho: [[Cv::zero(); N_OUT]; MAX_GROUPS],
            drho: [[[0.0; NP]; N_OUT]; MAX_GROUPS],
            gain: [[0.0; N_OUT]; MAX_GROUPS],
            dgain: [[0.0; N_OUT]; MAX_GROUPS],
        }
    }
}

/// Complex numbers on the `NP` places of the kept roots, real and imaginary parts apart.
#[derive(Debug, Clone, Copy)]
struct Cv<const NP: usize> {
    re: [f64; NP],
    im: [f64; NP],
}

impl<const NP: usize> Cv<NP> {
    fn zero() -> Self {
        Cv {
            re: [0.0; NP],
            im: [0.0; NP],
        }
    }

    /// `|re| + |im|` of each (between `|z|` and `sqrt 2 |z|`).
    fn l1(&self) -> [f64; NP] {
        std::array::from_fn(|k| self.re[k].abs() + self.im[k].abs())
    }
}

/// Powers `lambda^i` of the kept roots, `i = 0..=8`, real and imaginary parts apart.
#[derive(Debug, Clone, Copy)]
struct Powers<const NP: usize> {
    re: [[f64; NP]; NC],
    im: [[f64; NP]; NC],
}

/// The kept roots (one of each conjugate pair, every real one) with what the sums need,
/// on `NP` places (unused places are zero and weigh 0).
struct Poles<const NP: usize> {
    /// The roots, s^-1.
    lam: Cv<NP>,
    /// 2 for a complex root (the pair's sum is twice the real part), 1 for a real root.
    weight: [f64; NP],
    /// True for a complex root (its conjugate is a root too).
    pair: [bool; NP],
    /// `lambda_k^i`.
    pw: Powers<NP>,
    /// `|lambda_k|^i`.
    pw_abs: [[f64; NP]; NC],
    /// `1 / lambda_k`.
    ilam: Cv<NP>,
    /// `1 / (lambda_k D'(lambda_k))`, `D'` from the product over the roots, and its `l1`.
    ild: Cv<NP>,
    ild_l1: [f64; NP],
    /// Relative backward error of the roots: `max_i |d~_i / d_i - 1|` plus the rounding
    /// of the expansion, `d~` the coefficients of `d_2n prod (s - lambda_k)`.
    backward: f64,
    /// Twice the largest of `sum_i d_i w^i / |D(i w)|` at the resonances: how much a
    /// relative change of the coefficients of `D` can change `D(i w)`, relatively.
    mu: f64,
}

impl<const NP: usize> Poles<NP> {
    /// What the sums need from the roots `found` of `d`, or `None` when two roots are
    /// not resolved (a Newton step over 1/100 of the gap to the nearest other root).
    fn new(d: &[f64], found: &Roots) -> Option<Poles<NP>> {
        let deg = d.len() - 1;
        let n = found.n;
        let mut p = Poles {
            lam: Cv::zero(),
            weight: [0.0; NP],
            pair: [false; NP],
            pw: Powers {
                re: [[0.0; NP]; NC],
                im: [[0.0; NP]; NC],
            },
            pw_abs: [[0.0; NP]; NC],
            ilam: Cv::zero(),
            ild: Cv::zero(),
            ild_l1: [0.0; NP],
            backward: 0.0,
            mu: 1.0,
        };
        for k in 0..n {
            let l = found.z[k];
            p.lam.re[k] = l.re;
            p.lam.im[k] = l.im;
            p.pair[k] = found.pair[k];
            p.weight[k] = if found.pair[k] { 2.0 } else { 1.0 };
            let il = recip(l);
            p.ilam.re[k] = il.re;
            p.ilam.im[k] = il.im;
            let r = l.norm_sqr().sqrt();
            let mut z = C64::new(1.0, 0.0);
            let mut a = 1.0;
            for i in 0..NC {
                p.pw.re[i][k] = z.re;
                p.pw.im[i][k] = z.im;
                p.pw_abs[i][k] = a;
                z *= l;
                a *= r;
            }
            // D'(lambda_k) = d_deg prod over the other roots; a pair j gives the real
            // quadratic s^2 - 2 Re(lambda_j) s + |lambda_j|^2.
            let l2 = C64::new(p.pw.re[2][k], p.pw.im[2][k]);
            let mut dprime = C64::new(d[deg], 0.0);
            let mut near = f64::INFINITY;
            for j in 0..n {
                let lj = found.z[j];
                if found.pair[j] {
                    let quad = l2 - 2.0 * lj.re * l + lj.norm_sqr();
                    dprime *= if j == k { l - lj.conj() } else { quad };
                    near = near.min((l - lj.conj()).norm_sqr());
                } else if j != k {
                    dprime *= l - lj;
                }
                if j != k {
                    near = near.min((l - lj).norm_sqr());
                }
            }
            let ild = recip(l * dprime);
            p.ild.re[k] = ild.re;
            p.ild.im[k] = ild.im;
            p.ild_l1[k] = l1(ild);
            // The root must be resolved: its Newton step well inside the gap to the others.
            let mut value = C64::new(0.0, 0.0);
            for i in 0..=deg {
                value += d[i] * C64::new(p.pw.re[i][k], p.pw.im[i][k]);
            }
            let (residual, room) = (value.norm_sqr(), 1e-4 * near * dprime.norm_sqr());
            if residual.is_nan() || residual >= room {
                return None;
            }
        }
        // Backward error: d_deg prod (s - lambda_k) expanded (positive terms only).
        let mut prod = [0.0; NC];
        prod[0] = d[deg];
        let mut len = 1;
        for k in 0..n {
            let l = found.z[k];
            let factor: &[f64] = if found.pair[k] {
                &[l.norm_sqr(), -2.0 * l.re, 1.0]
            } else {
                &[-l.re, 1.0]
            };
            let mut next = [0.0; NC];
            for i in 0..len {
                for (f, c) in factor.iter().enumerate() {
                    next[i + f] += prod[i] * c;
                }
            }
            len += factor.len() - 1;
            prod = next;
        }
        p.backward = (0..deg)
            .map(|i| (prod[i] / d[i] - 1.0).abs())
            .fold(0.0, f64::max)
            + 2.0 * deg as f64 * f64::EPSILON;
        // mu: sum_i d_i w^i / |D(i w)| = prod_k |w - lambda_k| / |i w - lambda_k| at each
        // resonance w = Im lambda_q (and |lambda_q| for a real root), where it peaks.
        for q in 0..n {
            let lq = found.z[q];
            let w = if found.pair[q] { lq.im } else { -lq.re };
            // |w - z|^2 and |i w - z|^2 for z = x + i y (and its conjugate for a pair).
            let (mut num, mut den) = (1.0, 1.0);
            for k in 0..n {
                let (x, y) = (found.z[k].re, found.z[k].im);
                let real_axis = (w - x) * (w - x) + y * y;
                let imag_axis = x * x + (w - y) * (w - y);
                if found.pair[k] {
                    num *= real_axis * real_axis;
                    den *= imag_axis * (x * x + (w + y) * (w + y));
                } else {
                    num *= real_axis;
                    den *= imag_axis;
                }
            }
            p.mu = p.mu.max(2.0 * (num / den).sqrt());
        }
        Some(p)
    }
}

/// `S_km = -1 / (lambda_k + lambda_m)` over all roots, folded onto the kept ones:
/// `u = S z` for `z` given on the kept roots (conjugate on the others) is
/// `u_re = a z_re + b z_im`, `u_im = c z_re + dd z_im`; `abs_km` bounds `|S_km| + |S_km~|`
/// (`m~` the conjugate of a complex root `m`).
struct STable<const NP: usize> {
    a: [[f64; NP]; NP],
    b: [[f64; NP]; NP],
    c: [[f64; NP]; NP],
    dd: [[f64; NP]; NP],
    abs: [[f64; NP]; NP],
}

impl<const NP: usize> STable<NP> {
    fn new(p: &Poles<NP>) -> STable<NP> {
        let z = [[0.0; NP]; NP];
        let mut t = STable {
            a: z,
            b: z,
            c: z,
            dd: z,
            abs: z,
        };
        for k in 0..NP {
            for m in 0..NP {
                if p.weight[k] == 0.0 || p.weight[m] == 0.0 {
                    continue;
                }
                let (lk, lm) = (
                    C64::new(p.lam.re[k], p.lam.im[k]),
                    C64::new(p.lam.re[m], p.lam.im[m]),
                );
                let s = -recip(lk + lm);
                let sc = if p.pair[m] {
                    -recip(lk + lm.conj())
                } else {
                    C64::new(0.0, 0.0)
                };
                t.a[k][m] = s.re + sc.re;
                t.b[k][m] = sc.im - s.im;
                t.c[k][m] = s.im + sc.im;
                t.dd[k][m] = s.re - sc.re;
                t.abs[k][m] = l1(s) + l1(sc);
            }
        }
        t
    }

    /// `u_k = sum_m S_km z_m` over all roots.
    fn apply(&self, z: &Cv<NP>) -> Cv<NP> {
        let mut u = Cv::zero();
        for k in 0..NP {
            let (mut re, mut im) = (0.0, 0.0);
            for m in 0..NP {
                re += self.a[k][m] * z.re[m] + self.b[k][m] * z.im[m];
                im += self.c[k][m] * z.re[m] + self.dd[k][m] * z.im[m];
            }
            u.re[k] = re;
            u.im[k] = im;
        }
        u
    }
}

/// The first `deg + 1` coefficients of `p` in a fixed array.
fn fixed(p: &Poly, deg: usize) -> [f64; NC] {
    std::array::from_fn(|i| if i <= deg { p.coef(i) } else { 0.0 })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::car::{Car, QuarterCar};
    use crate::criteria::{criteria_exact, quarter_car_rms};
    use crate::model::{full_car, quarter_car, symmetric_half};
    use crate::road::{Road, RoadClass};

    fn rel(var: [f64; N_OUT], rms: [f64; N_OUT]) -> f64 {
        (0..N_OUT)
            .map(|o| (var[o].sqrt() / rms[o] - 1.0).abs())
            .fold(0.0, f64::max)
    }

    #[test]
    fn symmetric_half_matches_kronecker_within_its_bound() {
        let car = Car::datum();
        let road = Road::default();
        let half = |c: &Car| symmetric_half(&full_car(c));
        let mut free = car.clone();
        free.front.spring = 0.0;
        free.front.damper = 0.0;
        let free = half(&free);
        // The unit front spring and damper alone: the full-car matrices with nothing else.
        let mut bare = car.clone();
        bare.rear.spring = 0.0;
        bare.rear.damper = 0.0;
        bare.front.tire_stiffness = 0.0;
        bare.rear.tire_stiffness = 0.0;
        bare.front.spring = 1.0;
        bare.front.damper = 1.0;
        let unit = half(&bare);
        let fam = ResidueFamily::new(&free, &unit.k, &unit.c, &road, (19_960.0, 1_290.0)).unwrap();
        for ks in [10_000.0, 19_960.0, 40_000.0] {
            for cs in [500.0, 1_290.0, 4_000.0] {
                let Residue::Variances { var, bound } = fam.variances(ks, cs).unwrap() else {
                    panic!("declined at {ks}, {cs}");
                };
                let exact = criteria_exact(&half(&car.with_front(ks, cs).unwrap()), &road).unwrap();
                let e = rel(var, exact.to_array());
                assert!(e < 1e-12, "({ks}, {cs}): {e:e}");
                assert!(
                    bound < RESIDUE_TOLERANCE && 2.0 * e <= bound,
                    "{e:e} {bound:e}"
                );
            }
        }
    }

    #[test]
    fn quarter_car_family_matches_the_closed_forms() {
        let q = QuarterCar {
            ms: 400.0,
            mu: 40.0,
            ks: 0.0,
            cs: 0.0,
            kt: 180_000.0,
            ct: 0.0,
        };
        let road = Road {
            class: RoadClass::D,
            speed: 31.0,
            ..Road::default()
        };
        let free = quarter_car(&q);
        let unit = quarter_car(&QuarterCar {
            ms: 0.0,
            mu: 0.0,
            ks: 1.0,
            cs: 1.0,
            kt: 0.0,
            ..q
        });
        let fam = ResidueFamily::new(&free, &unit.k, &unit.c, &road, (20_000.0, 1_500.0)).unwrap();
        for (ks, cs) in [(8_000.0, 300.0), (20_000.0, 1_500.0), (60_000.0, 6_000.0)] {
            let Residue::Variances { var, bound } = fam.variances(ks, cs).unwrap() else {
                panic!("declined at {ks}, {cs}");
            };
            let closed = quarter_car_rms(&QuarterCar { ks, cs, ..q }, road.intensity());
            let e = rel(var, closed.to_array());
            assert!(
                e < 1e-12 && 2.0 * e <= bound,
                "({ks}, {cs}): {e:e} {bound:e}"
            );
        }
    }

    #[test]
    fn refuses_families_it_cannot_hold() {
        let car = Car::datum();
        let road = Road::default();
        let full = full_car(&car);
        let bad = |m: &LinearModel, dk: &DMatrix<f64>| {
            ResidueFamily::new(m, dk, dk, &road, (2e4, 1e3))
                .unwrap_err()
                .to_string()
        };
        // Seven coordinates, a rank-two design term, a design term that is not positive.
        assert!(bad(&full, &full.k).contains("2 to 4 coordinates"));
        let half = symmetric_half(&full);
        assert!(bad(&half, &half.k).contains("not one spring and damper"));
        assert!(bad(&half, &(-&half.m)).contains("not positive"));
    }
}
