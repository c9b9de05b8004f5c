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

use super::{OnPoint, Point, Residue, ResidueFamily, RESIDUE_TOLERANCE};
use crate::criteria::modal::{add_source_variances, inverse_sums};
use crate::error::{Result, RideError};
use crate::evaluate::Criteria;
use crate::model::N_OUT;
use num_complex::Complex64 as C64;

/// The largest cancellation accepted in a filter's partial fractions (the ratio of their
/// magnitudes' sum to the filter's value), so that the variances keep about 1e-10 of
/// their 16 digits: the routes that use the fractions decline above it.
const MAX_CANCELLATION: f64 = 1e4;

/// A stable real rational filter `F(s) = K prod_i (s + z_i) / (s + p_i)` with distinct
/// real poles `-p_i`, and its partial fractions `F(s) = K + sum_i c_i / (s - mu_i)`.
#[derive(Debug, Clone, PartialEq)]
pub struct PoleZeroFilter {
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
    pub fn new(gain: f64, zeros: &[f64], poles: &[f64]) -> Option<PoleZeroFilter> {
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
    pub fn at(&self, s: C64) -> C64 {
        self.zeros
            .iter()
            .zip(&self.poles)
            .fold(C64::new(self.gain, 0.0), |acc, (z, p)| {
                acc * (s + z) / (s + p)
            })
    }

    /// `F(0) = K prod z_i / p_i`.
    pub fn dc_gain(&self) -> f64 {
        self.zeros
            .iter()
            .zip(&self.poles)
            .fold(self.gain, |g, (z, p)| g * z / p)
    }

    /// The partial fractions `(mu_i, c_i)`.
    pub fn fractions(&self) -> &[(f64, f64)] {
        &self.fractions
    }
}

/// The residue route of one model family on a shaped road: the parts (family, weight,
/// the filter of its one source) whose weighted variances add (the symmetric half
/// driven by the sum of the tracks, the antisymmetric half by their difference).
#[derive(Debug, Clone, PartialEq)]
pub struct ShapedResidueRoute {
    parts: Vec<(ResidueFamily, f64, PoleZeroFilter)>,
}

impl ShapedResidueRoute {
    /// The route over `parts`; fails on no part, a weight that is not finite and
    /// positive, or a family of more than one source.
    pub fn new(parts: Vec<(ResidueFamily, f64, PoleZeroFilter)>) -> Result<ShapedResidueRoute> {
        let ok = !parts.is_empty()
            && parts
                .iter()
                .all(|(f, w, _)| w.is_finite() && *w > 0.0 && f.sources.len() == 1);
        if !ok {
            return Err(RideError::Numerical(
                "shaped residue route: needs one-source families with positive weights".into(),
            ));
        }
        Ok(ShapedResidueRoute { parts })
    }

    /// RMS `[BAcc m/s^2, DTL N, SWS m]` at `(ks, cs)` (N/m, N s/m), or `None` where the
    /// route declines (module doc); errors on a road warp.
    pub fn criteria(&self, ks: f64, cs: f64) -> Result<Option<Criteria>> {
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
        // Every root (a kept root and its conjugate), then the filter's poles.
        let mut lam: Vec<C64> = Vec::with_capacity(2 * NP + self.filter.fractions.len());
        let mut kept: Vec<(usize, bool)> = Vec::with_capacity(2 * NP);
        for k in 0..NP {
            if p.weight[k] == 0.0 {
                continue;
            }
            let l = C64::new(p.lam.re[k], p.lam.im[k]);
            lam.push(l);
            kept.push((k, false));
            if p.pair[k] {
                lam.push(l.conj());
                kept.push((k, true));
            }
        }
        let nr = lam.len();
        for &(mu, _) in &self.filter.fractions {
            if lam[..nr]
                .iter()
                .any(|&l| (l - mu).norm_sqr() <= 1e-6 * l.norm_sqr())
            {
                return None;
            }
            lam.push(C64::new(mu, 0.0));
        }
        let f_lam: Vec<C64> = lam[..nr].iter().map(|&l| self.filter.at(l)).collect();
        let f0 = self.filter.dc_gain();
        let groups = &family.sources[0];
        let res = &point.sources[0];
        let mut rho: Vec<Vec<Vec<C64>>> = Vec::with_capacity(groups.len());
        let mut gains: Vec<(f64, [f64; N_OUT])> = Vec::with_capacity(groups.len());
        for (g, grp) in groups.iter().enumerate() {
            let mut per_output = Vec::with_capacity(N_OUT);
            for o in 0..N_OUT {
                let r = &res.rho[g][o];
                let all: Vec<C64> = kept
                    .iter()
                    .map(|&(k, conj)| {
                        let z = C64::new(r.re[k], r.im[k]);
                        if conj {
                            z.conj()
                        } else {
                            z
                        }
                    })
                    .collect();
                let gain = res.gain[g][o];
                // T_g(mu) / mu, real for a real mu.
                let t_over_s = |mu: f64| -> f64 {
                    let s = C64::new(mu, 0.0);
                    all.iter()
                        .zip(&lam[..nr])
                        .map(|(&rk, &lk)| rk / (s - lk))
                        .sum::<C64>()
                        .re
                        + gain / mu
                };
                let row: Vec<C64> = all
                    .iter()
                    .zip(&f_lam)
                    .map(|(&rk, &f)| rk * f)
                    .chain(
                        self.filter
                            .fractions
                            .iter()
                            .map(|&(mu, c)| C64::new(c * t_over_s(mu), 0.0)),
                    )
                    .collect();
                per_output.push(row);
            }
            rho.push(per_output);
            gains.push((grp.tau, res.gain[g].map(|v| f0 * v)));
        }
        let mut var = [0.0; N_OUT];
        add_source_variances(&mut var, &lam, &inverse_sums(&lam), &gains, &rho, 1.0);
        Some(var)
    }
}
