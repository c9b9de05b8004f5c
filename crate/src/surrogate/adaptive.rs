//! Adaptive HiFi sampling (issue #15): start from a plan of `N0` HiFi runs, then add `K`
//! runs one at a time where the infill criterion ([`super::infill`]) says the decision
//! gains most, refitting the surrogate and its uncertainty after each; and the study that
//! compares the loop with Audze-Eglais plans of the same size on the HiFi.
//!
//! One step of [`AdaptiveLoop`]: fit the surrogate and its uncertainty to the samples, find
//! its feasible front by STM and the min-max pick, score the candidates, propose the best
//! ([`AdaptiveLoop::propose`]); the caller runs the HiFi there and hands the result back
//! ([`AdaptiveLoop::add`]), or lets the loop do both ([`AdaptiveLoop::step`]). [`run`] is
//! a plan plus `K` steps: the CLI's `--plan ae:5 --adaptive 5`, and what a page's "next
//! HiFi run" button repeats one step at a time, so both give the same samples.
//!
//! Bounds: `N0 + K <= ` [`MAX_HIFI_RUNS`] `= 100` HiFi samples (the explorer's plan bound),
//! candidate grid 2..=201 points per axis, minimum distance in `(0, 0.5]` normalised units.
//! Errors name the field: `adaptive`, `candidates`, `min-distance`, `plan`.

use super::fit::LmOptions;
use super::infill::{choose, reason, Candidate, Infill, InfillSetting};
use super::spec::PlanSpec;
use super::study::{Fitted, SurrogateReport};
use super::uncertainty::{Uncertain, UncertaintyMethod};
use super::{sample_plan, Sample, Setting, Surrogate, SurrogateSpec};
use crate::analysis::HiFi;
use crate::car::Car;
use crate::design::DesignBox;
use crate::dos::{DesignObjectives, DosContext};
use crate::error::{Result, RideError};
use crate::evaluate::{Criteria, Evaluator};
use crate::optimize::study::REFERENCE_MARGIN;
use crate::optimize::{
    hypervolume, min_max_pick, optimize_model, recheck, reference_point, stm, Counted,
    EvaluatorSpec, FrontPoint, Method, OptimizeReport, Pick, StmParams, SuspensionProblem,
};
use crate::road::Road;
use serde::{Deserialize, Serialize};
use std::fmt::Write;

/// Most HiFi samples a loop may hold (initial plan plus adaptive runs), the explorer's
/// `MAX_PLAN_POINTS`.
pub const MAX_HIFI_RUNS: usize = 100;

/// Default candidate grid, points per axis (`41 x 41`).
pub const DEFAULT_CANDIDATES: usize = 41;

/// Default minimum normalised distance of a new sample to every sample (2 % of the box).
pub const DEFAULT_MIN_DISTANCE: f64 = 0.02;

/// Settings of the adaptive loop.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct AdaptiveOptions {
    /// Adaptive HiFi runs `K` after the initial plan.
    pub runs: usize,
    /// Seed of the Levenberg-Marquardt starts (VBA, PBA); the rest is deterministic.
    pub seed: u64,
    /// The infill criterion.
    pub criterion: Infill,
    /// The uncertainty estimate; `None`: the surrogate's own where it has one, else LOO.
    pub uncertainty: Option<UncertaintyMethod>,
    /// Candidate grid points per axis, 2..=201.
    pub candidates: usize,
    /// Minimum normalised distance of a new sample to every sample, `(0, 0.5]`.
    pub min_distance: f64,
}

impl Default for AdaptiveOptions {
    /// No adaptive runs, seed 1, EHVI over the predicted front, the default
    /// uncertainty, a `41 x 41` candidate grid, minimum distance 0.02.
    fn default() -> Self {
        AdaptiveOptions {
            runs: 0,
            seed: 1,
            criterion: Infill::EhviFront,
            uncertainty: None,
            candidates: DEFAULT_CANDIDATES,
            min_distance: DEFAULT_MIN_DISTANCE,
        }
    }
}

