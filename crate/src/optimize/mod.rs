//! Pareto fronts of the suspension design problem (METHOD.md section 6).
//!
//! Minimise `[BAcc, DTL]` over `(Ks, Cs)` in the design box subject to the design
//! objectives ([`SuspensionProblem`], on any evaluator): [`stm()`] maps a dense grid and
//! refines it, [`nsga2()`] validates it; [`hypervolume()`] and [`front_distance`] measure
//! fronts; [`min_max_pick`] picks the balanced design against the datum car and
//! [`recheck`] re-evaluates it on the HiFi; [`run_study`] ties them together.
//! Both optimisers solve any bi-objective [`Problem`], so they are tested on ZDT1 and BNH too.

pub mod hypervolume;
pub mod minmax;
pub mod nsga2;
pub mod problem;
pub mod stm;
pub mod study;
pub mod suspension;
#[cfg(test)]
mod test_problems;
#[cfg(test)]
mod tests;
pub mod trust;

pub(crate) use hypervolume::{front_distance, reference_point};
pub use hypervolume::{hypervolume, FrontDistance};
#[cfg(test)]
pub(crate) use minmax::pseudo_weights;
pub use minmax::{min_max_pick, normalised_distances, pick, recheck, Pick, PickRule, Recheck};
pub use nsga2::{nsga2, Nsga2Params};
pub use problem::{non_dominated, Eval, Problem, Solution};
pub use stm::{stm, StmParams};
pub use study::{run_study, Method, Study};
pub(crate) use suspension::Counted;
pub use suspension::{FrontPoint, SuspensionProblem};
pub use trust::{pick_warnings, Warning};
