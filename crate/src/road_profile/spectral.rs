//! The frequency route on a shaped road's *raw* velocity PSD: the second, independent
//! route (no filter in it).
//!
//! For each source, its displacement transfer to each output is
//! `T(omega) = sum_j w_j exp(-i omega tau_j) T_j(omega)` over the wheels `j` it drives
//! (weight `w_j`, delay `tau_j`), with `T_j` from `Z(omega) q = Kr_j + i omega Cr_j`,
//! `Z = K + i omega C - omega^2 M` (one complex LU per frequency for all wheels) and the
//! output row `Yq + i omega Yv - omega^2 Ya` plus the feed-through `Yr_j`. The output PSD is
//! `P_y(f) = sum_sources |T(omega)|^2 / omega^2 Gv(f)`, with `Gv` the measured PSD
//! ([`super::VelocityPsd::at`]: the raw Welch bins interpolated log-log, white outside the
//! band), and the variance its integral over `[0, infinity)`.
//!
//! The integral is taken on `f = fc tan(theta)` (as `criteria::spectral` does, so the
//! `f^-2` DTL tail is integrated, not cut), by adaptive Gauss-Kronrod (7/15) whose initial
//! panels end at every breakpoint of every source's PSD (the interpolant's kinks), so each
//! panel's integrand is smooth.

use super::shaped::ShapedRoad;
use crate::criteria::{wk_gain, SpectralCriteria};
use crate::error::{Result, RideError};
use crate::evaluate::Criteria;
use crate::math;
use crate::model::{LinearModel, N_OUT};
use crate::road::N_MIN;
use nalgebra::DMatrix;
use num_complex::Complex64 as C64;
use std::cmp::Ordering;
use std::collections::BinaryHeap;
use std::f64::consts::PI;

/// Pivot of the `tan` substitution, Hz.
const FC: f64 = 4.0;
/// Most panel splits of the adaptive quadrature.
const MAX_SPLITS: usize = 20_000;

/// The frequency route of one model on one shaped road.
pub struct ShapedSpectrum<'a> {
    model: &'a LinearModel,
    road: &'a ShapedRoad,
    /// Per source: `(wheel, weight, delay s)`.
    channels: Vec<Vec<(usize, f64, f64)>>,
    /// Per source: the index into `road.sources`.
    source_of: Vec<usize>,
    /// Whether the unsprung block of the model is diagonal (and the body at most 3 DOF).
    eliminate: bool,
}

