//! One optimisation study on the suspension problem: front, its hypervolume against a
//! stated reference point, the min-max pick and the evaluation count, ready to serialise.

use super::hypervolume::{hypervolume, reference_point};
use super::minmax::{min_max_pick, Pick};
use super::nsga2::{nsga2, Nsga2Params};
use super::stm::{stm, StmParams};
use super::suspension::{FrontPoint, SuspensionProblem};
use crate::error::Result;
use crate::evaluate::Evaluator;
use serde::{Deserialize, Serialize};

/// Margin of the default hypervolume reference point: `nadir + 0.1 (nadir - ideal)`.
pub(crate) const REFERENCE_MARGIN: f64 = 0.1;

/// How the front is found.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "method", rename_all = "snake_case")]
pub enum Method {
    /// Space transformation: dense grid plus local refinement.
    Stm(StmParams),
    /// NSGA-II with constraint domination.
    Nsga2(Nsga2Params),
}

/// The outcome of one study.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Study {
    /// The method and its settings.
    pub method: Method,
    /// Name of the evaluator the front was found on.
    pub evaluator: String,
    /// Feasible non-dominated designs, by increasing BAcc (so decreasing DTL).
    pub front: Vec<FrontPoint>,
    /// Hypervolume reference point `[BAcc (m/s^2), DTL (N)]`.
    pub reference_point: [f64; 2],
    /// How the reference point was chosen.
    pub reference_rule: String,
    /// Hypervolume of the front against the reference point, (m/s^2) N.
    pub hypervolume: f64,
    /// The min-max pick against the datum of the problem's context.
    pub pick: Pick,
    /// Evaluator calls this study made.
    pub evaluations: usize,
}

/// Finds the front of `problem` with `method` and measures it. `reference` is the
/// hypervolume reference point to use (give the same one to studies that are compared);
/// `None` takes `nadir + 0.1 (nadir - ideal)` of this front.
pub fn run_study<E: Evaluator>(
    problem: &SuspensionProblem<E>,
    method: &Method,
    reference: Option<[f64; 2]>,
) -> Result<Study> {
    let before = problem.evaluations();
    let solutions = match method {
        Method::Stm(p) => stm(problem, p)?,
        Method::Nsga2(p) => nsga2(problem, p)?,
    };
    let front = FrontPoint::from_solutions(&solutions);
    let objectives: Vec<[f64; 2]> = front.iter().map(|p| [p.bacc, p.dtl]).collect();
    let (reference_point, reference_rule) = match reference {
        Some(r) => (r, "given by the caller".to_string()),
        None => (
            reference_point(&objectives, REFERENCE_MARGIN),
            format!("nadir + {REFERENCE_MARGIN} (nadir - ideal) of this front"),
        ),
    };
    Ok(Study {
        method: method.clone(),
        evaluator: problem.evaluator_name(),
        hypervolume: hypervolume(&objectives, reference_point),
        pick: min_max_pick(&front, &problem.context().datum)?,
        reference_point,
        reference_rule,
        evaluations: problem.evaluations() - before,
        front,
    })
}
