//! The frequency route: transfer functions, output PSDs and RMS by integrating
//! `P_y(f) = |H_y(f)|^2 Gv` over the whole band, with the exact delay factor
//! `exp(-i 2 pi f tau)` on every delayed wheel.
//!
//! `H_y` is the transfer from the road *velocity* of a source, `T_y(omega) / (i omega)`,
//! where `T_y` is the transfer from its displacement:
//! `Z(omega) q = sum_j (Kr_j + i omega Cr_j) exp(-i omega tau_j)` with the dynamic stiffness
//! `Z = K + i omega C - omega^2 M`. The unsprung masses couple only to the body, so each
//! frequency costs one `n_body x n_body` complex solve (3 x 3 for the full car) after
//! eliminating the diagonal unsprung block.
//!
//! The band `[f_lo, infinity)` is mapped to `theta in [atan(f_lo / fc), pi/2)` by
//! `f = fc tan(theta)`; there the integrand is finite at both ends (the DTL PSD decays
//! only as `f^-2`, whose tail a truncated band would miss), and adaptive Gauss-Kronrod
//! (7/15 points) with global error control integrates it to a relative tolerance.

use crate::error::{Result, RideError};
use crate::evaluate::Criteria;
use crate::math;
use crate::model::{Excitation, LinearModel, N_OUT};
use crate::road::Road;
use num_complex::Complex64 as C64;
use std::f64::consts::PI;

/// The adaptive quadrature's budget of panel splits (1004 panels, 15 060 frequencies).
const MAX_SPLITS: usize = 500;

/// Pivot of the `tan` substitution, Hz (between body and wheel-hop modes).
const FC: f64 = 4.0;

/// Result of the frequency route.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpectralCriteria {
    /// RMS criteria.
    pub criteria: Criteria,
    /// Lower band limit used, Hz (`None`: the whole band from 0).
    pub low_cutoff_hz: Option<f64>,
    /// Number of frequencies evaluated.
    pub evaluations: usize,
    /// The quadrature's own error estimate relative to the variance, the largest of the
    /// three outputs: at most the requested `rtol` unless the splits ran out (see
    /// `SpectralCriteria::converged`).
    pub relative_error: f64,
}

impl SpectralCriteria {
    /// Whether the quadrature met `rtol` (it stops after `MAX_SPLITS` panel splits).
    #[cfg(test)]
    pub(crate) fn converged(&self, rtol: f64) -> bool {
        self.relative_error <= rtol
    }
}

/// Precomputed pieces for evaluating transfer functions of one model quickly.
pub struct Spectrum<'a> {
    model: &'a LinearModel,
    exc: Excitation,
    gv: f64,
}

impl<'a> Spectrum<'a> {
    /// Prepares the frequency route for `model` on `road`.
    pub fn new(model: &'a LinearModel, road: &Road) -> Result<Self> {
        road.validate()?;
        let n = model.n();
        let nb = model.n_body;
        for i in nb..n {
            for j in 0..n {
                if i != j
                    && j >= nb
                    && (model.m[(i, j)] != 0.0 || model.c[(i, j)] != 0.0 || model.k[(i, j)] != 0.0)
                {
                    return Err(RideError::Numerical(
                        "unsprung block is not diagonal".into(),
                    ));
                }
            }
        }
        Ok(Spectrum {
            model,
            exc: model.excitation(road),
            gv: 2.0 * road.intensity(),
        })
    }

    /// Number of independent road sources.
    pub fn sources(&self) -> usize {
        self.exc.sources.len()
    }

