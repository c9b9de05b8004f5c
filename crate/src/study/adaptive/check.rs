//! The yardstick of the adaptive study: the HiFi's own front, and a surrogate's front
//! and pick judged on the HiFi against it.

use super::Decision;
use crate::design::DesignBox;
use crate::error::Result;
use crate::evaluate::Evaluator;
use crate::optimize::study::REFERENCE_MARGIN;
use crate::optimize::{hypervolume, min_max_pick, recheck, reference_point, Counted, StmParams};
use crate::surrogate::Surrogate;
use serde::Serialize;

/// Largest relative violation of the design objectives (`sum_j max(g_j, 0)`, e.g.
/// `SWS / limit - 1`) at which [`front_check`] still counts a front design as feasible on
/// the HiFi: 1e-4, 0.7 um on a 7 mm SWS limit. A surrogate's front ends on the SWS limit
/// by bisection, and there a surrogate good to 1e-8 still lands a hair outside on the HiFi
/// (the datum scenario's gp-mul front on 10 samples: SWS 7.000000025 mm); without the
/// tolerance such a point drops out and takes a sliver of about 1e-4 of the hypervolume
/// with it, a loss that says nothing about the surrogate. The errors compared are 1e-3
/// and up.
pub const HIFI_FEASIBILITY_TOLERANCE: f64 = 1e-4;

/// The reference HiFi front of a scenario: STM on the HiFi itself (the decision's
/// settings: by default a 201 x 201 grid, 3 refinement levels and the boundary bisection,
/// about 48 000 HiFi runs), the yardstick of every front of the study.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct HifiFront {
    /// STM settings.
    pub stm: StmParams,
    /// HiFi runs it took.
    pub hifi_runs: usize,
    /// Points of the front.
    pub front_points: usize,
    /// Reference point `nadir + 0.1 (nadir - ideal)` of the front `[BAcc (m/s^2), DTL (N)]`.
    pub reference_point: [f64; 2],
    /// Its hypervolume, (m/s^2) N.
    pub hypervolume: f64,
    /// `[BAcc, DTL]` of the front (left out of reports).
    #[serde(skip)]
    pub front: Vec<[f64; 2]>,
}

impl HifiFront {
    /// STM with `decision` on `hifi` over `design_box`. Errors name the binding objective
    /// when no design is feasible.
    pub fn new<E: Evaluator + ?Sized>(
        hifi: &E,
        decision: &Decision,
        design_box: &DesignBox,
    ) -> Result<HifiFront> {
        let counted = Counted::new(hifi);
        let front: Vec<[f64; 2]> = decision
            .front(&counted, design_box)?
            .iter()
            .map(|p| [p.bacc, p.dtl])
            .collect();
        let reference_point = reference_point(&front, REFERENCE_MARGIN);
        Ok(HifiFront {
            stm: decision.stm.clone(),
            hifi_runs: counted.count(),
            front_points: front.len(),
            hypervolume: hypervolume(&front, reference_point),
            reference_point,
            front,
        })
    }
}

/// A surrogate's front and pick judged on the HiFi.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FrontCheck {
    /// HiFi samples the surrogate was fitted to.
    pub hifi_runs: usize,
    /// Points of the surrogate's feasible front.
    pub front_points: usize,
    /// Of those, the points that meet the design objectives on the HiFi (to
    /// [`HIFI_FEASIBILITY_TOLERANCE`]).
    pub hifi_feasible_points: usize,
    /// Hypervolume of the front's designs re-evaluated on the HiFi (the HiFi-feasible ones)
    /// over the reference HiFi front's, both against the reference front's reference point, -
    /// (can pass 1 by a hair: see [`HIFI_FEASIBILITY_TOLERANCE`]).
    pub hypervolume_ratio: f64,
    /// Largest relative error `100 |S_k / F_k - 1|` over the front's designs and the three
    /// criteria, %.
    pub front_max_error_percent: f64,
    /// The pick's design `[Ks (N/m), Cs (N s/m)]`.
    pub pick: [f64; 2],
    /// The pick's HiFi re-check error `100 (S_k / F_k - 1)` of `[bacc, dtl, sws]`, %.
    pub recheck_percent: [f64; 3],
    /// Its largest magnitude, %.
    pub recheck_error_percent: f64,
}

/// Judges `model`'s front (found with `decision`) on `hifi` against `reference`.
pub fn front_check<E: Evaluator + ?Sized>(
    model: &dyn Surrogate,
    hifi: &E,
    decision: &Decision,
    design_box: &DesignBox,
    reference: &HifiFront,
    hifi_runs: usize,
) -> Result<FrontCheck> {
    let front = decision.front(model, design_box)?;
    let mut feasible = Vec::new();
    let mut worst: f64 = 0.0;
    for p in &front {
        let c = hifi.evaluate(p.ks, p.cs)?;
        let (s, f) = (p.criteria().to_array(), c.to_array());
        for k in 0..3 {
            worst = worst.max(100.0 * (s[k] / f[k] - 1.0).abs());
        }
        if decision.objectives.violation(&decision.ctx, p.ks, p.cs, &c)
            <= HIFI_FEASIBILITY_TOLERANCE
        {
            feasible.push([c.bacc, c.dtl]);
        }
    }
    let pick = min_max_pick(&front, &decision.ctx.datum)?;
    let r = recheck(&pick, hifi, &decision.ctx.datum)?;
    Ok(FrontCheck {
        hifi_runs,
        front_points: front.len(),
        hifi_feasible_points: feasible.len(),
        hypervolume_ratio: hypervolume(&feasible, reference.reference_point)
            / reference.hypervolume,
        front_max_error_percent: worst,
        pick: [pick.ks, pick.cs],
        recheck_percent: r.error_percent,
        recheck_error_percent: r.error_percent.iter().fold(0.0, |m, e| m.max(e.abs())),
    })
}
