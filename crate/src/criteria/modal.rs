//! The modal route: the exact variances of [`super::criteria_exact`] from a modal
//! expansion of the second-order model, fast enough for maps and optimisers.
//!
//! For symmetric `M`, `C`, `K` with distinct eigenvalues `lambda_k` of
//! `Q(s) = s^2 M + s C + K` and eigenvectors `phi_k`,
//! `Q(s)^-1 = sum_k phi_k phi_k^T / (N_k (s - lambda_k))`, `N_k = phi_k^T (2 lambda_k M + C) phi_k`.
//! The transfer from the road *velocity* of a wheel group `g` (delay `tau_g`,
//! displacement transfer `T_g(s) = row(s) Q(s)^-1 F_g(s) + Yr_g`, `F_g = Kr_g + s Cr_g`,
//! `row(s) = Yq + s Yv + s^2 Ya`) is then
//!
//! ```text
//! T_g(s) / s = sum_k rho_gk / (s - lambda_k) + G_g / s,
//! rho_gk = row(lambda_k) phi_k  phi_k^T F_g(lambda_k) / (lambda_k N_k),   G_g = T_g(0)
//! ```
//!
//! and with `sum_g G_g = 0` the impulse response is
//! `h(u) = sum_g [1(u >= tau_g) sum_k rho_gk e^{lambda_k (u - tau_g)} - G_g 1(u < tau_g)]`, whose
//! square integrates in closed form:
//!
//! ```text
//! int_0^inf (sum_k rho_gk e^{lambda_k s})(sum_m rho_lm e^{lambda_m (s + D)}) ds
//!     = sum_km rho_gk rho_lm e^{lambda_m D} / -(lambda_k + lambda_m)
//! int_{tau_l}^{tau_g} sum_k rho_lk e^{lambda_k (u - tau_l)} du = sum_k rho_lk (e^{lambda_k D} - 1) / lambda_k
//! ```
//!
//! Eigenvalues come from [`super::hqr`], eigenvectors from inverse iteration on `Q`.
//! The expansion is checked against a direct solve at one frequency; if it disagrees
//! (nearly repeated eigenvalues) the route declines and the caller uses the Kronecker route.

use super::exact::{check_stationary, rms_of};
use super::hqr;
use crate::error::{Result, RideError};
use crate::evaluate::Criteria;
use crate::math;
use crate::model::{LinearModel, N_OUT};
use crate::road::Road;
use nalgebra::{DMatrix, DVector};
use num_complex::Complex64 as C64;

const ZERO: C64 = C64::new(0.0, 0.0);

/// A wheel group of one source: delay, input polynomials and output feed-through.
pub(crate) struct Group {
    pub tau: f64,
    kr: Vec<f64>,
    cr: Vec<f64>,
    yr: [f64; N_OUT],
    pub g: [f64; N_OUT],
}

/// Exact RMS criteria by the modal route (see the module doc). Declines with an
/// `Err(ModalInapplicable(..))` when the modal expansion is not accurate.
pub fn criteria_modal(model: &LinearModel, road: &Road) -> Result<Criteria> {
    let Expansion {
        lam,
        sources,
        intensity,
    } = expand(model, road)?;
    let inv_sum = inverse_sums(&lam);
    let mut var = [0.0; N_OUT];
    for (groups, rho) in &sources {
        let gains: Vec<(f64, [f64; N_OUT])> = groups.iter().map(|g| (g.tau, g.g)).collect();
        add_source_variances(&mut var, &lam, &inv_sum, &gains, rho, intensity);
    }
    rms_of(var)
}

/// `1 / -(lambda_k + lambda_m)` for every pair of poles, row-major: shared by every
/// output and wheel-group pair of the closed form.
pub(crate) fn inverse_sums(lam: &[C64]) -> Vec<C64> {
    let ns = lam.len();
    let mut out = vec![ZERO; ns * ns];
    // Symmetric (the sum commutes, bit for bit): one inversion per pair.
    for k in 0..ns {
        for m in k..ns {
            let v = -(lam[k] + lam[m]).inv();
            out[k * ns + m] = v;
            out[m * ns + k] = v;
        }
    }
    out
}

