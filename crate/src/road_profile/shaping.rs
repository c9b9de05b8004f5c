//! The road velocity at a speed: its measured PSD ([`VelocityPsd`]) and a small stable
//! rational filter that shapes unit white noise into it ([`ShapingFilter`]).
//!
//! At speed `v` a spatial displacement PSD `Gd(n)` (m^3) is the temporal velocity PSD
//!
//! ```text
//! Gv(f) = (2 pi f)^2 Gd(f / v) / v          (m^2/s^2 per Hz, one-sided)
//! ```
//!
//! used over a band `[f_a, f_b]` (Hz) and extended outside it ([`Extension`]): from the
//! band's first and last smoothed points it keeps the slope of the band's first and last
//! octave for [`EXTENSION_SLOPE_OCTAVES`] (2) octaves, then turns white (ISO 8608's default,
//! `w = 2`), so the total variance stays finite at both ends and a kink the filter cannot
//! follow sits well outside the band.
//!
//! The filter is `F(s) = K prod_i (s + z_i) / (s + p_i)` with real `z_i, p_i > 0` (stable,
//! minimum phase; flat at both ends like the extension): driven by white noise of unit
//! intensity (`E[w(t) w(t')] = delta(t - t')`, one-sided PSD 2) its output has one-sided
//! PSD `2 |F(i 2 pi f)|^2`, fitted to `Gv` by least squares in log magnitude
//! (Levenberg-Marquardt on `ln K, ln z_i, ln p_i`, from poles and zeros interlaced along the
//! band with the spacing that gives the band's mean slope: the classic rational
//! approximation of a fractional slope) at
//!
//! - the band's 1/12-octave means of `Gv` (each of at least 3 Welch bins),
//! - a 1/6-octave grid over four octaves either side of the band and both asymptotes
//!   (`f = 0`, `f = infinity`), against the extensions,
//!
//! for 4, 6 and 8 poles (two starts each), keeping the fewest poles within 25 % of the
//! best error whose partial fractions do not cancel (for the fast routes,
//! [`crate::criteria::PoleZeroFilter::new`]), else the fewest within 10 % of the best. Its error in the band ([`ShapingFilter::max_error`]) is the largest
//! relative error of the power in a third-octave band (at least 8 Welch bins, so that the
//! estimate's own scatter, about 20 % from bin to bin, does not pass for the filter's),
//! `sum_k 2 |F(f_k)|^2 / sum_k Gv(f_k) - 1` over the band's bins: where `|H|^2` is nearly
//! constant over a third octave (it is, away from lightly damped modes) the criteria's
//! variances differ by at most that; outside the band it is the largest
//! `|2 |F|^2 / Gv - 1|` over the extensions' points and asymptotes
//! ([`ShapingFilter::max_error_outside`]).
//! A white `Gv` (waviness exactly 2) gives the constant filter `F = sqrt(Gv / 2)`.

use super::welch::{band_means, band_ranges};
use crate::criteria::PoleZeroFilter;
use crate::error::{Result, RideError};
use crate::math;
#[cfg(test)]
use crate::road::N0;
use levenberg_marquardt::{LeastSquaresProblem, LevenbergMarquardt};
use nalgebra::{storage::Owned, DMatrix, DVector, Dyn};
use serde::Serialize;
use std::f64::consts::PI;

/// Most poles of a shaping filter.
#[cfg(test)]
const MAX_FILTER_ORDER: usize = 8;
/// Filter orders tried.
const ORDERS: [usize; 3] = [4, 6, 8];
/// Band means per octave of the fit's target, and fewest Welch bins in each.
const TARGET_PER_OCTAVE: f64 = 12.0;
const TARGET_MIN_BINS: usize = 3;
/// Bands per octave over which the fit's error is stated, and fewest Welch bins in each.
const CHECK_PER_OCTAVE: f64 = 3.0;
const CHECK_MIN_BINS: usize = 8;
/// Octaves of extension fitted either side of the band.
const EXTENSION_OCTAVES: f64 = 4.0;
/// Log-spaced breakpoints per decade of an analytic (ISO) velocity PSD.
#[cfg(test)]
const ISO_PER_DECADE: f64 = 50.0;
/// Octaves over which a velocity PSD keeps its end slope beyond the band before it turns
/// white.
pub(crate) const EXTENSION_SLOPE_OCTAVES: f64 = 2.0;

