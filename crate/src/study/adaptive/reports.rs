//! The CLI's report of the adaptive loop in an optimisation: `ridelab optimize
//! --evaluator SURROGATE ... --adaptive K`, [`OptimizeRequest::run_adaptive`]
//! (`ridelab surrogate ... --adaptive K` is [`crate::study::SurrogateRequest`]'s).

use super::{run, AdaptiveOptions, AdaptiveReport, Decision};
use crate::analysis::HiFi;
use crate::comfort::Comfort;
use crate::error::{Result, RideError};
use crate::evaluate::Evaluator;
use crate::study::{optimize_model, EvaluatorSpec, OptimizeReport, OptimizeRequest};
use crate::surrogate::Setting;
use serde::Serialize;

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

impl OptimizeRequest<'_> {
    /// `ridelab optimize --evaluator SURROGATE --plan PLAN --adaptive K`: the loop judged
    /// by the request's objectives (against the datum's HiFi criteria) and, for STM, its
    /// STM settings ([`Decision::for_method`]), then [`optimize_model`] on its final
    /// surrogate (the request's comfort, compute and pick are the caller's: the loop is
    /// fitted to the unweighted BAcc on the CPU, the pick is min-max). Errors name
    /// `adaptive` for a model evaluator (the loop refits a surrogate), and the loop's fields.
    pub fn run_adaptive(&self, options: AdaptiveOptions) -> Result<AdaptiveOptimizeReport> {
        let OptimizeRequest {
            car,
            road,
            design_box,
            method,
            objectives,
            ..
        } = self;
        let EvaluatorSpec::Surrogate(spec) = self.evaluator else {
            return Err(RideError::field(
                "adaptive",
                "the adaptive loop refits a surrogate; give a surrogate --evaluator",
            ));
        };
        objectives.validate()?;
        let setting = Setting::new(car, road, design_box)?;
        let hifi = HiFi::new(car, road)?;
        let decision = Decision::for_method(car, &hifi, method, objectives.clone())?;
        let state = run(spec, &setting, &hifi, self.plan, &decision, options)?;
        let adaptive = state.report();
        let model: Box<dyn Evaluator + Sync> = Box::new(state.into_model());
        Ok(AdaptiveOptimizeReport {
            optimize: optimize_model(
                car,
                road,
                design_box,
                model,
                method,
                objectives.clone(),
                Comfort::Bacc,
            )?,
            adaptive,
        })
    }
}
