//! How far a pick can be trusted, said with the pick: a pick on an edge of the design box
//! (the box, not the trade-off, stopped it) and a prediction its HiFi re-check does not
//! confirm. Both are warnings beside the result (`warnings` in the JSON, a `warning:`
//! line in the text, a note on the page), never silent.

use super::minmax::{Pick, Recheck};
use crate::design::DesignBox;
use crate::domain::num;
use serde::Serialize;

/// Largest difference between a pick's predicted criteria and their HiFi re-check,
/// `100 |predicted / rechecked - 1|`, before the result warns, %. The surrogates of the
/// fidelity study stay within 1 % (README), the LoFi within about 2 % of the HiFi near
/// the datum; 3 % is beyond both, and a predicted improvement that large is no longer
/// the HiFi's.
pub(crate) const RECHECK_TOLERANCE_PERCENT: f64 = 3.0;

/// Relative distance from a box bound, of the box's width, within which a pick counts
/// as on the bound (STM's refinement and boundary bisection put a pick the box stops
/// exactly on it).
const EDGE: f64 = 1e-9;

/// One warning about a result.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Warning {
    /// `"box_edge"` or `"recheck"`.
    pub kind: &'static str,
    /// What it concerns: the box bound (`ks_min`, `ks_max`, `cs_min`, `cs_max`) or the
    /// criterion (`bacc`, `dtl`, `sws`).
    pub field: String,
    /// The warning in words, with the numbers and what to do.
    pub message: String,
}

/// The warnings of a pick at `(pick.ks, pick.cs)` in `dbox` and its re-check: each box
/// bound the pick sits on, each criterion whose prediction the re-check misses by more
/// than [`RECHECK_TOLERANCE_PERCENT`].
pub fn pick_warnings(pick: &Pick, recheck: &Recheck, dbox: &DesignBox) -> Vec<Warning> {
    let mut w = box_edges(pick.ks, pick.cs, dbox);
    w.extend(recheck_misses(recheck));
    w
}

/// One warning per bound of `dbox` that `(ks, cs)` sits on.
fn box_edges(ks: f64, cs: f64, dbox: &DesignBox) -> Vec<Warning> {
    let (wk, wc) = (dbox.ks_max - dbox.ks_min, dbox.cs_max - dbox.cs_min);
    let bounds = [
        ("ks_min", "lower Ks", ks, dbox.ks_min, wk, "N/m", "ks-range"),
        ("ks_max", "upper Ks", ks, dbox.ks_max, wk, "N/m", "ks-range"),
        (
            "cs_min",
            "lower Cs",
            cs,
            dbox.cs_min,
            wc,
            "N s/m",
            "cs-range",
        ),
        (
            "cs_max",
            "upper Cs",
            cs,
            dbox.cs_max,
            wc,
            "N s/m",
            "cs-range",
        ),
    ];
    bounds
        .into_iter()
        .filter(|(_, _, v, bound, width, _, _)| (v - bound).abs() <= EDGE * width)
        .map(|(field, what, _, bound, _, unit, option)| Warning {
            kind: "box_edge",
            field: field.into(),
            message: format!(
                "the pick sits on the design box's {what} bound ({} {unit}): the box, not the trade-off, stopped it; widen the box ({option}) to see past it",
                num(bound)
            ),
        })
        .collect()
}

/// One warning per criterion whose prediction the re-check misses by more than
/// [`RECHECK_TOLERANCE_PERCENT`].
fn recheck_misses(r: &Recheck) -> Vec<Warning> {
    const NAMES: [(&str, &str); 3] = [("bacc", "BAcc"), ("dtl", "DTL"), ("sws", "SWS")];
    r.error_percent
        .iter()
        .zip(NAMES)
        .enumerate()
        .filter(|(_, (e, _))| e.abs() > RECHECK_TOLERANCE_PERCENT)
        .map(|(k, (e, (field, name)))| Warning {
            kind: "recheck",
            field: field.into(),
            message: format!(
                "{name}: predicted {:+.2} % against the datum, the HiFi re-check gives {:+.2} %; the prediction is {:+.2} % off, beyond the {RECHECK_TOLERANCE_PERCENT} % tolerance: trust the re-check, not the prediction",
                r.predicted_change_percent[k],
                r.rechecked_change_percent[k],
                e
            ),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::evaluate::Criteria;

    fn recheck(error: [f64; 3]) -> Recheck {
        let c = Criteria {
            bacc: 1.0,
            dtl: 400.0,
            sws: 0.005,
        };
        Recheck {
            evaluator: "full".into(),
            predicted: c,
            rechecked: c,
            error_percent: error,
            predicted_change_percent: [-10.75, -3.0, 1.0],
            rechecked_change_percent: [2.83, -3.1, 1.2],
        }
    }

    #[test]
    fn a_pick_on_a_bound_names_it_and_one_inside_does_not() {
        let b = DesignBox::default();
        let w = box_edges(10_000.0, 1_677.0, &b);
        assert_eq!(w.len(), 1);
        assert_eq!(w[0].field, "ks_min");
        assert!(
            w[0].message.contains("lower Ks bound (10000 N/m)"),
            "{}",
            w[0].message
        );
        let corner = box_edges(40_000.0, 4_000.0, &b);
        let fields: Vec<&str> = corner.iter().map(|w| w.field.as_str()).collect();
        assert_eq!(fields, ["ks_max", "cs_max"]);
        assert!(box_edges(10_000.1, 1_677.0, &b).is_empty());
    }

    #[test]
    fn a_recheck_beyond_the_tolerance_warns_with_both_numbers() {
        let w = recheck_misses(&recheck([-12.9, 0.1, -3.01]));
        assert_eq!(w.len(), 2);
        assert_eq!((w[0].field.as_str(), w[1].field.as_str()), ("bacc", "sws"));
        assert!(
            w[0].message.starts_with(
                "BAcc: predicted -10.75 % against the datum, the HiFi re-check gives +2.83 %"
            ),
            "{}",
            w[0].message
        );
        assert!(recheck_misses(&recheck([2.99, -2.99, 0.0])).is_empty());
    }
}