impl AdaptiveOptions {
    /// Checks the options for an initial plan of `initial` samples; errors name the field.
    pub fn check(&self, initial: usize) -> Result<()> {
        if initial.saturating_add(self.runs) > MAX_HIFI_RUNS {
            return Err(RideError::field(
                "adaptive",
                format!(
                    "{initial} initial + {} adaptive HiFi runs exceed the {MAX_HIFI_RUNS} allowed",
                    self.runs
                ),
            ));
        }
        if !(2..=201).contains(&self.candidates) {
            return Err(RideError::field(
                "candidates",
                format!("needs 2 to 201 points per axis, got {}", self.candidates),
            ));
        }
        if !(self.min_distance > 0.0 && self.min_distance <= 0.5) {
            return Err(RideError::field(
                "min-distance",
                format!(
                    "needs 0 < distance <= 0.5 (normalised), got {}",
                    self.min_distance
                ),
            ));
        }
        Ok(())
    }

    /// The uncertainty method used for `spec`.
    pub fn uncertainty_for(&self, spec: &SurrogateSpec) -> UncertaintyMethod {
        self.uncertainty
            .unwrap_or_else(|| UncertaintyMethod::default_for(spec))
    }

    fn lm(&self) -> LmOptions {
        LmOptions {
            seed: self.seed,
            ..LmOptions::default()
        }
    }
}

/// What the decision is: the design objectives, the car context they are judged in, and
/// how fronts are found.
#[derive(Debug, Clone, PartialEq)]
pub struct Decision {
    /// The design objectives (the SWS limit among them).
    pub objectives: DesignObjectives,
    /// The car context (sprung mass, tyre rate, datum criteria).
    pub ctx: DosContext,
    /// STM settings of every front.
    pub stm: StmParams,
}

impl Decision {
    /// The decision of `car` on the HiFi `hifi`: default objectives, the datum's HiFi
    /// criteria (one HiFi run), default STM (201 x 201, 3 levels), as `ridelab optimize`.
    pub fn of_car<E: Evaluator + ?Sized>(car: &Car, hifi: &E) -> Result<Decision> {
        Ok(Decision {
            objectives: DesignObjectives::default(),
            ctx: DosContext::of_model(car, hifi)?,
            stm: StmParams::default(),
        })
    }

    /// The feasible front of `model` over `design_box` by STM, sorted by increasing BAcc.
    pub fn front<E: Evaluator>(&self, model: E, design_box: &DesignBox) -> Result<Vec<FrontPoint>> {
        let problem =
            SuspensionProblem::new(model, *design_box, self.objectives.clone(), self.ctx)?;
        Ok(FrontPoint::from_solutions(&stm(&problem, &self.stm)?))
    }
}

/// The next HiFi run the loop proposes.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Proposal {
    /// The chosen candidate and its scores.
    pub candidate: Candidate,
    /// Why, in words.
    pub reason: String,
}

/// One sample the loop added.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Added {
    /// Its number among all HiFi samples, 1-based (the initial plan's come first).
    pub run: usize,
    /// The sample (design and HiFi criteria).
    pub sample: Sample,
    /// The candidate's scores when it was chosen.
    pub candidate: Candidate,
    /// Why it was chosen.
    pub reason: String,
}

/// The surrogate's front and pick after a number of HiFi samples.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Step {
    /// HiFi samples the surrogate was fitted to.
    pub hifi_runs: usize,
    /// Points of its feasible front.
    pub front_points: usize,
    /// The front's hypervolume on the surrogate against the loop's reference point,
    /// (m/s^2) N.
    pub hypervolume: f64,
    /// Its min-max pick (as the surrogate predicts it).
    pub pick: Pick,
}

/// What [`run`] reports: the samples in the order they were added, with the reasons.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AdaptiveReport {
    /// Canonical surrogate name.
    pub surrogate: String,
    /// The initial plan (`ae:5`).
    pub plan: String,
    /// The options.
    pub options: AdaptiveOptions,
    /// The uncertainty estimate used.
    pub uncertainty: UncertaintyMethod,
    /// Hypervolume reference point `[BAcc (m/s^2), DTL (N)]`: `nadir + 0.1 (nadir - ideal)`
    /// of the surrogate's front on the initial plan, fixed for the whole loop.
    pub reference_point: [f64; 2],
    /// The initial plan's HiFi samples.
    pub initial: Vec<Sample>,
    /// The adaptive samples, in the order added.
    pub added: Vec<Added>,
    /// Front and pick after the initial plan and after each added sample.
    pub history: Vec<Step>,
}

