//! Robust design over several cases (issue #16): load cases of the car (extra mass with
//! its position: new sprung mass, CG and inertias, [`load`]) at several operating points
//! (road class and speed with weights, [`cases`]); the robust objective and DOS
//! ([`objective`]: worst case or weighted mean of each case normalised by its own datum;
//! feasible only where every case meets every objective). The robust map and the robust
//! optimisation are studies over them ([`crate::study::robust`]).

pub mod cases;
pub mod load;
pub mod objective;

pub use cases::{Case, CaseSet, CasesFile, Combine, Operating, MAX_CASES};
pub use load::{CarFile, LoadCase, MAX_LOAD_CASES};
pub use objective::{robust_constraints, Combination, RobustEvaluator};
