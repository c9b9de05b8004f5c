//! The fixed frequency rule of the GPU route: Gauss-Legendre panels in `f` graded by the
//! distance to the model's poles, Filon weights for the front-rear cross term, and a
//! `1/f` panel for the high-frequency tail.
//!
//! The variance of an output is `var = Gv int_{f_lo}^inf |T_f + T_r e^{-i w tau}|^2 / w^2 df`
//! (`w = 2 pi f`, `T_f`, `T_r` the displacement transfers from the front and rear wheel
//! groups of one road source, `tau = L / v`). The rule has three kinds of nodes:
//!
//! - **Combined** (`cross = e^{-i w tau}`): `weight |T_f + cross T_r|^2` on panels where the
//!   phase `w tau` turns by at most [`KAPPA_SPLIT`] radians either side of the panel's
//!   centre, so Gauss-Legendre sees a smooth integrand. This covers the low band, where
//!   `T_f` and `T_r` are O(1) but nearly cancel (their static gains sum to zero), so they
//!   must be summed before squaring.
//! - **Split** (`weight (|T_f|^2 + |T_r|^2) + Re(cross T_f conj(T_r))`): on panels where the
//!   phase turns faster, the smooth parts take Gauss-Legendre weights and the cross term
//!   `2 Re(T_f conj(T_r) e^{i w tau})` takes Filon weights: the exact integral of the
//!   panel's interpolating polynomial times `e^{i w tau}` (Legendre expansion, spherical
//!   Bessel moments), accurate however fast the phase turns.
//! - **Tail** (`cross = 0`): `[f_b, inf)` by Gauss-Legendre in `x = 1/f` on `[0, 1/f_b]`,
//!   where the `f^-2` tail of DTL (and of BAcc with tyre damping) is the smooth
//!   `P(1/x) / x^2 -> const`: integrated, not cut. The cross term decays at least as fast
//!   as `P` and oscillates, `|int_{f_b}^inf| <= |g(f_b)| / (pi tau)`; `f_b` is 50 times the
//!   highest pole frequency (at least 1 kHz), where that bound is below 1e-7 of the totals.
//!
//! Panels are graded by the poles of the integrand: each is at most [`BETA`] times as wide
//! as the distance from its start to the nearest pole of the model in the complex
//! `f`-plane (`f = lambda / (2 pi i)`, `lambda` the eigenvalues over the map's designs,
//! see [`PoleBand`]), and to `f = 0` (the cross term and, with a road warp, the whole
//! integrand grow as `f^-2` there). With the pole at normalised distance `2 / BETA` from
//! the panel, the 8-point interpolant converges like `rho^-8`, `rho = 2/BETA + sqrt(4/BETA^2 + 1)`.
//! The weights fold in `1 / w^2`, so a kernel only sums products.

use crate::error::{Result, RideError};
use crate::math;
use num_complex::Complex64 as C64;
use std::f64::consts::PI;

/// Gauss-Legendre nodes per panel.
pub(crate) const NODES_PER_PANEL: usize = 8;
/// Largest panel width over the distance to the nearest pole, -.
const BETA: f64 = 0.5;
/// Largest phase swing `pi tau (b - a)` of a combined panel, rad; wider panels are split.
const KAPPA_SPLIT: f64 = 2.0;
/// The tail starts at this many times the highest pole frequency ...
const TAIL_FACTOR: f64 = 50.0;
/// ... and not below this, Hz.
const TAIL_MIN_HZ: f64 = 1000.0;
/// Most panels a rule may have (weakly damped modes need many): 4096 nodes.
const MAX_PANELS: usize = 512;

/// One node of the rule (see the module doc for how `weight` and `cross` enter).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Node {
    /// Angular frequency `w = 2 pi f`, rad/s.
    pub omega: f64,
    /// Weight of the squared transfers, `df`-weight over `w^2`, s^2 Hz.
    pub weight: f64,
    /// Combined node: the delay factor `e^{-i w tau}`; split node: twice the Filon weight
    /// over `w^2`; tail node: 0.
    pub cross: C64,
}

/// A band of poles of the model over a design region: the damped frequency ranges over
/// `[lo, hi]` Hz and the decay rate `|Re lambda| / (2 pi)` is at least `decay` Hz.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PoleBand {
    /// Lowest damped frequency, Hz.
    pub lo: f64,
    /// Highest damped frequency, Hz.
    pub hi: f64,
    /// Smallest distance of the pole from the real axis, Hz.
    pub decay: f64,
}