/// The state of an adaptive loop: samples, the fitted surrogate with its uncertainty, its
/// front and pick.
pub struct AdaptiveLoop {
    spec: SurrogateSpec,
    setting: Setting,
    decision: Decision,
    options: AdaptiveOptions,
    plan: String,
    samples: Vec<Sample>,
    initial: usize,
    fitted: Uncertain,
    front: Vec<FrontPoint>,
    pick: Pick,
    reference: [f64; 2],
    added: Vec<Added>,
    history: Vec<Step>,
}

impl AdaptiveLoop {
    /// Fits `spec` to the `initial` samples (named `plan` in reports) and finds its front.
    /// `options.runs` is not used here (see [`run`]); the other options are checked.
    pub fn new(
        spec: SurrogateSpec,
        setting: Setting,
        decision: Decision,
        plan: String,
        initial: Vec<Sample>,
        options: AdaptiveOptions,
    ) -> Result<AdaptiveLoop> {
        options.check(initial.len())?;
        let method = options.uncertainty_for(&spec);
        let fitted = Uncertain::fit(&spec, &setting, &initial, &options.lm(), method)?;
        let front = decision.front(&*fitted.model, &setting.design_box)?;
        let objectives: Vec<[f64; 2]> = front.iter().map(|p| [p.bacc, p.dtl]).collect();
        let reference = reference_point(&objectives, REFERENCE_MARGIN);
        let pick = min_max_pick(&front, &decision.ctx.datum)?;
        let mut state = AdaptiveLoop {
            spec,
            setting,
            decision,
            options,
            plan,
            initial: initial.len(),
            samples: initial,
            fitted,
            front,
            pick,
            reference,
            added: Vec::new(),
            history: Vec::new(),
        };
        state.record();
        Ok(state)
    }

    /// Appends the current front and pick to the history.
    fn record(&mut self) {
        let f: Vec<[f64; 2]> = self.front.iter().map(|p| [p.bacc, p.dtl]).collect();
        self.history.push(Step {
            hifi_runs: self.samples.len(),
            front_points: self.front.len(),
            hypervolume: hypervolume(&f, self.reference),
            pick: self.pick.clone(),
        });
    }

    /// Where the next HiFi run should go, and why. Errors (naming `adaptive`) when the
    /// loop holds [`MAX_HIFI_RUNS`] samples or every candidate is too close to a sample.
    pub fn propose(&self) -> Result<Proposal> {
        if self.samples.len() >= MAX_HIFI_RUNS {
            return Err(RideError::field(
                "adaptive",
                format!("the loop holds {MAX_HIFI_RUNS} HiFi samples, the most allowed"),
            ));
        }
        let set = InfillSetting {
            objectives: &self.decision.objectives,
            ctx: &self.decision.ctx,
            design_box: &self.setting.design_box,
            front: &self.front,
            reference: self.reference,
            grid: self.options.candidates,
            min_distance: self.options.min_distance,
        };
        let candidate = choose(self.options.criterion, &self.fitted, &set, &self.samples)?
            .ok_or_else(|| {
                RideError::field(
                    "adaptive",
                    format!(
                        "every candidate lies within {} of a sample",
                        self.options.min_distance
                    ),
                )
            })?;
        Ok(Proposal {
            reason: reason(
                self.options.criterion,
                &candidate,
                self.decision.objectives.sws_limit,
            ),
            candidate,
        })
    }

    /// Adds the HiFi result `hifi` at the `proposal`'s design, refits, and finds the new
    /// front and pick.
    pub fn add(&mut self, proposal: Proposal, hifi: Criteria) -> Result<&Added> {
        let sample = Sample {
            ks: proposal.candidate.ks,
            cs: proposal.candidate.cs,
            hifi,
        };
        let mut samples = self.samples.clone();
        samples.push(sample);
        let method = self.fitted.method;
        let fitted = Uncertain::fit(
            &self.spec,
            &self.setting,
            &samples,
            &self.options.lm(),
            method,
        )?;
        let front = self
            .decision
            .front(&*fitted.model, &self.setting.design_box)?;
        self.pick = min_max_pick(&front, &self.decision.ctx.datum)?;
        self.front = front;
        self.fitted = fitted;
        self.samples = samples;
        self.added.push(Added {
            run: self.samples.len(),
            sample,
            candidate: proposal.candidate,
            reason: proposal.reason,
        });
        self.record();
        Ok(&self.added[self.added.len() - 1])
    }

