//! The road a report's sections run on: an ISO 8608 class ([`IsoRoad`]) or a measured
//! road ([`super::measured::OnRoad`]). Each section asks it for its models' results, so
//! the sections are written once ([`super::build`] and [`super::build_on`] are the same
//! code on either road), and the page's wasm, which builds ISO reports only, carries the
//! ISO road's code alone.

use super::{verify, Verification};
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

/// What the report's sections need of the road (see the module doc).
pub(super) trait SectionRoad {
    /// The road as the reports record it.
    fn scenario(&self) -> RoadScenario;
    /// The ISO road's velocity PSD, m^2/s^2/Hz (none on a measured road).
    fn velocity_psd(&self) -> Option<f64>;
    /// Section 1 at the datum design of `car`.
    fn verify(&self, car: &Car, seed: u64) -> Result<Verification>;
    /// Section 2: `kind`'s map of `car`.
    fn map(&self, kind: ModelKind, car: &Car, settings: &MapSettings) -> Result<MapReport>;
    /// Section 4: the fidelity study over `design_box`.
    fn study(&self, car: &Car, design_box: &DesignBox) -> Result<StudyReport>;
    /// Section 4: the chosen surrogate's report.
    fn surrogate(
        &self,
        spec: SurrogateSpec,
        plan: PlanSpec,
        car: &Car,
        design_box: &DesignBox,
    ) -> Result<SurrogateReport>;
    /// Section 5: one optimisation (the request's road is this one).
    fn optimize(&self, request: &OptimizeRequest) -> Result<OptimizeReport>;
    /// Section 5: the full car of `car` on this road.
    fn hifi(&self, car: &Car) -> Result<Box<dyn Evaluator + '_>>;
    /// Section 5: `r` picked again by `rule`, re-checked on the HiFi.
    fn repick(
        &self,
        r: &mut OptimizeReport,
        rule: PickRule,
        car: &Car,
        design_box: &DesignBox,
    ) -> Result<()>;
    /// Section 6: the adaptive loop's optimisation.
    fn adaptive(
        &self,
        request: &OptimizeRequest,
        options: AdaptiveOptions,
    ) -> Result<AdaptiveOptimizeReport>;
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
