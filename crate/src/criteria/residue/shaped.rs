//! The residue route on a shaped road (issue #31: a measured road's map as fast as an ISO
//! one): the road velocity of each source is a stable rational filter `F(s)` driven by
//! unit white noise instead of ISO's white velocity.
//!
//! At a design the family's point ([`Point`]: the roots `lambda_k` of `D`, the residues
//! `rho_gk` of `T_g(s) / s` and the static gains `G_g`) does not depend on the road. With
//! `F(s) = K + sum_i c_i / (s - mu_i)` ([`PoleZeroFilter`]) the transfer from the noise is
//! `F(s) T_g(s) / s`, whose partial fractions take each factor's residue times the other
//! factor's value there:
//!
//! ```text
//! F(s) T_g(s) / s = sum_k rho_gk F(lambda_k) / (s - lambda_k)
//!                 + sum_i c_i (T_g(mu_i) / mu_i) / (s - mu_i) + F(0) G_g / s
//! ```
//!
//! (conjugate roots keep conjugate residues, as `F` is real), and the closed form of the
//! modal route ([`crate::criteria::criteria_modal`]) over the roots and the filter's poles
//! gives the variances with unit intensity, the delays exact.
//!
//! **When it declines.** Everything the point holds is certified by the family's own
//! error bound on its ISO road ([`ResidueFamily::variances`]): where that bound exceeds
//! [`super::RESIDUE_TOLERANCE`], or the route declines there, this route declines too. The
//! filter adds only its values at the roots (a product of first-order factors) and at its
//! own poles; it declines where a filter pole comes within `1e-3` (relative) of a root,
//! where the two fractions would cancel, and is not built for a filter whose own
//! fractions cancel ([`PoleZeroFilter::new`]). The caller then takes the modal route with the
//! filters. Checked against the Lyapunov route on the road (`tests/hifi_roads.rs`).

use super::{OnPoint, Point, Residue, ResidueFamily, MAX_GROUPS, MAX_ROOTS, RESIDUE_TOLERANCE};
use crate::error::{Result, RideError};
use crate::evaluate::Criteria;
use crate::math;
use crate::model::N_OUT;
use num_complex::Complex64 as C64;

/// The largest cancellation accepted in a filter's partial fractions (the ratio of their
/// magnitudes' sum to the filter's value), so that the variances keep about 1e-10 of
/// their 16 digits: the routes that use the fractions decline above it.
const MAX_CANCELLATION: f64 = 1e4;

/// A stable real rational filter `F(s) = K prod_i (s + z_i) / (s + p_i)` with distinct
/// real poles `-p_i`, and its partial fractions `F(s) = K + sum_i c_i / (s - mu_i)`.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct PoleZeroFilter {
    gain: f64,
    zeros: Vec<f64>,
    poles: Vec<f64>,
    /// `(mu_i, c_i)`, `mu_i = -p_i`.
    fractions: Vec<(f64, f64)>,
}

impl PoleZeroFilter {
    /// The filter of gain `gain`, zeros `zeros` and poles `poles` (rad/s; `F` vanishes at
    /// `s = -z_i` and has poles at `s = -p_i`, as many zeros as poles); `None` when a pole
    /// is not positive, or when the partial fractions cancel: where the sum of their
    /// magnitudes, `|K| + sum_i |c_i / (i w - mu_i)|`, exceeds [`MAX_CANCELLATION`] times
    /// `|F(i w)|` at `w = 0` or at a pole's frequency `w = |mu_i|` (nearly repeated poles,
    /// which fits of steep slopes make, give huge `c_i` of opposite signs).
    pub(crate) fn new(gain: f64, zeros: &[f64], poles: &[f64]) -> Option<PoleZeroFilter> {
        if zeros.len() != poles.len() || poles.iter().any(|p| !(p.is_finite() && *p > 0.0)) {
            return None;
        }
        let mut fractions = Vec::with_capacity(poles.len());
        for (i, &pi) in poles.iter().enumerate() {
            // c_i = K prod_j (z_j - p_i) / prod_{j != i} (p_j - p_i).
            let mut c = gain;
            for (j, (&zj, &pj)) in zeros.iter().zip(poles).enumerate() {
                c *= zj - pi;
                if j != i {
                    let gap = pj - pi;
                    if gap == 0.0 {
                        return None;
                    }
                    c /= gap;
                }
            }
            fractions.push((-pi, c));
        }
        let filter = PoleZeroFilter {
            gain,
            zeros: zeros.to_vec(),
            poles: poles.to_vec(),
            fractions,
        };
        let worst = std::iter::once(0.0)
            .chain(poles.iter().copied())
            .map(|w| {
                let s = C64::new(0.0, w);
                let sum: f64 = filter
                    .fractions
                    .iter()
                    .map(|&(mu, c)| c.abs() / (s - mu).norm_sqr().sqrt())
                    .sum();
                (gain.abs() + sum) / filter.at(s).norm_sqr().sqrt()
            })
            .fold(0.0, f64::max);
        (worst <= MAX_CANCELLATION).then_some(filter)
    }