    /// Proposes, runs `hifi` there, and adds the result.
    pub fn step<E: Evaluator + ?Sized>(&mut self, hifi: &E) -> Result<&Added> {
        let proposal = self.propose()?;
        let c = hifi.evaluate(proposal.candidate.ks, proposal.candidate.cs)?;
        self.add(proposal, c)
    }

    /// The fitted surrogate.
    pub fn model(&self) -> &dyn Surrogate {
        &*self.fitted.model
    }

    /// The fitted surrogate with its uncertainty estimate (its map).
    pub fn uncertain(&self) -> &Uncertain {
        &self.fitted
    }

    /// All samples, in the order they were added.
    pub fn samples(&self) -> &[Sample] {
        &self.samples
    }

    /// The surrogate's current feasible front.
    pub fn front(&self) -> &[FrontPoint] {
        &self.front
    }

    /// The current min-max pick.
    pub fn pick(&self) -> &Pick {
        &self.pick
    }

    /// The report so far.
    pub fn report(&self) -> AdaptiveReport {
        AdaptiveReport {
            surrogate: self.spec.name(),
            plan: self.plan.clone(),
            options: self.options,
            uncertainty: self.fitted.method,
            reference_point: self.reference,
            initial: self.samples[..self.initial].to_vec(),
            added: self.added.clone(),
            history: self.history.clone(),
        }
    }

    /// The fitted surrogate, the loop ended.
    pub fn into_model(self) -> Box<dyn Surrogate> {
        self.fitted.model
    }
}

/// The HiFi samples of `plan` over `setting`'s box, then `options.runs` adaptive steps
/// (module doc): the loop with its report and final model.
pub fn run<E: Evaluator + ?Sized>(
    spec: SurrogateSpec,
    setting: &Setting,
    hifi: &E,
    plan: PlanSpec,
    decision: &Decision,
    options: AdaptiveOptions,
) -> Result<AdaptiveLoop> {
    let points = plan.plan()?;
    options.check(points.unit.len())?;
    let initial = sample_plan(&hifi, &points, &setting.design_box)?;
    let mut state = AdaptiveLoop::new(
        spec,
        setting.clone(),
        decision.clone(),
        plan.name(),
        initial,
        options,
    )?;
    for _ in 0..options.runs {
        state.step(hifi)?;
    }
    Ok(state)
}

/// `ridelab surrogate --plan PLAN --adaptive K`: the loop on `car` and `road` over
/// `design_box` (default objectives, the datum's HiFi criteria, default STM), then the
/// final surrogate's report as [`super::surrogate_report_in`] gives it for a plain plan,
/// with the loop's report in `adaptive`. Errors name the loop's fields, `plan` or
/// `predict-grid`.
pub fn surrogate_report(
    spec: SurrogateSpec,
    plan: PlanSpec,
    car: &Car,
    road: &Road,
    design_box: &DesignBox,
    predict_grid: Option<usize>,
    options: AdaptiveOptions,
) -> Result<SurrogateReport> {
    let setting = Setting::new(car, road, design_box)?;
    let hifi = Counted::new(HiFi::new(car, road)?);
    let decision = Decision::of_car(car, &hifi)?;
    let state = run(spec, &setting, &hifi, plan, &decision, options)?;
    let report = state.report();
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
        samples: state.samples().to_vec(),
        model: state.into_model(),
        options: options.lm(),
        adaptive: Some(report),
    };
    fitted.report(&setting, &hifi, predict_grid)
}

/// `ridelab optimize` with an adaptive surrogate: the optimisation report with the loop's
/// report beside it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AdaptiveOptimizeReport {
    /// Front, pick and HiFi re-check, as `ridelab optimize` gives them.
    #[serde(flatten)]
    pub optimize: OptimizeReport,
    /// The loop that chose the surrogate's samples.
    pub adaptive: AdaptiveReport,
}

