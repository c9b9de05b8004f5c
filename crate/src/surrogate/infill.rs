//! Infill: where the next HiFi run goes, chosen for the decision (the feasible BAcc-DTL
//! front and its min-max pick), not for the accuracy over the whole box.
//!
//! The criterion is the expected hypervolume improvement of the feasible front times the
//! probability that the design is feasible,
//!
//! ```text
//! a(x) = EHVI(x) PoF(x)
//! ```
//!
//! with the surrogate's prediction `mu_k(x)` and its uncertainty ([`super::uncertainty`])
//! taken as independent normal criteria `Y_k ~ N(mu_k, (mu_k sigma_k)^2)` (`sigma_k` the
//! relative 1-sigma error, so `mu_k sigma_k` is in the criterion's units).
//!
//! **EHVI** (minimisation, exact in 2-D): for an incumbent front `p_1 .. p_m` sorted by
//! increasing BAcc `a_i` (so decreasing DTL `b_i`) inside the reference point `r`, the region
//! a new point can add is the union of the strips `a_i <= z_1 < a_(i+1)`, `z_2 < b_i`
//! (`i = 0..m`, `a_0 = -inf`, `b_0 = r_2`, `a_(m+1) = r_1`), so the improvement of `y` is
//! `sum_i (a_(i+1) - max(a_i, y_1))^+ (b_i - y_2)^+` and its expectation factorises:
//!
//! ```text
//! EHVI = sum_(i=0..m) [psi_1(a_(i+1)) - psi_1(a_i)] psi_2(b_i),
//! psi_k(c) = E[(c - Y_k)^+] = (c - mu_k) Phi((c - mu_k) / s_k) + s_k phi((c - mu_k) / s_k),
//! ```
//!
//! `psi(-inf) = 0`, `s_k = mu_k sigma_k` ((m/s^2) N). With `s_k = 0` it is the plain
//! improvement `HV(P + y) - HV(P)`.
//!
//! **PoF**: the SWS limit `l` is met with probability `Phi((l - mu_sws) / s_sws)`, each
//! "no worse than the datum" objective likewise against the datum's value, the tyre-load
//! margin `k DTL <= F_static` against `F_static / k` and the travel budget `n SWS <= travel`
//! against `travel / n`; the body-bounce and damping-ratio bands depend on `(Ks, Cs)`
//! alone (0 or 1). The product assumes independence.
//!
//! **Incumbent front** ([`Infill`]): the feasible non-dominated HiFi samples (EGO's
//! classic choice), or the surrogate's own predicted front (improvement over what the
//! surrogate already promises: large only where the front is uncertain).
//!
//! **Candidates**: the designs of the surrogate's predicted front (the decision) then an
//! `n x n` grid over the box, in that fixed order; a candidate closer than the minimum
//! distance (normalised coordinates) to a sample is never taken, so no design is sampled
//! twice. The largest `a(x)` wins, the first on ties; when no candidate has `a > 0` the one
//! farthest from every sample is taken (space filling) and the reason says so. Nothing
//! depends on hashing or threads.

use super::uncertainty::Uncertain;
use super::Sample;
use crate::design::DesignBox;
use crate::dos::{DesignObjectives, DosContext, Objective};
use crate::error::{parse_choice, Result, RideError};
use crate::evaluate::Criteria;
use crate::math;
use crate::optimize::{non_dominated, FrontPoint};
use serde::{Deserialize, Serialize};
use strum::{EnumIter, EnumProperty, IntoStaticStr, VariantNames};

/// Which front the expected improvement is measured against.
#[derive(
    Debug,
    Clone,
    Copy,
    PartialEq,
    Eq,
    Serialize,
    Deserialize,
    EnumIter,
    EnumProperty,
    IntoStaticStr,
    VariantNames,
)]
#[serde(rename_all = "kebab-case")]
#[strum(serialize_all = "kebab-case")]
#[strum()]
pub enum Infill {
    /// EHVI x PoF over the feasible non-dominated HiFi samples.
    Ehvi,
    /// EHVI x PoF over the surrogate's predicted front.
    EhviFront,
}

impl std::str::FromStr for Infill {
    type Err = RideError;
    fn from_str(s: &str) -> Result<Infill> {
        Infill::parse(s)
    }
}

impl Infill {
    /// Parses `ehvi` or `ehvi-front` (any case; errors name `criterion`).
    pub fn parse(s: &str) -> Result<Infill> {
        parse_choice("criterion", s)
    }

