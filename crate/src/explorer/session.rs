//! The explorer's session: one object that owns the view's state, its parsed scenario,
//! the fitted surrogate and the kept map values, updated by small setters. The page's
//! wasm `Explorer` is this object; the CLI has no session (each command is one run).
//!
//! What is kept, and until when:
//! - the scenario: a new state re-parses only the fields that changed
//!   ([`State::scenario_after`]), so a slider move never re-reads a custom car's file;
//! - the fitted surrogate and each model's map values: until the car, road, design box
//!   or surrogate change ([`FitKey`]). The design objectives only judge a map's values,
//!   so an objective edit (the SWS limit dragged) re-judges the kept values instead of
//!   recomputing them: a 160 x 120 LoFi map then costs its mask;
//! - HiFi values computed elsewhere (the page's GPU path, `web::GpuMaps`), handed in by
//!   [`Session::keep_hifi_planes`]: kept like the session's own, with the path that made
//!   them ([`Session::hifi_path`]), and used by the HiFi and surrogate-error maps.
//!
//! A setter that fails leaves the session as it was (the last good state).

use super::hifi_front::{self, HifiFrontView};
use super::maps::{error_values, ModelMap};
use super::model::Model;
use super::state::{RoadResolver, Scenario, State};
use super::studies::{self, FrontResult, Spectra, TimeResult};
use super::surrogate::{fit, fit_report, FitKey, FitRecord, FittedSurrogate};
use super::tags::Tags;
use crate::analysis::{readout, report, ModelKind, Readout, Report};
use crate::comfort::Comfort;
use crate::dos::DosContext;
use crate::error::{Result, RideError};
use crate::evaluate::{Criteria, Evaluator};
use crate::gpu::{ComputePath, HiFiGrid};
use crate::maps::{DatumPoint, Dcs, DosMap, Grid, Scale};
use crate::report::MethodReport;
use crate::robust::{CaseSet, Combination, MAX_CASES};
use crate::study::robust::map::{robust_fields, CaseField};
use crate::study::robust::optimize::hifi_combination;
use crate::study::{StudySpec, SurrogateReport};
use crate::surrogate::Surrogate;
use crate::time_domain::TimeOptions;
use std::rc::Rc;

/// Map values kept at once: one per model and grid in use (the page shows one model's
/// maps, its objective plane uses the surrogate's feasible set, the worker the HiFi's),
/// and with robust cases one per case on the maps' and the plane's grids.
const KEPT_MAPS: usize = 8 + 2 * MAX_CASES;

/// The explorer's session (see the module documentation).
pub struct Session {
    state: State,
    scenario: Scenario,
    fit: Option<Rc<FittedSurrogate>>,
    /// Surrogate fits this session has made ([`Session::fit_count`]).
    fits: u64,
    /// A fit another session made ([`Session::offer_fit`]), adopted by the first
    /// scenario with its inputs that asks for the surrogate.
    offered: Option<FitRecord>,
    kept: Vec<Kept>,
    /// With robust cases, the robust front's combination and the cases' HiFi datums
    /// ([`hifi_combination`]), once per [`FitKey`]: a slider move then costs one LoFi
    /// run per case.
    robust: Option<Rc<(Combination, Vec<Criteria>)>>,
    /// What turns a state's `roadProfile` into its measured road (`None`: such a state
    /// is refused naming `road`).
    roads: Option<RoadResolver>,
}

/// One model's map values on one grid with one comfort measure, and the path that
/// computed them.
struct Kept {
    model: Model,
    grid: Grid,
    comfort: Comfort,
    /// The robust case whose loaded car and road made them (`None`: the scenario's own).
    case: Option<usize>,
    values: Rc<Dcs>,
    path: ComputePath,
}

impl Session {
    /// A session on `state`; errors name the field at fault.
    pub fn new(state: State) -> Result<Session> {
        Session::with_roads(state, None)
    }

