//! The explorer's surrogate: the tuned LoFi of the state's approach and plan, fitted to
//! HiFi samples over the state's design box.
//!
//! The page asks for the surrogate's readout, maps and front in separate calls; each
//! would refit (HiFi samples plus a Levenberg-Marquardt or RBF fit, a few ms). So the
//! last fit is kept per thread, keyed by everything it depends on: car, road, design box,
//! approach, scheme and plan. The key leaves out the design point and the objectives,
//! so dragging a slider or the SWS limit reuses the fit.

use super::state::Scenario;
use crate::car::Car;
use crate::design::DesignBox;
use crate::error::Result;
use crate::road::Road;
use crate::surrogate::{
    sample_plan, surrogate_report_in, LmOptions, PlanSpec, Sample, Setting, Surrogate,
    SurrogateReport, SurrogateSpec,
};
use std::cell::RefCell;
use std::rc::Rc;

/// A fitted surrogate with the samples it was fitted to.
pub struct FittedSurrogate {
    /// The fitted model (an [`Evaluator`]).
    pub model: Box<dyn Surrogate>,
    /// The plan.
    pub plan: PlanSpec,
    /// The HiFi samples at the plan's points.
    pub samples: Vec<Sample>,
}

/// Everything a fit depends on (and a map's values: the objectives only judge them).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct FitKey {
    car: Car,
    road: Road,
    dbox: DesignBox,
    spec: SurrogateSpec,
    plan: PlanSpec,
}

impl FitKey {
    pub(crate) fn of(s: &Scenario) -> FitKey {
        FitKey {
            car: s.datum.clone(),
            road: s.road,
            dbox: s.dbox,
            spec: s.surrogate,
            plan: s.plan,
        }
    }
}

thread_local! {
    static LAST_FIT: RefCell<Option<(FitKey, Rc<FittedSurrogate>)>> = const { RefCell::new(None) };
}

/// Fits the scenario's surrogate, or returns the last fit when nothing it depends on
/// has changed. Errors name `approach` or `plan`.
pub fn fitted(s: &Scenario) -> Result<Rc<FittedSurrogate>> {
    let key = FitKey::of(s);
    if let Some(hit) = LAST_FIT.with_borrow(|last| {
        last.as_ref()
            .filter(|(k, _)| *k == key)
            .map(|(_, f)| Rc::clone(f))
    }) {
        return Ok(hit);
    }
    let setting = Setting::new(&s.datum, &s.road, &s.dbox)?;
    let hifi = s.hifi()?;
    let samples = sample_plan(&hifi, &s.plan.plan()?, &s.dbox)?;
    let model = s.surrogate.fit(&setting, &samples, &LmOptions::default())?;
    let fit = Rc::new(FittedSurrogate {
        model,
        plan: s.plan,
        samples,
    });
    LAST_FIT.with_borrow_mut(|last| *last = Some((key, Rc::clone(&fit))));
    Ok(fit)
}

/// The surrogate's fit report over the scenario's design box: samples, tuning,
/// diagnostics and metrics on a `levels x levels` HiFi validation grid (the same report
/// as `ridelab surrogate`; refits, so it runs where the HiFi validation runs).
pub fn fit_report(s: &Scenario, levels: usize) -> Result<SurrogateReport> {
    surrogate_report_in(
        s.surrogate,
        s.plan,
        &s.datum,
        &s.road,
        &s.dbox,
        Some(levels),
    )
}