/// Adds one source's variances to `var` by the closed form of the module doc: its wheel
/// groups `(tau_g, G_g)` (by increasing delay) with the residues `rho[g][o][k]` of their
/// transfers on the poles `lam` (`inv_sum` from [`inverse_sums`]), times the source's
/// two-sided `intensity`.
pub(crate) fn add_source_variances(
    var: &mut [f64; N_OUT],
    lam: &[C64],
    inv_sum: &[C64],
    groups: &[(f64, [f64; N_OUT])],
    rho: &Residues,
    intensity: f64,
) {
    let ns = lam.len();
    // Buffers filled per group pair and output (a map calls this at every point).
    let (mut e, mut rle) = (vec![ZERO; ns], vec![ZERO; ns]);
    for (gi, &(g_tau, g_gain)) in groups.iter().enumerate() {
        for (li, &(l_tau, _)) in groups.iter().enumerate().take(gi + 1) {
            let dt = g_tau - l_tau;
            if dt == 0.0 {
                e.fill(C64::new(1.0, 0.0));
            } else {
                e.iter_mut()
                    .zip(lam)
                    .for_each(|(ek, &lm)| *ek = math::cexp(lm * dt));
            }
            for (o, vo) in var.iter_mut().enumerate() {
                let (rg, rl) = (&rho[gi][o], &rho[li][o]);
                rle.iter_mut()
                    .enumerate()
                    .for_each(|(m, x)| *x = rl[m] * e[m]);
                let mut t = ZERO;
                for k in 0..ns {
                    let row = &inv_sum[k * ns..(k + 1) * ns];
                    let inner: C64 = (0..ns).map(|m| rle[m] * row[m]).sum();
                    t += rg[k] * inner;
                }
                let mut t = t.re;
                if gi != li {
                    t *= 2.0; // the (l, g) ordered pair gives the same value
                    let bx: C64 = (0..ns).map(|k| rl[k] * (e[k] - 1.0) / lam[k]).sum();
                    t -= 2.0 * g_gain[o] * bx.re;
                }
                *vo += intensity * t;
            }
        }
    }
    for &(g_tau, g_gain) in groups {
        for &(l_tau, l_gain) in groups {
            for (o, v) in var.iter_mut().enumerate() {
                *v += intensity * g_gain[o] * l_gain[o] * g_tau.min(l_tau);
            }
        }
    }
}

/// The modal expansion of a model on a road: the poles `lambda_k` of the first-order
/// form and, per source, its wheel groups with the residues `rho[g][o][k]` of
/// `T_g(s) / s` (the transfer from group `g`'s road velocity to output `o`).
pub(crate) struct Expansion {
    /// The poles, rad/s.
    pub lam: Vec<C64>,
    /// Per source: the wheel groups (by increasing delay) and `rho[g][o][k]`.
    pub sources: Vec<(Vec<Group>, Residues)>,
    /// The white road velocity's intensity.
    pub intensity: f64,
}

/// `rho[g][o][k]`: group, output, pole.
pub(crate) type Residues = Vec<Vec<Vec<C64>>>;

/// The expansion of `model` on `road`, checked against a direct solve at 3 Hz; declines
/// with `Err(ModalInapplicable(..))` where it is not accurate.
pub(super) fn expand(model: &LinearModel, road: &Road) -> Result<Expansion> {
    road.validate()?;
    let exc = model.excitation(road);
    let sources: Vec<Vec<Channel>> = exc
        .sources
        .iter()
        .map(|s| s.channels.iter().map(|&(j, tau)| (j, tau, 1.0)).collect())
        .collect();
    expand_sources(model, &sources, exc.intensity)
}

/// A wheel's input column, its delay (s) and its weight in a source.
pub(crate) type Channel = (usize, f64, f64);

