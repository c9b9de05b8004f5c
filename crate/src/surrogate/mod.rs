//! Surrogates (METHOD.md section 5): the LoFi quarter car tuned so that it matches HiFi
//! (full car) samples, and the pure data fits it is compared with.
//!
//! Every surrogate is made the same way, egobox/linfa style: a parameter set
//! ([`SurrogateParams`]: [`RbaParams`], [`VbaParams`], [`PbaParams`], [`DataFitParams`], or a
//! parsed [`SurrogateSpec`] that dispatches to them) is checked against the samples, then
//! fitted into a model that implements [`Surrogate`] and so [`Evaluator`]: maps, optimisers
//! and the page take a fitted surrogate like the LoFi or the HiFi ("attach and detach").
//!
//! - **RBA** ([`rba`]): `S = f~(x) tau(x)` or `S = f~(x) + d(x)`, `tau`/`d` a polynomial or
//!   an RBF model over the normalised design.
//! - **VBA** ([`vba`]): `S = f~(tau(x))`, a per-variable transform of the design.
//! - **PBA** ([`pba`]): `S = f~(x; p(a))`, scaled LoFi masses (and tyre rate).
//! - **Data fits** ([`datafit`]): quadratic response surface or RBF on the HiFi samples alone.
//! - **GP correction** ([`gp`]): `S = f~(x) exp(g(x))`, `g` a Kriging model ([`kriging`]) of
//!   `ln(F / f~)` with its own predictive variance.
//!
//! Every surrogate has an uncertainty estimate over the box ([`uncertainty`]: leave-one-out
//! errors spread by a Kriging-variance shape, or the GP's own variance); [`infill`] picks
//! the next HiFi run for the decision (expected hypervolume improvement of the feasible
//! front); the adaptive loop that uses them, and compares itself with fixed Audze-Eglais
//! plans, is a study ([`crate::study::adaptive`]).
//!
//! VBA and PBA fit their tuning by Levenberg-Marquardt on relative errors ([`fit`]);
//! [`metrics`] scores a surrogate on a validation grid; the seed's fidelity study, every
//! approach, scheme and plan, is in [`crate::study::fidelity`].
//!
//! Coordinates: `u = (ks - ks_min) / (ks_max - ks_min)`, `v = (cs - cs_min) / (cs_max - cs_min)`
//! ([`DesignBox::normalize`]); criteria index `k`: 0 BAcc (m/s^2), 1 DTL (N), 2 SWS (m).

pub mod datafit;
mod dispatch;
pub mod fit;
pub mod gp;
mod guard;
pub mod infill;
pub mod kriging;
mod lofi;
pub mod metrics;
pub mod pba;
pub mod rba;
pub mod record;
pub mod response;
pub mod spec;
mod tuned;
pub mod uncertainty;
mod validation;
pub mod vba;

pub use datafit::{DataFit, DataFitParams};
pub use fit::{FitDiagnostics, LmOptions, Tuning};
pub use gp::{Gp, GpParams};
pub use guard::Guarded;
pub use lofi::SurrogateLoFi;
pub use metrics::{ByCriterion, ErrorMap, Metrics};
pub use pba::PbaParams;
pub use rba::{Rba, RbaParams};
pub use record::ModelRecord;
pub use response::{Kernel, ResponseKind};
pub use spec::{Approach, Form, PlanSpec, Scaling, SurrogateSpec, Transform};
pub use tuned::Tuned;
pub use validation::{ValidationSet, VALIDATION_LEVELS};
pub use vba::VbaParams;

use crate::car::{Car, QuarterCar};
use crate::design::DesignBox;
use crate::doe::Plan;
use crate::error::{Result, RideError};
use crate::evaluate::{Criteria, Evaluator, CRITERIA_NAMES};
use crate::road::Road;
use crate::road_profile::{ShapedQuarter, ShapedRoad};
use serde::{Deserialize, Serialize};