/// How a velocity PSD continues beyond its breakpoints: the power law of the band's end,
/// bending smoothly to white beyond `corner`:
///
/// ```text
/// low side  Gv(f) = level ((f^2 + fc^2) / (fa^2 + fc^2))^(slope / 2)
/// high side Gv(f) = level ((f^-2 + fc^-2) / (fa^-2 + fc^-2))^(-slope / 2)
/// ```
///
/// (`fa` the anchor, `fc` the corner): `level (f / fa)^slope` between them, constant beyond
/// the corner, with a knee a rational filter can follow (a hard corner it cannot).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Extension {
    /// Where the power law is anchored, Hz (the band's first or last smoothed point).
    pub anchor_hz: f64,
    /// `Gv` at the anchor, m^2/s^2 per Hz.
    pub level: f64,
    /// Log-log slope, -: the band's first or last octave's (`2 - w` for an ISO road).
    pub slope: f64,
    /// Where the velocity turns white, Hz ([`EXTENSION_SLOPE_OCTAVES`] octaves out).
    pub corner_hz: f64,
}

impl Extension {
    #[cfg(test)]
    fn white(gv: f64) -> Extension {
        Extension {
            anchor_hz: 1.0,
            level: gv,
            slope: 0.0,
            corner_hz: 1.0,
        }
    }

    /// `Gv(f)` on the low side or the high side (`f` may be 0 or infinite).
    fn at(&self, f: f64, low: bool) -> f64 {
        if self.slope == 0.0 {
            return self.level;
        }
        let (fa, fc) = (self.anchor_hz, self.corner_hz);
        let ratio = if low {
            (f * f + fc * fc) / (fa * fa + fc * fc)
        } else {
            let inv = |x: f64| if x.is_infinite() { 0.0 } else { 1.0 / (x * x) };
            (inv(fa) + inv(fc)) / (inv(f) + inv(fc))
        };
        self.level * math::powf(ratio, 0.5 * self.slope)
    }

    /// The constant `Gv` far beyond the corner.
    fn asymptote(&self, low: bool) -> f64 {
        self.at(if low { 0.0 } else { f64::INFINITY }, low)
    }
}

/// A one-sided road velocity PSD over temporal frequency (see the module doc).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct VelocityPsd {
    /// Breakpoints, Hz (increasing; empty for a white PSD).
    pub f: Vec<f64>,
    /// `Gv` at the breakpoints, m^2/s^2 per Hz (log-log interpolated between them).
    pub gv: Vec<f64>,
    /// How `Gv` continues below the first breakpoint.
    pub below: Extension,
    /// How `Gv` continues above the last breakpoint.
    pub above: Extension,
    /// The band where `Gv` is measured, Hz.
    pub band: [f64; 2],
    /// Smoothed `(f, Gv)` in the band: the filter fit's target.
    #[serde(skip)]
    target: Vec<(f64, f64)>,
    /// Third-octave bands of breakpoints (index ranges) over which the fit's error is stated.
    #[serde(skip)]
    checks: Vec<(usize, usize)>,
}

impl VelocityPsd {
    /// A white velocity PSD `gv` (m^2/s^2 per Hz) everywhere.
    #[cfg(test)]
    pub(crate) fn white(gv: f64, band: [f64; 2]) -> VelocityPsd {
        VelocityPsd {
            f: Vec::new(),
            gv: Vec::new(),
            below: Extension::white(gv),
            above: Extension::white(gv),
            band,
            target: Vec::new(),
            checks: Vec::new(),
        }
    }

    /// ISO 8608 with waviness `w` at speed `v`: `Gv(f) = (2 pi n0)^2 Gd(n0) v (f / (n0 v))^(2 - w)`
    /// over `band` and [`EXTENSION_SLOPE_OCTAVES`] octaves beyond it, white further out;
    /// exactly white for `w = 2`.
    #[cfg(test)]
    pub(crate) fn iso(gd_n0: f64, waviness: f64, speed: f64, band: [f64; 2]) -> VelocityPsd {
        let gv = |f: f64| {
            (2.0 * PI * N0).powi(2) * gd_n0 * speed * math::powf(f / (N0 * speed), 2.0 - waviness)
        };
        if waviness == 2.0 {
            return VelocityPsd::white(gv(1.0), band);
        }
        let decades = math::log10(band[1] / band[0]);
        let m = (decades * ISO_PER_DECADE).ceil().max(1.0) as usize;
        let f: Vec<f64> = (0..=m)
            .map(|i| band[0] * math::powf(band[1] / band[0], i as f64 / m as f64))
            .collect();
        let g: Vec<f64> = f.iter().map(|&x| gv(x)).collect();
        let out = math::powf(2f64, EXTENSION_SLOPE_OCTAVES);
        VelocityPsd {
            below: Extension {
                anchor_hz: band[0],
                level: g[0],
                slope: 2.0 - waviness,
                corner_hz: band[0] / out,
            },
            above: Extension {
                anchor_hz: band[1],
                level: g[m],
                slope: 2.0 - waviness,
                corner_hz: band[1] * out,
            },
            target: f.iter().copied().zip(g.iter().copied()).collect(),
            checks: band_ranges(&f, f[0], f[m], CHECK_PER_OCTAVE, CHECK_MIN_BINS),
            f,
            gv: g,
            band,
        }
    }

