//! One optimisation of a car on a road, as `ridelab optimize` runs it: the front on the
//! chosen evaluator (LoFi, HiFi or a surrogate fitted to HiFi samples), its min-max
//! pick against the datum and the pick re-checked on the HiFi.
//!
//! The design objectives' "no worse than the datum" and the ratios of the pick compare
//! against the datum car's **HiFi** criteria, whatever the evaluator: the HiFi is the
//! reference every evaluator is judged by.

use super::model::EvaluatorSpec;
use crate::analysis::{HiFi, ModelKind};
use crate::car::Car;
use crate::comfort::{Comfort, WkComfort};
use crate::design::DesignBox;
use crate::dos::{DesignObjectives, DosContext};
use crate::error::{Result, RideError};
use crate::evaluate::{Criteria, Evaluator};
use crate::gpu::{Compute, ComputePath, HiFiGrid};
use crate::maps::Grid;
use crate::optimize::minmax::{change_percent, pick, recheck, PickRule, Recheck};
use crate::optimize::study::{run_study, Method, Study};
use crate::optimize::suspension::SuspensionProblem;
use crate::optimize::trust::{pick_warnings, Warning};
use crate::road::Road;
use crate::surrogate::PlanSpec;
use serde::Serialize;

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
    /// The comfort measure of the front's BAcc axis, the datum's and the re-check's:
    /// `"wk"` for the ISO 2631-1 Wk-weighted RMS body acceleration, m/s^2; left out for
    /// the unweighted BAcc.
    #[serde(skip_serializing_if = "Comfort::is_bacc")]
    pub comfort: Comfort,
    /// The path that evaluated the HiFi designs, `"gpu"` or `"cpu"` (the GPU evaluates
    /// STM's grid on the full car, [`OptimizeRequest::run`]): there when a path was asked
    /// for or the GPU ran, so the default output stays as it was on the CPU.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub compute: Option<ComputePath>,
    /// The GPU adapter's name when the GPU ran.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub adapter: Option<String>,
    /// How far the pick can be trusted ([`crate::optimize::trust`]): a box bound it sits on, a
    /// criterion its HiFi re-check misses by more than the tolerance; empty when neither.
    pub warnings: Vec<Warning>,
    /// The pick against the datum on the optimisation's own model (the LoFi or a
    /// surrogate): like with like, where `pick.change_percent` (against the HiFi `datum`)
    /// includes that model's bias. Left out when the model is the HiFi, or cannot
    /// evaluate the datum design (a surrogate whose box leaves it out).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub same_model: Option<SameModel>,
}

/// The datum design evaluated on the model that drew the front, and the pick's change
/// against it: `100 (c_pick - c_datum) / c_datum` per criterion, %.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SameModel {
    /// The datum design's criteria on the model that drew the front.
    pub datum: Criteria,
    /// The pick's BAcc, DTL and SWS against `datum`, %.
    pub change_percent: [f64; 3],
}

impl SameModel {
    /// The datum design on `model`: `None` for the HiFi (its datum is the report's) or a
    /// model that cannot evaluate the datum design.
    fn datum(model: &dyn Evaluator, car: &Car) -> Option<Criteria> {
        if model.name() == "full" {
            return None;
        }
        model.evaluate(car.front.spring, car.front.damper).ok()
    }
}

impl OptimizeReport {
    /// Replaces the pick by `rule`'s on the same front and re-checks it on the HiFi of
    /// `car` on `road` (the report's datum is that HiFi's).
    pub fn repick(
        &mut self,
        rule: PickRule,
        car: &Car,
        road: &Road,
        design_box: &DesignBox,
    ) -> Result<()> {
        let hifi = self.comfort.evaluator(ModelKind::Full, car, road)?;
        self.repick_on(rule, &*hifi, design_box)
    }