/// One HiFi sample: a design point and the HiFi criteria there.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Sample {
    /// Front spring rate, N/m.
    pub ks: f64,
    /// Front damper rate, N s/m.
    pub cs: f64,
    /// HiFi criteria at `(ks, cs)`.
    pub hifi: Criteria,
}

/// Evaluates `hifi` at the points of `plan` scaled onto `design_box`. Wrap the evaluator in
/// [`crate::optimize::Counted`] to count the HiFi runs (the study reports them).
pub fn sample_plan<E: Evaluator>(
    hifi: &E,
    plan: &Plan,
    design_box: &DesignBox,
) -> Result<Vec<Sample>> {
    plan.points(design_box)
        .into_iter()
        .map(|(ks, cs)| {
            Ok(Sample {
                ks,
                cs,
                hifi: hifi.evaluate(ks, cs)?,
            })
        })
        .collect()
}

/// One named tuning parameter of a fitted surrogate.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Parameter {
    /// Name, prefixed by the criterion in the per-criterion scheme (`"dtl.ks.a1"`).
    pub name: String,
    /// Value (dimensionless unless the name says otherwise).
    pub value: f64,
}

/// Whether one tuning serves all three criteria or each criterion has its own.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Scheme {
    /// One tuning fitted to all three criteria at once.
    Shared,
    /// One tuning per criterion, each fitted to that criterion alone.
    PerCriterion,
}

impl Scheme {
    /// The criteria each fit covers: `[[0, 1, 2]]` or `[[0], [1], [2]]`.
    pub fn groups(self) -> &'static [&'static [usize]] {
        match self {
            Scheme::Shared => &[&[0, 1, 2]],
            Scheme::PerCriterion => &[&[0], &[1], &[2]],
        }
    }

    /// Prefix of the parameter names of fit `g`: `""` (shared) or `"bacc."` etc.
    fn prefix(self, g: usize) -> String {
        match self {
            Scheme::Shared => String::new(),
            Scheme::PerCriterion => format!("{}.", CRITERIA_NAMES[g]),
        }
    }

    /// Label of the criteria that fit `g` covers: `"all"` or a criterion name.
    fn label(self, g: usize) -> String {
        match self {
            Scheme::Shared => "all".into(),
            Scheme::PerCriterion => CRITERIA_NAMES[g].into(),
        }
    }
}

/// What every surrogate fit needs besides the samples: the LoFi (car and road) it tunes and
/// the design box that defines the normalised coordinates.
#[derive(Debug, Clone, PartialEq)]
pub struct Setting {
    /// The LoFi quarter car of the car on the road (an ISO class or a measured road).
    pub lofi: SurrogateLoFi,
    /// The box of the normalised coordinates `(u, v)`.
    pub design_box: DesignBox,
}

impl Setting {
    /// Validates `car`, `road` and `design_box` and builds the setting.
    pub fn new(car: &Car, road: &Road, design_box: &DesignBox) -> Result<Setting> {
        car.validate()?;
        road.validate()?;
        design_box.validate()?;
        design_box.check_on(&car.design_domain())?;
        Ok(Setting {
            lofi: SurrogateLoFi {
                car: car.clone(),
                road: *road,
                measured: None,
            },
            design_box: *design_box,
        })
    }

    /// The setting on a measured road, shaped at its speed: the LoFi of every surrogate
    /// then runs on it ([`SurrogateLoFi`]).
    pub fn measured(car: &Car, road: ShapedRoad, design_box: &DesignBox) -> Result<Setting> {
        let iso = Road {
            speed: road.speed,
            ..Road::default()
        };
        let mut setting = Setting::new(car, &iso, design_box)?;
        setting.lofi.measured = Some(std::sync::Arc::new(ShapedQuarter::new(road)));
        Ok(setting)
    }
}

/// A fitted surrogate: predicts the criteria (through [`Evaluator::evaluate`]) and reports
/// how it was tuned.
pub trait Surrogate: Evaluator + Send + Sync {
    /// What was fitted (approach and scheme).
    fn spec(&self) -> SurrogateSpec;

    /// The tuning parameters, names and values.
    fn tuning(&self) -> Vec<Parameter>;