/// `ridelab optimize --evaluator SURROGATE --plan PLAN --adaptive K`: the loop judged by the
/// same objectives (against the datum's HiFi criteria) and, for STM, the same STM settings
/// as the optimisation, then [`optimize_model`] on its final surrogate. Errors name
/// `adaptive` for a model evaluator (the loop refits a surrogate), and the loop's fields.
pub fn optimize_report(
    car: &Car,
    road: &Road,
    evaluator: EvaluatorSpec,
    plan: PlanSpec,
    method: &Method,
    objectives: DesignObjectives,
    options: AdaptiveOptions,
) -> Result<AdaptiveOptimizeReport> {
    let EvaluatorSpec::Surrogate(spec) = evaluator else {
        return Err(RideError::field(
            "adaptive",
            "the adaptive loop refits a surrogate; give a surrogate --evaluator",
        ));
    };
    objectives.validate()?;
    let design_box = DesignBox::default();
    let setting = Setting::new(car, road, &design_box)?;
    let hifi = HiFi::new(car, road)?;
    let decision = Decision {
        objectives: objectives.clone(),
        ctx: DosContext::of_model(car, &hifi)?,
        stm: match method {
            Method::Stm(p) => p.clone(),
            Method::Nsga2(_) => StmParams::default(),
        },
    };
    let state = run(spec, &setting, &hifi, plan, &decision, options)?;
    let adaptive = state.report();
    let model: Box<dyn Evaluator + Sync> = Box::new(state.into_model());
    Ok(AdaptiveOptimizeReport {
        optimize: optimize_model(car, road, model, method, objectives)?,
        adaptive,
    })
}

/// The reference HiFi front of a scenario: STM on the HiFi itself (the decision's
/// settings: by default a 201 x 201 grid, 3 refinement levels and the boundary bisection,
/// about 48 000 HiFi runs), the yardstick of every front of the study.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct HifiFront {
    /// STM settings.
    pub stm: StmParams,
    /// HiFi runs it took.
    pub hifi_runs: usize,
    /// Points of the front.
    pub front_points: usize,
    /// Reference point `nadir + 0.1 (nadir - ideal)` of the front `[BAcc (m/s^2), DTL (N)]`.
    pub reference_point: [f64; 2],
    /// Its hypervolume, (m/s^2) N.
    pub hypervolume: f64,
    /// `[BAcc, DTL]` of the front (left out of reports).
    #[serde(skip)]
    pub front: Vec<[f64; 2]>,
}

impl HifiFront {
    /// STM with `decision` on `hifi` over `design_box`. Errors name the binding objective
    /// when no design is feasible.
    pub fn new<E: Evaluator + ?Sized>(
        hifi: &E,
        decision: &Decision,
        design_box: &DesignBox,
    ) -> Result<HifiFront> {
        let counted = Counted::new(hifi);
        let front: Vec<[f64; 2]> = decision
            .front(&counted, design_box)?
            .iter()
            .map(|p| [p.bacc, p.dtl])
            .collect();
        let reference_point = reference_point(&front, REFERENCE_MARGIN);
        Ok(HifiFront {
            stm: decision.stm.clone(),
            hifi_runs: counted.count(),
            front_points: front.len(),
            hypervolume: hypervolume(&front, reference_point),
            reference_point,
            front,
        })
    }
}

/// A surrogate's front and pick judged on the HiFi.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FrontCheck {
    /// HiFi samples the surrogate was fitted to.
    pub hifi_runs: usize,
    /// Points of the surrogate's feasible front.
    pub front_points: usize,
    /// Of those, the points that meet the design objectives on the HiFi.
    pub hifi_feasible_points: usize,
    /// Hypervolume of the front's designs re-evaluated on the HiFi (the HiFi-feasible ones)
    /// over the reference HiFi front's, both against the reference front's reference point, -.
    pub hypervolume_ratio: f64,
    /// Largest relative error `100 |S_k / F_k - 1|` over the front's designs and the three
    /// criteria, %.
    pub front_max_error_percent: f64,
    /// The pick's design `[Ks (N/m), Cs (N s/m)]`.
    pub pick: [f64; 2],
    /// The pick's HiFi re-check error `100 (S_k / F_k - 1)` of `[bacc, dtl, sws]`, %.
    pub recheck_percent: [f64; 3],
    /// Its largest magnitude, %.
    pub recheck_error_percent: f64,
}