    /// A session on `state` whose `roadProfile`s `roads` resolves (the page's workers:
    /// the profiles dropped on the page); errors name the field at fault.
    pub fn with_roads(state: State, roads: Option<RoadResolver>) -> Result<Session> {
        let scenario = state.scenario_after(None, roads.as_ref())?;
        Ok(Session {
            state,
            scenario,
            fit: None,
            fits: 0,
            offered: None,
            kept: Vec::new(),
            robust: None,
            roads,
        })
    }

    /// The current state.
    pub fn state(&self) -> &State {
        &self.state
    }

    /// The current scenario.
    pub fn scenario(&self) -> &Scenario {
        &self.scenario
    }

    /// The tags of the current state (what the page keys its results by).
    pub fn tags(&self) -> Tags {
        let f = &self.scenario.datum.front;
        Tags::of(&self.state, (f.spring, f.damper))
    }

    /// Moves to `state`, re-parsing only what changed; the fit and the kept maps go when
    /// what they depend on changes. On error the session keeps its last good state.
    pub fn set_state(&mut self, state: State) -> Result<()> {
        if state == self.state {
            return Ok(());
        }
        let scenario =
            state.scenario_after(Some((&self.state, &self.scenario)), self.roads.as_ref())?;
        if FitKey::of(&scenario) != FitKey::of(&self.scenario) {
            self.fit = None;
            self.kept.clear();
            self.robust = None;
        }
        self.state = state;
        self.scenario = scenario;
        Ok(())
    }

    /// Moves the design to front spring `ks` (N/m) and damper `cs` (N s/m); errors name
    /// `ks` or `cs`.
    pub fn set_design(&mut self, ks: f64, cs: f64) -> Result<()> {
        let state = State {
            ks,
            cs,
            ..self.state.clone()
        };
        self.set_state(state)
    }

    /// The scenario's surrogate, fitted once per [`FitKey`], or adopted from the offered
    /// fit ([`Session::offer_fit`]) when that was made from the scenario's inputs.
    pub fn surrogate(&mut self) -> Result<Rc<FittedSurrogate>> {
        if let Some(f) = &self.fit {
            return Ok(Rc::clone(f));
        }
        let adopted = self.offered.as_ref().and_then(|r| r.adopt(&self.scenario));
        let f = Rc::new(match adopted {
            Some(f) => f,
            None => {
                let f = fit(&self.scenario)?;
                self.fits += 1;
                f
            }
        });
        self.fit = Some(Rc::clone(&f));
        Ok(f)
    }

    /// The scenario's fit as data, for another session to adopt (fitted here if not
    /// yet); `None` when the fit has no record.
    pub fn fit_record(&mut self) -> Result<Option<FitRecord>> {
        let f = self.surrogate()?;
        f.record(&self.scenario)
    }

    /// Offers this session another's fit: the surrogate of a scenario with the same fit
    /// inputs is that fit, not a new one (the latest offer replaces an earlier one).
    pub fn offer_fit(&mut self, record: FitRecord) {
        self.offered = Some(record);
    }

    /// The criteria of the design by the fast evaluators the maps and optimisers use; the
    /// LoFi's and HiFi's BAcc is the scenario's comfort measure, the surrogate's the
    /// unweighted BAcc it was fitted to.
    pub fn criteria(&mut self, model: Model) -> Result<Criteria> {
        let (ks, cs) = self.design();
        match model {
            Model::LoFi => self
                .scenario
                .evaluator(ModelKind::Quarter)?
                .evaluate(ks, cs),
            Model::HiFi => self.scenario.evaluator(ModelKind::Full)?.evaluate(ks, cs),
            Model::Surrogate => self.surrogate()?.model.evaluate(ks, cs),
            Model::Robust => {
                let robust = self.robust_combination()?;
                let per = self.case_criteria(ModelKind::Quarter)?;
                Ok(robust.0.apply(&per))
            }
            Model::SurrogateError => Err(model.refused("model", Model::CRITERIA)),
        }
    }