    /// One entry per fit: one for a shared tuning, three for a per-criterion one.
    fn diagnostics(&self) -> Vec<FitDiagnostics>;

    /// The tuned quarter car behind each criterion `[bacc, dtl, sws]` at design `(ks, cs)`
    /// (the same car three times in the shared scheme); `None` when the surrogate has no
    /// physical model (RBA corrects outputs, data fits have no model).
    fn tuned_quarters(&self, _ks: f64, _cs: f64) -> Result<Option<[QuarterCar; 3]>> {
        Ok(None)
    }

    /// The surrogate's own predictive standard deviation of the relative error
    /// `S_k / F_k - 1` of each criterion `[bacc, dtl, sws]` at `(ks, cs)`, -; `None` when it
    /// has none (only the GP correction has one; [`uncertainty`] estimates one for every
    /// surrogate by leave-one-out).
    fn relative_std(&self, _ks: f64, _cs: f64) -> Result<Option<[f64; 3]>> {
        Ok(None)
    }

    /// Whether the surrogate's LoFi runs on a measured road: its route there is not data,
    /// so such a fit has no record ([`Guarded::record`]).
    fn on_measured_road(&self) -> bool;
}

/// A parameter set that is checked, then fitted into a [`Surrogate`].
pub(crate) trait SurrogateParams {
    /// The fitted model.
    type Model: Surrogate + 'static;

    /// Rejects parameters the samples cannot support (too few samples or levels for the
    /// parameter count, a scheme the approach does not offer); errors name the field.
    fn check(&self, samples: &[Sample]) -> Result<()>;

    /// Checks, then fits to `samples`.
    fn fit(&self, setting: &Setting, samples: &[Sample]) -> Result<Self::Model>;
}

/// Rejects empty sample sets and non-finite or non-positive values (relative errors divide
/// by the HiFi criteria).
fn check_samples(samples: &[Sample]) -> Result<()> {
    if samples.is_empty() {
        return Err(RideError::field("plan", "no samples"));
    }
    for (i, s) in samples.iter().enumerate() {
        let ok = [s.ks, s.cs]
            .into_iter()
            .chain(s.hifi.to_array())
            .all(|x| x.is_finite() && x > 0.0);
        if !ok {
            return Err(RideError::field(
                format!("samples[{i}]"),
                "design and criteria must be finite and > 0",
            ));
        }
    }
    Ok(())
}

/// Errors unless `samples` holds at least `needed` points.
fn require_samples(samples: &[Sample], needed: usize, what: &str) -> Result<()> {
    if samples.len() < needed {
        return Err(RideError::field(
            "plan",
            format!(
                "{what} needs at least {needed} samples, the plan has {}",
                samples.len()
            ),
        ));
    }
    Ok(())
}

/// Number of distinct Ks and Cs values among the samples.
fn distinct_levels(samples: &[Sample]) -> [usize; 2] {
    let count = |f: fn(&Sample) -> f64| {
        let mut v: Vec<f64> = samples.iter().map(f).collect();
        crate::order::sort_by_f64_key(&mut v, |x| *x);
        v.dedup_by(|a, b| (*a - *b).abs() <= 1e-9 * b.abs());
        v.len()
    };
    [count(|s| s.ks), count(|s| s.cs)]
}

/// Half the sum of squared relative errors `(S_ik - F_ik) / F_ik` of `model` over the
/// samples `i` and the criteria `k` in `criteria`.
fn relative_cost<E: Evaluator + ?Sized>(
    model: &E,
    samples: &[Sample],
    criteria: &[usize],
) -> Result<f64> {
    let mut cost = 0.0;
    for s in samples {
        let p = model.evaluate(s.ks, s.cs)?.to_array();
        let f = s.hifi.to_array();
        cost += criteria
            .iter()
            .map(|&k| ((p[k] - f[k]) / f[k]).powi(2))
            .sum::<f64>();
    }
    Ok(0.5 * cost)
}

#[cfg(test)]
mod tests;