    /// Transfer from the displacement of source `s` to `[BAcc, DTL, SWS]` at angular
    /// frequency `omega` (rad/s), delays included: units 1/s^2, N/m, m/m.
    pub fn displacement_transfer(&self, s: usize, omega: f64) -> [C64; N_OUT] {
        let md = self.model;
        let n = md.n();
        let nb = md.n_body;
        let iw = C64::new(0.0, omega);
        let w2 = omega * omega;
        let z =
            |i: usize, j: usize| C64::new(md.k[(i, j)] - w2 * md.m[(i, j)], omega * md.c[(i, j)]);
        // Right-hand side: sum over the source's wheels of (Kr + i w Cr) exp(-i w tau).
        let mut f = [C64::new(0.0, 0.0); 16];
        let mut yr = [C64::new(0.0, 0.0); N_OUT];
        for &(j, tau) in &self.exc.sources[s].channels {
            let ph = math::cpolar(1.0, -omega * tau);
            for (i, fi) in f.iter_mut().enumerate().take(n) {
                *fi += (md.kr[(i, j)] + iw * md.cr[(i, j)]) * ph;
            }
            for (o, y) in yr.iter_mut().enumerate() {
                *y += md.outputs[o].r[j] * ph;
            }
        }
        // Eliminate the diagonal unsprung block: S = Zbb - Zbu Zuu^-1 Zub.
        let mut s_mat = [[C64::new(0.0, 0.0); 3]; 3];
        let mut rhs = [C64::new(0.0, 0.0); 3];
        for i in 0..nb {
            for j in 0..nb {
                s_mat[i][j] = z(i, j);
            }
            rhs[i] = f[i];
        }
        let mut dinv = [C64::new(0.0, 0.0); 16];
        for u in nb..n {
            dinv[u] = z(u, u).inv();
            for i in 0..nb {
                let ziu = z(i, u);
                if ziu == C64::new(0.0, 0.0) {
                    continue;
                }
                let t = ziu * dinv[u];
                for j in 0..nb {
                    s_mat[i][j] -= t * z(u, j);
                }
                rhs[i] -= t * f[u];
            }
        }
        let qb = solve_small(&mut s_mat, &mut rhs, nb);
        let mut q = [C64::new(0.0, 0.0); 16];
        q[..nb].copy_from_slice(&qb[..nb]);
        for u in nb..n {
            let mut acc = f[u];
            for j in 0..nb {
                acc -= z(u, j) * q[j];
            }
            q[u] = acc * dinv[u];
        }
        std::array::from_fn(|o| {
            let row = &md.outputs[o];
            let mut y = yr[o];
            for i in 0..n {
                let coef = row.q[i] + iw * row.v[i] - w2 * row.a[i];
                if coef != C64::new(0.0, 0.0) {
                    y += coef * q[i];
                }
            }
            y
        })
    }

    /// One-sided output PSDs `[P_bacc, P_dtl, P_sws]` at `f` Hz, summed over sources:
    /// units (m/s^2)^2/Hz, N^2/Hz, m^2/Hz.
    pub(crate) fn psd(&self, f: f64) -> [f64; N_OUT] {
        let omega = 2.0 * PI * f;
        let mut p = [0.0; N_OUT];
        for s in 0..self.sources() {
            let t = self.displacement_transfer(s, omega);
            for o in 0..N_OUT {
                p[o] += t[o].norm_sqr() / (omega * omega) * self.gv;
            }
        }
        p
    }

    /// RMS criteria over `[f_lo, infinity)` to relative tolerance `rtol`.
    pub fn rms(&self, f_lo: f64, rtol: f64) -> SpectralCriteria {
        self.rms_band(f_lo, f64::INFINITY, rtol)
    }

    /// RMS criteria over the band `[f_lo, f_hi]` (`f_hi` may be infinite) to relative
    /// tolerance `rtol` on the variance, with the number of frequencies evaluated and the
    /// error estimate reached (`low_cutoff_hz`: `f_lo` when it is above 0).
    pub fn rms_band(&self, f_lo: f64, f_hi: f64, rtol: f64) -> SpectralCriteria {
        let q = adaptive_gk15(|th| self.mapped_psd(th), theta(f_lo), theta(f_hi), rtol);
        SpectralCriteria {
            criteria: to_rms(q.value),
            low_cutoff_hz: (f_lo > 0.0).then_some(f_lo),
            evaluations: q.evaluations,
            relative_error: q.relative_error,
        }
    }