    /// The robust front's combination and the cases' HiFi datums, kept per [`FitKey`].
    fn robust_combination(&mut self) -> Result<Rc<(Combination, Vec<Criteria>)>> {
        if let Some(r) = &self.robust {
            return Ok(Rc::clone(r));
        }
        let set = self.cases("front")?;
        let r = Rc::new(hifi_combination(set, self.scenario.comfort)?);
        self.robust = Some(Rc::clone(&r));
        Ok(r)
    }

    /// The scenario's cases; without them an error naming `cases` that says `what` needs them.
    fn cases(&self, what: &str) -> Result<&CaseSet> {
        self.scenario.cases.as_ref().ok_or_else(|| {
            RideError::field(
                "cases",
                format!("the robust {what} needs load cases or operating points: there are none"),
            )
        })
    }

    /// The design's criteria in every robust case by `kind` (with the scenario's comfort
    /// measure), in case order: the robust readout of one design, one run per case.
    pub fn case_criteria(&self, kind: ModelKind) -> Result<Vec<Criteria>> {
        let (ks, cs) = self.design();
        let set = self.cases("readout")?;
        set.cases
            .iter()
            .map(|c| {
                self.scenario
                    .comfort
                    .evaluator(kind, &c.car, &c.road)?
                    .evaluate(ks, cs)
            })
            .collect()
    }

    /// The design's criteria as the LoFi or HiFi map (`kind`) shows them at its point, with
    /// the scenario's comfort measure: without cases the car's; with `case` K that case's;
    /// otherwise the robust map's ([`robust_fields`], as `ridelab map --cases`): the cases'
    /// criteria each scaled to its own datum on `kind` (the loaded car's front spring and
    /// damper), combined by the set's rule, in case 0's units. One run per case.
    pub fn map_criteria(&mut self, kind: ModelKind) -> Result<Criteria> {
        let (ks, cs) = self.design();
        let comfort = self.scenario.comfort;
        let Some(set) = self.scenario.cases.as_ref() else {
            return self.scenario.evaluator(kind)?.evaluate(ks, cs);
        };
        let one = |k: usize, at: (f64, f64)| {
            let c = &set.cases[k];
            comfort
                .evaluator(kind, &c.car, &c.road)?
                .evaluate(at.0, at.1)
        };
        if let Some(k) = self.scenario.case {
            return one(k, (ks, cs));
        }
        let mut per = Vec::with_capacity(set.cases.len());
        let mut datums = Vec::with_capacity(set.cases.len());
        for (k, c) in set.cases.iter().enumerate() {
            per.push(one(k, (ks, cs))?);
            datums.push(one(k, (c.car.front.spring, c.car.front.damper))?);
        }
        Ok(Combination::new(set.combine, &datums, &set.probabilities())?.apply(&per))
    }

    /// The full analysis report of the design by one model (as `ridelab eval`).
    pub fn report(&self, kind: ModelKind) -> Result<Report> {
        match &self.scenario.measured {
            Some(m) => {
                m.0.report(kind, &self.scenario.datum, &self.scenario.design, true)
            }
            None => report(kind, &self.scenario.design, &self.scenario.road),
        }
    }

    /// The design's readout by one model: the report without its second route (see
    /// [`Readout`]), what the page shows while a slider moves.
    pub fn readout(&self, kind: ModelKind) -> Result<Readout> {
        match &self.scenario.measured {
            Some(m) => {
                m.0.readout(kind, &self.scenario.datum, &self.scenario.design)
            }
            None => readout(kind, &self.scenario.design, &self.scenario.road),
        }
    }