    /// `F(s)` at a complex `s`, rad/s, from the product of first-order factors.
    pub(crate) fn at(&self, s: C64) -> C64 {
        self.zeros
            .iter()
            .zip(&self.poles)
            .fold(C64::new(self.gain, 0.0), |acc, (z, p)| {
                acc * (s + z) / (s + p)
            })
    }

    /// `F(s)` as [`PoleZeroFilter::at`], the numerator's and denominator's products apart
    /// and one division (what a map point takes; the two agree to rounding).
    pub(crate) fn at_once(&self, s: C64) -> C64 {
        let (mut num, mut den) = (C64::new(self.gain, 0.0), C64::new(1.0, 0.0));
        for (z, p) in self.zeros.iter().zip(&self.poles) {
            num *= s + z;
            den *= s + p;
        }
        num / den
    }

    /// `F(0) = K prod z_i / p_i`.
    pub(crate) fn dc_gain(&self) -> f64 {
        self.zeros
            .iter()
            .zip(&self.poles)
            .fold(self.gain, |g, (z, p)| g * z / p)
    }

    /// The partial fractions `(mu_i, c_i)`.
    pub(crate) fn fractions(&self) -> &[(f64, f64)] {
        &self.fractions
    }
}

/// The residue route of one model family on a shaped road: the parts (family, weight,
/// the filter of its one source) whose weighted variances add (the symmetric half
/// driven by the sum of the tracks, the antisymmetric half by their difference).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct ShapedResidueRoute {
    parts: Vec<(ResidueFamily, f64, PoleZeroFilter)>,
}

impl ShapedResidueRoute {
    /// The route over `parts`; fails on no part, a weight that is not finite and
    /// positive, a family of more than one source, or a filter of more than
    /// [`MAX_FILTER_POLES`] poles.
    pub(crate) fn new(
        parts: Vec<(ResidueFamily, f64, PoleZeroFilter)>,
    ) -> Result<ShapedResidueRoute> {
        let ok = !parts.is_empty()
            && parts.iter().all(|(f, w, filter)| {
                w.is_finite()
                    && *w > 0.0
                    && f.sources.len() == 1
                    && filter.fractions.len() <= MAX_FILTER_POLES
            });
        if !ok {
            return Err(RideError::Numerical(format!(
                "shaped residue route: needs one-source families with positive weights and \
                 filters of at most {MAX_FILTER_POLES} poles"
            )));
        }
        Ok(ShapedResidueRoute { parts })
    }

    /// RMS `[BAcc m/s^2, DTL N, SWS m]` at `(ks, cs)` (N/m, N s/m), or `None` where the
    /// route declines (module doc); errors on a road warp.
    pub(crate) fn criteria(&self, ks: f64, cs: f64) -> Result<Option<Criteria>> {
        let mut var = [0.0; N_OUT];
        for (family, weight, filter) in &self.parts {
            match family.at(ks, cs, Shaped { filter })? {
                Ok(Some(v)) => (0..N_OUT).for_each(|o| var[o] += weight * v[o]),
                _ => return Ok(None),
            }
        }
        if var.iter().any(|v| !v.is_finite() || *v <= 0.0) {
            return Ok(None);
        }
        Ok(Some(Criteria::from_array(var.map(f64::sqrt))))
    }
}

/// The variances of one family's point on the filter's road, `None` where they are not
/// certified (module doc).
struct Shaped<'a> {
    filter: &'a PoleZeroFilter,
}