    /// RMS criteria over the whole band by a fixed rule: `panels` equal panels in
    /// `theta` with 15-point Gauss-Kronrod each (for grid-convergence studies).
    pub fn rms_fixed(&self, panels: usize) -> Criteria {
        let (lo, hi) = (0.0, PI / 2.0);
        let w = (hi - lo) / panels as f64;
        let mut var = [0.0; N_OUT];
        for i in 0..panels {
            let (k, _) = gk15(
                &|th| self.mapped_psd(th),
                lo + i as f64 * w,
                lo + (i + 1) as f64 * w,
            );
            for o in 0..N_OUT {
                var[o] += k[o];
            }
        }
        to_rms(var)
    }

    /// `int_0^inf weight(f)^2 P_output(f) df` by adaptive Gauss-Kronrod to relative
    /// tolerance `rtol`: the variance of output `output` (0 BAcc, 1 DTL, 2 SWS) through
    /// a frequency weighting of gain `weight(f)`, and the error estimate reached relative
    /// to it (above `rtol` only when the splits ran out).
    pub(crate) fn weighted_variance(
        &self,
        output: usize,
        weight: impl Fn(f64) -> f64,
        rtol: f64,
    ) -> (f64, f64) {
        let q = adaptive_gk15(
            |th| {
                let t = math::tan(th);
                let w = weight(FC * t);
                let p = self.mapped_psd(th)[output] * w * w;
                std::array::from_fn(|o| if o == 0 { p } else { 0.0 })
            },
            0.0,
            PI / 2.0,
            rtol,
        );
        (q.value[0], q.relative_error)
    }

    /// The PSDs times the Jacobian of `f = FC tan(theta)`.
    fn mapped_psd(&self, th: f64) -> [f64; N_OUT] {
        let t = math::tan(th);
        let jac = FC * (1.0 + t * t);
        self.psd(FC * t).map(|p| p * jac)
    }
}

fn theta(f: f64) -> f64 {
    if f.is_infinite() {
        PI / 2.0
    } else {
        math::atan(f / FC)
    }
}

fn to_rms(var: [f64; N_OUT]) -> Criteria {
    Criteria::from_array(var.map(|v| v.max(0.0).sqrt()))
}

/// RMS criteria by the frequency route to relative tolerance `rtol` (on the variance).
/// If the response is unbounded at low frequency (road warp), the band starts at
/// ISO 8608's lowest spatial frequency 0.011 cycle/m and `low_cutoff_hz` says so. A
/// quadrature that runs out of splits before `rtol` says how far it got in
/// `relative_error` (see `SpectralCriteria::converged`).
pub fn criteria_spectral(model: &LinearModel, road: &Road, rtol: f64) -> Result<SpectralCriteria> {
    let sp = Spectrum::new(model, road)?;
    let cutoff = if warp_unbounded(&sp) {
        Some(road.lowest_frequency())
    } else {
        None
    };
    let out = sp.rms(cutoff.unwrap_or(0.0), rtol);
    if !out.criteria.to_array().iter().all(|v| v.is_finite()) {
        return Err(RideError::Numerical(
            "frequency integral did not converge".into(),
        ));
    }
    Ok(out)
}

/// True when the velocity transfer has a pole at zero frequency (static deflection
/// from a road warp), detected from the displacement transfer's limit at 0.
fn warp_unbounded(sp: &Spectrum) -> bool {
    let w = 1e-7;
    (0..sp.sources()).any(|s| {
        let t = sp.displacement_transfer(s, w);
        let big = sp.displacement_transfer(s, 2.0 * PI * 10.0);
        // |T(w)| stays O(1) instead of O(w) when the static gain is non-zero.
        (0..N_OUT).any(|o| math::cabs(t[o]) > 1e-4 * math::cabs(big[o]).max(1e-300))
    })
}