    /// `"ehvi"` or `"ehvi-front"`.
    pub fn name(self) -> &'static str {
        self.into()
    }
}

/// Deviations below the mean beyond which `psi` counts as zero in [`Staircase::ehvi`]
/// (`phi(8) = 5e-15`).
const TAIL_Z: f64 = 8.0;

/// The standard normal distribution function `Phi(z) = erfc(-z / sqrt 2) / 2`.
fn normal_cdf(z: f64) -> f64 {
    0.5 * libm::erfc(-z / std::f64::consts::SQRT_2)
}

/// The standard normal density `phi(z) = exp(-z^2 / 2) / sqrt(2 pi)`.
fn normal_pdf(z: f64) -> f64 {
    math::exp(-0.5 * z * z) / (2.0 * std::f64::consts::PI).sqrt()
}

/// `psi(c) = E[(c - Y)^+]` for `Y ~ N(mu, s^2)` (module doc); `(c - mu)^+` when `s = 0`.
fn shortfall(c: f64, mu: f64, s: f64) -> f64 {
    if c == f64::NEG_INFINITY {
        return 0.0;
    }
    if s <= 0.0 {
        return (c - mu).max(0.0);
    }
    let z = (c - mu) / s;
    (c - mu) * normal_cdf(z) + s * normal_pdf(z)
}

/// An incumbent front prepared for the expected hypervolume improvement: its
/// non-dominated points inside the reference point, by increasing `f1` (module doc).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Staircase {
    points: Vec<[f64; 2]>,
    reference: [f64; 2],
}

impl Staircase {
    /// Prepares `front` (any points; those outside `reference` and dominated ones are
    /// dropped) against `reference`.
    pub fn new(front: &[[f64; 2]], reference: [f64; 2]) -> Staircase {
        let inside: Vec<[f64; 2]> = front
            .iter()
            .copied()
            .filter(|p| p[0] < reference[0] && p[1] < reference[1])
            .collect();
        Staircase {
            points: non_dominated(&inside)
                .into_iter()
                .map(|i| inside[i])
                .collect(),
            reference,
        }
    }

    /// The expected hypervolume improvement of `Y ~ N(mean, diag(std^2))`, units of
    /// `f1 f2`. Strips where `psi_1(a_(i+1))` or `psi_2(b_i)` is below its value
    /// [`TAIL_Z`] deviations under the mean (about `1e-15 s_k`) are skipped, found by binary
    /// search: the result is exact to rounding, and a long predicted front costs only the
    /// strips near the point.
    pub fn ehvi(&self, mean: [f64; 2], std: [f64; 2]) -> f64 {
        let (p, r) = (&self.points, self.reference);
        let m = p.len();
        let a = |i: usize| match i {
            0 => f64::NEG_INFINITY,
            i if i == m + 1 => r[0],
            i => p[i - 1][0],
        };
        let b = |i: usize| if i == 0 { r[1] } else { p[i - 1][1] };
        // strips i < first end (a_(i+1) = p[i][0]) below mu_1 - TAIL_Z s_1
        let first = p.partition_point(|q| q[0] < mean[0] - TAIL_Z * std[0]);
        // strips 1..=last have b_i >= mu_2 - TAIL_Z s_2 (b falls along the front)
        let last = p.partition_point(|q| q[1] >= mean[1] - TAIL_Z * std[1]);
        let mut lower = shortfall(a(first), mean[0], std[0]);
        (first..=last.max(first))
            .map(|i| {
                let upper = shortfall(a(i + 1), mean[0], std[0]);
                let width = upper - lower;
                lower = upper;
                width * shortfall(b(i), mean[1], std[1])
            })
            .sum()
    }
}

