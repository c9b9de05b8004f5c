//! Adaptive HiFi sampling (issue #15): start from a plan of `N0` HiFi runs, then add `K`
//! runs one at a time where the infill criterion ([`crate::surrogate::infill`]) says the decision
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
//! candidate grid 2..=201 points per axis, minimum distance in `(0, 0.5]` normalised units,
//! stop threshold in `[0, 0.01]`. Errors name the field: `adaptive`, `candidates`,
//! `min-distance`, `stop-below`, `plan`.
//!
//! Convergence: a proposal whose criterion `EHVI x PoF` is below `stop_below` times the
//! current front's hypervolume is [`Proposal::converged`]; [`run`] stops there and says
//! so ([`AdaptiveReport::stopped`]), while [`AdaptiveLoop::step`] (the page's button) runs
//! it anyway. The default [`DEFAULT_STOP_BELOW`] `= 1e-7`: on the sedan (ae:5 plus 25
//! runs, rba-mul-rbf-mq and gp-mul) the hypervolume changed by less than 0.03 % after the
//! first proposal below it, while the criterion went on falling to 1e-130 and to 0.

mod check;
mod reports;
mod study;

pub use check::{front_check, FrontCheck, HifiFront, HIFI_FEASIBILITY_TOLERANCE};
pub use reports::AdaptiveOptimizeReport;
pub(crate) use study::adaptive_study_on;
pub use study::{adaptive_study, AdaptiveStudy, StudyOptions, StudyRow};

use crate::car::Car;
use crate::design::DesignBox;
use crate::dos::{DesignObjectives, DosContext};
use crate::error::{Result, RideError};
use crate::evaluate::{Criteria, Evaluator};
use crate::optimize::study::REFERENCE_MARGIN;
use crate::optimize::{
    hypervolume, min_max_pick, reference_point, stm, FrontPoint, Method, Pick, StmParams,
    SuspensionProblem,
};
use crate::surrogate::fit::LmOptions;
use crate::surrogate::infill::{choose, reason, Candidate, Infill, InfillSetting};
use crate::surrogate::spec::PlanSpec;
use crate::surrogate::uncertainty::{Uncertain, UncertaintyMethod};
use crate::surrogate::{sample_plan, Sample, Setting, Surrogate, SurrogateSpec};
use serde::{Deserialize, Serialize};

/// Most HiFi samples a loop may hold (initial plan plus adaptive runs), the explorer's
/// `MAX_PLAN_POINTS`.
pub const MAX_HIFI_RUNS: usize = 100;

/// Default candidate grid, points per axis (`41 x 41`).
pub const DEFAULT_CANDIDATES: usize = 41;

/// Default minimum normalised distance of a new sample to every sample (2 % of the box).
pub const DEFAULT_MIN_DISTANCE: f64 = 0.02;

/// Default stop threshold: `EHVI x PoF` below this fraction of the front's hypervolume
/// (module doc).
const DEFAULT_STOP_BELOW: f64 = 1e-7;

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
    /// Stop threshold, `[0, 0.01]`: [`run`] stops when the best candidate's `EHVI x PoF`
    /// is below this fraction of the front's hypervolume (0: never), -.
    pub stop_below: f64,
}

impl Default for AdaptiveOptions {
    /// No adaptive runs, seed 1, EHVI over the predicted front, the default
    /// uncertainty, a `41 x 41` candidate grid, minimum distance 0.02, stop below 1e-7.
    fn default() -> Self {
        AdaptiveOptions {
            runs: 0,
            seed: 1,
            criterion: Infill::EhviFront,
            uncertainty: None,
            candidates: DEFAULT_CANDIDATES,
            min_distance: DEFAULT_MIN_DISTANCE,
            stop_below: DEFAULT_STOP_BELOW,
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
        if !(0.0..=0.01).contains(&self.stop_below) {
            return Err(RideError::field(
                "stop-below",
                format!(
                    "needs 0 <= threshold <= 0.01 (a fraction of the front's hypervolume), got {}",
                    self.stop_below
                ),
            ));
        }
        Ok(())
    }

    /// The uncertainty method used for `spec`.
    fn uncertainty_for(&self, spec: &SurrogateSpec) -> UncertaintyMethod {
        self.uncertainty
            .unwrap_or_else(|| UncertaintyMethod::default_for(spec))
    }

    pub(crate) fn lm(&self) -> LmOptions {
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

    /// The decision an optimisation by `method` judges by: `objectives`, the datum's
    /// criteria on `hifi` (one run), and `method`'s STM settings (STM's defaults for
    /// NSGA-II), so that the loop's fronts are the optimisation's.
    pub(crate) fn for_method<E: Evaluator + ?Sized>(
        car: &Car,
        hifi: &E,
        method: &Method,
        objectives: DesignObjectives,
    ) -> Result<Decision> {
        objectives.validate()?;
        Ok(Decision {
            objectives,
            ctx: DosContext::of_model(car, hifi)?,
            stm: match method {
                Method::Stm(p) => p.clone(),
                Method::Nsga2(_) => StmParams::default(),
            },
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
    /// Whether its `EHVI x PoF` is below the stop threshold (module doc): the loop has
    /// converged, and a run there is not expected to move the front.
    pub converged: bool,
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
    /// Why [`run`] stopped before its `K` runs (converged), in words; left out otherwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stopped: Option<String>,
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
    stopped: Option<String>,
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
            stopped: None,
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
        let hv = self.history.last().map_or(0.0, |h| h.hypervolume);
        let limit = self.options.stop_below * hv;
        let converged = candidate.value < limit;
        let mut why = reason(
            self.options.criterion,
            &candidate,
            self.decision.objectives.sws_limit,
        );
        if converged {
            why += &format!(
                "; converged: EHVI x P(feasible) {:.3e} is below {:e} of the front's hypervolume \
                 {hv:.4} (m/s^2) N, so a run there is not expected to move the front",
                candidate.value, self.options.stop_below
            );
        }
        Ok(Proposal {
            reason: why,
            candidate,
            converged,
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

    /// What the loop decides for.
    pub fn decision(&self) -> &Decision {
        &self.decision
    }

    /// The loop's surrogate setting (LoFi and design box).
    pub fn setting(&self) -> &Setting {
        &self.setting
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
            stopped: self.stopped.clone(),
        }
    }

    /// The fitted surrogate, the loop ended.
    pub(crate) fn into_model(self) -> Box<dyn Surrogate> {
        self.fitted.model
    }
}

/// The HiFi samples of `plan` over `setting`'s box, then up to `options.runs` adaptive
/// steps, stopping at the first converged proposal (module doc): the loop with its report
/// and final model.
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
        let proposal = state.propose()?;
        if proposal.converged {
            state.stopped = Some(format!(
                "stopped after {} of {} adaptive runs: {}",
                state.added.len(),
                options.runs,
                proposal.reason
            ));
            break;
        }
        let c = hifi.evaluate(proposal.candidate.ks, proposal.candidate.cs)?;
        state.add(proposal, c)?;
    }
    Ok(state)
}