impl OnPoint for Shaped<'_> {
    type Out = Option<[f64; N_OUT]>;

    fn on<const NP: usize>(self, family: &ResidueFamily, point: &Point<NP>) -> Self::Out {
        let certified = matches!(
            family.accumulate(point, &family.delay_terms(point)),
            Residue::Variances { bound, .. } if bound <= RESIDUE_TOLERANCE
        );
        if !certified {
            return None;
        }
        let p = &point.poles;
        // The roots (one of each conjugate pair, then the real ones) and the residues of
        // `T_g(s) / s` there.
        let mut roots = ReducedPoles::default();
        let mut upper = [0usize; MAX_PAIRS];
        let mut real = [0usize; MAX_ROOTS];
        for k in 0..NP {
            if p.weight[k] == 0.0 {
                continue;
            }
            if p.pair[k] {
                roots.u[roots.nu] = C64::new(p.lam.re[k], p.lam.im[k]);
                upper[roots.nu] = k;
                roots.nu += 1;
            } else {
                roots.r[roots.nr] = p.lam.re[k];
                real[roots.nr] = k;
                roots.nr += 1;
            }
        }
        let groups = &family.sources[0];
        let res = &point.sources[0];
        let mut rho = [[ReducedResidues::default(); N_OUT]; MAX_GROUPS];
        let mut gains = [(0.0, [0.0; N_OUT]); MAX_GROUPS];
        for (g, grp) in groups.iter().enumerate() {
            for (o, out) in rho[g].iter_mut().enumerate() {
                let r = &res.rho[g][o];
                for (k, &at) in upper[..roots.nu].iter().enumerate() {
                    out.u[k] = C64::new(r.re[at], r.im[at]);
                }
                for (k, &at) in real[..roots.nr].iter().enumerate() {
                    out.r[k] = r.re[at];
                }
            }
            gains[g] = (grp.tau, res.gain[g]);
        }
        let gains = &mut gains[..groups.len()];
        let (ps, rho) = filtered(self.filter, &roots, &rho, gains, None)?;
        let mut var = [0.0; N_OUT];
        add_reduced_variances(&mut var, &ps, &ps.weights(), gains, &rho);
        Some(var)
    }
}