/// The expansion of `model` driven by independent white road-velocity `sources` of
/// two-sided `intensity` (m^2/s), each a list of weighted, delayed wheels; checked
/// against a direct solve at 3 Hz, declining with `Err(ModalInapplicable(..))` where it is
/// not accurate.
pub(crate) fn expand_sources(
    model: &LinearModel,
    sources_in: &[Vec<Channel>],
    intensity: f64,
) -> Result<Expansion> {
    let n = model.n();
    for (name, mat) in [("M", &model.m), ("C", &model.c), ("K", &model.k)] {
        let tol = 1e-12 * mat.amax();
        let asymmetric = (0..n).any(|i| (0..i).any(|j| (mat[(i, j)] - mat[(j, i)]).abs() > tol));
        if asymmetric {
            return Err(RideError::ModalInapplicable(format!(
                "{name} is not symmetric"
            )));
        }
    }
    let minv = model
        .m
        .clone()
        .try_inverse()
        .ok_or_else(|| RideError::Numerical("mass matrix is singular".into()))?;
    let kinv = model
        .k
        .clone()
        .try_inverse()
        .ok_or_else(|| RideError::Numerical("stiffness matrix is singular".into()))?;

    // Eigenvalues of the companion matrix [[0, I], [-M^-1 K, -M^-1 C]].
    let mk = &minv * &model.k;
    let mc = &minv * &model.c;
    let ns = 2 * n;
    let mut a = vec![0.0; ns * ns];
    for i in 0..n {
        a[i * ns + n + i] = 1.0;
        for j in 0..n {
            a[(n + i) * ns + j] = -mk[(i, j)];
            a[(n + i) * ns + n + j] = -mc[(i, j)];
        }
    }
    let lam = hqr::eigenvalues(&mut a, ns)
        .ok_or_else(|| RideError::ModalInapplicable("QR did not converge".into()))?;
    if lam.iter().any(|l| l.re.is_nan() || l.re >= 0.0) {
        return Err(RideError::Numerical(
            "model is not asymptotically stable".into(),
        ));
    }
    // Q(s) = s^2 M + s C + K, factorised by nalgebra's LU with partial pivoting.
    let q_lu = |s: C64| {
        DMatrix::<C64>::from_fn(n, n, |i, j| {
            s * s * model.m[(i, j)] + s * model.c[(i, j)] + model.k[(i, j)]
        })
        .lu()
    };
    // Eigenvectors and modal norms.
    let mut phi: Vec<Vec<C64>> = Vec::with_capacity(ns);
    let mut norm: Vec<C64> = Vec::with_capacity(ns);
    for &l in &lam {
        let shift = l + C64::new(1e-12, 1e-12) * math::cabs(l);
        let mut x = DVector::<C64>::from_fn(n, |i, _| {
            C64::new(1.0 + 0.1 * i as f64, 0.3 - 0.05 * i as f64)
        });
        let q = q_lu(shift);
        for _ in 0..2 {
            if !q.solve_mut(&mut x) {
                return Err(RideError::ModalInapplicable(
                    "inverse iteration failed".into(),
                ));
            }
            let s = x.iter().map(|v| v.norm_sqr()).sum::<f64>().sqrt();
            if !(s.is_finite() && s > 0.0) {
                return Err(RideError::ModalInapplicable(
                    "inverse iteration failed".into(),
                ));
            }
            x.iter_mut().for_each(|v| *v /= s);
        }
        let mut nk = ZERO;
        for i in 0..n {
            for j in 0..n {
                nk += x[i] * (2.0 * l * model.m[(i, j)] + model.c[(i, j)]) * x[j];
            }
        }
        phi.push(x.iter().copied().collect());
        norm.push(nk);
    }

    let row = |o: usize, s: C64| -> Vec<C64> {
        let r = &model.outputs[o];
        (0..n)
            .map(|i| r.q[i] + s * r.v[i] + s * s * r.a[i])
            .collect()
    };
    let rows_at_lam: Vec<[Vec<C64>; N_OUT]> = lam
        .iter()
        .map(|&l| std::array::from_fn(|o| row(o, l)))
        .collect();
    let mut sources = Vec::with_capacity(sources_in.len());
    for channels in sources_in {
        let groups = groups(model, &kinv, &minv, channels)?;
        // rho[g][o][k]
        let rho: Vec<Vec<Vec<C64>>> = groups
            .iter()
            .map(|g| {
                (0..N_OUT)
                    .map(|o| {
                        (0..ns)
                            .map(|k| {
                                let l = lam[k];
                                let rp: C64 =
                                    (0..n).map(|i| rows_at_lam[k][o][i] * phi[k][i]).sum();
                                let pf: C64 =
                                    (0..n).map(|i| phi[k][i] * (g.kr[i] + l * g.cr[i])).sum();
                                rp * pf / (l * norm[k])
                            })
                            .collect()
                    })
                    .collect()
            })
            .collect();
        // Check the expansion against a direct solve at 3 Hz.
        let s0 = C64::new(0.0, 2.0 * std::f64::consts::PI * 3.0);
        for (gi, g) in groups.iter().enumerate() {
            let mut x = DVector::<C64>::from_fn(n, |i, _| g.kr[i] + s0 * g.cr[i]);
            if !q_lu(s0).solve_mut(&mut x) {
                return Err(RideError::ModalInapplicable("check solve failed".into()));
            }
            for o in 0..N_OUT {
                let r0 = row(o, s0);
                let direct = ((0..n).map(|i| r0[i] * x[i]).sum::<C64>() + g.yr[o]) / s0;
                let modal: C64 =
                    (0..ns).map(|k| rho[gi][o][k] / (s0 - lam[k])).sum::<C64>() + g.g[o] / s0;
                if math::cabs(direct - modal) > 1e-7 * math::cabs(direct).max(1e-300) + 1e-300 {
                    return Err(RideError::ModalInapplicable(
                        "expansion check failed".into(),
                    ));
                }
            }
        }
        sources.push((groups, rho));
    }
    Ok(Expansion {
        lam,
        sources,
        intensity,
    })
}