    /// The velocity PSD at speed `v` of a Welch displacement PSD `gd` (m^3) over bins `n`
    /// (cycle/m), measured over `band` (Hz; within the bins' range). The extensions start
    /// from the first and last smoothed points with the slope of the band's first and last
    /// octave of smoothed points (clamped to [-2, 2]: waviness 0..4).
    pub(crate) fn from_spatial(
        n: &[f64],
        gd: &[f64],
        speed: f64,
        band: [f64; 2],
    ) -> Result<VelocityPsd> {
        let floor = gd.iter().copied().fold(0.0, f64::max) * 1e-15;
        let (f, g): (Vec<f64>, Vec<f64>) = n
            .iter()
            .zip(gd)
            .map(|(&nj, &p)| {
                let f = nj * speed;
                (f, (2.0 * PI * f).powi(2) * p.max(floor) / speed)
            })
            .filter(|(f, _)| *f >= band[0] && *f <= band[1])
            .unzip();
        if f.len() < 4 * TARGET_MIN_BINS || !g.iter().all(|v| v.is_finite() && *v > 0.0) {
            return Err(RideError::field(
                "distance_m",
                format!(
                    "the profile has too few PSD bins in {:.2}..{:.1} Hz at {speed} m/s",
                    band[0], band[1]
                ),
            ));
        }
        let last = f[f.len() - 1];
        let target = band_means(&f, &g, f[0], last, TARGET_PER_OCTAVE, TARGET_MIN_BINS);
        let out = math::powf(2f64, EXTENSION_SLOPE_OCTAVES);
        let (lo, hi) = (target[0], target[target.len() - 1]);
        let below = Extension {
            anchor_hz: lo.0,
            level: lo.1,
            slope: end_slope(target.iter().filter(|t| t.0 <= 2.0 * lo.0)),
            corner_hz: lo.0 / out,
        };
        let above = Extension {
            anchor_hz: hi.0,
            level: hi.1,
            slope: end_slope(target.iter().filter(|t| t.0 >= 0.5 * hi.0)),
            corner_hz: hi.0 * out,
        };
        Ok(VelocityPsd {
            checks: band_ranges(&f, f[0], last, CHECK_PER_OCTAVE, CHECK_MIN_BINS),
            f,
            gv: g,
            below,
            above,
            band,
            target,
        })
    }

    /// Whether the PSD is white (no breakpoints, no slopes, equal ends).
    fn is_white(&self) -> bool {
        self.f.is_empty()
            && self.below.slope == 0.0
            && self.above.slope == 0.0
            && self.below.level == self.above.level
    }

    /// `Gv(f)`, m^2/s^2 per Hz: log-log interpolation between breakpoints, the
    /// extensions outside them (`f` may be 0 or infinite).
    pub(crate) fn at(&self, f: f64) -> f64 {
        let m = self.f.len();
        if m == 0 {
            return if f <= self.below.anchor_hz {
                self.below.at(f, true)
            } else {
                self.above.at(f, false)
            };
        }
        if f < self.f[0] {
            return self.below.at(f, true);
        }
        if f > self.f[m - 1] {
            return self.above.at(f, false);
        }
        let k = self.f.partition_point(|&x| x <= f).clamp(1, m - 1);
        let (f0, f1) = (self.f[k - 1], self.f[k]);
        let (g0, g1) = (self.gv[k - 1], self.gv[k]);
        let t = math::ln(f / f0) / math::ln(f1 / f0);
        g0 * math::powf(g1 / g0, t)
    }

    /// The points the filter is fitted to and judged on, `(f Hz, Gv, in band)`, with
    /// `f = 0` and `f = infinity` for the asymptotes.
    fn fit_points(&self) -> Vec<(f64, f64, bool)> {
        let step = math::powf(2f64, 1.0 / TARGET_PER_OCTAVE);
        let count = (EXTENSION_OCTAVES * TARGET_PER_OCTAVE) as i32;
        let mut pts = vec![(0.0, self.below.asymptote(true), false)];
        let lo = self.target.first().map_or(self.band[0], |t| t.0);
        let hi = self.target.last().map_or(self.band[1], |t| t.0);
        pts.extend((1..=count).rev().map(|i| {
            let f = lo * step.powi(-i);
            (f, self.below.at(f, true), false)
        }));
        pts.extend(self.target.iter().map(|&(f, g)| (f, g, true)));
        pts.extend((1..=count).map(|i| {
            let f = hi * step.powi(i);
            (f, self.above.at(f, false), false)
        }));
        pts.push((f64::INFINITY, self.above.asymptote(false), false));
        pts
    }
}

