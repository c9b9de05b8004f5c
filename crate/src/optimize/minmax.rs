//! Picks on a front, normalised by a datum car, and their HiFi re-check.
//!
//! Datum normalisation `r_i = f_i / f_i(datum)` and normalised distances from the ideal
//! point `d_i = (r_i - r_i,min) / (r_i,max - r_i,min)`, `i` over BAcc and DTL. Rules
//! ([`PickRule`]): the thesis's min-max pick minimises `max_i d_i`; the knee minimises
//! `d_1 + d_2` (the point farthest below the line through the front's two extremes, Das
//! 1999); the weighted pick minimises the achievement scalarising function
//! `max(W d_1, (1 - W) d_2) + 1e-6 (d_1 + d_2)` with the comfort weight `W` in [0, 1]
//! (W = 0.5 is the min-max pick). Each point's pseudo-weights (Deb) are
//! `w_i = (1 - d_i) / sum_j (1 - d_j)`. The datum cancels in `d`, so it sets the reported
//! ratios and % changes, not the pick.

use super::suspension::FrontPoint;
use crate::error::{Result, RideError};
use crate::evaluate::{Criteria, Evaluator};
use serde::Serialize;

/// How a design is picked from a front.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum PickRule {
    /// The thesis's min-max pick.
    MinMax,
    /// The knee: least `d_1 + d_2`.
    Knee,
    /// Achievement scalarising function with comfort weight `W` in [0, 1].
    Asf(f64),
}

impl std::str::FromStr for PickRule {
    type Err = RideError;
    /// `minmax`, `knee` or `asf:W` with `0 <= W <= 1`; errors name `pick`.
    fn from_str(s: &str) -> Result<PickRule> {
        match s.trim() {
            "minmax" | "min-max" => Ok(PickRule::MinMax),
            "knee" => Ok(PickRule::Knee),
            t => match t.strip_prefix("asf:").map(|w| w.trim().parse::<f64>()) {
                Some(Ok(w)) if (0.0..=1.0).contains(&w) => Ok(PickRule::Asf(w)),
                Some(_) => Err(RideError::field(
                    "pick",
                    format!("'{t}': the comfort weight W of asf:W must be in [0, 1]"),
                )),
                None => Err(RideError::field(
                    "pick",
                    format!("'{t}' is not minmax, knee or asf:W"),
                )),
            },
        }
    }
}

impl PickRule {
    /// The rule's score of normalised distances `d` (least is picked).
    fn score(self, d: [f64; 2]) -> f64 {
        match self {
            PickRule::MinMax => d[0].max(d[1]),
            PickRule::Knee => d[0] + d[1],
            PickRule::Asf(w) => (w * d[0]).max((1.0 - w) * d[1]) + 1e-6 * (d[0] + d[1]),
        }
    }

    /// The rule as written on the command line.
    pub(crate) fn name(self) -> String {
        match self {
            PickRule::MinMax => "minmax".into(),
            PickRule::Knee => "knee".into(),
            PickRule::Asf(w) => format!("asf:{w}"),
        }
    }
}

/// A design picked from a front.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Pick {
    /// The rule that picked it (`minmax`, `knee`, `asf:W`).
    pub rule: String,
    /// Index of the pick in the front.
    pub index: usize,
    /// Front spring rate, N/m.
    pub ks: f64,
    /// Front damper rate, N s/m.
    pub cs: f64,
    /// Criteria at the pick, as the evaluator of the front predicts them.
    pub criteria: Criteria,
    /// `[r_bacc, r_dtl]`, `r_i = f_i / f_i(datum)`, -.
    pub ratio: [f64; 2],
    /// Normalised distances from the ideal point `(r_i - r_i,min) / (r_i,max - r_i,min)`, -.
    pub distance: [f64; 2],
    /// The rule's score (min-max: `max_i distance_i`), -.
    pub score: f64,
    /// Pseudo-weights `[w_bacc, w_dtl]` of the pick, `w_i = (1 - d_i) / sum_j (1 - d_j)`, -.
    pub pseudo_weights: [f64; 2],
    /// Change against the datum of `[bacc, dtl, sws]`, `100 (f / f_datum - 1)`, %.
    pub change_percent: [f64; 3],
}

/// Checks that the datum criteria are finite and positive (they divide).
fn check_datum(datum: &Criteria) -> Result<()> {
    if datum.to_array().iter().all(|v| v.is_finite() && *v > 0.0) {
        Ok(())
    } else {
        Err(RideError::field(
            "datum",
            "criteria must be finite numbers > 0",
        ))
    }
}

