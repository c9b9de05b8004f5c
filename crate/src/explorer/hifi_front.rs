//! The HiFi's own Pareto front beside the objective plane's (issue #13): STM on the full
//! car with the page's settings ([`studies::STM_GRID`], [`studies::STM_LEVELS`]), and the
//! plane model's front (the surrogate's, or with Wk comfort the LoFi's) judged on the
//! HiFi against it. This is the thesis's claim made visible: how close the surrogate's
//! front and pick, found on a handful of HiFi runs, come to the HiFi optimum that takes
//! thousands.
//!
//! Both hypervolumes are measured against one reference point, the HiFi front's own
//! `nadir + 0.1 (nadir - ideal)` ([`crate::optimize::reference_point`]), so they compare.
//! The plane front's designs are re-evaluated on the HiFi; those that break the design
//! objectives there by more than [`HIFI_FEASIBILITY_TOLERANCE`] add nothing.
//!
//! With robust cases both fronts are robust ([`robust_hifi_front`]): STM on the robust
//! objective of every case's full car against the plane's LoFi robust front.

use super::state::Scenario;
use super::studies::{self, FrontResult};
use crate::analysis::{HiFi, ModelKind};
use crate::comfort::Comfort;
use crate::dos::DosContext;
use crate::error::{Result, RideError};
use crate::evaluate::{Criteria, Evaluator};
use crate::gpu::{ComputePath, HiFiGrid};
use crate::maps::Grid;
use crate::optimize::{hypervolume, Counted};
use crate::robust::{robust_constraints, CaseSet, Combination};
use crate::study::adaptive::HIFI_FEASIBILITY_TOLERANCE;
use crate::study::robust::optimize::{case_contexts, case_hifis, datums_on};
use serde::Serialize;

/// The HiFi front of a scenario and the plane's front judged against it.
#[derive(Debug, Clone, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct HifiFrontView {
    /// STM on the HiFi; its pick by the scenario's rule, its re-check the HiFi itself.
    pub front: FrontResult,
    /// HiFi runs the front took: the datum's and every design STM evaluated (the
    /// starting grid's `STM_GRID^2` included, wherever they ran).
    pub hifi_runs: usize,
    /// Where STM's starting grid was evaluated: `"gpu"` (values handed in) or `"cpu"`.
    pub compute: ComputePath,
    /// The plane model's front judged on the HiFi.
    pub plane: PlaneCheck,
}

/// The objective plane's front (found on its model) judged on the HiFi against the HiFi
/// front, everything against the HiFi front's reference point.
#[derive(Debug, Clone, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct PlaneCheck {
    /// The plane's model: "surrogate", "lofi" or "robust" (the LoFi's robust objective).
    pub model: String,
    /// HiFi runs behind the plane's front and pick: the surrogate's samples and the
    /// pick's re-check (the LoFi: the re-check only; robust: every case's HiFi datum and
    /// the pick's re-check in every case).
    pub hifi_runs: usize,
    /// Points of the plane's front.
    pub front_points: usize,
    /// Of those, the points that meet the design objectives on the HiFi (to
    /// [`HIFI_FEASIBILITY_TOLERANCE`]).
    pub hifi_feasible_points: usize,
    /// Hypervolume of the plane's front as its model predicts it, (m/s^2) N.
    pub hypervolume: f64,
    /// Hypervolume of its HiFi-feasible designs re-evaluated on the HiFi, (m/s^2) N.
    pub hypervolume_on_hifi: f64,
    /// `hypervolume_on_hifi` over the HiFi front's hypervolume, -.
    pub hypervolume_ratio: f64,
    /// The plane pick's HiFi criteria against the HiFi pick's,
    /// `100 (c_plane / c_hifi - 1)` of `[bacc, dtl, sws]`, %.
    pub pick_gap_percent: [f64; 3],
}

