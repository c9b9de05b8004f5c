//! One optimisation of a car on a road, as `ridelab optimize` runs it: the front on the
//! chosen evaluator (LoFi, HiFi or a surrogate fitted to HiFi samples), its min-max
//! pick against the datum and the pick re-checked on the HiFi.
//!
//! The design objectives' "no worse than the datum" and the ratios of the pick compare
//! against the datum car's **HiFi** criteria, whatever the evaluator: the HiFi is the
//! reference every evaluator is judged by.

use super::minmax::{recheck, Recheck};
use super::study::{run_study, Method, Study};
use super::suspension::SuspensionProblem;
use crate::analysis::{HiFi, LoFi, ModelKind};
use crate::car::Car;
use crate::design::DesignBox;
use crate::dos::{DesignObjectives, DosContext};
use crate::error::{Result, RideError};
use crate::evaluate::{Criteria, Evaluator};
use crate::road::Road;
use crate::surrogate::{sample_plan, LmOptions, PlanSpec, Setting, SurrogateSpec};
use serde::Serialize;

/// What a study evaluates: one of the two models, or a surrogate of the HiFi.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum EvaluatorSpec {
    /// The quarter car or the full car.
    Model(ModelKind),
    /// A surrogate fitted to HiFi samples.
    Surrogate(SurrogateSpec),
}

impl std::str::FromStr for EvaluatorSpec {
    type Err = RideError;
    /// "quarter" / "lofi", "full" / "hifi", or a surrogate name (`ridelab surrogate`'s);
    /// errors name `evaluator`.
    fn from_str(s: &str) -> Result<EvaluatorSpec> {
        if let Ok(kind) = ModelKind::parse(s) {
            return Ok(EvaluatorSpec::Model(kind));
        }
        SurrogateSpec::parse(s)
            .map(EvaluatorSpec::Surrogate)
            .map_err(|e| match e {
                RideError::Field { reason, .. } => RideError::field(
                    "evaluator",
                    format!("'{s}' is not quarter, full or a surrogate: {reason}"),
                ),
                other => other,
            })
    }
}

impl EvaluatorSpec {
    /// The evaluator for `car` on `road` over `design_box`; a surrogate is fitted to the
    /// HiFi at `plan`'s points.
    pub fn build(
        &self,
        car: &Car,
        road: &Road,
        design_box: &DesignBox,
        plan: PlanSpec,
    ) -> Result<Box<dyn Evaluator + Sync>> {
        Ok(match self {
            EvaluatorSpec::Model(ModelKind::Quarter) => Box::new(LoFi::new(car, road)),
            EvaluatorSpec::Model(ModelKind::Full) => Box::new(HiFi::new(car, road)?),
            EvaluatorSpec::Surrogate(spec) => {
                let hifi = HiFi::new(car, road)?;
                let samples = sample_plan(&hifi, &plan.plan()?, design_box)?;
                let setting = Setting::new(car, road, design_box)?;
                Box::new(spec.fit(&setting, &samples, &LmOptions::default())?)
            }
        })
    }
}

/// The study, the datum's HiFi criteria and the pick's HiFi re-check (the JSON of
/// `ridelab optimize`: the study's fields at the top level).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct OptimizeReport {
    /// The front, its hypervolume, the pick and the evaluations.
    #[serde(flatten)]
    pub study: Study,
    /// The datum car's HiFi criteria.
    pub datum: Criteria,
    /// The pick re-evaluated on the HiFi.
    pub hifi_recheck: Recheck,
}

/// Optimises `car`'s front spring and damper on `road` over `design_box` by `method` on
/// `evaluator` (a surrogate fitted at `plan`) under `objectives`.
pub fn optimize_report(
    car: &Car,
    road: &Road,
    design_box: &DesignBox,
    evaluator: EvaluatorSpec,
    plan: PlanSpec,
    method: &Method,
    objectives: DesignObjectives,
) -> Result<OptimizeReport> {
    objectives.validate()?;
    let hifi = HiFi::new(car, road)?;
    let datum = hifi.evaluate(car.front.spring, car.front.damper)?;
    let model = evaluator.build(car, road, design_box, plan)?;
    let problem =
        SuspensionProblem::new(model, *design_box, objectives, DosContext::new(car, datum))?;
    let study = run_study(&problem, method, None)?;
    let hifi_recheck = recheck(&study.pick, &hifi, &datum)?;
    Ok(OptimizeReport {
        study,
        datum,
        hifi_recheck,
    })
}