/// Judges `model`'s front (found with `decision`) on `hifi` against `reference`.
pub fn front_check<E: Evaluator + ?Sized>(
    model: &dyn Surrogate,
    hifi: &E,
    decision: &Decision,
    design_box: &DesignBox,
    reference: &HifiFront,
    hifi_runs: usize,
) -> Result<FrontCheck> {
    let front = decision.front(model, design_box)?;
    let mut feasible = Vec::new();
    let mut worst: f64 = 0.0;
    for p in &front {
        let c = hifi.evaluate(p.ks, p.cs)?;
        let (s, f) = (p.criteria().to_array(), c.to_array());
        for k in 0..3 {
            worst = worst.max(100.0 * (s[k] / f[k] - 1.0).abs());
        }
        if decision.objectives.violation(&decision.ctx, p.ks, p.cs, &c) == 0.0 {
            feasible.push([c.bacc, c.dtl]);
        }
    }
    let pick = min_max_pick(&front, &decision.ctx.datum)?;
    let r = recheck(&pick, hifi, &decision.ctx.datum)?;
    Ok(FrontCheck {
        hifi_runs,
        front_points: front.len(),
        hifi_feasible_points: feasible.len(),
        hypervolume_ratio: hypervolume(&feasible, reference.reference_point)
            / reference.hypervolume,
        front_max_error_percent: worst,
        pick: [pick.ks, pick.cs],
        recheck_percent: r.error_percent,
        recheck_error_percent: r.error_percent.iter().fold(0.0, |m, e| m.max(e.abs())),
    })
}

/// Settings of the adaptive study.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct StudyOptions {
    /// Audze-Eglais points of the loop's initial plan.
    pub initial: usize,
    /// Smallest total of HiFi samples compared (> `initial`).
    pub min_runs: usize,
    /// Largest total of HiFi samples compared (<= [`MAX_HIFI_RUNS`]).
    pub max_runs: usize,
    /// STM settings of every front (the HiFi's own included).
    pub stm: StmParams,
    /// The loop's settings (`runs` is set by the study).
    pub adaptive: AdaptiveOptions,
}

impl Default for StudyOptions {
    /// 5 Audze-Eglais points, then 6 to 20 HiFi samples in all; default STM (201 x 201,
    /// 3 levels).
    fn default() -> Self {
        StudyOptions {
            initial: 5,
            min_runs: 6,
            max_runs: 20,
            stm: StmParams::default(),
            adaptive: AdaptiveOptions::default(),
        }
    }
}

/// One sample budget of the study.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StudyRow {
    /// HiFi samples in all.
    pub hifi_runs: usize,
    /// The loop: the initial plan plus `hifi_runs - initial` adaptive samples.
    pub adaptive: FrontCheck,
    /// An Audze-Eglais plan of `hifi_runs` points.
    pub audze_eglais: FrontCheck,
}

/// The adaptive study's results.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AdaptiveStudy {
    /// Car name.
    pub car: String,
    /// Road scenario.
    pub road: Road,
    /// Canonical surrogate name.
    pub surrogate: String,
    /// The uncertainty estimate the loop used.
    pub uncertainty: UncertaintyMethod,
    /// The settings.
    pub options: StudyOptions,
    /// The reference HiFi front (STM on the HiFi).
    pub hifi_front: HifiFront,
    /// One row per sample budget, increasing.
    pub rows: Vec<StudyRow>,
    /// The loop's samples in the order added (the last budget's).
    pub samples: Vec<Sample>,
    /// Why each adaptive sample was chosen.
    pub reasons: Vec<String>,
    /// Wall time of the whole study, s (`None` in the browser, which has no clock here).
    pub seconds: Option<f64>,
}