/// Least-squares log-log slope of `(f, Gv)` points, clamped to [-2, 2] (0 for fewer
/// than two points).
fn end_slope<'a>(pts: impl Iterator<Item = &'a (f64, f64)>) -> f64 {
    let p: Vec<(f64, f64)> = pts.map(|(f, g)| (math::ln(*f), math::ln(*g))).collect();
    if p.len() < 2 {
        return 0.0;
    }
    let k = p.len() as f64;
    let xm = p.iter().map(|q| q.0).sum::<f64>() / k;
    let ym = p.iter().map(|q| q.1).sum::<f64>() / k;
    let sxx: f64 = p.iter().map(|q| (q.0 - xm).powi(2)).sum();
    let sxy: f64 = p.iter().map(|q| (q.0 - xm) * (q.1 - ym)).sum();
    if sxx > 0.0 {
        (sxy / sxx).clamp(-2.0, 2.0)
    } else {
        0.0
    }
}

/// `F(s) = K prod (s + z_i) / (s + p_i)`: road velocity (m/s) from unit white noise.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ShapingFilter {
    /// `K`, m/s^0.5 (the high-frequency gain).
    pub gain: f64,
    /// Zeros `z_i`, rad/s (`F` vanishes at `s = -z_i`).
    pub zeros: Vec<f64>,
    /// Poles `p_i`, rad/s (at `s = -p_i`).
    pub poles: Vec<f64>,
    /// The fit's error in the band, -: the largest relative error of the power of a
    /// third-octave band (at least 8 Welch bins), `sum 2 |F(f_k)|^2 / sum Gv(f_k) - 1`
    /// over the band's bins `f_k`.
    pub max_error: f64,
    /// RMS of those third-octave errors, -.
    pub rms_error: f64,
    /// Largest `|2 |F|^2 / Gv - 1|` over the extensions' points and both asymptotes, -.
    pub max_error_outside: f64,
    /// The band the PSD was measured over, Hz.
    pub band: [f64; 2],
}

impl ShapingFilter {
    /// The constant filter `sqrt(gv / 2)` of a white velocity PSD `gv`.
    pub(crate) fn constant(gv: f64, band: [f64; 2]) -> ShapingFilter {
        ShapingFilter {
            gain: (gv / 2.0).sqrt(),
            zeros: Vec::new(),
            poles: Vec::new(),
            max_error: 0.0,
            rms_error: 0.0,
            max_error_outside: 0.0,
            band,
        }
    }

    /// Fits the filter to `psd` (see the module doc).
    pub(crate) fn fit(psd: &VelocityPsd) -> Result<ShapingFilter> {
        if psd.is_white() {
            return Ok(ShapingFilter::constant(psd.below.level, psd.band));
        }
        let pts = psd.fit_points();
        let jobs: Vec<(usize, usize)> = ORDERS
            .iter()
            .flat_map(|&m| (0..STARTS).map(move |k| (m, k)))
            .collect();
        let mut runs = each_job(&jobs, |&(m, k)| fit_start(psd, &pts, m, k)).into_iter();
        // Per order, the better of its starts (the first of equals).
        let mut fits: Vec<ShapingFilter> = ORDERS
            .iter()
            .filter_map(|_| {
                runs.by_ref().take(STARTS).flatten().reduce(|a, b| {
                    if b.error() < a.error() {
                        b
                    } else {
                        a
                    }
                })
            })
            .collect();
        let score = |f: &ShapingFilter| f.max_error.max(f.max_error_outside);
        let best = fits.iter().map(score).fold(f64::INFINITY, f64::min);
        // The fewest poles within 10 % of the best error; first among the filters whose
        // partial fractions do not cancel (within 25 % of the best error), which the modal
        // and residue routes take (nearly repeated poles send every design to the
        // Lyapunov route, ten times slower).
        let pick = fits
            .iter()
            .position(|f| score(f) <= 1.25 * best && f.pole_zero().is_some())
            .or_else(|| fits.iter().position(|f| score(f) <= 1.1 * best));
        pick.map(|i| fits.swap_remove(i))
            .ok_or_else(|| RideError::Numerical("the shaping filter fit did not converge".into()))
    }

    /// The largest error in and outside the band, -.
    pub(crate) fn error(&self) -> f64 {
        self.max_error.max(self.max_error_outside)
    }

    /// Number of poles (states).
    pub(crate) fn order(&self) -> usize {
        self.poles.len()
    }