/// The HiFi front of `s` and `plane` (the plane model's front, `plane_model` its name,
/// `plane_runs` the HiFi runs behind it) judged against it. `grid_values`: the HiFi
/// criteria of STM's `STM_GRID x STM_GRID` starting grid computed on the GPU (row-major,
/// Cs rows; the GPU route, within 1e-4 of the CPU HiFi), or `None` to run STM wholly on
/// the CPU HiFi. The GPU computes the unweighted BAcc: values with Wk comfort are an
/// error naming `comfort`, and a wrong length one naming `values`.
pub fn hifi_front(
    s: &Scenario,
    plane: &FrontResult,
    plane_model: &str,
    plane_runs: usize,
    grid_values: Option<&[Criteria]>,
) -> Result<HifiFrontView> {
    let (front, hifi_runs, compute) =
        match grid_values {
            None => {
                let hifi = s.evaluator(ModelKind::Full)?;
                let counted = Counted::new(&*hifi);
                let front = studies::front(s, "stm", &counted)?;
                (front, counted.count(), ComputePath::Cpu)
            }
            Some(_) if s.comfort != Comfort::Bacc => return Err(RideError::field(
                "comfort",
                "wk: the GPU path computes the unweighted BAcc; the Wk HiFi front runs on the CPU",
            )),
            Some(values) => {
                let n = studies::STM_GRID;
                let grid = Grid::over_box(&s.dbox, n, n)?;
                if values.len() != grid.len() {
                    return Err(RideError::field(
                        "values",
                        format!(
                            "{} designs for STM's {n} x {n} grid, got {}",
                            grid.len(),
                            values.len()
                        ),
                    ));
                }
                let hifi = HiFi::new(&s.datum, &s.road)?;
                let on_grid = HiFiGrid::from_values(hifi, grid, values.to_vec(), ComputePath::Gpu);
                let counted = Counted::new(&on_grid);
                let front = studies::front(s, "stm", &counted)?;
                // The grid's designs ran on the GPU; the count saw them as answers from it.
                (front, counted.count(), ComputePath::Gpu)
            }
        };
    let full = s.evaluator(ModelKind::Full)?;
    let ctx = DosContext::new(&s.datum, front.datum);
    let plane = plane_check(&front, plane, plane_model, plane_runs, |ks, cs| {
        let c = full.evaluate(ks, cs)?;
        Ok((s.objectives.violation(&ctx, ks, cs, &c) <= HIFI_FEASIBILITY_TOLERANCE).then_some(c))
    })?;
    Ok(HifiFrontView {
        front,
        hifi_runs,
        compute,
        plane,
    })
}

/// The robust HiFi front of `s`'s cases `set` (STM on every case's full car, the robust
/// objective and DOS of `ridelab optimize --cases --evaluator full`) and the plane's
/// LoFi robust front `plane` judged against it: each of its designs re-run on every
/// case's HiFi, combined as the HiFi front combines them, and kept where it meets the
/// objectives in every case (to [`HIFI_FEASIBILITY_TOLERANCE`]). HiFi runs: the HiFi
/// front's `evaluations` (designs x cases) and its cases' datums; the plane's, its cases'
/// HiFi datums (its normalisation) and its pick's re-check in every case.
pub(crate) fn robust_hifi_front(
    s: &Scenario,
    set: &CaseSet,
    plane: &FrontResult,
) -> Result<HifiFrontView> {
    let front = studies::robust_front(s, set, "stm", ModelKind::Full)?;
    let n = set.cases.len();
    let hifi_runs = front.study.evaluations + n;
    // The cases' HiFis and their datums: the robust objective the HiFi front optimises.
    let hifis = case_hifis(set, s.comfort)?;
    let datums = datums_on(set, &hifis)?;
    let combination = Combination::new(set.combine, &datums, &set.probabilities())?;
    let ctxs = case_contexts(set, &datums);
    let plane = plane_check(&front, plane, "robust", 2 * n, |ks, cs| {
        let per = hifis
            .iter()
            .map(|h| h.evaluate(ks, cs))
            .collect::<Result<Vec<_>>>()?;
        let g = robust_constraints(&s.objectives, &ctxs, ks, cs, &per);
        let violation: f64 = g.iter().map(|(_, v)| v.max(0.0)).sum();
        Ok((violation <= HIFI_FEASIBILITY_TOLERANCE).then(|| combination.apply(&per)))
    })?;
    Ok(HifiFrontView {
        front,
        hifi_runs,
        compute: ComputePath::Cpu,
        plane,
    })
}

/// `plane` judged on the HiFi against `hifi` (see [`PlaneCheck`]); `on_hifi(ks, cs)`: a
/// design's HiFi criteria where it meets the objectives there, else `None`.
fn plane_check(
    hifi: &FrontResult,
    plane: &FrontResult,
    model: &str,
    plane_runs: usize,
    on_hifi: impl Fn(f64, f64) -> Result<Option<Criteria>>,
) -> Result<PlaneCheck> {
    let reference = hifi.study.reference_point;
    let predicted: Vec<[f64; 2]> = plane.study.front.iter().map(|p| [p.bacc, p.dtl]).collect();
    let mut kept = Vec::new();
    for p in &plane.study.front {
        if let Some(c) = on_hifi(p.ks, p.cs)? {
            kept.push([c.bacc, c.dtl]);
        }
    }
    let on_hifi = kept;
    let hv_on_hifi = hypervolume(&on_hifi, reference);
    let (a, b) = (
        plane.recheck.rechecked.to_array(),
        hifi.study.pick.criteria.to_array(),
    );
    Ok(PlaneCheck {
        model: model.to_string(),
        hifi_runs: plane_runs,
        front_points: plane.study.front.len(),
        hifi_feasible_points: on_hifi.len(),
        hypervolume: hypervolume(&predicted, reference),
        hypervolume_on_hifi: hv_on_hifi,
        hypervolume_ratio: hv_on_hifi / hifi.study.hypervolume,
        pick_gap_percent: std::array::from_fn(|k| 100.0 * (a[k] / b[k] - 1.0)),
    })
}