    /// What the page shows of a new design on a slider step, in one call: its LoFi
    /// readout, its surrogate criteria, its criteria on the objective plane's model
    /// `plane` (`None` when that is the surrogate) and with `with_hifi` its HiFi readout
    /// (`None` when that fails or is not finite: the HiFi worker's full report says why).
    /// Errors as the first of [`Self::readout`] and [`Self::criteria`] to fail.
    /// Both models' readouts leave out the report's frequency-route check (the quarter
    /// car's adaptive quadrature is 90 of the 104 us of its report natively, a third of a
    /// step; on a measured road, ten times the rest): the page asks for both full reports
    /// once the design rests, from its HiFi worker.
    pub fn design_step(&mut self, plane: Model, with_hifi: bool) -> Result<DesignStep> {
        let lofi = self.readout(ModelKind::Quarter)?;
        let surrogate = self.criteria(Model::Surrogate)?;
        let plane = match plane {
            Model::Surrogate => None,
            other => Some(self.criteria(other)?),
        };
        let hifi = with_hifi
            .then(|| self.readout(ModelKind::Full).ok())
            .flatten()
            .filter(|r| crate::finite::check(r).is_ok());
        Ok(DesignStep {
            lofi,
            surrogate,
            plane,
            hifi,
            tags: self.tags(),
        })
    }

    /// The map of `model` on the `nx` x `ny` cell-centre grid of the design box, its
    /// objectives judged against the model's own datum (errors name `nx` or `ny`). The
    /// LoFi's and HiFi's BAcc plane is the scenario's comfort measure; the surrogate's and
    /// the error map's are the unweighted BAcc.
    pub fn map(&mut self, model: Model, nx: usize, ny: usize) -> Result<ModelMap> {
        let grid = Grid::cells(&self.scenario.dbox, nx, ny)?;
        if model == Model::Robust {
            return self.robust_front_map(&grid);
        }
        if let (Some(n), Model::LoFi | Model::HiFi) =
            (self.scenario.cases.as_ref().map(|c| c.cases.len()), model)
        {
            return match self.scenario.case {
                Some(k) => {
                    let values = self.values_in(model, &grid, self.scenario.comfort, Some(k))?;
                    let dos = self.judge_case(&values, k, values.datum.criteria)?;
                    Ok(ModelMap { values, dos })
                }
                None => self.robust_map(model, &grid, n),
            };
        }
        if model == Model::SurrogateError {
            // The surrogate is fitted to the unweighted BAcc: it is compared with the HiFi's.
            let hifi = self.values_with(Model::HiFi, &grid, Comfort::Bacc)?;
            let sur = self.values(Model::Surrogate, &grid)?;
            let dos = self.judge(&hifi)?;
            return Ok(ModelMap {
                values: Rc::new(error_values(&sur, &hifi)),
                dos,
            });
        }
        let values = self.values(model, &grid)?;
        let dos = self.judge(&values)?;
        Ok(ModelMap { values, dos })
    }

    /// The design objectives on a model's absolute map (the datum's criteria are the map's).
    fn judge(&self, values: &Dcs) -> Result<DosMap> {
        let ctx = DosContext::new(&self.scenario.datum, values.datum.criteria);
        DosMap::new(values, &self.scenario.objectives, &ctx)
    }

    /// The design objectives on robust case `k`'s absolute map, in that case's context
    /// (its loaded car) against the datum criteria `datum`.
    fn judge_case(&self, values: &Dcs, k: usize, datum: Criteria) -> Result<DosMap> {
        let set = self.cases("map")?;
        let ctx = DosContext::new(&set.cases[k].car, datum);
        DosMap::new(values, &self.scenario.objectives, &ctx)
    }