    /// `F(i omega)` at `f` Hz.
    #[cfg(test)]
    fn response(&self, f: f64) -> num_complex::Complex64 {
        let s = num_complex::Complex64::new(0.0, 2.0 * PI * f);
        self.zeros.iter().zip(&self.poles).fold(
            num_complex::Complex64::new(self.gain, 0.0),
            |acc, (z, p)| acc * (s + z) / (s + p),
        )
    }

    /// The filter with its partial fractions, for the modal and residue routes; `None`
    /// when its partial fractions cancel ([`PoleZeroFilter::new`]).
    pub(crate) fn pole_zero(&self) -> Option<PoleZeroFilter> {
        PoleZeroFilter::new(self.gain, &self.zeros, &self.poles)
    }

    /// The velocity PSD the filter gives, `2 |F(i 2 pi f)|^2`, m^2/s^2 per Hz (`f` may be
    /// infinite).
    pub(crate) fn psd(&self, f: f64) -> f64 {
        let w2 = (2.0 * PI * f).powi(2);
        let mut g = 2.0 * self.gain * self.gain;
        if f.is_infinite() {
            return g;
        }
        for (z, p) in self.zeros.iter().zip(&self.poles) {
            g *= (w2 + z * z) / (w2 + p * p);
        }
        g
    }

    /// A state-space realisation `(A_f, B_f, C_f, D_f)` (cascade of first-order sections
    /// `(s + z) / (s + p) = 1 + (z - p) / (s + p)`, well conditioned for poles spread over
    /// decades): `x' = A_f x + B_f w`, `u = C_f x + D_f w`, with
    /// `A_f[i][i] = -p_i`, `A_f[i][k] = z_k - p_k` (k < i), `B_f = K`, `C_f[k] = z_k - p_k`, `D_f = K`.
    pub(crate) fn state_space(&self) -> (DMatrix<f64>, DVector<f64>, DVector<f64>, f64) {
        let m = self.order();
        let mut a = DMatrix::zeros(m, m);
        for i in 0..m {
            a[(i, i)] = -self.poles[i];
            for k in 0..i {
                a[(i, k)] = self.zeros[k] - self.poles[k];
            }
        }
        let b = DVector::from_element(m, self.gain);
        let c = DVector::from_fn(m, |k, _| self.zeros[k] - self.poles[k]);
        (a, b, c, self.gain)
    }
}

/// Starting points of each order's fit.
const STARTS: usize = 2;

/// `f` of every job, in order: natively each on its own scoped thread (the fits are
/// independent and take most of the time of shaping a road), on wasm32 (no threads) one
/// after the other.
fn each_job<T: Sync, R: Send>(jobs: &[T], f: impl Fn(&T) -> R + Sync) -> Vec<R> {
    #[cfg(not(target_arch = "wasm32"))]
    {
        std::thread::scope(|s| {
            let f = &f;
            let handles: Vec<_> = jobs.iter().map(|j| s.spawn(move || f(j))).collect();
            handles
                .into_iter()
                .map(|h| h.join().unwrap_or_else(|p| std::panic::resume_unwind(p)))
                .collect()
        })
    }
    #[cfg(target_arch = "wasm32")]
    {
        jobs.iter().map(f).collect()
    }
}

/// The least-squares fit with `m` pole-zero pairs from start `k` of [`STARTS`]: the pairs
/// interlaced along the band (0), or along the band and its extensions (1); `None` if it
/// fails.
fn fit_start(
    psd: &VelocityPsd,
    pts: &[(f64, f64, bool)],
    m: usize,
    k: usize,
) -> Option<ShapingFilter> {
    let band = psd.band;
    let (wa, wb) = (2.0 * PI * band[0], 2.0 * PI * band[1]);
    let out = math::powf(2f64, EXTENSION_SLOPE_OCTAVES);
    let inner: Vec<(f64, f64)> = pts.iter().filter(|p| p.2).map(|p| (p.0, p.1)).collect();
    let slope = end_slope(inner.iter());
    let (la, lb) = match k {
        0 => (math::ln(wa), math::ln(wb)),
        _ => (math::ln(wa / out), math::ln(wb * out)),
    };
    fit_from(psd, pts, m, slope, la, lb, 0.5)
}

