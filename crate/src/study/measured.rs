//! Optimisations on a measured road: `ridelab optimize --road FILE` and the report's
//! sections 5 and 6 on one. The front's model is the quarter or the full car on the road
//! (the exact routes with its shaping filters, [`MeasuredModel`]) or a surrogate fitted to
//! the full car's samples there (its LoFi the quarter car there), or with the adaptive
//! loop's options that loop's final surrogate; the datum and the pick's re-check are the
//! full car on the road. The maps on a measured road ([`measured_map`]) are here too.

use super::adaptive::{run, AdaptiveOptions, AdaptiveReport, Decision};
use super::map::{MapReport, MapRequest, WK_SURROGATE_MAP};
use super::{optimize_on_models, EvaluatorSpec, OptimizeReport, OptimizeRequest};
use crate::analysis::ModelKind;
use crate::comfort::Comfort;
use crate::error::{Result, RideError};
use crate::evaluate::Evaluator;
use crate::gpu::ComputePath;
use crate::road_profile::{MeasuredModel, MeasuredRoad, ProfileTracks, RoadScenario, ShapedRoad};
use crate::surrogate::{sample_plan, Guarded, LmOptions, PlanSpec, Setting, SurrogateSpec};

/// What an optimisation on a measured road refuses, naming the field: the adaptive loop
/// with a model evaluator (it refits a surrogate), and a surrogate with the Wk-weighted
/// comfort (the surrogates are fitted to the unweighted BAcc).
pub(crate) fn check_measured_request(
    evaluator: EvaluatorSpec,
    comfort: Comfort,
    adaptive: bool,
) -> Result<()> {
    match (evaluator, comfort, adaptive) {
        (EvaluatorSpec::Surrogate(_), Comfort::Wk, _) => Err(RideError::field(
            "comfort",
            "wk needs --evaluator quarter or full: the surrogates are fitted to the unweighted BAcc",
        )),
        (EvaluatorSpec::Model(_), _, true) => Err(RideError::field(
            "adaptive",
            "the adaptive loop refits a surrogate; give a surrogate --evaluator",
        )),
        _ => Ok(()),
    }
}

/// The optimisation `request` asks for on the road of `hifi` (the full car of
/// `request.car` there, with the request's comfort measure; `request.road` is not used),
/// with `options` through the adaptive loop (its fronts the request's objectives and STM
/// settings, [`Decision::for_method`]); the loop's report beside it. The request's
/// compute and pick are the caller's (the pick is min-max).
pub(crate) fn optimize_measured(
    request: &OptimizeRequest,
    hifi: &MeasuredModel,
    options: Option<AdaptiveOptions>,
) -> Result<(OptimizeReport, Option<AdaptiveReport>)> {
    let OptimizeRequest {
        car,
        design_box,
        method,
        objectives,
        comfort,
        ..
    } = request;
    check_measured_request(request.evaluator, *comfort, options.is_some())?;
    let mut looped = None;
    let model: Box<dyn Evaluator + Sync> = match request.evaluator {
        EvaluatorSpec::Model(ModelKind::Full) => Box::new(hifi.clone()),
        EvaluatorSpec::Model(ModelKind::Quarter) => Box::new(
            MeasuredModel::new(ModelKind::Quarter, car, hifi.road().clone()).with_comfort(*comfort),
        ),
        EvaluatorSpec::Surrogate(spec) => {
            let setting = Setting::measured(car, hifi.road().clone(), design_box)?;
            match options {
                None => Box::new(fit_on(spec, &setting, hifi, request.plan)?),
                Some(options) => {
                    let decision = Decision::for_method(car, hifi, method, objectives.clone())?;
                    let state = run(spec, &setting, hifi, request.plan, &decision, options)?;
                    looped = Some(state.report());
                    Box::new(state.into_model())
                }
            }
        }
    };
    let out = optimize_on_models(
        car,
        design_box,
        model,
        hifi,
        method,
        objectives.clone(),
        *comfort,
    )?;
    Ok((out, looped))
}

/// The map `request` asks for (its model, plan, car and settings; its ISO road and compute
/// are not read) on the shaped measured road `road` (shaped from the profile `file` with
/// `tracks`), as `ridelab map --road FILE` prints it and the page's road panel draws it:
/// the quarter or full car by the exact routes of [`MeasuredModel`] (with the settings'
/// comfort in the comfort slot), or a surrogate fitted there to the full car at the plan's
/// points over the grid's box (its LoFi the quarter car there; the Wk-weighted comfort is
/// refused naming `comfort`), over the request's [`MapRequest::surrogate_box`]. The datum is the car's own front design, the report's `road`
/// the measured one and its compute path the CPU. The caller bounds the grid
/// ([`crate::budget::check_measured`], naming its own option).
pub(crate) fn measured_map(
    request: &MapRequest,
    road: &ShapedRoad,
    file: &str,
    tracks: ProfileTracks,
) -> Result<MapReport> {
    let (car, settings) = (request.car, &request.settings);
    let model: Box<dyn Evaluator + Sync> = match request.model {
        EvaluatorSpec::Model(kind) => {
            Box::new(MeasuredModel::new(kind, car, road.clone()).with_comfort(settings.comfort))
        }
        EvaluatorSpec::Surrogate(spec) => {
            if settings.comfort == Comfort::Wk {
                return Err(RideError::field("comfort", WK_SURROGATE_MAP));
            }
            settings.validate()?;
            let design_box = request.surrogate_box()?;
            let hifi = MeasuredModel::new(ModelKind::Full, car, road.clone());
            let setting = Setting::measured(car, road.clone(), &design_box)?;
            Box::new(fit_on(spec, &setting, &hifi, request.plan)?)
        }
    };
    let mut r = request.run_on(&*model)?;
    r.road = RoadScenario::Measured(MeasuredRoad::of(file, road, tracks));
    r.compute = ComputePath::Cpu;
    Ok(r)
}

/// `spec` fitted in `setting` (on the measured road) to `hifi`'s samples at `plan`'s
/// points over the setting's box: the fit of a front's and of a map's surrogate there.
fn fit_on(
    spec: SurrogateSpec,
    setting: &Setting,
    hifi: &MeasuredModel,
    plan: PlanSpec,
) -> Result<Guarded> {
    let samples = sample_plan(hifi, &plan.plan()?, &setting.design_box)?;
    spec.fit(setting, &samples, &LmOptions::default())
}