    /// Every robust case's values of `model` on `grid` (kept or computed), each judged
    /// against its datum `datums[k]` (`None`: the case's own datum on `model`), combined
    /// by [`robust_fields`] with `combination` (`None`: the cases' own datums, as
    /// `ridelab map --cases`).
    fn combined(
        &mut self,
        model: Model,
        grid: &Grid,
        n: usize,
        hifi: Option<&[Criteria]>,
    ) -> Result<ModelMap> {
        let comfort = self.scenario.comfort;
        let values: Vec<Rc<Dcs>> = (0..n)
            .map(|k| self.values_in(model, grid, comfort, Some(k)))
            .collect::<Result<_>>()?;
        let doses: Vec<DosMap> = values
            .iter()
            .enumerate()
            .map(|(k, v)| self.judge_case(v, k, hifi.map_or(v.datum.criteria, |d| d[k])))
            .collect::<Result<_>>()?;
        let fields: Vec<CaseField> = values
            .iter()
            .zip(&doses)
            .enumerate()
            .map(|(k, (v, d))| CaseField {
                evaluator: &v.evaluator,
                datum: DatumPoint {
                    criteria: hifi.map_or(v.datum.criteria, |h| h[k]),
                    ..v.datum
                },
                bacc: &v.bacc,
                dtl: &v.dtl,
                sws: &v.sws,
                mask: &d.mask,
            })
            .collect();
        let set = self.cases("map")?;
        let active = doses[0].active.clone();
        let (abs, dos) = robust_fields(set, *grid, &self.scenario.objectives, active, &fields)?;
        Ok(ModelMap {
            values: Rc::new(abs),
            dos,
        })
    }

    /// The robust map of `model` (LoFi or HiFi) over the `n` cases: the fields and mask
    /// of `ridelab map --cases` (each case against its own datum on `model`).
    fn robust_map(&mut self, model: Model, grid: &Grid, n: usize) -> Result<ModelMap> {
        self.combined(model, grid, n, None)
    }

    /// The robust front's problem on `grid`: the LoFi's robust objective with each case
    /// scaled to, and judged against, its HiFi datum ([`hifi_combination`], as
    /// `ridelab optimize --cases`), so the plane's feasible set and its front agree.
    fn robust_front_map(&mut self, grid: &Grid) -> Result<ModelMap> {
        let n = self.cases("front")?.cases.len();
        let robust = self.robust_combination()?;
        self.combined(Model::LoFi, grid, n, Some(&robust.1))
    }

    /// A model's values on `grid` with the scenario's comfort measure, kept or computed.
    fn values(&mut self, model: Model, grid: &Grid) -> Result<Rc<Dcs>> {
        self.values_with(model, grid, self.scenario.comfort)
    }

    /// A model's values on `grid` with `comfort`, kept or computed.
    fn values_with(&mut self, model: Model, grid: &Grid, comfort: Comfort) -> Result<Rc<Dcs>> {
        self.values_in(model, grid, comfort, None)
    }

    /// A model's values on `grid` with `comfort` in the LoFi's or HiFi's BAcc plane (the
    /// surrogate's is always the unweighted BAcc), for robust case `case`'s loaded car and
    /// road (`None`: the scenario's car and road), kept or computed.
    fn values_in(
        &mut self,
        model: Model,
        grid: &Grid,
        comfort: Comfort,
        case: Option<usize>,
    ) -> Result<Rc<Dcs>> {
        let comfort = match model {
            Model::LoFi | Model::HiFi | Model::Robust => comfort,
            Model::Surrogate | Model::SurrogateError => Comfort::Bacc,
        };
        if let Some(k) = self
            .kept
            .iter()
            .find(|k| k.model == model && k.grid == *grid && k.comfort == comfort && k.case == case)
        {
            return Ok(Rc::clone(&k.values));
        }
        let s = &self.scenario;
        let loaded = match case {
            Some(k) => Some(&self.cases("map")?.cases[k]),
            None => None,
        };
        let car = loaded.map_or(&s.datum, |c| &c.car);
        let at = (car.front.spring, car.front.damper);
        // The scenario's car on its road (measured or not), or a case's loaded car and road.
        let model_on = |kind: ModelKind| match loaded {
            Some(c) => comfort.evaluator(kind, &c.car, &c.road),
            None => s.evaluator_with(kind, comfort),
        };
        let v = Rc::new(match model {
            Model::LoFi | Model::Robust => {
                let e = model_on(ModelKind::Quarter)?;
                Dcs::compute(&*e, grid, at, Scale::Absolute)?
            }
            Model::HiFi => {
                let e = model_on(ModelKind::Full)?;
                Dcs::compute(&*e, grid, at, Scale::Absolute)?
            }
            Model::Surrogate | Model::SurrogateError => {
                let fit = self.surrogate()?;
                // As a trait object, as the maps take every surrogate: one compiled map.
                let model: &dyn Surrogate = &fit.model;
                Dcs::compute(model, grid, at, Scale::Absolute)?
            }
        });
        self.keep(model, *grid, comfort, case, Rc::clone(&v), ComputePath::Cpu);
        Ok(v)
    }