/// One Levenberg-Marquardt fit from `m` cells along `[la, lb]` (log rad/s), in each a
/// pole-zero pair whose log distance is the share of the cell that gives `slope` (-2
/// between a pole and its zero, +2 between a zero and its pole), the cell centres shifted
/// by `shift` cells.
fn fit_from(
    psd: &VelocityPsd,
    pts: &[(f64, f64, bool)],
    m: usize,
    slope: f64,
    la: f64,
    lb: f64,
    shift: f64,
) -> Option<ShapingFilter> {
    let band = psd.band;
    let (wa, wb) = (2.0 * PI * band[0], 2.0 * PI * band[1]);
    let cell = (lb - la) / m as f64;
    let frac = (slope.abs() / 2.0).clamp(0.05, 0.95);
    let mut theta = vec![0.0; 2 * m + 1];
    for i in 0..m {
        let c = la + (i as f64 + shift) * cell;
        let (first, second) = (c - 0.5 * frac * cell, c + 0.5 * frac * cell);
        let (lz, lp) = if slope < 0.0 {
            (second, first)
        } else {
            (first, second)
        };
        theta[1 + i] = lz;
        theta[1 + m + i] = lp;
    }
    let mut problem = FitProblem::new(
        pts.iter()
            .map(|&(f, g, _)| (2.0 * PI * f, math::ln(g)))
            .collect(),
        m,
        (math::ln(wa / 100.0), math::ln(wb * 100.0)),
        theta,
    );
    // Gain: match the mean level in log.
    let r0 = problem.residuals_at(&problem.theta);
    let mean = r0.iter().take(pts.len()).sum::<f64>() / pts.len() as f64;
    problem.theta[0] = -0.5 * mean;
    // Relative tolerances of 1e-6 on the cost and the parameters: the fit is judged in per
    // cent; tighter ones only spend evaluations.
    let (problem, _report) = LevenbergMarquardt::new()
        .with_tol(1e-6)
        .with_patience(100)
        .minimize(problem);
    let th = &problem.theta;
    if !th.iter().all(|v| v.is_finite()) {
        return None;
    }
    let mut pairs: Vec<(f64, f64)> = (0..m)
        .map(|i| (math::exp(th[1 + i]), math::exp(th[1 + m + i])))
        .collect();
    crate::order::sort_by_f64_key(&mut pairs, |p| p.1);
    let mut f = ShapingFilter {
        gain: math::exp(th[0]),
        zeros: pairs.iter().map(|p| p.0).collect(),
        poles: pairs.iter().map(|p| p.1).collect(),
        max_error: 0.0,
        rms_error: 0.0,
        max_error_outside: 0.0,
        band,
    };
    // In the band: the power of every third-octave band (of at least 8 breakpoints),
    // filter against PSD; outside: the extensions' points and the asymptotes.
    let (mut sum2, mut count) = (0.0, 0usize);
    for &(i, j) in &psd.checks {
        let num: f64 = psd.f[i..j].iter().map(|&fk| f.psd(fk)).sum();
        let den: f64 = psd.gv[i..j].iter().sum();
        let e = num / den - 1.0;
        f.max_error = f.max_error.max(e.abs());
        sum2 += e * e;
        count += 1;
    }
    for &(fk, g, inside) in pts {
        if !inside {
            f.max_error_outside = f.max_error_outside.max((f.psd(fk) / g - 1.0).abs());
        }
    }
    f.rms_error = (sum2 / count.max(1) as f64).sqrt();
    f.error().is_finite().then_some(f)
}

/// The log-magnitude least-squares problem: residuals `ln(2 |F(i w_k)|^2) - ln Gv_k`, then
/// one bound penalty per pole and zero (kept within two decades beyond the band).
///
/// Written for speed (the fit is most of the time of shaping a road, and a map on a
/// measured road shapes it once): `e^{2 t}` once per pole or zero and call, `1 / w^2`
/// once per point, and one logarithm per point for the product of the sections' ratios,
/// `sum_i ln(1 + a_zi) - ln(1 + a_pi) = ln prod_i (1 + a_zi) / (1 + a_pi)` with
/// `a = e^{2 t} / w^2`, instead of an exponential and a logarithm per section and point.
struct FitProblem {
    /// `(omega rad/s, ln Gv)`; omega 0 and infinity for the asymptotes.
    pts: Vec<(f64, f64)>,
    /// `1 / omega^2` of each point (0 at omega infinity, infinite at omega 0).
    inv_w2: Vec<f64>,
    m: usize,
    bounds: (f64, f64),
    /// `[ln K, ln z_1..m, ln p_1..m]`.
    theta: DVector<f64>,
}

impl FitProblem {
    fn new(pts: Vec<(f64, f64)>, m: usize, bounds: (f64, f64), theta: Vec<f64>) -> FitProblem {
        FitProblem {
            inv_w2: pts.iter().map(|&(w, _)| 1.0 / (w * w)).collect(),
            pts,
            m,
            bounds,
            theta: DVector::from_vec(theta),
        }
    }

    /// `e^{2 t}` of every zero and pole, `[z_1..m, p_1..m]`.
    fn squares(th: &DVector<f64>, m: usize) -> Vec<f64> {
        (0..2 * m).map(|i| math::exp(2.0 * th[1 + i])).collect()
    }