/// The expansion of `F(s) T_g(s) / s` (module doc) from that of `T_g(s) / s`: its roots
/// `roots` (one of each pair, then the real ones), residues `rho[g][o]` there and, in
/// `groups`, each group's delay and static gains `G_g`. Returns the poles (the roots, then
/// the filter's poles among the real ones) and residues `rho_gk F(lambda_k)` and
/// `c_i T_g(mu_i) / mu_i`, and turns the gains into `F(0) G_g`; `None` where a filter pole
/// comes within `1e-3` (relative) of a root. Shared by the families' route and the quarter
/// car's closed form (one copy in the page's wasm).
///
/// `exact`, where given, is `T_0(mu) / mu` of the one group's outputs straight from the
/// transfer (the quarter car's), in place of the sum over the roots.
#[inline(never)]
pub(super) fn filtered(
    filter: &PoleZeroFilter,
    roots: &ReducedPoles,
    rho: &[[ReducedResidues; N_OUT]; MAX_GROUPS],
    groups: &mut [(f64, [f64; N_OUT])],
    exact: Option<&dyn Fn(f64) -> [f64; N_OUT]>,
) -> Option<(ReducedPoles, [[ReducedResidues; N_OUT]; MAX_GROUPS])> {
    let (nu, nrr) = (roots.nu, roots.nr);
    let fractions = &filter.fractions;
    if fractions.len() > MAX_FILTER_POLES {
        return None;
    }
    let mut ps = ReducedPoles {
        nr: nrr + fractions.len(),
        ..*roots
    };
    let near = |l: C64, mu: f64| (l - mu).norm_sqr() <= 1e-6 * l.norm_sqr();
    for (i, &(mu, _)) in fractions.iter().enumerate() {
        if ps.u[..nu].iter().any(|&l| near(l, mu))
            || ps.r[..nrr].iter().any(|&l| near(C64::new(l, 0.0), mu))
        {
            return None;
        }
        ps.r[nrr + i] = mu;
    }
    let zero = C64::new(0.0, 0.0);
    let (mut f_u, mut f_r) = ([zero; MAX_PAIRS], [0.0; MAX_ROOTS]);
    for k in 0..nu {
        f_u[k] = filter.at_once(ps.u[k]);
    }
    for k in 0..nrr {
        f_r[k] = filter.at_once(C64::new(ps.r[k], 0.0)).re;
    }
    // 1 / (mu_i - lambda_k) for the filter's poles against the roots, once a point
    // (every group and output takes them).
    let mut to_u = [[zero; MAX_PAIRS]; MAX_FILTER_POLES];
    let mut to_r = [[0.0; MAX_ROOTS]; MAX_FILTER_POLES];
    for (i, &(mu, _)) in fractions.iter().enumerate() {
        for k in 0..nu {
            to_u[i][k] = (C64::new(mu, 0.0) - ps.u[k]).inv();
        }
        for k in 0..nrr {
            to_r[i][k] = 1.0 / (mu - ps.r[k]);
        }
    }
    let f0 = filter.dc_gain();
    let mut out = [[ReducedResidues::default(); N_OUT]; MAX_GROUPS];
    for (g, (_, gain)) in groups.iter_mut().enumerate() {
        for o in 0..N_OUT {
            let (r, x) = (&rho[g][o], &mut out[g][o]);
            for k in 0..nu {
                x.u[k] = r.u[k] * f_u[k];
            }
            for k in 0..nrr {
                x.r[k] = r.r[k] * f_r[k];
            }
            // c_i T_g(mu_i) / mu_i, real: a pair's two roots give twice the real part.
            if exact.is_none() {
                for (i, &(mu, c)) in fractions.iter().enumerate() {
                    let pairs: f64 = (0..nu).map(|k| (r.u[k] * to_u[i][k]).re).sum();
                    let reals: f64 = (0..nrr).map(|k| r.r[k] * to_r[i][k]).sum();
                    x.r[nrr + i] = c * (2.0 * pairs + reals + gain[o] / mu);
                }
            }
        }
        if let Some(t) = exact {
            for (i, &(mu, c)) in fractions.iter().enumerate() {
                let t = t(mu);
                for o in 0..N_OUT {
                    out[g][o].r[nrr + i] = c * t[o];
                }
            }
        }
        *gain = gain.map(|v| f0 * v);
    }
    Some((ps, out))
}

/// Most kept roots that are one of a conjugate pair (a degree-8 denominator).
const MAX_PAIRS: usize = MAX_ROOTS / 2;
/// Most poles of a shaping filter this route takes ([`ShapedResidueRoute::new`] refuses
/// more; the fits make at most 8).
pub(super) const MAX_FILTER_POLES: usize = 8;
/// Most real poles: the model's real roots and the filter's.
const MAX_REAL: usize = MAX_ROOTS + MAX_FILTER_POLES;

/// The poles of one source's transfer in the form the reduced sums take them (why and how:
/// [`add_reduced_variances`]): `u`, one root of each conjugate pair (the other is its
/// conjugate), and `r`, the real poles, on fixed places (a map point allocates nothing).
#[derive(Default, Clone, Copy)]
pub(super) struct ReducedPoles {
    pub(super) u: [C64; MAX_PAIRS],
    pub(super) nu: usize,
    pub(super) r: [f64; MAX_REAL],
    pub(super) nr: usize,
}

/// The residues of one group's transfer to one output on [`ReducedPoles`]' places (a
/// pair's other root has the conjugate residue, as the transfer is real).
#[derive(Clone, Copy)]
pub(super) struct ReducedResidues {
    pub(super) u: [C64; MAX_PAIRS],
    pub(super) r: [f64; MAX_REAL],
}

impl Default for ReducedResidues {
    fn default() -> Self {
        ReducedResidues {
            u: [C64::new(0.0, 0.0); MAX_PAIRS],
            r: [0.0; MAX_REAL],
        }
    }
}

