//! One study's inputs as one type (issue #28): the car, the road (an ISO class or a
//! measured profile), the design box, the design objectives, the comfort measure, the
//! load cases and the compute path. A map and a front are its methods
//! ([`StudySpec::map`], [`StudySpec::front`]): each takes the model it is drawn on
//! ([`EvaluatorSpec`]) and its own settings, and dispatches to the one pipeline for the
//! road and the cases, so `ridelab map` and `ridelab optimize` no longer branch on them
//! themselves. What a study cannot combine is refused here, naming the field: a measured
//! road is one scenario (no cases, no GPU path); the adaptive loop runs on one case.

use super::adaptive::{AdaptiveOptimizeReport, AdaptiveOptions};
use super::map::{MapReport, MapRequest, MapSettings};
use super::measured::{check_measured_request, measured_map, optimize_measured};
use super::model::EvaluatorSpec;
use super::optimize::{OptimizeReport, OptimizeRequest};
use super::robust::{CaseMapReport, RobustMapReport, RobustOptimizeReport};
use crate::analysis::ModelKind;
use crate::budget::{check_measured, stm_runs};
use crate::car::Car;
use crate::comfort::Comfort;
use crate::design::DesignBox;
use crate::dos::DesignObjectives;
use crate::error::{Result, RideError};
use crate::gpu::{Compute, ComputePath};
use crate::maps::{Grid, Scale};
use crate::optimize::{Method, PickRule};
use crate::road::Road;
use crate::road_profile::{
    road_error, MeasuredModel, MeasuredRoad, Profile, ProfileTracks, ShapedRoad,
};
use crate::robust::{CaseSet, Combine};
use crate::surrogate::PlanSpec;
use serde::Serialize;
use std::sync::Arc;

/// The road a study drives on.
#[derive(Debug, Clone)]
pub enum StudyRoad {
    /// An ISO 8608 class at a speed, the tracks correlated or not.
    Iso(Road),
    /// A measured profile, shaped at a speed.
    Measured(MeasuredSource),
}

/// A measured road profile as a study uses it: the file's name (what reports call the
/// road), the profile, how its tracks drive the car and the profile shaped at the speed
/// ([`ShapedRoad`]: the models' exact routes run with its filters). The CLI reads one per
/// run; the page's session holds one per profile, speed and tracks (shared: the profile
/// is behind an `Arc`), and both report on it through [`StudySpec::report`].
#[derive(Debug, Clone)]
pub struct MeasuredSource {
    /// The file's name.
    pub file: String,
    /// The profile as read.
    pub profile: Arc<Profile>,
    /// One track on both wheels, independent tracks, or two measured ones.
    pub tracks: ProfileTracks,
    /// The profile shaped at the speed.
    pub shaped: ShapedRoad,
}

impl MeasuredSource {
    /// `profile` (read from `file`) shaped at `speed`, m/s, with `tracks`; errors name
    /// `road` (with the profile's own field) as [`road_error`] words them.
    pub fn new(file: &str, profile: Profile, speed: f64, tracks: ProfileTracks) -> Result<Self> {
        let shaped = ShapedRoad::from_profile(&profile, speed, tracks).map_err(road_error)?;
        Ok(MeasuredSource {
            file: file.to_string(),
            profile: Arc::new(profile),
            tracks,
            shaped,
        })
    }

    /// What reports say of the road.
    pub fn about(&self) -> MeasuredRoad {
        MeasuredRoad::of(&self.file, &self.shaped, self.tracks)
    }
}

/// The inputs of a study.
#[derive(Debug, Clone)]
pub struct StudySpec {
    /// The datum car (its own front spring and damper are the datum design).
    pub car: Car,
    /// The road.
    pub road: StudyRoad,
    /// The design box, N/m and N s/m: a front's, and the box a map's surrogate is fitted
    /// over.
    pub design_box: DesignBox,
    /// The design objectives of maps' masks and fronts.
    pub objectives: DesignObjectives,
    /// The comfort measure in the BAcc slot.
    pub comfort: Comfort,
    /// The load cases and operating points of a robust design; `None`: the car as given.
    pub cases: Option<CaseSet>,
    /// The HiFi's path; `None`: auto, and a front's report leaves it out.
    pub compute: Option<Compute>,
}

