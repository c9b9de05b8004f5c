//! The robust optimisation (`ridelab optimize --cases FILE`): minimise the robust
//! `[BAcc, DTL]` ([`crate::robust::objective`]) over the design box, feasible only where the
//! design objectives hold in every case; the pick on the robust front, its numbers in
//! each case, and each case re-checked on that case's HiFi.
//!
//! As in [`crate::study::OptimizeRequest::run`], every case's datum is the datum
//! design's **HiFi** criteria in that case (with the chosen comfort measure), whatever the
//! evaluator the front is found on.

use super::map::{CaseInfo, NORMALISATION};
use crate::analysis::{HiFiRoads, ModelKind};
use crate::comfort::Comfort;
use crate::design::DesignBox;
use crate::dos::{DesignObjectives, DosContext, Objective};
use crate::error::{Result, RideError};
use crate::evaluate::{Criteria, Evaluator};
use crate::optimize::hypervolume::{hypervolume, reference_point};
use crate::optimize::minmax::{change_percent, pick, recheck, Recheck};
use crate::optimize::problem::{Eval, Problem};
use crate::optimize::study::REFERENCE_MARGIN;
use crate::optimize::suspension::LeastViolation;
use crate::optimize::trust::{pick_warnings, Warning};
use crate::optimize::{nsga2, stm, FrontPoint, Method, Study};
use crate::robust::cases::CaseSet;
use crate::robust::objective::{robust_constraints, CaseRun, Combination, RobustEvaluator};
use crate::study::{EvaluatorSpec, OptimizeRequest};
use serde::Serialize;
use std::cell::{Cell, RefCell};

/// The robust problem: robust objectives, robust constraints, counting model runs.
pub struct RobustProblem<E> {
    evaluator: RobustEvaluator<E>,
    design: DesignBox,
    objectives: DesignObjectives,
    ctxs: Vec<DosContext>,
    runs: Cell<usize>,
    least: RefCell<Option<LeastViolation>>,
}

impl<E: CaseRun> RobustProblem<E> {
    /// The problem over `design` with one evaluator and one context per case.
    pub fn new(
        evaluator: RobustEvaluator<E>,
        design: DesignBox,
        objectives: DesignObjectives,
        ctxs: Vec<DosContext>,
    ) -> Result<Self> {
        design.validate()?;
        for ctx in &ctxs {
            design.check_on(&crate::car::DesignDomain::new(
                ctx.sprung_mass,
                ctx.tire_stiffness,
            ))?;
        }
        objectives.validate()?;
        Ok(RobustProblem {
            evaluator,
            design,
            objectives,
            ctxs,
            runs: Cell::new(0),
            least: RefCell::new(None),
        })
    }

    /// Model runs so far (designs x cases).
    pub fn runs(&self) -> usize {
        self.runs.get()
    }
}

impl<E: CaseRun> Problem for RobustProblem<E> {
    type Info = Criteria;

    fn bounds(&self) -> Vec<(f64, f64)> {
        let b = &self.design;
        vec![(b.ks_min, b.ks_max), (b.cs_min, b.cs_max)]
    }

    /// `f` = the robust `[BAcc, DTL]`, violation `sum_j max(0, max_k g_kj)`.
    fn evaluate(&self, x: &[f64]) -> Result<Eval<Criteria>> {
        let (ks, cs) = (x[0], x[1]);
        self.runs.set(self.runs.get() + self.evaluator.case_count());
        let per = self.evaluator.evaluate_cases(ks, cs)?;
        let c = self.evaluator.combination.apply(&per);
        if !c.to_array().iter().all(|v| v.is_finite()) {
            return Err(RideError::Numerical(format!(
                "{} gave non-finite criteria at Ks = {ks} N/m, Cs = {cs} N s/m",
                self.evaluator.name()
            )));
        }
        let g = robust_constraints(&self.objectives, &self.ctxs, ks, cs, &per);
        let violation: f64 = g.iter().map(|(_, gj)| gj.max(0.0)).sum();
        LeastViolation::keep(&self.least, ks, cs, &g, violation);
        Ok(Eval {
            f: [c.bacc, c.dtl],
            violation,
            info: c,
        })
    }

    /// Names what the least-violating design breaks in some case.
    fn infeasible(&self) -> RideError {
        match self.least.borrow().as_ref() {
            Some(LeastViolation { ks, cs, broken, .. }) => {
                let labels: Vec<&str> = broken.iter().map(|o| o.label()).collect();
                RideError::Infeasible {
                    field: "cases".into(),
                    reason: format!(
                        "no design meets the objectives in every case; the closest (Ks = {ks:.0} N/m, Cs = {cs:.0} N s/m) breaks {} in at least one case",
                        labels.join(" and ")
                    ),
                }
            }
            None => RideError::Numerical("no feasible design: nothing was evaluated".into()),
        }
    }
}