/// Probability that the design `(ks, cs)` with criteria `Y_k ~ N(mean_k, (mean_k
/// relative_std_k)^2)` meets the design objectives (module doc).
pub fn probability_feasible(
    objectives: &DesignObjectives,
    ctx: &DosContext,
    ks: f64,
    cs: f64,
    mean: &Criteria,
    relative_std: [f64; 3],
) -> f64 {
    let m = mean.to_array();
    let below = |bound: f64, k: usize| {
        let s = m[k] * relative_std[k];
        if s > 0.0 {
            normal_cdf((bound - m[k]) / s)
        } else if m[k] <= bound {
            1.0
        } else {
            0.0
        }
    };
    let mut p = 1.0;
    for (objective, g) in objectives.constraints(ctx, ks, cs, mean) {
        p *= match objective {
            Objective::SwsLimit => objectives.sws_limit.map_or(1.0, |l| below(l, 2)),
            Objective::BaccDatum => below(ctx.datum.bacc, 0),
            Objective::DtlDatum => below(ctx.datum.dtl, 1),
            Objective::SwsDatum => below(ctx.datum.sws, 2),
            // k DTL <= F_static and n SWS <= travel: bounds on DTL and on SWS.
            Objective::DtlMargin => objectives
                .dtl_margin
                .map_or(1.0, |k| below(ctx.static_wheel_load / k, 1)),
            Objective::Travel => objectives.travel.map_or(1.0, |(t, n)| below(t / n, 2)),
            Objective::BounceBand | Objective::DampingBand if g <= 0.0 => 1.0,
            Objective::BounceBand | Objective::DampingBand => 0.0,
        };
    }
    p
}

/// One scored candidate design.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Candidate {
    /// Front spring rate, N/m.
    pub ks: f64,
    /// Front damper rate, N s/m.
    pub cs: f64,
    /// Whether it is a design of the surrogate's predicted front (else a grid point).
    pub on_front: bool,
    /// The surrogate's prediction.
    pub predicted: Criteria,
    /// Its relative 1-sigma uncertainty `[bacc, dtl, sws]`, -.
    pub relative_std: [f64; 3],
    /// Expected hypervolume improvement, (m/s^2) N.
    pub ehvi: f64,
    /// Probability of meeting the design objectives, -.
    pub probability_feasible: f64,
    /// The criterion `EHVI x PoF`, (m/s^2) N.
    pub value: f64,
    /// Normalised distance to the nearest sample, -.
    pub distance: f64,
}

/// What the criterion needs besides the fitted surrogate.
pub(crate) struct InfillSetting<'a> {
    /// The design objectives.
    pub objectives: &'a DesignObjectives,
    /// The car context of the objectives.
    pub ctx: &'a DosContext,
    /// The design box.
    pub design_box: &'a DesignBox,
    /// The surrogate's predicted feasible front.
    pub front: &'a [FrontPoint],
    /// The hypervolume reference point `[BAcc, DTL]`.
    pub reference: [f64; 2],
    /// Grid points per axis of the candidate grid.
    pub grid: usize,
    /// Minimum normalised distance of a new design to every sample.
    pub min_distance: f64,
}

/// The incumbent front of `criterion`: `[BAcc, DTL]` of the feasible HiFi samples or of
/// the predicted front.
pub(crate) fn incumbent(
    criterion: Infill,
    set: &InfillSetting,
    samples: &[Sample],
) -> Vec<[f64; 2]> {
    match criterion {
        Infill::Ehvi => samples
            .iter()
            .filter(|s| set.objectives.violation(set.ctx, s.ks, s.cs, &s.hifi) == 0.0)
            .map(|s| [s.hifi.bacc, s.hifi.dtl])
            .collect(),
        Infill::EhviFront => set.front.iter().map(|p| [p.bacc, p.dtl]).collect(),
    }
}

/// The best candidate by `criterion` (module doc) and, when none scores above 0, the
/// farthest from every sample; `None` only when every candidate is too close to a sample.
pub(crate) fn choose(
    criterion: Infill,
    est: &Uncertain,
    set: &InfillSetting,
    samples: &[Sample],
) -> Result<Option<Candidate>> {
    let b = set.design_box;
    let staircase = Staircase::new(&incumbent(criterion, set, samples), set.reference);
    let taken: Vec<[f64; 2]> = samples
        .iter()
        .map(|s| {
            let (u, v) = b.normalize(s.ks, s.cs);
            [u, v]
        })
        .collect();
    let n = set.grid.max(2);
    let grid = (0..n).flat_map(|i| {
        (0..n).map(move |j| (i as f64 / (n - 1) as f64, j as f64 / (n - 1) as f64, false))
    });
    let front = set.front.iter().map(|p| {
        let (u, v) = b.normalize(p.ks, p.cs);
        (u, v, true)
    });
    let mut best: Option<Candidate> = None;
    let mut farthest: Option<Candidate> = None;
    for (u, v, on_front) in front.chain(grid) {
        let distance = taken
            .iter()
            .map(|t| math::hypot(u - t[0], v - t[1]))
            .fold(f64::INFINITY, f64::min);
        if distance < set.min_distance {
            continue;
        }
        let (ks, cs) = b.scale(u, v);
        let (predicted, relative_std) = est.predict(ks, cs)?;
        let m = predicted.to_array();
        let gain = staircase.ehvi(
            [m[0], m[1]],
            [m[0] * relative_std[0], m[1] * relative_std[1]],
        );
        let pof = probability_feasible(set.objectives, set.ctx, ks, cs, &predicted, relative_std);
        let c = Candidate {
            ks,
            cs,
            on_front,
            predicted,
            relative_std,
            ehvi: gain,
            probability_feasible: pof,
            value: gain * pof,
            distance,
        };
        if c.value.is_finite() && c.value > 0.0 && best.is_none_or(|b| c.value > b.value) {
            best = Some(c);
        }
        if farthest.is_none_or(|f| c.distance > f.distance) {
            farthest = Some(c);
        }
    }
    Ok(best.or(farthest))
}

