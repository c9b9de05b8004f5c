//! The explorer's surrogate: the tuned LoFi of the state's approach and plan, fitted to
//! HiFi samples over the state's design box.
//!
//! A fit (HiFi samples plus a Levenberg-Marquardt or RBF fit, a few ms) depends on the
//! car, road, design box, approach, scheme and plan ([`FitKey`]), not on the design point
//! or the objectives: the [`super::Session`] keeps it until one of those changes, so
//! dragging a slider or the SWS limit reuses it.

use super::state::Scenario;
use crate::analysis::ModelKind;
use crate::car::Car;
use crate::comfort::Comfort;
use crate::design::DesignBox;
use crate::error::{Result, RideError};
use crate::evaluate::Evaluator;
use crate::optimize::Counted;
use crate::road::Road;
use crate::robust::CaseSet;
use crate::study::fidelity::Fitted;
use crate::study::SurrogateReport;
use crate::surrogate::{
    sample_plan, Guarded, LmOptions, ModelRecord, PlanSpec, Sample, Setting, SurrogateSpec,
};
use serde::{Deserialize, Serialize};

/// A fitted surrogate with the samples it was fitted to.
pub struct FittedSurrogate {
    /// The fitted model (an [`Evaluator`] and a [`crate::surrogate::Surrogate`]).
    pub model: Guarded,
    /// The plan.
    pub plan: PlanSpec,
    /// How the plan was made (the fit report says so; kept, not searched for again).
    pub plan_method: String,
    /// The HiFi samples at the plan's points.
    pub samples: Vec<Sample>,
}

/// Everything a fit depends on, and a map's values: the objectives only judge them; the
/// comfort measure fills the LoFi and HiFi maps' BAcc plane (a fit does not depend on it,
/// but a session keeps its fit and maps together); the robust cases fill the LoFi and
/// HiFi maps.
#[derive(Debug, Clone, PartialEq)]
pub struct FitKey {
    car: Car,
    /// The ISO road (`None` on a measured road: its key holds the speed and tracks).
    road: Option<Road>,
    dbox: DesignBox,
    spec: SurrogateSpec,
    plan: PlanSpec,
    comfort: Comfort,
    cases: Option<CaseSet>,
    /// The measured road's key (`None`: the ISO class).
    measured: Option<String>,
}

impl FitKey {
    /// The key of a scenario.
    pub fn of(s: &Scenario) -> FitKey {
        FitKey {
            car: s.datum.clone(),
            road: iso_road(s),
            dbox: s.dbox,
            spec: s.surrogate,
            plan: s.plan,
            comfort: s.comfort,
            cases: s.cases.clone(),
            measured: measured_key(s),
        }
    }
}

/// What a fit depends on ([`fit`]'s inputs): the datum car, road, design box, approach
/// and plan; a record carries them as bytes, compared with the adopting scenario's.
#[derive(Serialize)]
struct FitInputs {
    car: Car,
    road: Option<Road>,
    dbox: DesignBox,
    spec: SurrogateSpec,
    plan: PlanSpec,
    measured: Option<String>,
}

/// The scenario's ISO road, `None` on a measured road (the class under it is not used).
fn iso_road(s: &Scenario) -> Option<Road> {
    s.measured.is_none().then_some(s.road)
}

/// The key of the scenario's measured road (`None` on an ISO class).
fn measured_key(s: &Scenario) -> Option<String> {
    s.measured.as_ref().map(|m| m.0.key().to_string())
}

/// The surrogate's setting for scenario `s` (on its measured road if it has one) and the
/// HiFi it is fitted to (the full car there, unweighted BAcc).
fn setting_and_hifi(s: &Scenario) -> Result<(Setting, Box<dyn Evaluator + Sync>)> {
    let setting = match &s.measured {
        Some(m) => m.0.setting(&s.datum, &s.dbox)?,
        None => Setting::new(&s.datum, &s.road, &s.dbox)?,
    };
    Ok((setting, s.evaluator_with(ModelKind::Full, Comfort::Bacc)?))
}