/// One case at the pick: the front evaluator's prediction and the case's HiFi re-check.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CasePick {
    /// The case.
    pub case: CaseInfo,
    /// The pick in this case on the front's evaluator, its change against the case's
    /// datum, and the case's HiFi re-check.
    pub hifi_recheck: Recheck,
    /// Objectives the HiFi re-check breaks in this case (empty when met).
    pub broken: Vec<Objective>,
}

/// Everything `ridelab optimize --cases` prints.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RobustOptimizeReport {
    /// The robust front (criteria in case 0's units), its hypervolume, the pick and the
    /// model runs (designs x cases).
    #[serde(flatten)]
    pub study: Study,
    /// The robust datum: case 0's HiFi datum.
    pub datum: Criteria,
    /// The pick's robust criteria re-checked on every case's HiFi.
    pub hifi_recheck: Recheck,
    /// The comfort measure (left out for the unweighted BAcc).
    #[serde(skip_serializing_if = "Comfort::is_bacc")]
    pub comfort: Comfort,
    /// Worst case or weighted mean, and the normalisation.
    pub combine: crate::robust::cases::Combine,
    /// The normalisation sentence.
    pub normalisation: &'static str,
    /// The pick in each case.
    pub cases: Vec<CasePick>,
    /// How far the pick can be trusted ([`crate::optimize::trust`]): a box bound it sits
    /// on, a criterion whose robust HiFi re-check misses the prediction.
    pub warnings: Vec<Warning>,
}

/// Every case's datum criteria: the datum design (the loaded car's own front spring and
/// damper) on that case's evaluator `evaluators[k]`.
pub(crate) fn datums_on(
    set: &CaseSet,
    evaluators: &[Box<dyn Evaluator + Sync>],
) -> Result<Vec<Criteria>> {
    set.cases
        .iter()
        .zip(evaluators)
        .map(|(c, e)| e.evaluate(c.car.front.spring, c.car.front.damper))
        .collect()
}

/// Every case's HiFi (the full car of its loaded car on its road) with the `comfort`
/// measure, in case order.
pub(crate) fn case_hifis(
    set: &CaseSet,
    comfort: Comfort,
) -> Result<Vec<Box<dyn Evaluator + Sync>>> {
    set.cases
        .iter()
        .map(|c| comfort.evaluator(ModelKind::Full, &c.car, &c.road))
        .collect()
}

/// Every case's DOS context: its loaded car against its datum criteria `datums[k]`.
pub(crate) fn case_contexts(set: &CaseSet, datums: &[Criteria]) -> Vec<DosContext> {
    set.cases
        .iter()
        .zip(datums)
        .map(|(c, d)| DosContext::new(&c.car, *d))
        .collect()
}

/// The combination of the robust optimisation ([`OptimizeRequest::run_robust`]): the cases'
/// criteria scaled to their HiFi datums (with the `comfort` measure), the set's rule
/// and probabilities; also the HiFi datums. What the front's robust objective of a
/// design is, `combination.apply(per-case criteria)`.
pub(crate) fn hifi_combination(
    set: &CaseSet,
    comfort: Comfort,
) -> Result<(Combination, Vec<Criteria>)> {
    let datums = datums_on(set, &case_hifis(set, comfort)?)?;
    Ok((
        Combination::new(set.combine, &datums, &set.probabilities())?,
        datums,
    ))
}