/// Wheel groups of one source (its weighted wheels summed per delay) with their static
/// gains; refuses unbounded responses.
fn groups(
    model: &LinearModel,
    kinv: &DMatrix<f64>,
    minv: &DMatrix<f64>,
    channels: &[Channel],
) -> Result<Vec<Group>> {
    let n = model.n();
    let mut groups: Vec<Group> = Vec::new();
    for &(j, tau, w) in channels {
        let kr: Vec<f64> = (0..n).map(|i| model.kr[(i, j)] * w).collect();
        let cr: Vec<f64> = (0..n).map(|i| model.cr[(i, j)] * w).collect();
        let yr: [f64; N_OUT] = std::array::from_fn(|o| model.outputs[o].r[j] * w);
        match groups
            .iter_mut()
            .find(|g| (g.tau - tau).abs() <= 1e-12 * (1.0 + tau))
        {
            Some(g) => {
                for i in 0..n {
                    g.kr[i] += kr[i];
                    g.cr[i] += cr[i];
                }
                for o in 0..N_OUT {
                    g.yr[o] += yr[o];
                }
            }
            None => groups.push(Group {
                tau,
                kr,
                cr,
                yr,
                g: [0.0; N_OUT],
            }),
        }
    }
    crate::order::sort_by_f64_key(&mut groups, |g| g.tau);
    let scale = model.outputs.iter().map(|r| r.r.amax()).fold(1.0, f64::max);
    for g in groups.iter_mut() {
        let static_q = kinv * nalgebra::DVector::from_column_slice(&g.kr);
        let accel_in = minv * nalgebra::DVector::from_column_slice(&g.cr);
        for o in 0..N_OUT {
            let r = &model.outputs[o];
            g.g[o] = r.q.dot(&static_q) + g.yr[o];
            if r.a.dot(&accel_in).abs() > 1e-12 * scale {
                return Err(RideError::Numerical(
                    "an output feeds through the white road velocity: its RMS is unbounded".into(),
                ));
            }
        }
    }
    check_stationary(groups.iter().map(|g| g.g), scale)?;
    Ok(groups)
}

/// Exact criteria: the modal route when it is accurate, the Kronecker route otherwise.
pub fn criteria_fast_exact(model: &LinearModel, road: &Road) -> Result<Criteria> {
    match criteria_modal(model, road) {
        Err(RideError::ModalInapplicable(_)) => super::criteria_exact(model, road),
        other => other,
    }
}