/// A map of a study: the model it is drawn on, a surrogate's plan, the grid, the scale,
/// and with cases, one case's own map in place of the robust one.
#[derive(Debug, Clone, Copy)]
pub struct MapAsk {
    /// The quarter car, the full car or a surrogate of the full car.
    pub model: EvaluatorSpec,
    /// A surrogate's HiFi sampling plan.
    pub plan: PlanSpec,
    /// The Ks x Cs grid.
    pub grid: Grid,
    /// Absolute values or ratios to the datum.
    pub scale: Scale,
    /// Case K's own map (its loaded car on its road, its own datum), cases numbered
    /// load-case-major from 0; `None`: the robust map when there are cases.
    pub case: Option<usize>,
}

/// A map as the study gives it: one scenario's, one case's, or the robust map over the
/// cases (each serialises as `ridelab map --json` writes it).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(untagged)]
pub enum StudyMap {
    /// One scenario (an ISO class or a measured road).
    One(MapReport),
    /// One case's own map.
    Case(CaseMapReport),
    /// The robust map over the cases.
    Robust(RobustMapReport),
}

impl StudyMap {
    /// The map report (the robust fields for a robust map).
    pub fn into_map(self) -> MapReport {
        match self {
            StudyMap::One(m) => m,
            StudyMap::Case(c) => c.map,
            StudyMap::Robust(r) => r.map,
        }
    }
}

/// A front of a study: the model it is found on, a surrogate's plan, the method, the pick
/// rule and the adaptive loop's options (a surrogate's samples placed one at a time).
#[derive(Debug, Clone)]
pub struct FrontAsk {
    /// The quarter car, the full car or a surrogate of the full car.
    pub evaluator: EvaluatorSpec,
    /// A surrogate's HiFi sampling plan (the loop's initial plan).
    pub plan: PlanSpec,
    /// STM or NSGA-II.
    pub method: Method,
    /// The pick rule on the front.
    pub pick: PickRule,
    /// The adaptive loop after the plan; `None`: the plan alone.
    pub adaptive: Option<AdaptiveOptions>,
}

/// A front as the study gives it (each serialises as `ridelab optimize --json` writes
/// it).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(untagged)]
pub enum FrontReport {
    /// One scenario's front, pick and HiFi re-check.
    One(OptimizeReport),
    /// The same on the adaptive loop's surrogate, with the loop's report.
    Adaptive(Box<AdaptiveOptimizeReport>),
    /// The robust front over the cases.
    Robust(RobustOptimizeReport),
}

/// A front and, on a measured road, what the report says of the road.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StudyFront {
    /// The front, its pick and re-check.
    #[serde(flatten)]
    pub front: FrontReport,
    /// The measured road; left out on an ISO class.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub road: Option<MeasuredRoad>,
}

impl StudySpec {
    /// `car` on `road` over the default box with the default objectives, the unweighted
    /// BAcc, no cases, the path auto.
    pub fn new(car: Car, road: StudyRoad) -> StudySpec {
        StudySpec {
            car,
            road,
            design_box: DesignBox::default(),
            objectives: DesignObjectives::default(),
            comfort: Comfort::Bacc,
            cases: None,
            compute: None,
        }
    }