    /// Keeps `values` of `model` on `grid`, replacing any kept there, the oldest going
    /// past [`KEPT_MAPS`].
    fn keep(
        &mut self,
        model: Model,
        grid: Grid,
        comfort: Comfort,
        case: Option<usize>,
        values: Rc<Dcs>,
        path: ComputePath,
    ) {
        self.kept.retain(|k| {
            !(k.model == model && k.grid == grid && k.comfort == comfort && k.case == case)
        });
        if self.kept.len() >= KEPT_MAPS {
            self.kept.remove(0);
        }
        self.kept.push(Kept {
            model,
            grid,
            comfort,
            case,
            values,
            path,
        });
    }

    /// Keeps HiFi criteria computed on the GPU path for the current scenario on the
    /// `nx` x `ny` cell-centre grid of its design box: `planes` as a map's `values`
    /// (BAcc m/s^2, DTL N, SWS m planes, each row-major with Cs rows; `3 nx ny` finite
    /// positive numbers, else an error naming `values`). The HiFi and surrogate-error maps
    /// on that grid then show them (the datum's criteria stay the CPU HiFi's) until the
    /// car, road, box or surrogate change.
    pub fn keep_hifi_planes(&mut self, nx: usize, ny: usize, planes: &[f64]) -> Result<()> {
        self.scenario.gpu_on_iso()?;
        let grid = Grid::cells(&self.scenario.dbox, nx, ny)?;
        let values = criteria_of_planes(planes, grid.len(), &format!("3 x {nx} x {ny}"))?;
        let given = HiFiGrid::from_values(self.scenario.hifi()?, grid, values, ComputePath::Gpu);
        let datum = &self.scenario.datum;
        let at = (datum.front.spring, datum.front.damper);
        let dcs = Dcs::compute_with_threads(&given, &grid, at, Scale::Absolute, 1)?;
        // The GPU kernel computes the unweighted BAcc.
        self.keep(
            Model::HiFi,
            grid,
            Comfort::Bacc,
            None,
            Rc::new(dcs),
            ComputePath::Gpu,
        );
        Ok(())
    }

    /// The path that computed the kept HiFi values on the `nx` x `ny` cell-centre grid,
    /// `None` when none are kept there.
    pub fn hifi_path(&self, nx: usize, ny: usize) -> Option<ComputePath> {
        let grid = Grid::cells(&self.scenario.dbox, nx, ny).ok()?;
        self.kept
            .iter()
            .find(|k| {
                k.model == Model::HiFi
                    && k.grid == grid
                    && k.comfort == self.scenario.comfort
                    && k.case.is_none()
            })
            .map(|k| k.path)
    }

    /// The Pareto front of comfort and DTL on `model` by `method` ("stm" or "nsga2"), the
    /// scenario's pick on it re-checked on the HiFi (both with the scenario's comfort
    /// measure). The surrogate is fitted to the unweighted BAcc: with Wk comfort its front
    /// is refused (an error naming `comfort`), as `ridelab optimize --comfort wk` refuses it.
    ///
    /// With robust cases the LoFi's front is the robust one ([`Session::robust_front`]).
    pub fn front(&mut self, method: &str, model: Model) -> Result<FrontResult> {
        if self.scenario.cases.is_some() {
            return self.robust_front(method, model);
        }
        self.single_front(method, model)
    }