/// `100 (f / f_datum - 1)` for `[bacc, dtl, sws]`, %.
pub(crate) fn change_percent(c: &Criteria, datum: &Criteria) -> [f64; 3] {
    let (v, d) = (c.to_array(), datum.to_array());
    [0, 1, 2].map(|i| 100.0 * (v[i] / d[i] - 1.0))
}

/// Normalised distances `(r_i - r_i,min) / (r_i,max - r_i,min)` of every front point
/// for `[bacc, dtl]`; an objective with no spread on the front gets 0.
pub fn normalised_distances(front: &[FrontPoint], datum: &Criteria) -> Vec<[f64; 2]> {
    let ratio = |p: &FrontPoint| [p.bacc / datum.bacc, p.dtl / datum.dtl];
    let r: Vec<[f64; 2]> = front.iter().map(ratio).collect();
    let (lo, hi) = super::hypervolume::ideal_nadir(&r);
    r.iter()
        .map(|ri| {
            [0, 1].map(|k| {
                let span = hi[k] - lo[k];
                if span > 0.0 {
                    (ri[k] - lo[k]) / span
                } else {
                    0.0
                }
            })
        })
        .collect()
}

/// Pseudo-weights `[w_bacc, w_dtl]` of normalised distances `d` (`[0.5, 0.5]` when both
/// are 1, a front of one point).
pub(crate) fn pseudo_weights(d: [f64; 2]) -> [f64; 2] {
    let (a, b) = (1.0 - d[0], 1.0 - d[1]);
    if a + b > 0.0 {
        [a / (a + b), b / (a + b)]
    } else {
        [0.5, 0.5]
    }
}

/// The min-max pick on `front` against `datum` (the first point on ties).
pub fn min_max_pick(front: &[FrontPoint], datum: &Criteria) -> Result<Pick> {
    pick(front, datum, PickRule::MinMax)
}

/// The pick of `rule` on `front` against `datum` (the first point on ties).
pub fn pick(front: &[FrontPoint], datum: &Criteria, rule: PickRule) -> Result<Pick> {
    check_datum(datum)?;
    let d = normalised_distances(front, datum);
    let score = |k: usize| rule.score(d[k]);
    let index = (0..front.len())
        .min_by(|&a, &b| score(a).total_cmp(&score(b)))
        .ok_or_else(|| RideError::field("front", "is empty, nothing to pick"))?;
    let p = front[index];
    let criteria = p.criteria();
    Ok(Pick {
        rule: rule.name(),
        index,
        ks: p.ks,
        cs: p.cs,
        criteria,
        ratio: [p.bacc / datum.bacc, p.dtl / datum.dtl],
        distance: d[index],
        score: score(index),
        pseudo_weights: pseudo_weights(d[index]),
        change_percent: change_percent(&criteria, datum),
    })
}

/// The pick re-evaluated on another (reference, typically HiFi) evaluator.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Recheck {
    /// Name of the re-checking evaluator.
    pub evaluator: String,
    /// Criteria the front's evaluator predicted at the pick.
    pub predicted: Criteria,
    /// Criteria the re-checking evaluator gives at the pick.
    pub rechecked: Criteria,
    /// Prediction error `100 (predicted / rechecked - 1)` of `[bacc, dtl, sws]`, %.
    pub error_percent: [f64; 3],
    /// Predicted change against the datum (as in [`Pick::change_percent`]), %.
    pub predicted_change_percent: [f64; 3],
    /// Re-checked change against the datum on the re-checking evaluator, %.
    pub rechecked_change_percent: [f64; 3],
}

