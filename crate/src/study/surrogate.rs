//! `ridelab surrogate`'s request: one surrogate fitted to HiFi samples over a design box
//! (its plan, then adaptive runs when asked) and validated on a HiFi grid, on an ISO class
//! or, with the caller's setting and HiFi, on a measured road.

use super::adaptive::{run, AdaptiveOptions, Decision};
use super::fidelity::{surrogate_report_on, Fitted, SurrogateReport};
use crate::analysis::HiFi;
use crate::car::Car;
use crate::design::DesignBox;
use crate::dos::DesignObjectives;
use crate::error::Result;
use crate::evaluate::Evaluator;
use crate::optimize::Counted;
use crate::road::Road;
use crate::surrogate::{PlanSpec, Setting, SurrogateSpec};

/// What one surrogate fit is asked with.
#[derive(Debug, Clone, PartialEq)]
pub struct SurrogateRequest {
    /// The approach and scheme.
    pub spec: SurrogateSpec,
    /// The HiFi sampling plan (the adaptive loop's initial plan).
    pub plan: PlanSpec,
    /// The design box the plan, the normalisation and the validation grid span.
    pub design_box: DesignBox,
    /// Validate on a `grid:N` HiFi grid instead of the 20 x 20 one and list the
    /// predictions there.
    pub predict_grid: Option<usize>,
    /// The adaptive loop after the plan; `None`: the plan alone.
    pub adaptive: Option<AdaptiveOptions>,
    /// What the loop's fronts and its probability of feasibility judge designs by (the
    /// SWS limit among them); a plain fit judges no designs.
    pub objectives: DesignObjectives,
}

impl SurrogateRequest {
    /// `spec` on `plan` over the default box, validated on the 20 x 20 grid, no adaptive
    /// runs, the default objectives.
    pub fn new(spec: SurrogateSpec, plan: PlanSpec) -> SurrogateRequest {
        SurrogateRequest {
            spec,
            plan,
            design_box: DesignBox::default(),
            predict_grid: None,
            adaptive: None,
            objectives: DesignObjectives::default(),
        }
    }

    /// `approach` (e.g. `vba-qts`) on `plan` (e.g. `ae:10`) as `ridelab surrogate` names
    /// them, with [`Self::new`]'s defaults; errors name `approach` or `plan`.
    pub fn parse(approach: &str, plan: &str) -> Result<SurrogateRequest> {
        Ok(SurrogateRequest::new(
            SurrogateSpec::parse(approach)?,
            PlanSpec::parse(plan)?,
        ))
    }

    /// The report of `car` on the ISO `road` (the HiFi the full car there). Errors name
    /// the request's field at fault (`plan`, `predict-grid`, the loop's fields, an
    /// objective).
    pub fn report(&self, car: &Car, road: &Road) -> Result<SurrogateReport> {
        let setting = Setting::new(car, road, &self.design_box)?;
        self.report_on(car, &setting, HiFi::new(car, road)?)
    }

    /// The report in `setting` (an ISO class or a measured road, [`Setting::measured`],
    /// over the request's box) with `hifi` the full car of `car` there: the one
    /// evaluator of the plan, the loop's runs, the datum and the validation grid. The
    /// report's `road` is the setting's ISO road, which the caller replaces for a
    /// measured one.
    ///
    /// With adaptive runs: the loop judged by the request's objectives against the
    /// datum's HiFi criteria (default STM), then the final surrogate's report as a plain
    /// plan gives it, with the loop's report in `adaptive`.
    pub fn report_on<E: Evaluator>(
        &self,
        car: &Car,
        setting: &Setting,
        hifi: E,
    ) -> Result<SurrogateReport> {
        let (spec, plan) = (self.spec, self.plan);
        let Some(options) = self.adaptive else {
            return surrogate_report_on(spec, plan, setting, hifi, self.predict_grid);
        };
        self.objectives.validate()?;
        let hifi = Counted::new(hifi);
        let decision = Decision {
            objectives: self.objectives.clone(),
            ..Decision::of_car(car, &hifi)?
        };
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
        fitted.report(setting, &hifi, self.predict_grid)
    }
}