impl FitInputs {
    /// Scenario `s`'s fit inputs as postcard bytes.
    fn bytes(s: &Scenario) -> Result<Vec<u8>> {
        let inputs = FitInputs {
            car: s.datum.clone(),
            road: iso_road(s),
            dbox: s.dbox,
            spec: s.surrogate,
            plan: s.plan,
            measured: measured_key(s),
        };
        postcard::to_allocvec(&inputs).map_err(|e| RideError::field("fit", e.to_string()))
    }
}

/// A fit as data, with the inputs it was made from: a session that fitted hands it to
/// another ([`super::Session::fit_record`], [`super::Session::offer_fit`]), which adopts
/// it for a scenario with the same inputs instead of fitting again. The page's main
/// thread fits once per scenario change and its background worker adopts that fit.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct FitRecord {
    /// [`FitInputs::bytes`] of the scenario fitted.
    inputs: Vec<u8>,
    plan_method: String,
    samples: Vec<Sample>,
    model: ModelRecord,
}

impl FittedSurrogate {
    /// This fit of scenario `s` as data; `None` when its model has no record (a measured
    /// road's LoFi).
    pub fn record(&self, s: &Scenario) -> Result<Option<FitRecord>> {
        let Some(model) = self.model.record() else {
            return Ok(None);
        };
        Ok(Some(FitRecord {
            inputs: FitInputs::bytes(s)?,
            plan_method: self.plan_method.clone(),
            samples: self.samples.clone(),
            model,
        }))
    }
}

impl FitRecord {
    /// The record as postcard bytes.
    pub fn to_bytes(&self) -> Result<Vec<u8>> {
        postcard::to_allocvec(self).map_err(|e| RideError::field("fit", e.to_string()))
    }

    /// A record from [`FitRecord::to_bytes`]; errors name `fit`.
    pub fn from_bytes(bytes: &[u8]) -> Result<FitRecord> {
        postcard::from_bytes(bytes)
            .map_err(|e| RideError::field("fit", format!("not a fit record ({e})")))
    }

    /// The fit again, if it was made from scenario `s`'s inputs (else `None`): the same
    /// samples and a model with the same predictions, bit for bit.
    pub(crate) fn adopt(&self, s: &Scenario) -> Option<FittedSurrogate> {
        let same = FitInputs::bytes(s).is_ok_and(|b| b == self.inputs);
        same.then(|| FittedSurrogate {
            model: Guarded::new(self.model.clone(), s.dbox),
            plan: s.plan,
            plan_method: self.plan_method.clone(),
            samples: self.samples.clone(),
        })
    }
}

/// Fits the scenario's surrogate to HiFi samples at its plan. Errors name `approach` or `plan`.
pub fn fit(s: &Scenario) -> Result<FittedSurrogate> {
    let (setting, hifi) = setting_and_hifi(s)?;
    let plan = s.plan.plan()?;
    let samples = sample_plan(&hifi, &plan, &s.dbox)?;
    let model = s.surrogate.fit(&setting, &samples, &LmOptions::default())?;
    Ok(FittedSurrogate {
        model,
        plan: s.plan,
        plan_method: plan.method,
        samples,
    })
}

/// The fit report of `fitted` (the scenario's surrogate, fitted by [`fit`]) over the
/// scenario's design box: samples, tuning, diagnostics and metrics on a `levels x levels`
/// HiFi validation grid, the same report as `ridelab surrogate` (whose fit is the same:
/// the same HiFi samples, the same options), without fitting again.
pub fn fit_report(
    s: &Scenario,
    fitted: &FittedSurrogate,
    levels: usize,
) -> Result<SurrogateReport> {
    let (setting, hifi) = setting_and_hifi(s)?;
    let hifi = Counted::with_count(hifi, fitted.samples.len());
    Fitted {
        spec: s.surrogate,
        plan: s.plan.name(),
        plan_method: fitted.plan_method.clone(),
        samples: fitted.samples.clone(),
        model: &fitted.model,
        options: LmOptions::default(),
        adaptive: None,
    }
    .report(&setting, &hifi, Some(levels))
}