impl PoleBand {
    /// Distance in the complex `f`-plane from real `f` to the nearest pole of the band.
    pub fn distance(&self, f: f64) -> f64 {
        let d = if f < self.lo {
            self.lo - f
        } else if f > self.hi {
            f - self.hi
        } else {
            0.0
        };
        math::hypot(d, self.decay)
    }
}

/// The frequency rule of one map: nodes for `[f_lo, inf)` (see the module doc).
#[derive(Debug, Clone, PartialEq)]
pub struct FrequencyRule {
    /// Combined nodes, [`NODES_PER_PANEL`] per panel.
    pub combined: Vec<Node>,
    /// Split and tail nodes, [`NODES_PER_PANEL`] per panel.
    pub split: Vec<Node>,
    /// Lower band limit, Hz (0 unless a road warp needs ISO 8608's cutoff).
    pub f_lo: f64,
    /// Start of the tail panel, Hz.
    pub f_tail: f64,
}

impl FrequencyRule {
    /// The rule for poles `bands`, band start `f_lo` (Hz, >= 0) and front-rear delay
    /// `tau` (s, > 0). Errors when the poles demand more than [`MAX_PANELS`] panels.
    pub fn new(bands: &[PoleBand], f_lo: f64, tau: f64) -> Result<FrequencyRule> {
        if bands.is_empty() || bands.iter().any(|b| !(b.decay > 0.0 && b.hi.is_finite())) {
            return Err(RideError::Numerical(
                "frequency rule: every pole must lie off the real axis".into(),
            ));
        }
        let f_max = bands
            .iter()
            .map(|b| math::hypot(b.hi, b.decay))
            .fold(0.0, f64::max);
        let f_tail = (TAIL_FACTOR * f_max).max(TAIL_MIN_HZ);
        let nearest = |f: f64| {
            bands
                .iter()
                .map(|b| b.distance(f))
                .fold(f64::INFINITY, f64::min)
        };
        // Breakpoints: the first panel from 0 needs only the model's poles (the integrand
        // is analytic at 0 without a warp); later ones also keep away from f = 0.
        let mut edges = vec![f_lo];
        let mut a = f_lo;
        while a < f_tail {
            let width = if a == 0.0 {
                BETA * nearest(0.0)
            } else {
                BETA * nearest(a).min(a)
            };
            a = (a + width).min(f_tail);
            // A sliver before the tail is merged into the last panel.
            if f_tail - a < 0.25 * width {
                a = f_tail;
            }
            edges.push(a);
            if edges.len() > MAX_PANELS {
                return Err(RideError::Numerical(format!(
                    "frequency rule: the poles need more than {MAX_PANELS} panels \
                     (a mode is damped too weakly for the GPU route)"
                )));
            }
        }
        let (x, w) = gauss_legendre(NODES_PER_PANEL);
        let beta = 2.0 * PI * tau;
        let mut combined = Vec::new();
        let mut split = Vec::new();
        for pair in edges.windows(2) {
            let (lo, hi) = (pair[0], pair[1]);
            let (mid, half) = (0.5 * (lo + hi), 0.5 * (hi - lo));
            let kappa = beta * half;
            if kappa <= KAPPA_SPLIT {
                for k in 0..NODES_PER_PANEL {
                    let f = mid + half * x[k];
                    let omega = 2.0 * PI * f;
                    combined.push(Node {
                        omega,
                        weight: half * w[k] / (omega * omega),
                        cross: math::cpolar(1.0, -omega * tau),
                    });
                }
            } else {
                let c = filon_weights(&x, &w, kappa);
                let shift = math::cpolar(half, beta * mid);
                for k in 0..NODES_PER_PANEL {
                    let f = mid + half * x[k];
                    let omega = 2.0 * PI * f;
                    split.push(Node {
                        omega,
                        weight: half * w[k] / (omega * omega),
                        cross: 2.0 * shift * c[k] / (omega * omega),
                    });
                }
            }
        }
        // Tail: f = 1 / x on x in [0, 1 / f_tail], df = dx / x^2.
        let xt = 0.5 / f_tail;
        for k in 0..NODES_PER_PANEL {
            let xk = xt * (1.0 + x[k]);
            let omega = 2.0 * PI / xk;
            split.push(Node {
                omega,
                weight: xt * w[k] / (xk * xk) / (omega * omega),
                cross: C64::new(0.0, 0.0),
            });
        }
        Ok(FrequencyRule {
            combined,
            split,
            f_lo,
            f_tail,
        })
    }