    /// [`Self::repick`] re-checked on `hifi` (the HiFi of a measured road, say).
    pub fn repick_on(
        &mut self,
        rule: PickRule,
        hifi: &dyn Evaluator,
        design_box: &DesignBox,
    ) -> Result<()> {
        let p = pick(&self.study.front, &self.datum, rule)?;
        self.hifi_recheck = recheck(&p, hifi, &self.datum)?;
        self.warnings = pick_warnings(&p, &self.hifi_recheck, design_box);
        self.study.pick = p;
        Ok(())
    }
}

/// The optimisation on an evaluator built already (the adaptive loop's surrogate), where
/// `model` gives the comfort measure `comfort` in its BAcc slot: the datum and the pick's
/// re-check use the HiFi of `car` on `road` with the same measure.
pub fn optimize_model(
    car: &Car,
    road: &Road,
    design_box: &DesignBox,
    model: Box<dyn Evaluator + Sync>,
    method: &Method,
    objectives: DesignObjectives,
    comfort: Comfort,
) -> Result<OptimizeReport> {
    let hifi: Box<dyn Evaluator + Sync> = match comfort {
        Comfort::Bacc => Box::new(HiFi::new(car, road)?),
        Comfort::Wk => Box::new(WkComfort::full(HiFi::new(car, road)?)),
    };
    optimize_on_models(car, design_box, model, &*hifi, method, objectives, comfort)
}

/// The optimisation on `model` with the datum and the pick's re-check on `hifi` (both
/// built by the caller: the models of a measured road, say); `comfort` labels the
/// report (the models give the measure they were built with).
pub fn optimize_on_models(
    car: &Car,
    design_box: &DesignBox,
    model: Box<dyn Evaluator + Sync>,
    hifi: &dyn Evaluator,
    method: &Method,
    objectives: DesignObjectives,
    comfort: Comfort,
) -> Result<OptimizeReport> {
    objectives.validate()?;
    let datum = hifi.evaluate(car.front.spring, car.front.damper)?;
    let model_datum = SameModel::datum(&*model, car);
    let problem =
        SuspensionProblem::new(model, *design_box, objectives, DosContext::new(car, datum))?;
    let study = run_study(&problem, method, None)?;
    let hifi_recheck = recheck(&study.pick, hifi, &datum)?;
    let same_model = model_datum.map(|d| SameModel {
        datum: d,
        change_percent: change_percent(&study.pick.criteria, &d),
    });
    Ok(OptimizeReport {
        same_model,
        warnings: pick_warnings(&study.pick, &hifi_recheck, design_box),
        study,
        datum,
        hifi_recheck,
        comfort,
        compute: None,
        adapter: None,
    })
}

/// One optimisation as `ridelab optimize` asks for it: the front of `car`'s front spring
/// and damper on `road` over `design_box` by `method` on `evaluator`, its pick by `pick`
/// against the datum, re-checked on the HiFi. [`Self::run`] prepares the HiFi once and
/// every part uses it: the full car evaluator, a surrogate's samples, the GPU grid's
/// off-grid points, the datum and the re-check (`tests/hifi_builds.rs`).
#[derive(Debug, Clone)]
pub struct OptimizeRequest<'a> {
    /// The datum car (its front spring and damper are the datum design).
    pub car: &'a Car,
    /// The road.
    pub road: &'a Road,
    /// The design box, N/m and N s/m.
    pub design_box: DesignBox,
    /// The model the front is drawn on.
    pub evaluator: EvaluatorSpec,
    /// A surrogate's HiFi sampling plan.
    pub plan: PlanSpec,
    /// STM or NSGA-II.
    pub method: Method,
    /// The design objectives.
    pub objectives: DesignObjectives,
    /// The comfort measure in the BAcc slot of the front, the datum and the re-check.
    pub comfort: Comfort,
    /// The HiFi's path (`None`: auto, unreported).
    pub compute: Option<Compute>,
    /// The pick rule on the front.
    pub pick: PickRule,
}

