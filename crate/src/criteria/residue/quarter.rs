//! The quarter car on a shaped road in closed form (issue #31: the LoFi of every
//! measured-road map, surrogate and adaptive loop as fast as on an ISO class).
//!
//! With `A = ms s^2 + cs s + ks`, `B = cs s + ks`, `C = mu s^2 + (cs + ct) s + ks + kt`
//! and `R = ct s + kt`, the quarter car's equations give the body and wheel
//! displacements `Zs = B R / D Zr` and `Zu = A R / D Zr` from the road's, with
//!
//! ```text
//! D = A C - B^2 = ms mu s^4 + (ms (cs + ct) + mu cs) s^3 + (ms (ks + kt) + mu ks + cs ct) s^2
//!               + (cs kt + ks ct) s + ks kt,
//! ```
//!
//! so the outputs of [`crate::model::quarter_car`] have the displacement transfers
//! `H_o = N_o / D`: BAcc `N = s^2 B R`, DTL `N = kt (A R - D)` (the tyre's spring force;
//! `kt (Zu - Zr)`), SWS `N = (B - A) R`. Each `H_o(0) = 0` (the static gains vanish), so
//! the transfer from the road velocity, `H_o(s) / s`, has the residue
//! `rho_k = N_o(lambda_k) / (lambda_k D'(lambda_k))` at each root of `D`. A source's
//! velocity is its filter `F(s) = K + sum_i c_i / (s - mu_i)` driven by unit white noise,
//! so `F(s) H_o(s) / s` has the residues `rho_k F(lambda_k)` at the roots and
//! `c_i H_o(mu_i) / mu_i` at the filter's poles, and the closed form of the modal route
//! gives the variances ([`super::shaped`]'s reduced sums). A quartic's roots (from the
//! body's and the wheel's modes apart) and a few products: about a microsecond a design,
//! where the general modal route takes the model's eigenvectors.
//!
//! **When it declines** (`None`; the caller then takes the modal route): the roots are
//! not found or not stable, a filter pole comes within `1e-3` (relative) of a root, a
//! filter has more than 8 poles, or the partial fractions miss
//! `F(s) H_o(s) / s` at 1 Hz or 10 Hz by more than `1e-9` (nearly repeated roots, whose
//! residues cancel).

use super::shaped::{
    add_reduced_variances, filtered, PoleZeroFilter, ReducedPoles, ReducedResidues,
};
use super::MAX_GROUPS;
use crate::car::QuarterCar;
use crate::criteria::poly::{roots, Roots, MAX_ROOTS};
use crate::evaluate::Criteria;
use crate::model::N_OUT;
use num_complex::Complex64 as C64;
use std::f64::consts::PI;

/// Where the root finder starts: the body's and the wheel's modes apart (the body on the
/// spring in series with the tyre, the wheel between both springs), whose roots are near
/// `D`'s, so that a design costs a few Aberth iterations instead of the companion matrix's
/// eigenvalues; `None` (the companion matrix) where either is overdamped.
fn start(q: &QuarterCar) -> Option<Roots> {
    let mode = |m: f64, c: f64, k: f64| {
        let disc = 4.0 * m * k - c * c;
        (disc > 0.0).then(|| C64::new(-c / (2.0 * m), disc.sqrt() / (2.0 * m)))
    };
    let body = mode(q.ms, q.cs, q.ks * q.kt / (q.ks + q.kt))?;
    let wheel = mode(q.mu, q.cs + q.ct, q.ks + q.kt)?;
    let mut r = Roots {
        n: 2,
        z: [C64::new(0.0, 0.0); MAX_ROOTS],
        pair: [false; MAX_ROOTS],
    };
    r.z[..2].copy_from_slice(&[body, wheel]);
    r.pair[..2].copy_from_slice(&[true, true]);
    Some(r)
}

