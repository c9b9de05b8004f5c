//! The robust objective and the robust DOS over a set of cases (issue #16).
//!
//! Normalisation: each case `k` is scaled to the first (reference) case's datum,
//! `s_kj = d_1j / d_kj` for criterion `j` of `[bacc, dtl, sws]`, `d_k` the datum design's
//! criteria in case `k`. The robust criteria, in the reference case's units
//! (m/s^2, N, m), are
//!
//! - worst case: `R_j = max_k s_kj c_kj`, i.e. `d_1j` times the largest ratio of a case's
//!   value to that case's datum;
//! - weighted mean: `R_j = sum_k p_k s_kj c_kj`, `p_k = w_k / sum w`.
//!
//! With one case `s = 1` and `p = 1` exactly, so the robust criteria are that case's bit
//! for bit. The robust datum is `d_1` (every case at its datum has ratio 1).
//!
//! The robust DOS: a design is feasible when it meets every objective in **every** case,
//! each case with its own context (its loaded car's quarter-car mass and static wheel
//! load, and its own datum for "no worse than the datum"). Each objective's constraint
//! value is the largest over the cases, `g_j = max_k g_kj`, so the objectives, their order
//! and their mask bits are those of one case.

use super::cases::Combine;
use crate::analysis::HiFiRoads;
use crate::dos::{DesignObjectives, DosContext, Objective};
use crate::error::{Result, RideError};
use crate::evaluate::{Criteria, Evaluator};

/// The combination rule with its per-case scales and probabilities.
#[derive(Debug, Clone, PartialEq)]
pub struct Combination {
    /// Worst case or weighted mean.
    pub combine: Combine,
    /// `s_kj = d_1j / d_kj` per case.
    pub scales: Vec<[f64; 3]>,
    /// `p_k = w_k / sum w` per case.
    pub probabilities: Vec<f64>,
    /// The reference datum `d_1` (the robust datum).
    pub datum: Criteria,
}

impl Combination {
    /// The combination of cases with datum criteria `datums` and probabilities `p`.
    /// Errors name `datum` when a datum criterion is not finite and > 0 (it divides).
    pub fn new(combine: Combine, datums: &[Criteria], p: &[f64]) -> Result<Combination> {
        let first = *datums
            .first()
            .ok_or_else(|| RideError::field("cases", "is empty"))?;
        for (k, d) in datums.iter().enumerate() {
            if !d.to_array().iter().all(|v| v.is_finite() && *v > 0.0) {
                return Err(RideError::field(
                    "datum",
                    format!("case {k}: the datum's criteria must be finite numbers > 0"),
                ));
            }
        }
        let d1 = first.to_array();
        Ok(Combination {
            combine,
            scales: datums
                .iter()
                .map(|d| {
                    let d = d.to_array();
                    [d1[0] / d[0], d1[1] / d[1], d1[2] / d[2]]
                })
                .collect(),
            probabilities: p.to_vec(),
            datum: first,
        })
    }

    /// The robust criteria of the cases' criteria `per` (one per case, in case order).
    pub fn apply(&self, per: &[Criteria]) -> Criteria {
        let mut r = [0.0; 3];
        for j in 0..3 {
            let scaled = per
                .iter()
                .zip(&self.scales)
                .map(|(c, s)| c.to_array()[j] * s[j]);
            r[j] = match self.combine {
                Combine::Worst => scaled.fold(f64::NEG_INFINITY, f64::max),
                Combine::Mean => scaled.zip(&self.probabilities).map(|(v, p)| p * v).sum(),
            };
        }
        Criteria::from_array(r)
    }
}

/// Calls `f(objective, g)` for each active objective with `g = max_k g_k` over the cases
/// (contexts `ctxs`, criteria `per`), in the order of [`DesignObjectives::constraints`].
pub fn robust_constraints(
    objectives: &DesignObjectives,
    ctxs: &[DosContext],
    ks: f64,
    cs: f64,
    per: &[Criteria],
) -> Vec<(Objective, f64)> {
    let mut g: Vec<(Objective, f64)> = Vec::new();
    for (k, (ctx, c)) in ctxs.iter().zip(per).enumerate() {
        let mut i = 0;
        objectives.each_constraint(ctx, ks, cs, c, |o, v| {
            if k == 0 {
                g.push((o, v));
            } else if v > g[i].1 {
                g[i].1 = v;
            }
            i += 1;
        });
    }
    g
}

/// The evaluator of a run of consecutive cases: one case's [`Evaluator`], or the HiFi of
/// one loaded car on its cases' roads ([`HiFiRoads`], which shares the road-independent
/// work and gives each case's own HiFi criteria bit for bit).
pub trait CaseRun {
    /// Number of cases.
    fn cases(&self) -> usize;
    /// Appends the cases' criteria at `(ks, cs)` to `out`, in case order; the first
    /// case's error where one fails.
    fn evaluate_into(&self, ks: f64, cs: f64, out: &mut Vec<Criteria>) -> Result<()>;
    /// The evaluator's name ([`Evaluator::name`]).
    fn run_name(&self) -> String;
}

impl<E: Evaluator> CaseRun for E {
    fn cases(&self) -> usize {
        1
    }
    fn evaluate_into(&self, ks: f64, cs: f64, out: &mut Vec<Criteria>) -> Result<()> {
        out.push(self.evaluate(ks, cs)?);
        Ok(())
    }
    fn run_name(&self) -> String {
        self.name()
    }
}