impl<'a> ShapedSpectrum<'a> {
    /// Prepares the route.
    pub fn new(model: &'a LinearModel, road: &'a ShapedRoad) -> Result<ShapedSpectrum<'a>> {
        road.validate()?;
        let mut channels = Vec::new();
        let mut source_of = Vec::new();
        for (s, src) in road.sources.iter().enumerate() {
            let ch: Vec<(usize, f64, f64)> = model
                .wheels
                .iter()
                .enumerate()
                .filter_map(|(j, w)| {
                    let weight = src.weights[w.track.min(1)];
                    (weight != 0.0).then_some((j, weight, w.behind / road.speed))
                })
                .collect();
            if !ch.is_empty() {
                channels.push(ch);
                source_of.push(s);
            }
        }
        let (n, nb) = (model.n(), model.n_body);
        let eliminate = nb <= 3
            && (nb..n).all(|i| {
                (nb..n).all(|j| {
                    i == j
                        || (model.m[(i, j)] == 0.0
                            && model.c[(i, j)] == 0.0
                            && model.k[(i, j)] == 0.0)
                })
            });
        Ok(ShapedSpectrum {
            model,
            road,
            channels,
            source_of,
            eliminate,
        })
    }

    /// Displacement transfers `T_oj(omega)` of every output `o` and wheel `j` (1/s^2, N/m,
    /// m/m): `Z q = Kr_j + i omega Cr_j` solved after eliminating the unsprung masses, whose
    /// block of `Z` is diagonal (as `criteria::spectral` does: a `n_body x n_body` solve per
    /// frequency), or by a full complex LU for a model without that structure.
    fn wheel_transfers(&self, omega: f64) -> Option<Vec<[C64; N_OUT]>> {
        let md = self.model;
        let n = md.n();
        let nb = md.n_body;
        let wheels = md.kr.ncols();
        let w2 = omega * omega;
        let z =
            |i: usize, j: usize| C64::new(md.k[(i, j)] - w2 * md.m[(i, j)], omega * md.c[(i, j)]);
        let q = if self.eliminate {
            let mut q = DMatrix::from_element(n, wheels, C64::new(0.0, 0.0));
            let dinv: Vec<C64> = (nb..n).map(|u| z(u, u).inv()).collect();
            // S = Zbb - Zbu Zuu^-1 Zub, shared by every wheel.
            let mut s = [[C64::new(0.0, 0.0); 3]; 3];
            for i in 0..nb {
                for j in 0..nb {
                    let mut v = z(i, j);
                    for u in nb..n {
                        v -= z(i, u) * dinv[u - nb] * z(u, j);
                    }
                    s[i][j] = v;
                }
            }
            for w in 0..wheels {
                let f = |i: usize| C64::new(md.kr[(i, w)], omega * md.cr[(i, w)]);
                let mut rhs = [C64::new(0.0, 0.0); 3];
                for (i, r) in rhs.iter_mut().enumerate().take(nb) {
                    let mut v = f(i);
                    for u in nb..n {
                        v -= z(i, u) * dinv[u - nb] * f(u);
                    }
                    *r = v;
                }
                let qb = solve_small(s, rhs, nb)?;
                for i in 0..nb {
                    q[(i, w)] = qb[i];
                }
                for u in nb..n {
                    let mut v = f(u);
                    for j in 0..nb {
                        v -= z(u, j) * qb[j];
                    }
                    q[(u, w)] = v * dinv[u - nb];
                }
            }
            q
        } else {
            let zm = DMatrix::from_fn(n, n, z);
            let rhs = DMatrix::from_fn(n, wheels, |i, j| {
                C64::new(md.kr[(i, j)], omega * md.cr[(i, j)])
            });
            zm.lu().solve(&rhs)?
        };
        Some(
            (0..wheels)
                .map(|j| {
                    std::array::from_fn(|o| {
                        let row = &md.outputs[o];
                        let mut y = C64::new(row.r[j], 0.0);
                        for i in 0..n {
                            let c = C64::new(row.q[i] - w2 * row.a[i], omega * row.v[i]);
                            if c != C64::new(0.0, 0.0) {
                                y += c * q[(i, j)];
                            }
                        }
                        y
                    })
                })
                .collect(),
        )
    }

    /// Per source, its displacement transfer to each output at `omega` rad/s.
    fn source_transfers(&self, omega: f64) -> Vec<[C64; N_OUT]> {
        let Some(t) = self.wheel_transfers(omega) else {
            return vec![[C64::new(f64::NAN, 0.0); N_OUT]; self.channels.len()];
        };
        self.channels
            .iter()
            .map(|ch| {
                let mut s = [C64::new(0.0, 0.0); N_OUT];
                for &(j, w, tau) in ch {
                    let ph = math::cpolar(w, -omega * tau);
                    for o in 0..N_OUT {
                        s[o] += t[j][o] * ph;
                    }
                }
                s
            })
            .collect()
    }

    /// One-sided output PSDs `[P_bacc, P_dtl, P_sws]` at `f` Hz on the measured PSD:
    /// (m/s^2)^2/Hz, N^2/Hz, m^2/Hz.
    pub(crate) fn psd(&self, f: f64) -> [f64; N_OUT] {
        self.psd_with(f, |s, f| self.road.sources[s].psd.at(f))
    }

    fn psd_with(&self, f: f64, gv: impl Fn(usize, f64) -> f64) -> [f64; N_OUT] {
        let omega = 2.0 * PI * f;
        let mut p = [0.0; N_OUT];
        for (k, t) in self.source_transfers(omega).iter().enumerate() {
            let g = gv(self.source_of[k], f) / (omega * omega);
            for o in 0..N_OUT {
                p[o] += t[o].norm_sqr() * g;
            }
        }
        p
    }

    /// Whether some source's static gains do not cancel (a road warp: the response to
    /// the road's random walk is unbounded at zero frequency).
    fn warp(&self) -> bool {
        let Some(t) = self.wheel_transfers(0.0) else {
            return false;
        };
        self.channels.iter().any(|ch| {
            (0..N_OUT).any(|o| {
                let sum: f64 = ch.iter().map(|&(j, w, _)| w * t[j][o].re).sum();
                let size: f64 = ch.iter().map(|&(j, w, _)| (w * t[j][o].re).abs()).sum();
                size > 1e-12 && sum.abs() > 1e-9 * size
            })
        })
    }

    /// RMS criteria over `[f_lo, infinity)` to relative tolerance `rtol` on the variance.
    pub(crate) fn rms(&self, f_lo: f64, rtol: f64) -> SpectralCriteria {
        let q = adaptive(|th| self.mapped_psd(th), &self.cuts(f_lo), rtol);
        SpectralCriteria {
            criteria: Criteria::from_array(q.value.map(|v| v.max(0.0).sqrt())),
            low_cutoff_hz: (f_lo > 0.0).then_some(f_lo),
            evaluations: q.evaluations,
            relative_error: q.relative_error,
        }
    }

    /// The ISO 2631-1 Wk-weighted RMS body acceleration, m/s^2:
    /// `int_0^inf |Wk(f)|^2 P_bacc(f) df` on the raw PSD to relative tolerance `rtol` (the
    /// check of [`super::bacc_wk_shaped_fast`]; Wk vanishes at 0 Hz, so a road warp needs
    /// no low cutoff here).
    pub fn bacc_wk(&self, rtol: f64) -> Result<f64> {
        let q = adaptive(
            |th| {
                let t = math::tan(th);
                let f = FC * t;
                let w = wk_gain(f);
                [self.psd(f)[0] * w * w * FC * (1.0 + t * t), 0.0, 0.0]
            },
            &self.cuts(0.0),
            rtol,
        );
        let var = q.value[0];
        if !var.is_finite() {
            return Err(RideError::Numerical(
                "frequency integral did not converge".into(),
            ));
        }
        Ok(var.max(0.0).sqrt())
    }

    /// The panels' edges in `theta = atan(f / FC)` over `[f_lo, infinity)`: the PSD's
    /// breakpoints, at least 8 panels on each side of the measured band and over the whole
    /// range.
    fn cuts(&self, f_lo: f64) -> Vec<f64> {
        let th_lo = math::atan(f_lo / FC);
        let mut edges: Vec<f64> = self
            .source_of
            .iter()
            .flat_map(|&s| self.road.sources[s].psd.f.iter().copied())
            .filter(|&f| f > f_lo)
            .map(|f| math::atan(f / FC))
            .collect();
        edges.push(th_lo);
        edges.push(PI / 2.0);
        crate::order::sort_by_f64_key(&mut edges, |x| *x);
        edges.dedup_by(|a, b| (*a - *b).abs() < 1e-15);
        let mut cuts = Vec::with_capacity(edges.len() + 16);
        for w in edges.windows(2) {
            let parts = if edges.len() < 16 || w[1] - w[0] > 0.05 {
                4
            } else {
                1
            };
            for i in 0..parts {
                cuts.push(w[0] + (w[1] - w[0]) * i as f64 / parts as f64);
            }
        }
        cuts.push(PI / 2.0);
        cuts
    }

    fn mapped_psd(&self, th: f64) -> [f64; N_OUT] {
        let t = math::tan(th);
        let jac = FC * (1.0 + t * t);
        self.psd(FC * t).map(|p| p * jac)
    }
}

