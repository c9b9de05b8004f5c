//! The study report as a method of the study (issue #28): [`StudySpec::report`] builds it
//! on the study's road, an ISO class ([`build`]) or a measured profile ([`build_on`]),
//! with the study's car, box and objectives. The method lives here, beside the report,
//! because the report is built on the study layer (`crate::study` never imports
//! `crate::report`).

use super::{build, build_on, MethodReport, ReportInputs};
use crate::error::{Result, RideError};
use crate::road::Road;
use crate::study::{StudyRoad, StudySpec};
use crate::surrogate::{PlanSpec, SurrogateSpec};

impl StudySpec {
    /// The study report of the study's car on its road over its box with its objectives:
    /// `surrogate` the surrogate and plan of sections 4 and 5 (`None`: the fidelity
    /// study's best at 10 HiFi samples), `seed` that of the time-domain record and of
    /// NSGA-II; `progress(k)` is called as section `k` starts ([`super::SECTIONS`]). The
    /// report is of one scenario: the study's cases are refused naming `cases`.
    pub fn report(
        &self,
        surrogate: Option<(SurrogateSpec, PlanSpec)>,
        seed: u64,
        progress: impl FnMut(usize),
    ) -> Result<MethodReport> {
        if self.cases.is_some() {
            return Err(RideError::field(
                "cases",
                "the report is of one scenario: the robust cases take map and optimize",
            ));
        }
        let inputs = |road: Road| ReportInputs {
            design_box: self.design_box,
            objectives: self.objectives.clone(),
            surrogate,
            seed,
            ..ReportInputs::new(self.car.clone(), road)
        };
        match &self.road {
            StudyRoad::Iso(road) => build(&inputs(*road), progress),
            StudyRoad::Measured(m) => {
                // The measured road's speed; its class is not read.
                let road = Road {
                    speed: m.shaped.speed,
                    ..Road::default()
                };
                build_on(&inputs(road), m, progress)
            }
        }
    }
}