impl<'a> OptimizeRequest<'a> {
    /// The full car, a surrogate's plan `ae:10`, unweighted BAcc, the path auto, the
    /// min-max pick.
    pub fn new(
        car: &'a Car,
        road: &'a Road,
        design_box: DesignBox,
        method: Method,
        objectives: DesignObjectives,
    ) -> Self {
        OptimizeRequest {
            car,
            road,
            design_box,
            evaluator: EvaluatorSpec::Model(ModelKind::Full),
            plan: PlanSpec::AudzeEglais(10),
            method,
            objectives,
            comfort: Comfort::Bacc,
            compute: None,
            pick: PickRule::MinMax,
        }
    }

    /// Runs it. STM on the full car with the unweighted BAcc evaluates its
    /// `grid x grid` starting grid on the GPU when `compute` takes it there
    /// ([`HiFiGrid::on_gpu`]: `Auto` only on a hardware adapter); the refinements, the
    /// datum and the re-check stay on the CPU HiFi. Anything else runs on the CPU, and
    /// `Compute::Gpu` there is an error naming `compute`. The report's `compute` is set
    /// when `compute` is given or the GPU ran.
    pub fn run(&self) -> Result<OptimizeReport> {
        let (car, road, design_box) = (self.car, self.road, &self.design_box);
        let asked = self.compute.unwrap_or_default();
        let stm_grid = match (self.evaluator, &self.method, self.comfort) {
            (EvaluatorSpec::Model(ModelKind::Full), Method::Stm(p), Comfort::Bacc) => Some(p),
            _ => None,
        };
        if stm_grid.is_none() && asked == Compute::Gpu {
            return Err(RideError::field(
                "compute",
                "gpu: the GPU path evaluates STM's grid on the full car with the unweighted \
                 BAcc (--evaluator full --method stm --comfort bacc); use --compute cpu or auto",
            ));
        }
        if let (Comfort::Wk, EvaluatorSpec::Surrogate(_)) = (self.comfort, self.evaluator) {
            return Err(RideError::field(
                "comfort",
                "wk needs --evaluator quarter or full: the surrogates are fitted to the unweighted BAcc",
            ));
        }
        self.objectives.validate()?;
        // The one HiFi of the run.
        let hifi = HiFi::new(car, road)?;
        let gpu = match stm_grid {
            Some(p) if asked != Compute::Cpu => {
                p.validate()?;
                HiFiGrid::on_gpu(&hifi, &Grid::over_box(design_box, p.grid, p.grid)?, asked)?
            }
            _ => None,
        };
        let path = match &gpu {
            Some(_) => Some(ComputePath::Gpu),
            None => self.compute.map(|_| ComputePath::Cpu),
        };
        let adapter = gpu.as_ref().and_then(|g| g.adapter().map(str::to_string));
        let model: Box<dyn Evaluator + Sync> = match (gpu, self.comfort, self.evaluator) {
            (Some(grid), _, _) => Box::new(grid),
            (None, Comfort::Bacc, e) => e.build_on(&hifi, design_box, self.plan)?,
            (None, Comfort::Wk, EvaluatorSpec::Model(ModelKind::Full)) => {
                Box::new(WkComfort::full(hifi.clone()))
            }
            (None, Comfort::Wk, _) => Box::new(WkComfort::quarter(car, road)),
        };
        let reference: Box<dyn Evaluator + Sync> = match self.comfort {
            Comfort::Bacc => Box::new(hifi),
            Comfort::Wk => Box::new(WkComfort::full(hifi)),
        };
        let mut r = optimize_on_models(
            car,
            design_box,
            model,
            &*reference,
            &self.method,
            self.objectives.clone(),
            self.comfort,
        )?;
        if self.pick != PickRule::MinMax {
            r.repick_on(self.pick, &*reference, design_box)?;
        }
        r.compute = path;
        r.adapter = adapter;
        Ok(r)
    }

    /// Runs it on the CPU whatever GPU the machine has, the report's `compute` left out:
    /// the same report on every machine (the study report's fronts, a library caller's).
    pub fn run_cpu(&self) -> Result<OptimizeReport> {
        let mut r = OptimizeRequest {
            compute: Some(Compute::Cpu),
            ..self.clone()
        }
        .run()?;
        r.compute = None;
        Ok(r)
    }
}