/// RMS criteria of `model` on the shaped road by the frequency route on the raw PSD, to
/// relative tolerance `rtol` on the variance (see the module doc). On a road warp the band
/// starts at ISO 8608's lowest spatial frequency (0.011 cycle/m, `low_cutoff_hz` says so).
pub fn criteria_shaped_spectral(
    model: &LinearModel,
    road: &ShapedRoad,
    rtol: f64,
) -> Result<SpectralCriteria> {
    let sp = ShapedSpectrum::new(model, road)?;
    let f_lo = if sp.warp() { N_MIN * road.speed } else { 0.0 };
    let out = sp.rms(f_lo, rtol);
    if !out.criteria.to_array().iter().all(|v| v.is_finite()) {
        return Err(RideError::Numerical(
            "frequency integral did not converge".into(),
        ));
    }
    Ok(out)
}

/// Gaussian elimination with partial pivoting for `n <= 3` unknowns; `None` if singular.
fn solve_small(mut a: [[C64; 3]; 3], mut b: [C64; 3], n: usize) -> Option<[C64; 3]> {
    for k in 0..n {
        let p = (k..n).max_by(|&i, &j| math::cabs(a[i][k]).total_cmp(&math::cabs(a[j][k])))?;
        a.swap(k, p);
        b.swap(k, p);
        if math::cabs(a[k][k]) == 0.0 {
            return None;
        }
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
        let mut v = b[k];
        for j in k + 1..n {
            v -= a[k][j] * x[j];
        }
        x[k] = v / a[k][k];
    }
    Some(x)
}