impl CaseRun for HiFiRoads {
    fn cases(&self) -> usize {
        self.hifis().len()
    }
    fn evaluate_into(&self, ks: f64, cs: f64, out: &mut Vec<Criteria>) -> Result<()> {
        out.extend(self.evaluate(ks, cs)?);
        Ok(())
    }
    fn run_name(&self) -> String {
        "full".into()
    }
}

/// An evaluator over the cases: the evaluators of runs of cases ([`CaseRun`]: each case's
/// own evaluator, or one for several cases), and the robust criteria of [`Combination`]
/// as its [`Evaluator::evaluate`].
pub struct RobustEvaluator<E> {
    /// The runs' evaluators, in case order.
    pub cases: Vec<E>,
    /// How their criteria combine.
    pub combination: Combination,
}

impl<E: CaseRun> RobustEvaluator<E> {
    /// Every case's criteria at `(ks, cs)`, in case order.
    pub(crate) fn evaluate_cases(&self, ks: f64, cs: f64) -> Result<Vec<Criteria>> {
        let mut out = Vec::with_capacity(self.case_count());
        for e in &self.cases {
            e.evaluate_into(ks, cs, &mut out)?;
        }
        Ok(out)
    }

    /// Number of cases.
    pub(crate) fn case_count(&self) -> usize {
        self.cases.iter().map(CaseRun::cases).sum()
    }
}

impl<E: CaseRun> Evaluator for RobustEvaluator<E> {
    fn evaluate(&self, ks: f64, cs: f64) -> Result<Criteria> {
        Ok(self.combination.apply(&self.evaluate_cases(ks, cs)?))
    }
    fn name(&self) -> String {
        match self.cases.first() {
            Some(e) if self.case_count() == 1 => e.run_name(),
            Some(e) => format!("{} x {} cases", e.run_name(), self.case_count()),
            None => "no cases".into(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::LoFi;
    use crate::car::Car;
    use crate::road::{Road, RoadClass};

    /// One case: the robust criteria are the case's bit for bit, for both rules.
    #[test]
    fn one_case_is_that_case_exactly() {
        let car = Car::datum();
        let road = Road::default();
        let lofi = LoFi::new(&car, &road);
        let d = lofi.evaluate(car.front.spring, car.front.damper).unwrap();
        for combine in [Combine::Worst, Combine::Mean] {
            let r = RobustEvaluator {
                cases: vec![LoFi::new(&car, &road)],
                combination: Combination::new(combine, &[d], &[1.0]).unwrap(),
            };
            for (ks, cs) in [(12_000.0, 700.0), (31_000.0, 3300.0)] {
                assert_eq!(r.evaluate(ks, cs).unwrap(), lofi.evaluate(ks, cs).unwrap());
            }
        }
    }

    /// Two cases against a hand computation of both rules (1e-15 relative), and the
    /// robust DOS's g is the larger of the cases' g per objective.
    #[test]
    fn two_cases_by_hand() {
        let car = Car::datum();
        let roads = [
            Road::default(),
            Road {
                class: RoadClass::C,
                speed: 30.0,
                ..Road::default()
            },
        ];
        let evs: Vec<LoFi> = roads.iter().map(|r| LoFi::new(&car, r)).collect();
        let d: Vec<Criteria> = evs
            .iter()
            .map(|e| e.evaluate(car.front.spring, car.front.damper).unwrap())
            .collect();
        let (ks, cs) = (27_000.0, 1900.0);
        let c: Vec<[f64; 3]> = evs
            .iter()
            .map(|e| e.evaluate(ks, cs).unwrap().to_array())
            .collect();
        let (d0, d1) = (d[0].to_array(), d[1].to_array());
        for (combine, p) in [(Combine::Worst, [0.5, 0.5]), (Combine::Mean, [0.25, 0.75])] {
            let r = RobustEvaluator {
                cases: evs.clone(),
                combination: Combination::new(combine, &d, &p).unwrap(),
            };
            let got = r.evaluate(ks, cs).unwrap().to_array();
            for j in 0..3 {
                let (r0, r1) = (c[0][j] / d0[j], c[1][j] / d1[j]);
                let want = d0[j]
                    * match combine {
                        Combine::Worst => r0.max(r1),
                        Combine::Mean => p[0] * r0 + p[1] * r1,
                    };
                assert!((got[j] / want - 1.0).abs() < 1e-15, "{combine:?} {j}");
            }
        }
        let o = DesignObjectives {
            dtl_margin: Some(3.0),
            no_worse_than_datum: [true, false, true],
            ..DesignObjectives::default()
        };
        let ctxs: Vec<DosContext> = d.iter().map(|d| DosContext::new(&car, *d)).collect();
        let per: Vec<Criteria> = c.iter().map(|a| Criteria::from_array(*a)).collect();
        let g = robust_constraints(&o, &ctxs, ks, cs, &per);
        let g0 = o.constraints(&ctxs[0], ks, cs, &per[0]);
        let g1 = o.constraints(&ctxs[1], ks, cs, &per[1]);
        assert_eq!(g.len(), 4);
        for i in 0..g.len() {
            assert_eq!(g[i].0, g0[i].0);
            assert_eq!(g[i].1, g0[i].1.max(g1[i].1));
        }
    }
}