    /// Number of nodes.
    pub fn len(&self) -> usize {
        self.combined.len() + self.split.len()
    }

    /// Always false: a rule has at least the tail panel.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// `n`-point Gauss-Legendre nodes (ascending) and weights on `[-1, 1]`, by Newton's
/// method on `P_n` from Tricomi's initial guesses.
fn gauss_legendre(n: usize) -> (Vec<f64>, Vec<f64>) {
    let mut x = vec![0.0; n];
    let mut w = vec![0.0; n];
    let nf = n as f64;
    for i in 0..n.div_ceil(2) {
        let mut z = math::cos(PI * (i as f64 + 0.75) / (nf + 0.5));
        let mut dp = 1.0;
        for _ in 0..100 {
            let (p, d) = legendre_and_derivative(n, z);
            dp = d;
            let dz = p / d;
            z -= dz;
            if dz.abs() < 1e-16 {
                break;
            }
        }
        let (_, d) = legendre_and_derivative(n, z);
        dp = if d.is_finite() { d } else { dp };
        let wi = 2.0 / ((1.0 - z * z) * dp * dp);
        x[i] = -z;
        x[n - 1 - i] = z;
        w[i] = wi;
        w[n - 1 - i] = wi;
    }
    (x, w)
}

/// `(P_n(z), P_n'(z))` by the three-term recurrence.
fn legendre_and_derivative(n: usize, z: f64) -> (f64, f64) {
    let (mut p0, mut p1) = (1.0, z);
    if n == 0 {
        return (1.0, 0.0);
    }
    for k in 2..=n {
        let kf = k as f64;
        let p2 = ((2.0 * kf - 1.0) * z * p1 - (kf - 1.0) * p0) / kf;
        p0 = p1;
        p1 = p2;
    }
    let nf = n as f64;
    (p1, nf * (z * p1 - p0) / (z * z - 1.0))
}

/// Legendre polynomials `P_0(z) .. P_{n-1}(z)`.
fn legendre_all(n: usize, z: f64) -> Vec<f64> {
    let mut p = vec![0.0; n];
    p[0] = 1.0;
    if n > 1 {
        p[1] = z;
    }
    for k in 2..n {
        let kf = k as f64;
        p[k] = ((2.0 * kf - 1.0) * z * p[k - 1] - (kf - 1.0) * p[k - 2]) / kf;
    }
    p
}

/// Spherical Bessel functions `j_0(x) .. j_{n-1}(x)`, `x >= 0`: the power series below
/// `x = 10` (at most 4 digits lost to cancellation), upward recurrence above (stable
/// for `x > l`).
fn spherical_bessel(n: usize, x: f64) -> Vec<f64> {
    let mut j = vec![0.0; n];
    if x < 10.0 {
        // j_l(x) = x^l / (2l+1)!! sum_m (-x^2/2)^m / (m! (2l+3)(2l+5)..(2l+2m+1))
        let mut lead = 1.0; // x^l / (2l+1)!!
        for (l, jl) in j.iter_mut().enumerate() {
            if l > 0 {
                lead *= x / (2 * l + 1) as f64;
            }
            let mut term = 1.0;
            let mut sum = 1.0;
            for m in 1..200 {
                term *= -0.5 * x * x / (m as f64 * (2 * l + 2 * m + 1) as f64);
                sum += term;
                if term.abs() < 1e-18 * sum.abs().max(1e-300) {
                    break;
                }
            }
            *jl = lead * sum;
        }
    } else {
        let (s, c) = math::sin_cos(x);
        j[0] = s / x;
        if n > 1 {
            j[1] = s / (x * x) - c / x;
        }
        for l in 1..n.saturating_sub(1) {
            j[l + 1] = (2 * l + 1) as f64 / x * j[l] - j[l - 1];
        }
    }
    j
}

/// Filon weights on `[-1, 1]`: `c_k = int_{-1}^{1} l_k(x) e^{i kappa x} dx` for the Lagrange
/// basis `l_k` of the Gauss-Legendre nodes `x` (weights `w`), from
/// `l_k = sum_j (2j+1)/2 w_k P_j(x_k) P_j` and `int P_j e^{i kappa x} = 2 i^j j_j(kappa)`.
fn filon_weights(x: &[f64], w: &[f64], kappa: f64) -> Vec<C64> {
    let n = x.len();
    let jb = spherical_bessel(n, kappa);
    let ipow = [
        C64::new(1.0, 0.0),
        C64::new(0.0, 1.0),
        C64::new(-1.0, 0.0),
        C64::new(0.0, -1.0),
    ];
    (0..n)
        .map(|k| {
            let p = legendre_all(n, x[k]);
            (0..n)
                .map(|j| ipow[j % 4] * ((2 * j + 1) as f64 * w[k] * p[j] * jb[j]))
                .sum()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gauss_legendre_is_exact_to_degree_2n_minus_1() {
        for n in [1, 2, 5, 8, 12] {
            let (x, w) = gauss_legendre(n);
            for d in 0..2 * n {
                let q: f64 = x.iter().zip(&w).map(|(x, w)| w * x.powi(d as i32)).sum();
                let exact = if d % 2 == 1 {
                    0.0
                } else {
                    2.0 / (d + 1) as f64
                };
                assert!(
                    (q - exact).abs() < 1e-14,
                    "n {n} degree {d}: {q} vs {exact}"
                );
            }
        }
    }

    #[test]
    fn spherical_bessel_matches_closed_forms_on_both_sides_of_the_switch() {
        for x in [0.0, 1e-3, 0.7, 3.0, 9.99, 10.0, 25.0, 400.0] {
            let j = spherical_bessel(3, x);
            let (s, c) = (x.sin(), x.cos());
            // Below 0.5 the closed forms cancel (j_2 at 1e-3 keeps 2 digits): there the
            // series' first two terms, exact to O(x^4) relative.
            let closed = if x < 0.5 {
                let x2 = x * x;
                [
                    1.0 - x2 / 6.0,
                    x / 3.0 * (1.0 - x2 / 10.0),
                    x2 / 15.0 * (1.0 - x2 / 14.0),
                ]
            } else {
                [
                    s / x,
                    s / (x * x) - c / x,
                    (3.0 / (x * x) - 1.0) * s / x - 3.0 * c / (x * x),
                ]
            };
            for l in 0..3 {
                assert!(
                    (j[l] - closed[l]).abs() < 1e-11,
                    "x {x} l {l}: {} vs {}",
                    j[l],
                    closed[l]
                );
            }
        }
    }

    /// The Filon weights integrate `x^d e^{i kappa x}` exactly for `d < n`, compared with
    /// a 200-panel Gauss-Legendre reference.
    #[test]
    fn filon_weights_are_exact_for_polynomials_times_the_phase() {
        let (x, w) = gauss_legendre(NODES_PER_PANEL);
        let (xr, wr) = gauss_legendre(20);
        for kappa in [0.0, 0.3, 2.0, 9.9, 10.1, 57.0, 800.0] {
            let c = filon_weights(&x, &w, kappa);
            for d in 0..NODES_PER_PANEL {
                let q: C64 = (0..x.len()).map(|k| c[k] * x[k].powi(d as i32)).sum();
                let mut r = C64::new(0.0, 0.0);
                let panels = 400;
                for p in 0..panels {
                    let (lo, h) = (-1.0 + 2.0 * p as f64 / panels as f64, 1.0 / panels as f64);
                    for k in 0..xr.len() {
                        let t = lo + h * (1.0 + xr[k]);
                        r += h * wr[k] * t.powi(d as i32) * C64::from_polar(1.0, kappa * t);
                    }
                }
                assert!(
                    (q - r).norm() < 1e-11,
                    "kappa {kappa} degree {d}: {q} vs {r}"
                );
            }
        }
    }

    #[test]
    fn a_rule_refuses_undamped_poles_and_too_many_panels() {
        let b = PoleBand {
            lo: 1.0,
            hi: 1.0,
            decay: 0.0,
        };
        assert!(FrequencyRule::new(&[b], 0.0, 0.1).is_err());
        // Panels shrink geometrically towards a pole (ratio 1 + BETA): a decay of 1e-200 Hz
        // needs about 2 ln(1e200) / ln(1.5) = 2300 of them.
        let sharp = PoleBand { decay: 1e-200, ..b };
        let e = FrequencyRule::new(&[sharp], 0.0, 0.1).unwrap_err();
        assert!(e.to_string().contains("panels"), "{e}");
    }
}