    fn residuals_at(&self, th: &DVector<f64>) -> DVector<f64> {
        let m = self.m;
        let e = FitProblem::squares(th, m);
        let mut r = DVector::zeros(self.pts.len() + 2 * m);
        let level = math::ln(2.0f64) + 2.0 * th[0];
        for (k, (&(w, lg), &q)) in self.pts.iter().zip(&self.inv_w2).enumerate() {
            let sections = if w == 0.0 {
                (0..m).map(|i| 2.0 * (th[1 + i] - th[1 + m + i])).sum()
            } else if w.is_infinite() {
                0.0
            } else {
                let ratio =
                    (0..m).fold(1.0, |acc, i| acc * (1.0 + e[i] * q) / (1.0 + e[m + i] * q));
                if ratio.is_finite() && ratio >= f64::MIN_POSITIVE {
                    math::ln(ratio)
                } else {
                    // Far outside the bounds (a trial step): section by section.
                    (0..m)
                        .map(|i| log_section(w, th[1 + i]) - log_section(w, th[1 + m + i]))
                        .sum()
                }
            };
            r[k] = level + sections - lg;
        }
        let (lo, hi) = self.bounds;
        for i in 0..2 * m {
            let t = th[1 + i];
            r[self.pts.len() + i] = (lo - t).max(0.0) + (t - hi).max(0.0);
        }
        r
    }
}

/// `ln(w^2 + e^{2 t})` less its value's `t`-free part at the ends: `ln(1 + (e^t / w)^2)`
/// written so that `w = 0` and `w = infinity` are finite (the constant `2 ln w` cancels
/// between a zero and a pole).
fn log_section(w: f64, t: f64) -> f64 {
    if w == 0.0 {
        2.0 * t
    } else if w.is_infinite() {
        0.0
    } else {
        let x = 2.0 * (t - math::ln(w));
        // ln(1 + e^x), stable for large |x|.
        if x > 30.0 {
            x
        } else {
            math::ln_1p(math::exp(x))
        }
    }
}

/// `d log_section / dt = 2 a / (1 + a)` with `a = e^{2t} / w^2` (`e2t` = `e^{2t}`, `q` =
/// `1 / w^2`): 2 at `w = 0`, 0 at `w = infinity`.
fn d_log_section(e2t: f64, q: f64) -> f64 {
    let a = e2t * q;
    if q.is_infinite() || a.is_infinite() {
        2.0
    } else {
        2.0 * a / (1.0 + a)
    }
}

impl LeastSquaresProblem<f64, Dyn, Dyn> for FitProblem {
    type ResidualStorage = Owned<f64, Dyn>;
    type JacobianStorage = Owned<f64, Dyn, Dyn>;
    type ParameterStorage = Owned<f64, Dyn>;

    fn set_params(&mut self, p: &DVector<f64>) {
        self.theta.copy_from(p);
    }

    fn params(&self) -> DVector<f64> {
        self.theta.clone()
    }

    fn residuals(&self) -> Option<DVector<f64>> {
        let r = self.residuals_at(&self.theta);
        r.iter().all(|v| v.is_finite()).then_some(r)
    }