/// Gauss-Kronrod 7/15 nodes (positive half, centre first) and weights, and the Gauss
/// 7-point weights of the odd-index nodes (the tables of `criteria::spectral`).
#[allow(clippy::excessive_precision)]
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
#[allow(clippy::excessive_precision)]
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
#[allow(clippy::excessive_precision)]
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
    err: [f64; N_OUT],
    key: f64,
}

impl PartialEq for Panel {
    fn eq(&self, other: &Self) -> bool {
        self.key == other.key
    }
}
impl Eq for Panel {}
impl PartialOrd for Panel {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for Panel {
    fn cmp(&self, other: &Self) -> Ordering {
        self.key.total_cmp(&other.key)
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

struct Quadrature {
    value: [f64; N_OUT],
    evaluations: usize,
    relative_error: f64,
}

/// Adaptive Gauss-Kronrod over the panels between consecutive `cuts`: splits the panel of
/// largest error (relative to the first totals) until every output's summed error estimate
/// is below `rtol` times its total, or [`MAX_SPLITS`] splits.
fn adaptive<F: Fn(f64) -> [f64; N_OUT]>(f: F, cuts: &[f64], rtol: f64) -> Quadrature {
    let make = |lo: f64, hi: f64, scale: &[f64; N_OUT]| {
        let (val, g) = gk15(&f, lo, hi);
        let err: [f64; N_OUT] = std::array::from_fn(|o| {
            ((val[o] - g[o]).abs() - 50.0 * f64::EPSILON * val[o].abs()).max(0.0)
        });
        let key = (0..N_OUT).map(|o| err[o] / scale[o]).fold(0.0, f64::max);
        Panel {
            lo,
            hi,
            val,
            err,
            key,
        }
    };
    let ones = [1.0; N_OUT];
    let first: Vec<Panel> = cuts.windows(2).map(|w| make(w[0], w[1], &ones)).collect();
    let mut evaluations = 15 * first.len();
    let mut total = [0.0; N_OUT];
    for p in &first {
        for o in 0..N_OUT {
            total[o] += p.val[o];
        }
    }
    let scale = total.map(|t| t.abs().max(f64::MIN_POSITIVE));
    let mut err = [0.0; N_OUT];
    let mut heap = BinaryHeap::with_capacity(first.len() + 2 * MAX_SPLITS);
    for mut p in first {
        p.key = (0..N_OUT).map(|o| p.err[o] / scale[o]).fold(0.0, f64::max);
        for o in 0..N_OUT {
            err[o] += p.err[o];
        }
        heap.push(p);
    }
    for _ in 0..MAX_SPLITS {
        if (0..N_OUT).all(|o| err[o] <= rtol * total[o].abs()) {
            break;
        }
        let Some(p) = heap.pop() else { break };
        let mid = 0.5 * (p.lo + p.hi);
        let a = make(p.lo, mid, &scale);
        let b = make(mid, p.hi, &scale);
        evaluations += 30;
        for o in 0..N_OUT {
            total[o] += a.val[o] + b.val[o] - p.val[o];
            err[o] += a.err[o] + b.err[o] - p.err[o];
        }
        heap.push(a);
        heap.push(b);
    }
    // Sum afresh (the running totals carry the updates' rounding).
    let mut value = [0.0; N_OUT];
    let mut e = [0.0; N_OUT];
    for p in heap.iter() {
        for o in 0..N_OUT {
            value[o] += p.val[o];
            e[o] += p.err[o];
        }
    }
    let relative_error = (0..N_OUT)
        .map(|o| {
            if e[o] == 0.0 {
                0.0
            } else {
                e[o] / value[o].abs()
            }
        })
        .fold(0.0, f64::max);
    Quadrature {
        value,
        evaluations,
        relative_error,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::car::Car;
    use crate::criteria::{criteria_exact, criteria_spectral};
    use crate::model::{full_car, quarter_car};
    use crate::road::{Road, RoadClass, Tracks};
    use crate::road_profile::{criteria_shaped, ShapedRoad};

    /// Waviness 2: the frequency route is `criteria_exact` to 1e-9 (quarter and full car,
    /// both track settings), and a road warp starts the band at ISO's 0.011 cycle/m like
    /// `criteria_spectral` does.
    #[test]
    fn waviness_two_is_criteria_exact() {
        let car = Car::datum();
        for tracks in [Tracks::Correlated, Tracks::Independent] {
            let road = Road {
                class: RoadClass::C,
                speed: 25.0,
                tracks,
            };
            let shaped = ShapedRoad::iso(&road, 2.0).unwrap();
            for model in [quarter_car(&car.quarter()), full_car(&car)] {
                let a = criteria_shaped_spectral(&model, &shaped, 1e-11).unwrap();
                let b = criteria_exact(&model, &road).unwrap();
                for (x, y) in a.criteria.to_array().iter().zip(b.to_array()) {
                    assert!((x / y - 1.0).abs() < 1e-9, "{x} vs {y}");
                }
            }
        }
        let mut warped = car.clone();
        warped.track_rear = 1.4;
        let road = Road {
            tracks: Tracks::Independent,
            ..Road::default()
        };
        let shaped = ShapedRoad::iso(&road, 2.0).unwrap();
        let a = criteria_shaped_spectral(&full_car(&warped), &shaped, 1e-9).unwrap();
        let b = criteria_spectral(&full_car(&warped), &road, 1e-9).unwrap();
        assert_eq!(a.low_cutoff_hz, b.low_cutoff_hz);
        for (x, y) in a.criteria.to_array().iter().zip(b.criteria.to_array()) {
            assert!((x / y - 1.0).abs() < 1e-7, "{x} vs {y}");
        }
    }

    /// An ISO road of waviness 2.5 and 3: the filter route is within the filter's stated
    /// error of the frequency route on the (exactly power-law) PSD.
    #[test]
    fn the_filter_route_is_within_its_error_on_iso_waviness() {
        let car = Car::datum();
        for w in [2.5, 3.0] {
            for tracks in [Tracks::Correlated, Tracks::Independent] {
                let road = Road {
                    class: RoadClass::C,
                    speed: 20.0,
                    tracks,
                };
                let shaped = ShapedRoad::iso(&road, w).unwrap();
                let err = shaped.fit_error();
                for model in [quarter_car(&car.quarter()), full_car(&car)] {
                    let a = criteria_shaped(&model, &shaped).unwrap();
                    let b = criteria_shaped_spectral(&model, &shaped, 1e-8).unwrap();
                    for (x, y) in a.to_array().iter().zip(b.criteria.to_array()) {
                        let d = (x / y - 1.0).abs();
                        assert!(d <= err, "w {w}: {x} vs {y} ({d:.2e} > stated {err:.2e})");
                    }
                }
            }
        }
    }
}
