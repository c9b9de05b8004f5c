//! The one model type of a study (issue #28): what a map or a front is drawn on, the
//! quarter car (LoFi), the full car (HiFi) or a surrogate of the full car fitted to HiFi
//! samples at a plan. [`crate::study::MapRequest`] and [`crate::study::OptimizeRequest`]
//! both take it, so `ridelab map --model` and `ridelab optimize --evaluator` name the same
//! models; robust design combines any of them over load cases
//! ([`crate::study::MapRequest::run_robust`]). Beneath it,
//! [`crate::analysis::ModelKind`] is the physical model a criteria route builds.

use crate::analysis::{HiFi, LoFi, ModelKind};
use crate::car::Car;
use crate::design::DesignBox;
use crate::error::{Result, RideError};
use crate::evaluate::Evaluator;
use crate::road::Road;
use crate::surrogate::{sample_plan, LmOptions, PlanSpec, Setting, SurrogateSpec};

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
    /// [`EvaluatorSpec::parse`] with errors naming `evaluator`.
    fn from_str(s: &str) -> Result<EvaluatorSpec> {
        EvaluatorSpec::parse("evaluator", s)
    }
}

impl EvaluatorSpec {
    /// "quarter" / "lofi", "full" / "hifi", or a surrogate name (`ridelab surrogate`'s);
    /// errors name `field` (`evaluator` for `ridelab optimize`, `model` for `ridelab map`).
    pub fn parse(field: &str, s: &str) -> Result<EvaluatorSpec> {
        if let Ok(kind) = ModelKind::parse(s) {
            return Ok(EvaluatorSpec::Model(kind));
        }
        SurrogateSpec::parse(s)
            .map(EvaluatorSpec::Surrogate)
            .map_err(|e| match e {
                RideError::Field { reason, .. } => RideError::field(
                    field,
                    format!("'{s}' is not quarter, full or a surrogate: {reason}"),
                ),
                other => other,
            })
    }

    /// The evaluator for `car` on `road` over `design_box`; a surrogate is fitted to the
    /// HiFi at `plan`'s points.
    pub fn build(
        &self,
        car: &Car,
        road: &Road,
        design_box: &DesignBox,
        plan: PlanSpec,
    ) -> Result<Box<dyn Evaluator + Sync>> {
        match self {
            EvaluatorSpec::Model(ModelKind::Quarter) => Ok(Box::new(LoFi::new(car, road))),
            _ => self.build_on(&HiFi::new(car, road)?, design_box, plan),
        }
    }

    /// [`Self::build`] on a HiFi prepared already (its car and road): the full car is a
    /// copy of it, a surrogate's samples are its evaluations.
    pub(crate) fn build_on(
        &self,
        hifi: &HiFi,
        design_box: &DesignBox,
        plan: PlanSpec,
    ) -> Result<Box<dyn Evaluator + Sync>> {
        let (car, road) = (hifi.car(), hifi.road());
        Ok(match self {
            EvaluatorSpec::Model(ModelKind::Quarter) => Box::new(LoFi::new(car, road)),
            EvaluatorSpec::Model(ModelKind::Full) => Box::new(hifi.clone()),
            EvaluatorSpec::Surrogate(spec) => {
                let samples = sample_plan(hifi, &plan.plan()?, design_box)?;
                let setting = Setting::new(car, road, design_box)?;
                Box::new(spec.fit(&setting, &samples, &LmOptions::default())?)
            }
        })
    }
}

impl From<ModelKind> for EvaluatorSpec {
    fn from(kind: ModelKind) -> EvaluatorSpec {
        EvaluatorSpec::Model(kind)
    }
}