/// Gaussian elimination with partial pivoting for a system of size `n <= 3`.
fn solve_small(a: &mut [[C64; 3]; 3], b: &mut [C64; 3], n: usize) -> [C64; 3] {
    for k in 0..n {
        let p = (k..n)
            .max_by(|&i, &j| math::cabs(a[i][k]).total_cmp(&math::cabs(a[j][k])))
            .unwrap_or(k);
        a.swap(k, p);
        b.swap(k, p);
        let inv = a[k][k].inv();
        for i in k + 1..n {
            let l = a[i][k] * inv;
            for j in k..n {
                let akj = a[k][j];
                a[i][j] -= l * akj;
            }
            let bk = b[k];
            b[i] -= l * bk;
        }
    }
    let mut x = [C64::new(0.0, 0.0); 3];
    for k in (0..n).rev() {
        let mut s = b[k];
        for j in k + 1..n {
            s -= a[k][j] * x[j];
        }
        x[k] = s / a[k][k];
    }
    x
}

/// Gauss-Kronrod 7/15 nodes on [-1, 1] (positive half, centre first) and weights.
const XGK: [f64; 8] = [
    0.0,
    0.207_784_955_007_898_467_6,
    0.405_845_151_377_397_166_9,
    0.586_087_235_467_691_130_3,
    0.741_531_185_599_394_439_9,
    0.864_864_423_359_769_072_8,
    0.949_107_912_342_758_524_5,
    0.991_455_371_120_812_639_2,
];
const WGK: [f64; 8] = [
    0.209_482_141_084_727_828_0,
    0.204_432_940_075_298_892_4,
    0.190_350_578_064_785_409_9,
    0.169_004_726_639_267_902_8,
    0.140_653_259_715_525_918_7,
    0.104_790_010_322_250_183_8,
    0.063_092_092_629_978_553_3,
    0.022_935_322_010_529_224_9,
];
/// Gauss 7-point weights for the Kronrod nodes with odd index (centre, 2, 4, 6).
const WG: [f64; 4] = [
    0.417_959_183_673_469_387_8,
    0.381_830_050_505_118_944_9,
    0.279_705_391_489_276_667_9,
    0.129_484_966_168_869_693_3,
];

struct Panel {
    lo: f64,
    hi: f64,
    val: [f64; N_OUT],
    /// Absolute error estimate per component: Kronrod-Gauss difference above a roundoff floor.
    err: [f64; N_OUT],
}

impl Panel {
    fn new<F: Fn(f64) -> [f64; N_OUT]>(f: &F, lo: f64, hi: f64) -> Panel {
        let (val, g) = gk15(f, lo, hi);
        let err = std::array::from_fn(|o| {
            ((val[o] - g[o]).abs() - 50.0 * f64::EPSILON * val[o].abs()).max(0.0)
        });
        Panel { lo, hi, val, err }
    }

    /// The panel's largest error relative to the component totals.
    fn weight(&self, total: &[f64; N_OUT]) -> f64 {
        (0..N_OUT)
            .map(|o| self.err[o] / total[o].abs().max(f64::MIN_POSITIVE))
            .fold(0.0, f64::max)
    }
}

fn gk15<F: Fn(f64) -> [f64; N_OUT]>(f: &F, lo: f64, hi: f64) -> ([f64; N_OUT], [f64; N_OUT]) {
    let c = 0.5 * (lo + hi);
    let h = 0.5 * (hi - lo);
    let fc = f(c);
    let mut k = fc.map(|v| v * WGK[0]);
    let mut g = fc.map(|v| v * WG[0]);
    for i in 1..8 {
        let a = f(c - h * XGK[i]);
        let b = f(c + h * XGK[i]);
        for o in 0..N_OUT {
            let s = a[o] + b[o];
            k[o] += WGK[i] * s;
            if i % 2 == 0 {
                g[o] += WG[i / 2] * s;
            }
        }
    }
    (k.map(|v| v * h), g.map(|v| v * h))
}