/// The numerators `N_o(s)` of the module doc at `s` and `D(s)`.
fn numerators(q: &QuarterCar, s: C64) -> ([C64; N_OUT], C64) {
    let a = (s * q.ms + q.cs) * s + q.ks;
    let b = s * q.cs + q.ks;
    let c = (s * q.mu + (q.cs + q.ct)) * s + (q.ks + q.kt);
    let r = s * q.ct + q.kt;
    let d = a * c - b * b;
    ([s * s * b * r, q.kt * (a * r - d), (b - a) * r], d)
}

/// RMS `[BAcc m/s^2, DTL N, SWS m]` of the quarter car `q` whose wheel each source drives
/// with its `weight` (its velocity the `filter` driven by unit white noise; independent
/// sources add), by the closed form of the module doc; `None` where it declines.
pub(crate) fn quarter_shaped(
    q: &QuarterCar,
    sources: &[(f64, PoleZeroFilter)],
) -> Option<Criteria> {
    let d = [
        q.ks * q.kt,
        q.cs * q.kt + q.ks * q.ct,
        q.ms * (q.ks + q.kt) + q.mu * q.ks + q.cs * q.ct,
        q.ms * (q.cs + q.ct) + q.mu * q.cs,
        q.ms * q.mu,
    ];
    let found = roots(&d, start(q).as_ref())?;
    let kept = &found.z[..found.n];
    // Every root stable (a NaN is not).
    if !kept.iter().all(|l| l.re < 0.0) {
        return None;
    }
    // D'(lambda) by Horner.
    let slope = |l: C64| ((l * (4.0 * d[4]) + 3.0 * d[3]) * l + 2.0 * d[2]) * l + d[1];
    // The residues of H_o(s) / s at the roots, the pairs' then the real ones'.
    let mut roots = ReducedPoles::default();
    let mut rho = [[ReducedResidues::default(); N_OUT]; MAX_GROUPS];
    for (&l, &pair) in kept.iter().zip(&found.pair) {
        let (n, _) = numerators(q, l);
        let ld = l * slope(l);
        for o in 0..N_OUT {
            let r = n[o] / ld;
            if pair {
                rho[0][o].u[roots.nu] = r;
            } else {
                rho[0][o].r[roots.nr] = r.re;
            }
        }
        if pair {
            roots.u[roots.nu] = l;
            roots.nu += 1;
        } else {
            roots.r[roots.nr] = l.re;
            roots.nr += 1;
        }
    }
    let mut var = [0.0; N_OUT];
    for (weight, filter) in sources {
        if *weight == 0.0 {
            continue;
        }
        // One wheel at no delay, no static gain.
        let mut groups = [(0.0, [0.0; N_OUT])];
        // The filter poles' residues from the transfer itself rather than from the sum
        // over the roots (they cancel less where a real root nears a filter pole).
        let exact = |mu: f64| {
            let (n, dm) = numerators(q, C64::new(mu, 0.0));
            n.map(|n| (n / (dm * mu)).re)
        };
        let (ps, rho) = filtered(filter, &roots, &rho, &mut groups, Some(&exact))?;
        // The expansion against F(s) H_o(s) / s at 1 Hz and 10 Hz.
        for hz in [1.0, 10.0] {
            let s = C64::new(0.0, 2.0 * PI * hz);
            let (n, ds) = numerators(q, s);
            let f = filter.at_once(s);
            for o in 0..N_OUT {
                let direct = f * n[o] / (ds * s);
                let r = &rho[0][o];
                let pairs: C64 = (0..ps.nu)
                    .map(|k| r.u[k] / (s - ps.u[k]) + r.u[k].conj() / (s - ps.u[k].conj()))
                    .sum();
                let reals: C64 = (0..ps.nr).map(|k| r.r[k] / (s - ps.r[k])).sum();
                if (direct - pairs - reals).norm_sqr() > 1e-18 * direct.norm_sqr() {
                    return None;
                }
            }
        }
        let mut v = [0.0; N_OUT];
        add_reduced_variances(&mut v, &ps, &ps.weights(), &groups, &rho);
        for o in 0..N_OUT {
            var[o] += weight * weight * v[o];
        }
    }
    if var.iter().any(|v| !(v.is_finite() && *v > 0.0)) {
        return None;
    }
    Some(Criteria::from_array(var.map(f64::sqrt)))
}