/// The closed form's weights `w(k, m) = -1 / (lambda_k + lambda_m)` on [`ReducedPoles`]:
/// `uu[k][m]` and `uc[k][m]` for a pair root against a pair root and against its
/// conjugate, `ur[k][m]` for a pair root against a real pole, `rr[k][m]` for two real ones.
pub(super) struct ReducedWeights {
    uu: [[C64; MAX_PAIRS]; MAX_PAIRS],
    uc: [[C64; MAX_PAIRS]; MAX_PAIRS],
    ur: [[C64; MAX_REAL]; MAX_PAIRS],
    rr: [[f64; MAX_REAL]; MAX_REAL],
}

impl ReducedPoles {
    pub(super) fn weights(&self) -> ReducedWeights {
        let zero = C64::new(0.0, 0.0);
        let mut w = ReducedWeights {
            uu: [[zero; MAX_PAIRS]; MAX_PAIRS],
            uc: [[zero; MAX_PAIRS]; MAX_PAIRS],
            ur: [[zero; MAX_REAL]; MAX_PAIRS],
            rr: [[0.0; MAX_REAL]; MAX_REAL],
        };
        let (u, r) = (&self.u[..self.nu], &self.r[..self.nr]);
        for (k, &uk) in u.iter().enumerate() {
            for (m, &um) in u.iter().enumerate() {
                w.uu[k][m] = -(uk + um).inv();
                w.uc[k][m] = -(uk + um.conj()).inv();
            }
            for (m, &rm) in r.iter().enumerate() {
                w.ur[k][m] = -(uk + rm).inv();
            }
        }
        for (k, &rk) in r.iter().enumerate() {
            for (m, &rm) in r.iter().enumerate() {
                w.rr[k][m] = -1.0 / (rk + rm);
            }
        }
        w
    }
}