    /// The map `ask` asks for: on an ISO class the model's map ([`MapRequest::run`]), one
    /// case's ([`MapRequest::run_case`]; without cases, case 0 is the car itself) or the
    /// robust map over the cases ([`MapRequest::run_robust`], on the CPU: `compute` gpu
    /// is refused naming it); on a measured road the map there ([`measured_map`]), the
    /// grid bounded by [`crate::budget::MAX_MEASURED_RUNS`] points (naming `ks-range`). A
    /// surrogate is fitted over the study's design box.
    pub fn map(&self, ask: &MapAsk) -> Result<StudyMap> {
        let settings = MapSettings {
            grid: ask.grid,
            scale: ask.scale,
            objectives: self.objectives.clone(),
            comfort: self.comfort,
            ..MapSettings::default()
        };
        let road = match &self.road {
            StudyRoad::Iso(road) => road,
            StudyRoad::Measured(m) => {
                self.one_scenario(ask.case.is_some())?;
                let g = &ask.grid;
                check_measured(
                    (g.ks.n as u64) * (g.cs.n as u64),
                    "ks-range",
                    &format!("a {} x {} map", g.ks.n, g.cs.n),
                    "the points of --ks-range or --cs-range",
                )?;
                // The ISO road is only recorded: the measured one replaces it.
                let iso = Road::default();
                let request = self.map_request(ask, &iso, settings);
                return measured_map(&request, &m.shaped, &m.file, m.tracks).map(StudyMap::One);
            }
        };
        if self.cases.is_some() && self.compute == Some(Compute::Gpu) {
            return Err(RideError::field(
                "compute",
                "gpu: the robust maps' cases are evaluated on the CPU; use --compute cpu or auto",
            ));
        }
        let request = self.map_request(ask, road, settings);
        Ok(match (&self.cases, ask.case) {
            (None, None) => StudyMap::One(request.run()?),
            (Some(set), None) => StudyMap::Robust(request.run_robust(set)?),
            (Some(set), Some(k)) => StudyMap::Case(request.run_case(set, k)?),
            (None, Some(k)) => {
                let set = CaseSet::new(&self.car, road, &[], &[], Combine::Worst)?;
                StudyMap::Case(request.run_case(&set, k)?)
            }
        })
    }