/// Re-evaluates `pick` on `reference` and compares; `datum` is the datum car's
/// criteria on that same reference evaluator.
pub fn recheck<E: Evaluator + ?Sized>(
    pick: &Pick,
    reference: &E,
    datum: &Criteria,
) -> Result<Recheck> {
    check_datum(datum)?;
    let rechecked = reference.evaluate(pick.ks, pick.cs)?;
    Ok(Recheck {
        evaluator: reference.name(),
        predicted: pick.criteria,
        rechecked,
        error_percent: change_percent(&pick.criteria, &rechecked),
        predicted_change_percent: pick.change_percent,
        rechecked_change_percent: change_percent(&rechecked, datum),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(bacc: f64, dtl: f64) -> FrontPoint {
        FrontPoint {
            ks: 1e4 * bacc,
            cs: 1e3 * dtl,
            bacc,
            dtl,
            sws: 0.005,
        }
    }

    #[test]
    fn pick_balances_the_normalised_distances() {
        // bacc 1..2, dtl 300..500: distances (0,1), (0.2,0.5), (0.6,0.25), (1,0),
        // scores 1, 0.5, 0.6, 1
        let front = [
            point(1.0, 500.0),
            point(1.2, 400.0),
            point(1.6, 350.0),
            point(2.0, 300.0),
        ];
        let datum = Criteria {
            bacc: 1.25,
            dtl: 500.0,
            sws: 0.004,
        };
        let p = min_max_pick(&front, &datum).unwrap();
        assert_eq!(p.index, 1);
        assert!((p.score - 0.5).abs() < 1e-12);
        assert!((p.distance[0] - 0.2).abs() < 1e-12 && (p.distance[1] - 0.5).abs() < 1e-12);
        assert!((p.ratio[0] - 0.96).abs() < 1e-12 && (p.ratio[1] - 0.8).abs() < 1e-12);
        // 1.2/1.25 = -4 %, 400/500 = -20 %, 5/4 = +25 %
        let c = p.change_percent;
        assert!(
            (c[0] + 4.0).abs() < 1e-9 && (c[1] + 20.0).abs() < 1e-9 && (c[2] - 25.0).abs() < 1e-9
        );
    }

    #[test]
    fn pick_has_the_least_score_of_every_point_and_the_first_on_ties() {
        // bacc 1..2, dtl 300..500 and a unit datum: distances (0, 1), (0.4, 0.5),
        // (0.5, 0.45), (0.7, 0.25), (1, 0); scores 1, 0.5, 0.5, 0.7, 1: a tie at 0.5.
        let front = [
            point(1.0, 500.0),
            point(1.4, 400.0),
            point(1.5, 390.0),
            point(1.7, 350.0),
            point(2.0, 300.0),
        ];
        let datum = Criteria {
            bacc: 1.0,
            dtl: 1.0,
            sws: 0.005,
        };
        let want = [1.0, 0.5, 0.5, 0.7, 1.0];
        let p = min_max_pick(&front, &datum).unwrap();
        for (k, d) in normalised_distances(&front, &datum).iter().enumerate() {
            // 1e-12: (1.4 - 1) / 1 is 0.3999999999999999 in binary.
            assert!((d[0].max(d[1]) - want[k]).abs() < 1e-12, "point {k}: {d:?}");
            assert!(p.score <= d[0].max(d[1]), "point {k} beats the pick");
        }
        assert_eq!(p.index, 1, "the first of the tied points");
        assert_eq!(p.score, 0.5);
        // Reversed, the other tied point comes first and is picked.
        let mut rev = front;
        rev.reverse();
        let q = min_max_pick(&rev, &datum).unwrap();
        assert_eq!((q.index, q.ks), (2, front[2].ks));
    }

    #[test]
    fn recheck_reports_both_and_the_error() {
        struct Fixed;
        impl Evaluator for Fixed {
            fn evaluate(&self, _ks: f64, _cs: f64) -> Result<Criteria> {
                Ok(Criteria {
                    bacc: 1.0,
                    dtl: 400.0,
                    sws: 0.005,
                })
            }
            fn name(&self) -> String {
                "fixed".into()
            }
        }
        let front = [point(1.1, 380.0)];
        let datum = Criteria {
            bacc: 1.0,
            dtl: 400.0,
            sws: 0.005,
        };
        let p = min_max_pick(&front, &datum).unwrap();
        let r = recheck(&p, &Fixed, &datum).unwrap();
        assert_eq!(r.evaluator, "fixed");
        assert!(
            (r.error_percent[0] - 10.0).abs() < 1e-9 && (r.error_percent[1] + 5.0).abs() < 1e-9
        );
        assert_eq!(r.rechecked_change_percent, [0.0, 0.0, 0.0]);
    }

    #[test]
    fn empty_front_and_bad_datum_are_errors() {
        let datum = Criteria {
            bacc: 1.0,
            dtl: 400.0,
            sws: 0.005,
        };
        assert!(min_max_pick(&[], &datum)
            .unwrap_err()
            .to_string()
            .starts_with("front"));
        let bad = Criteria { dtl: 0.0, ..datum };
        assert!(min_max_pick(&[point(1.0, 1.0)], &bad)
            .unwrap_err()
            .to_string()
            .starts_with("datum"));
    }
}