/// Adaptive Gauss-Kronrod on `[lo, hi]` for three non-negative integrands at once:
/// splits the panel with the largest error relative to the totals until, for every
/// component, the summed error estimate is below `rtol` times the total (at most
/// `MAX_SPLITS` splits).
fn adaptive_gk15<F: Fn(f64) -> [f64; N_OUT]>(f: F, lo: f64, hi: f64, rtol: f64) -> Quadrature {
    const INITIAL: usize = 4;
    let width = (hi - lo) / INITIAL as f64;
    let mut panels: Vec<Panel> = (0..INITIAL)
        .map(|i| Panel::new(&f, lo + i as f64 * width, lo + (i + 1) as f64 * width))
        .collect();
    let total = |ps: &[Panel]| -> [f64; N_OUT] {
        std::array::from_fn(|o| ps.iter().map(|p| p.val[o]).sum())
    };
    for _ in 0..MAX_SPLITS {
        let t = total(&panels);
        let converged =
            (0..N_OUT).all(|o| panels.iter().map(|p| p.err[o]).sum::<f64>() <= rtol * t[o].abs());
        if converged {
            break;
        }
        let worst = (0..panels.len())
            .max_by(|&i, &j| panels[i].weight(&t).total_cmp(&panels[j].weight(&t)))
            .unwrap_or(0);
        let p = panels.swap_remove(worst);
        let mid = 0.5 * (p.lo + p.hi);
        panels.push(Panel::new(&f, p.lo, mid));
        panels.push(Panel::new(&f, mid, p.hi));
    }
    let value = total(&panels);
    let relative_error = (0..N_OUT)
        .map(|o| {
            let err: f64 = panels.iter().map(|p| p.err[o]).sum();
            if err == 0.0 {
                0.0
            } else {
                err / value[o].abs()
            }
        })
        .fold(0.0, f64::max);
    Quadrature {
        value,
        // Every split evaluates two new panels: 15 (INITIAL + 2 splits) points in all.
        evaluations: 15 * (2 * panels.len() - INITIAL),
        relative_error,
    }
}

/// What [`adaptive_gk15`] returns.
struct Quadrature {
    /// The three integrals.
    value: [f64; N_OUT],
    /// Integrand evaluations.
    evaluations: usize,
    /// The summed error estimate relative to the integral, the largest of the three.
    relative_error: f64,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::car::{Car, QuarterCar};
    use crate::criteria::quarter_car_rms;
    use crate::model::quarter_car;

    /// The quadrature says how far it got: at 1e-8 it meets the tolerance and agrees with
    /// the closed form; asked for a tolerance of 0 (which no error estimate meets) the
    /// splits run out, and `converged` and the estimate say so.
    #[test]
    fn a_quadrature_that_runs_out_of_splits_says_so() {
        let q = QuarterCar {
            ct: 0.0,
            ..Car::datum().quarter()
        };
        let road = Road::default();
        let model = quarter_car(&q);
        let ok = criteria_spectral(&model, &road, 1e-8).unwrap();
        assert!(ok.converged(1e-8) && ok.relative_error <= 1e-8);
        let exact = quarter_car_rms(&q, road.intensity()).to_array();
        for (a, b) in ok.criteria.to_array().iter().zip(exact) {
            assert!((a / b - 1.0).abs() < 1e-7, "{a} vs closed form {b}");
        }
        let sp = Spectrum::new(&model, &road).unwrap();
        let tight = sp.rms(0.0, 0.0);
        assert!(
            !tight.converged(0.0),
            "error estimate {}",
            tight.relative_error
        );
        assert!(
            tight.relative_error < 1e-12,
            "and the estimate is still small"
        );
        assert_eq!(tight.evaluations, 15 * (2 * (4 + MAX_SPLITS) - 4));
        let out = criteria_spectral(&model, &road, 0.0).unwrap();
        assert!(!out.converged(0.0) && out.relative_error == tight.relative_error);
    }
}