/// The adaptive study of `spec` for `car` on `road` over the default box (module doc):
/// for every total `N` of HiFi samples from `min_runs` to `max_runs`, the loop (an
/// Audze-Eglais plan of `initial` points plus `N - initial` adaptive runs; one loop serves
/// every `N`, as it adds one sample at a time) against an Audze-Eglais plan of `N` points,
/// both judged on the HiFi by [`front_check`] against the HiFi's own STM front.
/// Errors name `initial`, `min_runs`, `max_runs` or the loop's fields.
pub fn adaptive_study(
    car: &Car,
    road: &Road,
    spec: SurrogateSpec,
    options: &StudyOptions,
) -> Result<AdaptiveStudy> {
    #[cfg(not(target_arch = "wasm32"))]
    let start = std::time::Instant::now();
    if options.initial < 2 {
        return Err(RideError::field("initial", "needs at least 2 points"));
    }
    if options.min_runs <= options.initial {
        return Err(RideError::field(
            "min_runs",
            format!("must exceed the {} initial points", options.initial),
        ));
    }
    if options.max_runs < options.min_runs || options.max_runs > MAX_HIFI_RUNS {
        return Err(RideError::field(
            "max_runs",
            format!(
                "needs min_runs ({}) <= max_runs <= {MAX_HIFI_RUNS}",
                options.min_runs
            ),
        ));
    }
    let design_box = DesignBox::default();
    let setting = Setting::new(car, road, &design_box)?;
    let hifi = HiFi::new(car, road)?;
    let decision = Decision {
        stm: options.stm.clone(),
        ..Decision::of_car(car, &hifi)?
    };
    let hifi_front = HifiFront::new(&hifi, &decision, &design_box)?;
    let adaptive = AdaptiveOptions {
        runs: options.max_runs - options.initial,
        ..options.adaptive
    };
    let plan = PlanSpec::AudzeEglais(options.initial);
    let initial = sample_plan(&hifi, &plan.plan()?, &design_box)?;
    let mut state = AdaptiveLoop::new(
        spec,
        setting.clone(),
        decision.clone(),
        plan.name(),
        initial,
        adaptive,
    )?;
    let lm = adaptive.lm();
    let mut rows = Vec::new();
    for n in options.initial + 1..=options.max_runs {
        state.step(&hifi)?;
        if n < options.min_runs {
            continue;
        }
        let looped = front_check(state.model(), &hifi, &decision, &design_box, &hifi_front, n)?;
        let ae = sample_plan(&hifi, &PlanSpec::AudzeEglais(n).plan()?, &design_box)?;
        let model = spec.fit(&setting, &ae, &lm)?;
        let fixed = front_check(&*model, &hifi, &decision, &design_box, &hifi_front, n)?;
        rows.push(StudyRow {
            hifi_runs: n,
            adaptive: looped,
            audze_eglais: fixed,
        });
    }
    let report = state.report();
    #[cfg(not(target_arch = "wasm32"))]
    let seconds = Some(start.elapsed().as_secs_f64());
    #[cfg(target_arch = "wasm32")]
    let seconds = None;
    Ok(AdaptiveStudy {
        car: car.name.clone(),
        road: *road,
        surrogate: spec.name(),
        uncertainty: report.uncertainty,
        options: StudyOptions {
            adaptive,
            ..options.clone()
        },
        hifi_front,
        rows,
        samples: state.samples().to_vec(),
        reasons: report.added.into_iter().map(|a| a.reason).collect(),
        seconds,
    })
}

impl AdaptiveStudy {
    /// The study as a markdown table.
    pub fn to_markdown(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(
            s,
            "# Adaptive HiFi sampling: {} ({:?} road, {} m/s), {} with {} uncertainty\n\n\
             Adaptive = Audze-Eglais {} + the rest by {}; AE = an Audze-Eglais plan of the same size. \
             HV ratio: the front's designs re-run on the HiFi, against STM on the HiFi itself \
             ({} HiFi runs, hypervolume {:.5} (m/s^2) N). Re-check: the min-max pick's largest \
             HiFi error. Front error: the largest error over the front's designs.{}\n",
            self.car,
            self.road.class,
            self.road.speed,
            self.surrogate,
            self.uncertainty.name(),
            self.options.initial,
            self.options.adaptive.criterion.name(),
            self.hifi_front.hifi_runs,
            self.hifi_front.hypervolume,
            self.seconds
                .map_or(String::new(), |t| format!(" Study time {t:.1} s.")),
        );
        let _ = writeln!(
            s,
            "| HiFi runs | re-check % adaptive | re-check % AE | HV ratio adaptive | HV ratio AE | front error % adaptive | front error % AE |"
        );
        let _ = writeln!(s, "|{}", "---|".repeat(7));
        for r in &self.rows {
            let (a, e) = (&r.adaptive, &r.audze_eglais);
            let _ = writeln!(
                s,
                "| {} | {:.3} | {:.3} | {:.5} | {:.5} | {:.3} | {:.3} |",
                r.hifi_runs,
                a.recheck_error_percent,
                e.recheck_error_percent,
                a.hypervolume_ratio,
                e.hypervolume_ratio,
                a.front_max_error_percent,
                e.front_max_error_percent
            );
        }
        s
    }
}
