//! The report on an ISO 8608 class ([`build`]): the road its sections run on, [`IsoRoad`]
//! (the sections need of the road what [`super::SectionRoad`] says; the module
//! [`super::measured`] has the measured road's).

use super::{build_with, verify, MethodReport, ReportInputs, SectionRoad, Verification};
use crate::analysis::{HiFi, ModelKind};
use crate::car::Car;
use crate::design::DesignBox;
use crate::error::Result;
use crate::evaluate::Evaluator;
use crate::optimize::PickRule;
use crate::road::Road;
use crate::road_profile::RoadScenario;
use crate::study::adaptive::{AdaptiveOptimizeReport, AdaptiveOptions};
use crate::study::{study, SurrogateRequest};
use crate::study::{MapReport, MapRequest, MapSettings, OptimizeReport, OptimizeRequest};
use crate::study::{StudyReport, SurrogateReport};
use crate::surrogate::{PlanSpec, SurrogateSpec};

/// Builds the report; `progress(k)` is called as section `k` of
/// [`SECTIONS`](super::SECTIONS) starts and with `SECTIONS.len()` at the end (the CLI times
/// the sections with it).
pub fn build(inputs: &ReportInputs, progress: impl FnMut(usize)) -> Result<MethodReport> {
    build_with(inputs, &IsoRoad(&inputs.road), progress)
}

/// An ISO 8608 road.
pub(super) struct IsoRoad<'a>(pub(super) &'a Road);

impl SectionRoad for IsoRoad<'_> {
    fn scenario(&self) -> RoadScenario {
        RoadScenario::Iso(*self.0)
    }

    fn velocity_psd(&self) -> Option<f64> {
        Some(self.0.velocity_psd())
    }

    fn verify(&self, car: &Car, seed: u64) -> Result<Verification> {
        verify(car, self.0, seed)
    }

    fn map(&self, kind: ModelKind, car: &Car, settings: &MapSettings) -> Result<MapReport> {
        MapRequest::new(kind, car, self.0, settings.clone()).run()
    }

    fn study(&self, car: &Car, design_box: &DesignBox) -> Result<StudyReport> {
        study(car, self.0, design_box)
    }

    fn surrogate(
        &self,
        spec: SurrogateSpec,
        plan: PlanSpec,
        car: &Car,
        design_box: &DesignBox,
    ) -> Result<SurrogateReport> {
        SurrogateRequest {
            design_box: *design_box,
            ..SurrogateRequest::new(spec, plan)
        }
        .report(car, self.0)
    }

    fn optimize(&self, r: &OptimizeRequest) -> Result<OptimizeReport> {
        OptimizeRequest {
            evaluator: r.evaluator,
            plan: r.plan,
            ..OptimizeRequest::new(
                r.car,
                self.0,
                r.design_box,
                r.method.clone(),
                r.objectives.clone(),
            )
        }
        .run_cpu()
    }

    fn hifi(&self, car: &Car) -> Result<Box<dyn Evaluator + '_>> {
        Ok(Box::new(HiFi::new(car, self.0)?))
    }

    fn repick(
        &self,
        r: &mut OptimizeReport,
        rule: PickRule,
        car: &Car,
        design_box: &DesignBox,
    ) -> Result<()> {
        r.repick(rule, car, self.0, design_box)
    }

    fn adaptive(
        &self,
        request: &OptimizeRequest,
        options: AdaptiveOptions,
    ) -> Result<AdaptiveOptimizeReport> {
        request.run_adaptive(options)
    }
}
