//! Robust design over several cases as a study ([`crate::robust`] holds the cases and the
//! robust objective): the robust map ([`map`]) and the robust optimisation ([`optimize`]).

pub mod map;
pub mod optimize;

pub use map::{CaseInfo, CaseMapReport, RobustMapReport};
pub use optimize::{RobustOptimizeReport, RobustProblem};