/// Why `c` was chosen, in words.
pub fn reason(criterion: Infill, c: &Candidate, sws_limit: Option<f64>) -> String {
    let p = c.predicted;
    let s = c.relative_std.map(|v| 100.0 * v);
    let place = if c.on_front {
        "a design of the predicted front"
    } else {
        "a grid point"
    };
    let predicted = format!(
        "predicted BAcc {:.4} m/s^2 +- {:.2} %, DTL {:.1} N +- {:.2} %, SWS {:.3} mm +- {:.2} %",
        p.bacc,
        s[0],
        p.dtl,
        s[1],
        p.sws * 1e3,
        s[2]
    );
    if c.value > 0.0 {
        let against = match criterion {
            Infill::Ehvi => "the feasible HiFi samples' front",
            Infill::EhviFront => "the predicted front",
        };
        let limit = sws_limit.map_or(String::new(), |l| format!(" (SWS <= {:.2} mm)", l * 1e3));
        format!(
            "largest expected hypervolume improvement over {against} times probability of feasibility: \
             EHVI {:.4e} (m/s^2) N x P(feasible){limit} {:.3} = {:.4e}; {place}; {predicted}",
            c.ehvi, c.probability_feasible, c.value
        )
    } else {
        format!(
            "no candidate has a positive expected improvement: the candidate farthest from every sample \
             (normalised distance {:.3}); {place}; {predicted}",
            c.distance
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::optimize::hypervolume;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// Box-Muller standard normal draw.
    fn normal(rng: &mut ChaCha8Rng) -> f64 {
        let (u1, u2): (f64, f64) = (rng.random_range(1e-300..1.0), rng.random());
        (-2.0 * u1.ln()).sqrt() * (2.0 * std::f64::consts::PI * u2).cos()
    }

    #[test]
    fn ehvi_matches_monte_carlo_and_the_deterministic_limit() {
        let front = [[1.0, 3.0], [2.0, 2.0], [3.0, 1.0], [2.5, 2.5], [5.0, 0.5]];
        let r = [4.0, 4.0];
        let base = hypervolume(&front, r);
        // Deterministic limit: the plain improvement.
        for y in [[1.5, 1.5], [0.5, 3.5], [3.5, 0.2], [2.0, 2.0], [4.5, 1.0]] {
            let mut with = front.to_vec();
            with.push(y);
            let want = hypervolume(&with, r) - base;
            let got = Staircase::new(&front, r).ehvi(y, [0.0, 0.0]);
            assert!((got - want).abs() < 1e-12, "{y:?}: {got} vs {want}");
        }
        // Monte Carlo with 200 000 seeded draws: within 4 standard errors.
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        for (mean, std) in [([1.8, 1.9], [0.4, 0.7]), ([3.0, 3.0], [1.0, 0.3])] {
            let n = 200_000;
            let (mut sum, mut sq) = (0.0, 0.0);
            for _ in 0..n {
                let y = [
                    mean[0] + std[0] * normal(&mut rng),
                    mean[1] + std[1] * normal(&mut rng),
                ];
                let mut with = front.to_vec();
                with.push(y);
                let hvi = hypervolume(&with, r) - base;
                sum += hvi;
                sq += hvi * hvi;
            }
            let m = sum / n as f64;
            let se = ((sq / n as f64 - m * m) / n as f64).sqrt();
            let got = Staircase::new(&front, r).ehvi(mean, std);
            assert!(
                (got - m).abs() < 4.0 * se,
                "{mean:?}: {got} vs MC {m} +- {se}"
            );
        }
        // Empty front: the expected box to the reference point.
        let got = Staircase::new(&[], r).ehvi([3.0, 3.0], [0.0, 0.0]);
        assert!((got - 1.0).abs() < 1e-12);
    }

    #[test]
    fn normal_functions_by_hand() {
        assert!((normal_cdf(0.0) - 0.5).abs() < 1e-15);
        // Phi(1.959963984540054) = 0.975 (tables)
        assert!((normal_cdf(1.959_963_984_540_054) - 0.975).abs() < 1e-12);
        assert!((normal_cdf(-1.0) - 0.158_655_253_931_457_05).abs() < 1e-12);
        assert!((normal_pdf(0.0) - 0.398_942_280_401_432_7).abs() < 1e-15);
        // psi(c) for s -> 0 is (c - mu)^+; for c = mu it is s phi(0).
        assert!((shortfall(2.0, 2.0, 0.5) - 0.5 * normal_pdf(0.0)).abs() < 1e-15);
        assert_eq!(shortfall(1.0, 2.0, 0.0), 0.0);
    }

    #[test]
    fn feasibility_probability_of_the_sws_limit_and_bands() {
        let ctx = DosContext {
            sprung_mass: 467.7,
            tire_stiffness: 175_500.0,
            datum: Criteria::from_array([1.0, 400.0, 0.006]),
            static_wheel_load: 4000.0,
        };
        let o = DesignObjectives::default();
        let mean = Criteria::from_array([1.0, 400.0, 0.007]);
        // On the limit: one half; 1 sigma below it: Phi(1).
        let p = probability_feasible(&o, &ctx, 20_000.0, 1500.0, &mean, [0.0, 0.0, 0.1]);
        assert!((p - 0.5).abs() < 1e-12);
        let below = Criteria {
            sws: 0.007 / 1.1,
            ..mean
        };
        let p = probability_feasible(&o, &ctx, 20_000.0, 1500.0, &below, [0.0, 0.0, 0.1]);
        assert!((p - normal_cdf(1.0)).abs() < 1e-12, "{p}");
        assert_eq!(
            probability_feasible(&o, &ctx, 20_000.0, 1500.0, &below, [0.0; 3]),
            1.0
        );
        // A band missed by (Ks, Cs) is certain whatever the criteria.
        let banded = DesignObjectives {
            bounce_band: Some((2.0, 3.0)),
            ..o
        };
        assert_eq!(
            probability_feasible(&banded, &ctx, 20_000.0, 1500.0, &below, [0.0, 0.0, 0.1]),
            0.0
        );
        // The tyre-load margin k DTL <= F_static (k = 8: DTL <= 500 N) and the travel
        // budget n SWS <= travel (3 SWS <= 0.021 m: SWS <= 7 mm), with the SWS limit off:
        // on the bound one half, 1 sigma below it Phi(1), and both together the product.
        let none = DesignObjectives {
            sws_limit: None,
            ..o
        };
        let margin = DesignObjectives {
            dtl_margin: Some(8.0),
            ..none
        };
        let on = Criteria::from_array([1.0, 500.0, 0.007]);
        let p = probability_feasible(&margin, &ctx, 20_000.0, 1500.0, &on, [0.0, 0.1, 0.0]);
        assert!((p - 0.5).abs() < 1e-12, "{p}");
        let inside = Criteria {
            dtl: 500.0 / 1.1,
            ..on
        };
        let p = probability_feasible(&margin, &ctx, 20_000.0, 1500.0, &inside, [0.0, 0.1, 0.0]);
        assert!((p - normal_cdf(1.0)).abs() < 1e-12, "{p}");
        let travel = DesignObjectives {
            travel: Some((0.021, 3.0)),
            ..margin
        };
        let p = probability_feasible(&travel, &ctx, 20_000.0, 1500.0, &inside, [0.0, 0.1, 0.1]);
        assert!((p - 0.5 * normal_cdf(1.0)).abs() < 1e-12, "{p}");
        assert!(Infill::parse("x")
            .unwrap_err()
            .to_string()
            .starts_with("criterion"));
        assert_eq!(Infill::parse("EHVI-front").unwrap().name(), "ehvi-front");
    }
}