    /// With robust cases, the LoFi's robust front ([`Model::Robust`], as `ridelab
    /// optimize --cases`: every case's datum is its HiFi datum); the surrogate is fitted to
    /// one case, so its front is refused (an error naming `cases`); without cases an error
    /// naming `cases`. The page's workers answer it: its first-screen wasm leaves the
    /// robust optimisation out (issue #29).
    pub fn robust_front(&self, method: &str, model: Model) -> Result<FrontResult> {
        let set = self.cases("front")?;
        match model {
            Model::LoFi | Model::Robust => {
                studies::robust_front(&self.scenario, set, method, ModelKind::Quarter)
            }
            Model::Surrogate => Err(RideError::field(
                "cases",
                "the surrogate is fitted to the car as given (one case); the robust front is the LoFi's",
            )),
            Model::HiFi | Model::SurrogateError => Err(model.refused("frontModel", Model::FRONT)),
        }
    }

    /// The front of a scenario without robust cases ([`Session::front`]); with cases an
    /// error naming `cases` (their front is [`Session::robust_front`]'s).
    pub fn single_front(&mut self, method: &str, model: Model) -> Result<FrontResult> {
        if self.scenario.cases.is_some() {
            return Err(RideError::field(
                "cases",
                "with robust cases the front is the robust one (robustFront)",
            ));
        }
        match model {
            Model::Robust => Err(self.cases("front").unwrap_err()),
            Model::LoFi => {
                let lofi = self.scenario.evaluator(ModelKind::Quarter)?;
                studies::front(&self.scenario, method, &*lofi)
            }
            Model::Surrogate if self.scenario.comfort == Comfort::Wk => Err(RideError::field(
                "comfort",
                "wk: the surrogates are fitted to the unweighted BAcc; the Wk front is the LoFi's",
            )),
            Model::Surrogate => {
                let fit = self.surrogate()?;
                let model: &dyn Surrogate = &fit.model;
                studies::front(&self.scenario, method, model)
            }
            Model::HiFi | Model::SurrogateError => Err(model.refused("frontModel", Model::FRONT)),
        }
    }

    /// The HiFi's own front (STM on the full car, the page's settings) and the objective
    /// plane's front (the surrogate's; with Wk comfort the LoFi's) judged on the HiFi
    /// against it ([`hifi_front::hifi_front`]). `grid_planes`: the HiFi criteria of STM's
    /// starting grid from the GPU (`GpuMaps.stmGrid`'s `values`: BAcc, DTL, SWS planes of
    /// `STM_GRID^2` designs; errors name `values`), or `None` for the CPU HiFi.
    /// With robust cases both fronts are the robust ones ([`hifi_front::robust_hifi_front`]:
    /// `ridelab optimize --cases --evaluator full` against the plane's LoFi robust front),
    /// on the CPU (GPU values are refused naming `cases`).
    pub fn hifi_front(&mut self, grid_planes: Option<&[f64]>) -> Result<HifiFrontView> {
        if let Some(set) = self.scenario.cases.clone() {
            if grid_planes.is_some() {
                return Err(RideError::field(
                    "cases",
                    "the GPU grid is one case's; the robust HiFi front runs on the CPU",
                ));
            }
            let plane = self.front("stm", Model::Robust)?;
            return hifi_front::robust_hifi_front(&self.scenario, &set, &plane);
        }
        let n = studies::STM_GRID * studies::STM_GRID;
        let given = match grid_planes {
            Some(p) => {
                self.scenario.gpu_on_iso()?;
                Some(criteria_of_planes(p, n, &format!("3 x {n}"))?)
            }
            None => None,
        };
        let (model, name, runs) = match self.scenario.comfort {
            Comfort::Wk => (Model::LoFi, "lofi", 0),
            Comfort::Bacc => (
                Model::Surrogate,
                "surrogate",
                self.surrogate()?.samples.len(),
            ),
        };
        let plane = self.front("stm", model)?;
        // The plane's pick costs one HiFi run more: its re-check.
        hifi_front::hifi_front(&self.scenario, &plane, name, runs + 1, given.as_deref())
    }

