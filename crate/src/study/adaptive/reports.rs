//! The CLI's reports of the adaptive loop: `ridelab surrogate ... --adaptive K` and
//! `ridelab optimize --evaluator SURROGATE ... --adaptive K`.

use super::{run, AdaptiveOptions, AdaptiveReport, Decision};
use crate::analysis::HiFi;
use crate::car::Car;
use crate::design::DesignBox;
use crate::error::{Result, RideError};
use crate::evaluate::Evaluator;
use crate::optimize::Counted;
use crate::road::Road;
use crate::study::fidelity::{Fitted, SurrogateReport};
use crate::study::{optimize_model, EvaluatorSpec, OptimizeReport, OptimizeRequest};
use crate::surrogate::{PlanSpec, Setting, SurrogateSpec};
use serde::Serialize;

/// `ridelab surrogate --plan PLAN --adaptive K`: the loop on `car` and `road` over
/// `design_box` (default objectives, the datum's HiFi criteria, default STM), then the
/// final surrogate's report as [`super::surrogate_report_in`] gives it for a plain plan,
/// with the loop's report in `adaptive`. Errors name the loop's fields, `plan` or
/// `predict-grid`.
pub fn surrogate_report(
    spec: SurrogateSpec,
    plan: PlanSpec,
    car: &Car,
    road: &Road,
    design_box: &DesignBox,
    predict_grid: Option<usize>,
    options: AdaptiveOptions,
) -> Result<SurrogateReport> {
    let setting = Setting::new(car, road, design_box)?;
    surrogate_report_on(
        spec,
        plan,
        car,
        &setting,
        HiFi::new(car, road)?,
        predict_grid,
        options,
    )
}

/// [`surrogate_report`] on `setting` (an ISO class or a measured road: its LoFi and box)
/// with `hifi` the full car of `car` there (the one evaluator of the plan, the loop's
/// runs, the datum and the validation grid).
pub fn surrogate_report_on<E: Evaluator>(
    spec: SurrogateSpec,
    plan: PlanSpec,
    car: &Car,
    setting: &Setting,
    hifi: E,
    predict_grid: Option<usize>,
    options: AdaptiveOptions,
) -> Result<SurrogateReport> {
    let hifi = Counted::new(hifi);
    let decision = Decision::of_car(car, &hifi)?;
    let state = run(spec, setting, &hifi, plan, &decision, options)?;
    let report = state.report();
    let samples = state.samples().to_vec();
    let model = state.into_model();
    let fitted = Fitted {
        spec,
        plan: format!(
            "{} + {} adaptive ({})",
            plan.name(),
            options.runs,
            options.criterion.name()
        ),
        plan_method: format!(
            "{}, then {} HiFi runs by {} on the {} uncertainty",
            plan.plan()?.method,
            options.runs,
            options.criterion.name(),
            report.uncertainty.name()
        ),
        samples,
        model: &*model,
        options: options.lm(),
        adaptive: Some(report),
    };
    fitted.report(setting, &hifi, predict_grid)
}

/// `ridelab optimize` with an adaptive surrogate: the optimisation report with the loop's
/// report beside it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AdaptiveOptimizeReport {
    /// Front, pick and HiFi re-check, as `ridelab optimize` gives them.
    #[serde(flatten)]
    pub optimize: OptimizeReport,
    /// The loop that chose the surrogate's samples.
    pub adaptive: AdaptiveReport,
}

/// `ridelab optimize --evaluator SURROGATE --plan PLAN --adaptive K`: the loop judged by the
/// request's objectives (against the datum's HiFi criteria) and, for STM, its STM settings
/// ([`Decision::for_method`]), then [`optimize_model`] on its final surrogate (the
/// request's comfort, compute and pick are the caller's: the loop is fitted to the
/// unweighted BAcc on the CPU, the pick is min-max). Errors name `adaptive` for a model
/// evaluator (the loop refits a surrogate), and the loop's fields.
pub fn optimize_report(
    request: &OptimizeRequest,
    options: AdaptiveOptions,
) -> Result<AdaptiveOptimizeReport> {
    let OptimizeRequest {
        car,
        road,
        design_box,
        method,
        objectives,
        ..
    } = request;
    let EvaluatorSpec::Surrogate(spec) = request.evaluator else {
        return Err(RideError::field(
            "adaptive",
            "the adaptive loop refits a surrogate; give a surrogate --evaluator",
        ));
    };
    objectives.validate()?;
    let setting = Setting::new(car, road, design_box)?;
    let hifi = HiFi::new(car, road)?;
    let decision = Decision::for_method(car, &hifi, method, objectives.clone())?;
    let state = run(spec, &setting, &hifi, request.plan, &decision, options)?;
    let adaptive = state.report();
    let model: Box<dyn Evaluator + Sync> = Box::new(state.into_model());
    Ok(AdaptiveOptimizeReport {
        optimize: optimize_model(car, road, design_box, model, method, objectives.clone())?,
        adaptive,
    })
}