/// Adds one source's variances (unit intensity) to `var`: the closed form of
/// [`crate::criteria::criteria_modal`] over the poles `P` of its transfer, the wheel
/// groups `(tau_g, G_g)` (by increasing delay) and the residues `rho[g][o]`, summed on
/// half the terms. The poles are closed under conjugation with conjugate residues (a real
/// transfer), so the sum over all of them,
///
/// ```text
/// t = Re sum_{k, m in P} a_k b_m w(k, m),   a = rho_g,  b_m = rho_lm e^(lambda_m dt),
/// ```
///
/// takes the rows of one root `k` of each pair (`U`) twice and the real poles' (`R`) once:
///
/// ```text
/// t = 2 Re sum_{k in U} a_k [sum_{m in U} (b_m w(k, m) + conj(b_m) w(k, conj m))
///                            + sum_{m in R} b_m w(k, m)]
///   + sum_{k in R} a_k [2 Re sum_{m in U} b_m w(k, m) + sum_{m in R} b_m w(k, m)],
/// ```
///
/// the last line in real arithmetic but for one product per pair: with the four root
/// pairs of a half car and an 8-pole filter, 96 complex and 64 real products per group
/// pair and output instead of 256 complex ones. The same sums as
/// [`crate::criteria::modal::add_source_variances`] on the whole pole list, to rounding
/// (tested).
pub(super) fn add_reduced_variances(
    var: &mut [f64; N_OUT],
    ps: &ReducedPoles,
    w: &ReducedWeights,
    groups: &[(f64, [f64; N_OUT])],
    rho: &[[ReducedResidues; N_OUT]; MAX_GROUPS],
) {
    let (nu, nr) = (ps.nu, ps.nr);
    let one = C64::new(1.0, 0.0);
    for (gi, &(g_tau, g_gain)) in groups.iter().enumerate() {
        for (li, &(l_tau, _)) in groups.iter().enumerate().take(gi + 1) {
            let dt = g_tau - l_tau;
            let mut eu = [one; MAX_PAIRS];
            let mut er = [1.0; MAX_REAL];
            if dt != 0.0 {
                for k in 0..nu {
                    eu[k] = math::cexp(ps.u[k] * dt);
                }
                for k in 0..nr {
                    er[k] = math::exp(ps.r[k] * dt);
                }
            }
            for (o, vo) in var.iter_mut().enumerate() {
                let (a, l) = (&rho[gi][o], &rho[li][o]);
                let bu: [C64; MAX_PAIRS] = std::array::from_fn(|m| l.u[m] * eu[m]);
                let br: [f64; MAX_REAL] = std::array::from_fn(|m| l.r[m] * er[m]);
                let mut tu = C64::new(0.0, 0.0);
                for k in 0..nu {
                    let mut inner = C64::new(0.0, 0.0);
                    for m in 0..nu {
                        inner += bu[m] * w.uu[k][m] + bu[m].conj() * w.uc[k][m];
                    }
                    for m in 0..nr {
                        inner += w.ur[k][m] * br[m];
                    }
                    tu += a.u[k] * inner;
                }
                let mut tr = 0.0;
                for k in 0..nr {
                    let mut pairs = 0.0;
                    for m in 0..nu {
                        pairs += (bu[m] * w.ur[m][k]).re;
                    }
                    let mut reals = 0.0;
                    for m in 0..nr {
                        reals += br[m] * w.rr[k][m];
                    }
                    tr += a.r[k] * (2.0 * pairs + reals);
                }
                let mut t = 2.0 * tu.re + tr;
                if gi != li {
                    t *= 2.0; // the (l, g) ordered pair gives the same value
                    let bx_u: C64 = (0..nu).map(|k| l.u[k] * (eu[k] - 1.0) / ps.u[k]).sum();
                    let bx_r: f64 = (0..nr).map(|k| l.r[k] * (er[k] - 1.0) / ps.r[k]).sum();
                    t -= 2.0 * g_gain[o] * (2.0 * bx_u.re + bx_r);
                }
                *vo += t;
            }
        }
    }
    for &(g_tau, g_gain) in groups {
        for &(l_tau, l_gain) in groups {
            for (o, v) in var.iter_mut().enumerate() {
                *v += g_gain[o] * l_gain[o] * g_tau.min(l_tau);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::criteria::modal::{add_source_variances, inverse_sums};

    /// The reduced sums equal the closed form on the whole pole list (every root with its
    /// conjugate, conjugate residues), with two wheel groups 0.1 s apart, real roots of the
    /// model among the poles and static gains, to 1e-12.
    #[test]
    fn the_reduced_sums_are_the_closed_form_on_every_pole() {
        let u = [C64::new(-1.2, 6.5), C64::new(-9.0, 55.0)];
        let r = [-30.0, -0.4, -4.5, -80.0];
        let mut ps = ReducedPoles::default();
        ps.u[..2].copy_from_slice(&u);
        ps.r[..4].copy_from_slice(&r);
        (ps.nu, ps.nr) = (2, 4);
        let groups = [(0.0, [0.3, -1.1, 0.02]), (0.1, [-0.2, 0.7, 0.05])];
        let mut rho = [[ReducedResidues::default(); N_OUT]; MAX_GROUPS];
        let mut full: Vec<Vec<Vec<C64>>> = vec![vec![Vec::new(); N_OUT]; 2];
        for g in 0..2 {
            for o in 0..N_OUT {
                let x = (1 + g * N_OUT + o) as f64;
                let ru = [
                    C64::new(0.3 * x, -1.0 + 0.1 * x),
                    C64::new(-2.0 / x, 0.5 * x),
                ];
                let rr = [0.7 - 0.2 * x, 1.0 / x, -0.05 * x, 2.0];
                rho[g][o].u[..2].copy_from_slice(&ru);
                rho[g][o].r[..4].copy_from_slice(&rr);
                full[g][o] = ru
                    .iter()
                    .flat_map(|&z| [z, z.conj()])
                    .chain(rr.iter().map(|&x| C64::new(x, 0.0)))
                    .collect();
            }
        }
        let lam: Vec<C64> = u
            .iter()
            .flat_map(|&z| [z, z.conj()])
            .chain(r.iter().map(|&x| C64::new(x, 0.0)))
            .collect();
        let (mut a, mut b) = ([0.0; N_OUT], [0.0; N_OUT]);
        add_reduced_variances(&mut a, &ps, &ps.weights(), &groups, &rho);
        add_source_variances(&mut b, &lam, &inverse_sums(&lam), &groups, &full, 1.0);
        for o in 0..N_OUT {
            assert!(b[o].abs() > 1e-3, "output {o}: {}", b[o]);
            assert!(
                (a[o] / b[o] - 1.0).abs() < 1e-12,
                "output {o}: {} vs {}",
                a[o],
                b[o]
            );
        }
    }
}