    /// The map request of `ask` on `road` with `settings`.
    fn map_request<'a>(
        &'a self,
        ask: &MapAsk,
        road: &'a Road,
        settings: MapSettings,
    ) -> MapRequest<'a> {
        MapRequest {
            compute: self.compute.unwrap_or_default(),
            plan: ask.plan,
            fit_box: Some(self.design_box),
            ..MapRequest::new(ask.model, &self.car, road, settings)
        }
    }

    /// The front `ask` asks for, its pick and the pick's HiFi re-check: on an ISO class
    /// [`OptimizeRequest::run`], through the adaptive loop
    /// ([`OptimizeRequest::run_adaptive`], on the CPU with the unweighted BAcc) or robust
    /// over the cases ([`OptimizeRequest::run_robust`], on the CPU, one case per loop);
    /// on a measured road [`optimize_measured`], its runs bounded by
    /// [`crate::budget::MAX_MEASURED_RUNS`] (naming `grid` or `generations`). Each
    /// combination a study cannot run is refused naming its field.
    pub fn front(&self, ask: &FrontAsk) -> Result<StudyFront> {
        let road = match &self.road {
            StudyRoad::Iso(road) => road,
            StudyRoad::Measured(m) => return self.front_measured(ask, m),
        };
        let request = OptimizeRequest {
            evaluator: ask.evaluator,
            plan: ask.plan,
            comfort: self.comfort,
            compute: self.compute,
            pick: ask.pick,
            ..OptimizeRequest::new(
                &self.car,
                road,
                self.design_box,
                ask.method.clone(),
                self.objectives.clone(),
            )
        };
        let front = match (&self.cases, ask.adaptive) {
            (Some(_), _) if self.compute == Some(Compute::Gpu) => {
                return Err(RideError::field(
                    "compute",
                    "gpu: the robust design's cases are evaluated on the CPU; use --compute cpu or auto",
                ))
            }
            (Some(_), Some(_)) => {
                return Err(RideError::field(
                    "adaptive",
                    "the adaptive loop runs on one case: leave out --cases (and the car file's load_cases)",
                ))
            }
            (Some(set), None) => FrontReport::Robust(request.run_robust(set)?),
            (None, None) => FrontReport::One(request.run()?),
            (None, Some(_)) if self.compute == Some(Compute::Gpu) => {
                return Err(RideError::field(
                    "compute",
                    "gpu: the adaptive loop's HiFi runs are single designs on the CPU; use --compute cpu or auto",
                ))
            }
            (None, Some(_)) if self.comfort == Comfort::Wk => {
                return Err(RideError::field(
                    "comfort",
                    "wk needs --evaluator quarter or full: the adaptive loop's surrogates are fitted to the unweighted BAcc",
                ))
            }
            (None, Some(options)) => {
                let r = request.run_adaptive(options)?;
                let mut optimize = r.optimize;
                optimize.compute = self.compute.map(|_| ComputePath::Cpu);
                if ask.pick != PickRule::MinMax {
                    optimize.repick(ask.pick, &self.car, road, &self.design_box)?;
                }
                FrontReport::Adaptive(Box::new(AdaptiveOptimizeReport {
                    optimize,
                    adaptive: r.adaptive,
                }))
            }
        };
        Ok(StudyFront { front, road: None })
    }

    /// [`Self::front`] on the measured road `m`: the front of the LoFi, the HiFi or a
    /// surrogate there (the models by the exact route at every design; a surrogate fitted
    /// to the HiFi's samples there, its LoFi the quarter car there), the datum and the
    /// pick's re-check on its HiFi; with the adaptive loop the surrogate is the loop's on
    /// this road. A run costs more here than on an ISO class (the residue route with the
    /// road's filters: the default STM on the HiFi, 48 517 runs, took 0.17 s on the
    /// shipped slab road), so the work is bounded: `grid^2 + 12 (grid - 1) 2^levels`
    /// runs for STM, `population (generations + 1)` for NSGA-II, plus the loop's plan
    /// and added HiFi runs.
    fn front_measured(&self, ask: &FrontAsk, m: &MeasuredSource) -> Result<StudyFront> {
        self.one_scenario(false)?;
        check_measured_request(ask.evaluator, self.comfort, ask.adaptive.is_some())?;
        let plan_runs = match ask.adaptive {
            Some(o) => ask.plan.plan()?.points(&self.design_box).len() as u64 + o.runs as u64,
            None => 0,
        };
        let (runs, field, options) = match &ask.method {
            Method::Stm(p) => (stm_runs(p.grid, p.levels), "grid", "--grid or --levels"),
            Method::Nsga2(p) => (
                (p.population as u64).saturating_mul(p.generations as u64 + 1),
                "generations",
                "--generations or --population",
            ),
        };
        check_measured(
            runs.saturating_add(plan_runs),
            field,
            "this optimisation",
            options,
        )?;
        let hifi = MeasuredModel::new(ModelKind::Full, &self.car, m.shaped.clone())
            .with_comfort(self.comfort);
        // The request's ISO road is not used: the models are on the measured one.
        let unused = Road::default();
        let request = OptimizeRequest {
            evaluator: ask.evaluator,
            plan: ask.plan,
            comfort: self.comfort,
            ..OptimizeRequest::new(
                &self.car,
                &unused,
                self.design_box,
                ask.method.clone(),
                self.objectives.clone(),
            )
        };
        let (mut optimize, looped) = optimize_measured(&request, &hifi, ask.adaptive)?;
        optimize.compute = self.compute.map(|_| ComputePath::Cpu);
        if ask.pick != PickRule::MinMax {
            optimize.repick_on(ask.pick, &hifi, &self.design_box)?;
        }
        let front = match looped {
            None => FrontReport::One(optimize),
            Some(adaptive) => {
                FrontReport::Adaptive(Box::new(AdaptiveOptimizeReport { optimize, adaptive }))
            }
        };
        Ok(StudyFront {
            front,
            road: Some(m.about()),
        })
    }

    /// What a measured road (one scenario, computed on the CPU) cannot be combined with,
    /// naming the field: cases (the study's, or `case`: one asked for) and `compute` gpu.
    fn one_scenario(&self, case: bool) -> Result<()> {
        one_scenario(
            self.cases.is_some() || case,
            self.compute == Some(Compute::Gpu),
        )
    }
}

/// What a measured road (one scenario, computed on the CPU) cannot be combined with: an
/// error naming `road` when `cases` (cases, a case, a car file's load cases) and
/// `compute` when `gpu`.
pub fn one_scenario(cases: bool, gpu: bool) -> Result<()> {
    if cases {
        return Err(RideError::field(
            "road",
            "a measured road is one scenario: --cases, --case and a car file's load_cases take ISO classes (--class)",
        ));
    }
    if gpu {
        return Err(RideError::field(
            "compute",
            "gpu: on a measured road the models run on the CPU; use --compute cpu or auto",
        ));
    }
    Ok(())
}