    fn jacobian(&self) -> Option<DMatrix<f64>> {
        let m = self.m;
        let th = &self.theta;
        let e = FitProblem::squares(th, m);
        let np = self.pts.len();
        let mut j = DMatrix::zeros(np + 2 * m, 2 * m + 1);
        for (k, &q) in self.inv_w2.iter().enumerate() {
            j[(k, 0)] = 2.0;
            for i in 0..m {
                j[(k, 1 + i)] = d_log_section(e[i], q);
                j[(k, 1 + m + i)] = -d_log_section(e[m + i], q);
            }
        }
        let (lo, hi) = self.bounds;
        for i in 0..2 * m {
            let t = th[1 + i];
            j[(np + i, 1 + i)] = if t < lo {
                -1.0
            } else if t > hi {
                1.0
            } else {
                0.0
            };
        }
        Some(j)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn waviness_two_gives_a_constant_filter() {
        let p = VelocityPsd::iso(256e-6, 2.0, 20.0, [0.3, 100.0]);
        assert!(p.is_white());
        let f = ShapingFilter::fit(&p).unwrap();
        assert_eq!(f.order(), 0);
        let gv = (2.0 * PI * N0).powi(2) * 256e-6 * 20.0;
        assert!((f.psd(3.0) / gv - 1.0).abs() < 1e-15);
        assert_eq!(f.max_error, 0.0);
    }

    /// Fractional slopes over 2.5 decades (and their extensions): under 1 % with at most 8
    /// poles, and the
    /// realisation's transfer is the product form's.
    #[test]
    fn iso_waviness_fits_within_a_few_per_cent() {
        for w in [1.5, 2.5, 3.0, 3.5] {
            let p = VelocityPsd::iso(256e-6, w, 20.0, [0.3, 100.0]);
            let f = ShapingFilter::fit(&p).unwrap();
            assert!(f.order() <= MAX_FILTER_ORDER);
            assert!(f.error() < 0.01, "w {w}: {f:?}");
            assert!(f.poles.iter().chain(&f.zeros).all(|v| *v > 0.0));
            let (a, b, c, d) = f.state_space();
            for fr in [0.05, 1.0, 13.0, 400.0] {
                let s = num_complex::Complex64::new(0.0, 2.0 * PI * fr);
                let m = a.map(num_complex::Complex64::from);
                let eye = DMatrix::<num_complex::Complex64>::identity(a.nrows(), a.nrows());
                let x = (eye * s - m)
                    .lu()
                    .solve(&b.map(num_complex::Complex64::from))
                    .unwrap();
                let h = c.map(num_complex::Complex64::from).dot(&x) + d;
                assert!((h - f.response(fr)).norm() < 1e-9 * f.response(fr).norm());
            }
            eprintln!(
                "w {w}: order {} max error {:.4} rms {:.4} outside {:.4}",
                f.order(),
                f.max_error,
                f.rms_error,
                f.max_error_outside
            );
        }
    }

    /// The fit's fast residuals (one logarithm per point of the product of the sections'
    /// ratios) equal the section-by-section sum to 1e-12, at the asymptotes too, and its
    /// Jacobian equals central differences of the residuals to 1e-6.
    #[test]
    fn fast_residuals_and_jacobian_match_the_sections() {
        let p = VelocityPsd::iso(256e-6, 2.5, 20.0, [0.3, 100.0]);
        let pts: Vec<(f64, f64)> = p
            .fit_points()
            .iter()
            .map(|&(f, g, _)| (2.0 * PI * f, math::ln(g)))
            .collect();
        let m = 6;
        let theta: Vec<f64> = (0..2 * m + 1)
            .map(|i| 0.3 + 0.41 * i as f64 - if i > m { 0.2 } else { 0.0 })
            .collect();
        let fp = FitProblem::new(pts.clone(), m, (-3.0, 12.0), theta);
        let r = fp.residuals_at(&fp.theta);
        for (k, &(w, lg)) in pts.iter().enumerate() {
            let th = &fp.theta;
            let slow = math::ln(2.0f64)
                + 2.0 * th[0]
                + (0..m)
                    .map(|i| log_section(w, th[1 + i]) - log_section(w, th[1 + m + i]))
                    .sum::<f64>()
                - lg;
            assert!(
                (r[k] - slow).abs() < 1e-12 * (1.0 + slow.abs()),
                "{k}: {} {slow}",
                r[k]
            );
        }
        let j = fp.jacobian().unwrap();
        for c in 0..2 * m + 1 {
            let h = 1e-6;
            let (mut up, mut down) = (fp.theta.clone(), fp.theta.clone());
            up[c] += h;
            down[c] -= h;
            let d = (fp.residuals_at(&up) - fp.residuals_at(&down)) / (2.0 * h);
            for k in 0..pts.len() {
                assert!(
                    (j[(k, c)] - d[k]).abs() < 1e-6,
                    "({k}, {c}): {} {}",
                    j[(k, c)],
                    d[k]
                );
            }
        }
    }

    #[test]
    fn interpolation_is_log_log_with_flat_ends() {
        let p = VelocityPsd::iso(256e-6, 3.0, 20.0, [0.3, 100.0]);
        let gv = |f: f64| (2.0 * PI * N0).powi(2) * 256e-6 * 20.0 * (f / 2.0).powf(-1.0);
        for f in [0.3, 0.77, 5.5, 99.0] {
            assert!((p.at(f) / gv(f) - 1.0).abs() < 1e-9, "{f}");
        }
        // The power law bends to white two octaves beyond the band: at the corner the
        // extension is sqrt(2)^slope... of the power law's value, far out constant.
        let knee = |f: f64, fa: f64, fc: f64| {
            gv(fa) * ((f * f + fc * fc) / (fa * fa + fc * fc)).powf(-0.5)
        };
        assert!((p.at(0.1) / knee(0.1, 0.3, 0.075) - 1.0).abs() < 1e-9);
        assert!((p.at(0.2999) / gv(0.2999) - 1.0).abs() < 0.07);
        assert!((p.at(0.0) / knee(0.0, 0.3, 0.075) - 1.0).abs() < 1e-12);
        assert!((p.at(1e6) / p.at(f64::INFINITY) - 1.0).abs() < 1e-6);
        assert!(p.at(f64::INFINITY) < gv(400.0) && p.at(f64::INFINITY) > 0.5 * gv(400.0));
    }
}
