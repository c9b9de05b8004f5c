//! Problems with known fronts, and a closed-form quarter car, for the optimiser tests.

use super::problem::{Eval, Problem};
use crate::error::Result;
use crate::evaluate::{Criteria, Evaluator};

/// ZDT1 (Zitzler, Deb, Thiele 2000): `f1 = x1`, `g = 1 + 9 sum_{i>=2} x_i / (n - 1)`,
/// `f2 = g (1 - sqrt(f1 / g))`, `x` in `[0, 1]^n`; front `f2 = 1 - sqrt(f1)`.
pub(crate) struct Zdt1 {
    /// Number of variables.
    pub n: usize,
}

impl Zdt1 {
    /// `k` points of the analytic front, evenly spaced in `f1`.
    pub(crate) fn true_front(k: usize) -> Vec<[f64; 2]> {
        (0..k)
            .map(|i| {
                let f1 = i as f64 / (k - 1) as f64;
                [f1, 1.0 - f1.sqrt()]
            })
            .collect()
    }
}

impl Problem for Zdt1 {
    type Info = ();
    fn bounds(&self) -> Vec<(f64, f64)> {
        vec![(0.0, 1.0); self.n]
    }
    fn evaluate(&self, x: &[f64]) -> Result<Eval<()>> {
        let g = 1.0 + 9.0 * x[1..].iter().sum::<f64>() / (self.n - 1) as f64;
        let f2 = g * (1.0 - (x[0] / g).sqrt());
        Ok(Eval {
            f: [x[0], f2],
            violation: 0.0,
            info: (),
        })
    }
}

/// BNH (Binh and Korn 1997): `f1 = 4 x1^2 + 4 x2^2`, `f2 = (x1 - 5)^2 + (x2 - 5)^2`,
/// `x1` in `[0, 5]`, `x2` in `[0, 3]`, subject to `(x1 - 5)^2 + x2^2 <= 25` and
/// `(x1 - 8)^2 + (x2 + 3)^2 >= 7.7`. Pareto set: `x1 = x2` in `[0, 3]`, then `x2 = 3`
/// for `x1` in `[3, 5]`.
pub(crate) struct Bnh;

impl Bnh {
    fn f(x1: f64, x2: f64) -> [f64; 2] {
        [
            4.0 * (x1 * x1 + x2 * x2),
            (x1 - 5.0).powi(2) + (x2 - 5.0).powi(2),
        ]
    }

    /// `k` points of the analytic Pareto set mapped to the objectives, evenly
    /// spaced along the set's length (3 sqrt 2 on the diagonal, then 2).
    pub(crate) fn true_front(k: usize) -> Vec<[f64; 2]> {
        let diag = 3.0 * 2f64.sqrt();
        let total = diag + 2.0;
        (0..k)
            .map(|i| {
                let s = total * i as f64 / (k - 1) as f64;
                if s <= diag {
                    let t = s / 2f64.sqrt();
                    Bnh::f(t, t)
                } else {
                    Bnh::f(3.0 + (s - diag), 3.0)
                }
            })
            .collect()
    }
}

impl Problem for Bnh {
    type Info = ();
    fn bounds(&self) -> Vec<(f64, f64)> {
        vec![(0.0, 5.0), (0.0, 3.0)]
    }
    fn evaluate(&self, x: &[f64]) -> Result<Eval<()>> {
        let g1 = (x[0] - 5.0).powi(2) + x[1] * x[1] - 25.0;
        let g2 = 7.7 - (x[0] - 8.0).powi(2) - (x[1] + 3.0).powi(2);
        Ok(Eval {
            f: Bnh::f(x[0], x[1]),
            violation: g1.max(0.0) + g2.max(0.0),
            info: (),
        })
    }
}

/// Closed-form quarter car on white-noise road velocity (a cheap stand-in for a
/// surrogate). `W = 2 pi^2 Gd n0^2 v` (m^2/s^3) with `Gd = 64e-6 m^3`, `n0 = 0.1 1/m`,
/// `v = 20 m/s`; `ms = 467.7 kg`, `mu = 40 kg`, `kt = 175500 N/m`, `M = ms + mu`:
/// `var(BAcc) = W (ks^2 M + cs^2 kt) / (2 cs ms^2)`, `var(SWS) = W M / (2 cs)`,
/// `var(DTL) = W / (2 cs) [kt^2 mu + (M/ms)^2 (ks^2 M + cs^2 kt) - 2 ks kt mu M / ms]`.
pub(crate) struct QuarterCar;

impl QuarterCar {
    /// Sprung mass, kg.
    pub(crate) const MS: f64 = 467.7;
    /// Unsprung mass, kg.
    pub(crate) const MU: f64 = 40.0;
    /// Tyre rate, N/m.
    pub(crate) const KT: f64 = 175_500.0;

    /// Road input intensity `W = 2 pi^2 Gd n0^2 v`, m^2/s^3.
    pub(crate) fn w() -> f64 {
        2.0 * std::f64::consts::PI.powi(2) * 64e-6 * 0.1f64.powi(2) * 20.0
    }
}

impl Evaluator for QuarterCar {
    fn evaluate(&self, ks: f64, cs: f64) -> Result<Criteria> {
        let q = crate::car::QuarterCar {
            ms: Self::MS,
            mu: Self::MU,
            ks,
            cs,
            kt: Self::KT,
            ct: 0.0,
        };
        Ok(crate::criteria::quarter_car_rms(&q, Self::w()))
    }
    fn name(&self) -> String {
        "quarter-closed-form".into()
    }
}
