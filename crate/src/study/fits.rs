//! A study's surrogate fits as methods of [`StudySpec`] (issue #28): one surrogate fitted
//! and validated ([`StudySpec::surrogate`], `ridelab surrogate`), the fidelity study over
//! every approach and plan ([`StudySpec::fidelity`], `ridelab study`) and the adaptive
//! study of one surrogate ([`StudySpec::adaptive_study`], `ridelab study --adaptive`).
//! Each runs in the study's setting, an ISO class or a measured road: the HiFi samples
//! and the validation grid are the full car there, the surrogates' LoFi the quarter car
//! there, over the study's design box, judged (where designs are judged) by its
//! objectives. A fit is of one scenario: the study's cases are refused naming `cases`.

use super::adaptive::{
    adaptive_study, adaptive_study_on, AdaptiveOptions, AdaptiveStudy, StudyOptions,
};
use super::fidelity::{study, study_on, StudyReport, SurrogateReport};
use super::spec::{MeasuredSource, StudyRoad, StudySpec};
use super::surrogate::SurrogateRequest;
use crate::analysis::ModelKind;
use crate::budget::check_measured;
use crate::error::{Result, RideError};
use crate::road_profile::{MeasuredModel, RoadScenario};
use crate::surrogate::{PlanSpec, Setting, SurrogateSpec, VALIDATION_LEVELS};

impl StudySpec {
    /// `spec` fitted to the HiFi at `plan`'s points over the study's box (with
    /// `adaptive`, that many more HiFi runs placed one at a time, judged by the study's
    /// objectives) and validated on a `predict_grid` x `predict_grid` HiFi grid (default
    /// 20 x 20). On a measured road the HiFi runs (the plan, the loop's and the
    /// validation grid) are bounded by [`crate::budget::MAX_MEASURED_RUNS`], naming `plan`.
    pub fn surrogate(
        &self,
        spec: SurrogateSpec,
        plan: PlanSpec,
        predict_grid: Option<usize>,
        adaptive: Option<AdaptiveOptions>,
    ) -> Result<SurrogateReport> {
        self.one_case()?;
        let request = SurrogateRequest {
            design_box: self.design_box,
            predict_grid,
            adaptive,
            objectives: self.objectives.clone(),
            ..SurrogateRequest::new(spec, plan)
        };
        let m = match &self.road {
            StudyRoad::Iso(road) => return request.report(&self.car, road),
            StudyRoad::Measured(m) => m,
        };
        let levels = predict_grid.unwrap_or(VALIDATION_LEVELS) as u64;
        check_measured(
            plan.plan()?.points(&self.design_box).len() as u64
                + adaptive.map_or(0, |o| o.runs as u64)
                + levels * levels,
            "plan",
            "the plan, the adaptive runs and the validation grid",
            "the plan's size, --adaptive or --predict",
        )?;
        let (setting, hifi) = self.measured_setting(m)?;
        let mut r = request.report_on(&self.car, &setting, hifi)?;
        r.road = RoadScenario::Measured(m.about());
        Ok(r)
    }

    /// The fidelity study in the study's box: every approach and scheme at every plan,
    /// validated on the 20 x 20 HiFi grid (fixed work: about 3 s on the shipped slab
    /// road).
    pub fn fidelity(&self) -> Result<StudyReport> {
        self.one_case()?;
        match &self.road {
            StudyRoad::Iso(road) => study(&self.car, road, &self.design_box),
            StudyRoad::Measured(m) => {
                let (setting, hifi) = self.measured_setting(m)?;
                study_on(&self.car, &setting, hifi, RoadScenario::Measured(m.about()))
            }
        }
    }

    /// The adaptive study of `spec`: for every total of HiFi runs in `options`, its
    /// Audze-Eglais plan plus adaptive runs against an Audze-Eglais plan of that size,
    /// each front judged on the HiFi; the box and objectives are the study's (those of
    /// `options` are replaced). Bounded as [`adaptive_study_on`] says.
    pub fn adaptive_study(
        &self,
        spec: SurrogateSpec,
        options: &StudyOptions,
    ) -> Result<AdaptiveStudy> {
        self.one_case()?;
        let options = StudyOptions {
            design_box: self.design_box,
            objectives: self.objectives.clone(),
            ..options.clone()
        };
        match &self.road {
            StudyRoad::Iso(road) => adaptive_study(&self.car, road, spec, &options),
            StudyRoad::Measured(m) => {
                let (setting, hifi) = self.measured_setting(m)?;
                let about = RoadScenario::Measured(m.about());
                adaptive_study_on(&self.car, &setting, &hifi, about, spec, &options)
            }
        }
    }

    /// The surrogates' setting on the measured road `m` over the study's box, and the
    /// full car there.
    fn measured_setting(&self, m: &MeasuredSource) -> Result<(Setting, MeasuredModel)> {
        Ok((
            Setting::measured(&self.car, m.shaped.clone(), &self.design_box)?,
            MeasuredModel::new(ModelKind::Full, &self.car, m.shaped.clone()),
        ))
    }

    /// A fit is of one scenario: the study's cases are refused naming `cases`.
    fn one_case(&self) -> Result<()> {
        match self.cases {
            None => Ok(()),
            Some(_) => Err(RideError::field(
                "cases",
                "a surrogate is fitted on one scenario: the robust cases take map and optimize",
            )),
        }
    }
}