impl OptimizeRequest<'_> {
    /// The robust optimisation: this request run over the cases of `set` (built from the
    /// request's car and road: each case brings its loaded car and its road) and combined
    /// by the set's rule. Over the request's design box by its method on its evaluator (a
    /// surrogate per case, fitted to that case's HiFi at the request's plan), with its
    /// objectives and comfort measure, picked by its pick rule; on the CPU (the request's
    /// `compute` is not read).
    pub fn run_robust(&self, set: &CaseSet) -> Result<RobustOptimizeReport> {
        let (design_box, method, evaluator, plan) =
            (&self.design_box, &self.method, self.evaluator, self.plan);
        let (objectives, comfort, rule) = (self.objectives.clone(), self.comfort, self.pick);
        objectives.validate()?;
        match method {
            Method::Stm(p) => p.check_runs(set.cases.len())?,
            Method::Nsga2(p) => p.check_runs(set.cases.len())?,
        }
        let mut models = Vec::with_capacity(set.cases.len());
        let mut hifis = Vec::with_capacity(set.cases.len());
        for c in &set.cases {
            models.push(match (comfort, evaluator) {
            (Comfort::Bacc, _) => Run::One(evaluator.build(&c.car, &c.road, design_box, plan)?),
            (Comfort::Wk, EvaluatorSpec::Model(kind)) => {
                Run::One(comfort.evaluator(kind, &c.car, &c.road)?)
            }
            (Comfort::Wk, EvaluatorSpec::Surrogate(_)) => {
                return Err(RideError::field(
                    "comfort",
                    "wk needs --evaluator quarter or full: the surrogates are fitted to the unweighted BAcc",
                ))
            }
        });
            hifis.push(comfort.evaluator(ModelKind::Full, &c.car, &c.road)?);
        }
        // The HiFi front: the cases of one loaded car together (the same criteria bit for
        // bit, the road-independent work once a design).
        if (comfort, evaluator) == (Comfort::Bacc, EvaluatorSpec::Model(ModelKind::Full)) {
            models = set
                .car_runs()
                .into_iter()
                .map(|run| {
                    let roads: Vec<_> = set.cases[run.clone()].iter().map(|c| c.road).collect();
                    Ok(Run::Roads(HiFiRoads::new(
                        &set.cases[run.start].car,
                        &roads,
                    )?))
                })
                .collect::<Result<_>>()?;
        }
        let datums = datums_on(set, &hifis)?;
        let combination = Combination::new(set.combine, &datums, &set.probabilities())?;
        let ctxs = case_contexts(set, &datums);
        let problem = RobustProblem::new(
            RobustEvaluator {
                cases: models,
                combination: combination.clone(),
            },
            *design_box,
            objectives.clone(),
            ctxs.clone(),
        )?;
        let solutions = match method {
            Method::Stm(p) => stm(&problem, p)?,
            Method::Nsga2(p) => nsga2(&problem, p)?,
        };
        let front = FrontPoint::from_solutions(&solutions);
        let f: Vec<[f64; 2]> = front.iter().map(|p| [p.bacc, p.dtl]).collect();
        let reference = reference_point(&f, REFERENCE_MARGIN);
        let datum = combination.datum;
        let picked = pick(&front, &datum, rule)?;
        let study = Study {
            method: method.clone(),
            evaluator: problem.evaluator.name(),
            front,
            reference_point: reference,
            reference_rule: format!("nadir + {REFERENCE_MARGIN} (nadir - ideal) of this front"),
            hypervolume: hypervolume(&f, reference),
            pick: picked.clone(),
            evaluations: problem.runs(),
        };
        let robust_hifi = RobustEvaluator {
            cases: hifis,
            combination,
        };
        let hifi_recheck = recheck(&picked, &robust_hifi, &datum)?;
        let predicted = problem.evaluator.evaluate_cases(picked.ks, picked.cs)?;
        let mut cases = Vec::with_capacity(set.cases.len());
        for (k, (hifi, c)) in robust_hifi.cases.iter().zip(&predicted).enumerate() {
            let case_pick = crate::optimize::Pick {
                criteria: *c,
                change_percent: change_percent(c, &datums[k]),
                ..picked.clone()
            };
            let check = recheck(&case_pick, &**hifi, &datums[k])?;
            let broken = objectives.broken(&ctxs[k], picked.ks, picked.cs, &check.rechecked);
            cases.push(CasePick {
                case: CaseInfo::new(set, k, datums[k]),
                hifi_recheck: check,
                broken,
            });
        }
        Ok(RobustOptimizeReport {
            warnings: pick_warnings(&picked, &hifi_recheck, design_box),
            study,
            datum,
            hifi_recheck,
            comfort,
            combine: set.combine,
            normalisation: NORMALISATION,
            cases,
        })
    }
}

/// The front evaluator of a run of cases: one case's, or the HiFi of one loaded car on
/// its cases' roads.
enum Run {
    One(Box<dyn Evaluator + Sync>),
    Roads(HiFiRoads),
}

impl CaseRun for Run {
    fn cases(&self) -> usize {
        match self {
            Run::One(e) => e.cases(),
            Run::Roads(r) => r.cases(),
        }
    }
    fn evaluate_into(&self, ks: f64, cs: f64, out: &mut Vec<Criteria>) -> Result<()> {
        match self {
            Run::One(e) => e.evaluate_into(ks, cs, out),
            Run::Roads(r) => r.evaluate_into(ks, cs, out),
        }
    }
    fn run_name(&self) -> String {
        match self {
            Run::One(e) => e.run_name(),
            Run::Roads(r) => r.run_name(),
        }
    }
}