    /// FRFs and PSDs of the design by the LoFi, the HiFi and the surrogate.
    pub fn spectra(&mut self, nfreq: usize) -> Result<Spectra> {
        let fit = self.surrogate()?;
        studies::spectra(&self.scenario, &fit, nfreq)
    }

    /// Seeded time responses of the design by both models (as `ridelab simulate`).
    pub fn time_response(&self, opt: &TimeOptions) -> Result<TimeResult> {
        studies::time_response(&self.scenario, opt)
    }

    /// The surrogate's fit report validated on a `levels x levels` HiFi grid (as
    /// `ridelab surrogate`), on the session's fit (fitted here if not yet; the HiFi
    /// validation grid takes a while, so the page runs it in a worker).
    pub fn fit_report(&mut self, levels: usize) -> Result<SurrogateReport> {
        let fitted = self.surrogate()?;
        fit_report(&self.scenario, &fitted, levels)
    }

    /// The surrogate fits this session has made: one per scenario change that asks for
    /// the surrogate (its maps, front, readout or fit report), whatever asks.
    pub fn fit_count(&self) -> u64 {
        self.fits
    }

    /// The study report of this scenario: its study's ([`Scenario::study`]) report with
    /// the view's surrogate and plan, seed 1, as `ridelab report` (with `--road FILE` on a
    /// measured road) writes it. It is of the car as given: with robust cases, those take
    /// the maps and fronts. It takes seconds, so the page runs it in a worker.
    pub fn study_report(&self) -> Result<MethodReport> {
        let s = &self.scenario;
        let study = StudySpec {
            cases: None,
            ..s.study()
        };
        study.report(Some((s.surrogate, s.plan)), 1, |_| {})
    }

    fn design(&self) -> (f64, f64) {
        let f = &self.scenario.design.front;
        (f.spring, f.damper)
    }
}

/// A slider step's results ([`Session::design_step`]).
#[derive(Debug, Clone, serde::Serialize)]
pub struct DesignStep {
    /// The design's LoFi readout (`ridelab eval --model quarter`'s numbers, without its
    /// frequency-route check).
    pub lofi: Readout,
    /// The design's surrogate criteria (m/s^2, N, m).
    pub surrogate: Criteria,
    /// Its criteria on the objective plane's model; `None` when that is the surrogate.
    pub plane: Option<Criteria>,
    /// Its HiFi readout, when asked for and it succeeds.
    pub hifi: Option<Readout>,
    /// The session's tags at the design.
    pub tags: Tags,
}

/// `planes` (BAcc m/s^2, DTL N, SWS m planes of `n` designs each, a map's `values`
/// layout) as criteria; `3 n` finite positive numbers (`size` says how many in words),
/// else an error naming `values`.
fn criteria_of_planes(planes: &[f64], n: usize, size: &str) -> Result<Vec<Criteria>> {
    if planes.len() != 3 * n {
        return Err(RideError::field(
            "values",
            format!(
                "must hold {size} = {} numbers (got {})",
                3 * n,
                planes.len()
            ),
        ));
    }
    if let Some(k) = planes.iter().position(|v| !(v.is_finite() && *v > 0.0)) {
        return Err(RideError::field(
            "values",
            format!(
                "value {k} is {}, not a finite positive criterion",
                planes[k]
            ),
        ));
    }
    Ok((0..n)
        .map(|k| Criteria::from_array([planes[k], planes[n + k], planes[2 * n + k]]))
        .collect())
}
