//! The study layer: what `ridelab map`, `optimize`, `surrogate` and `report` and the page
//! run over the algorithms below them. A study takes a car, a road (an ISO class or a
//! measured profile), a design box, the design objectives, a comfort measure, the load
//! cases and a compute path, and returns a map, a front with its pick, a fitted surrogate
//! with its validation, or an adaptive run.
//!
//! The data flow, one way:
//!
//! ```text
//! car + road ─▶ model (analysis, model, road_profile) ─▶ criteria (criteria, comfort)
//!            ─▶ study (maps, fronts, picks, surrogates, adaptive runs)  ─▶ page or CLI
//! ```
//!
//! The algorithms ([`crate::maps`], [`crate::optimize`], [`crate::surrogate`],
//! [`crate::doe`], [`crate::robust`]'s cases and objective) know nothing of this layer;
//! `tests/structure.rs` keeps the modules' imports free of cycles.
//!
//! - [`spec`]: a study's inputs as one type, [`StudySpec`], with its map and its front as
//!   methods over the pipelines below (`ridelab map` and `ridelab optimize` run them).
//! - [`fits`]: a study's surrogate fits, its fidelity study and its adaptive study as
//!   methods of [`StudySpec`] (`ridelab surrogate` and `ridelab study` run them).
//! - [`map`]: a design map of one model (`ridelab map`).
//! - [`optimize`]: a front and its min-max pick on any evaluator (`ridelab optimize`).
//! - [`fidelity`]: one surrogate fitted and validated (`ridelab surrogate`), and the
//!   fidelity study over every approach, scheme and plan.
//! - [`adaptive`]: adaptive HiFi sampling and its study.
//! - [`robust`]: the map and the front over several load cases and operating points.

pub mod adaptive;
pub mod fidelity;
pub mod fits;
pub mod map;
pub mod measured;
pub mod model;
pub mod optimize;
pub mod robust;
pub mod spec;
pub mod surrogate;
#[cfg(test)]
mod tests_spec;

pub(crate) use fidelity::study_on;
pub use fidelity::{study, StudyReport, SurrogateReport};
pub use map::{
    map_csv, CriteriaContours, Feasibility, MapReport, MapRequest, MapSettings, MaskBit, Units,
    LAYOUT,
};
pub use model::EvaluatorSpec;
pub use optimize::{
    optimize_model, optimize_on_models, OptimizeReport, OptimizeRequest, SameModel,
};
pub use robust::{CaseInfo, CaseMapReport, RobustMapReport, RobustOptimizeReport, RobustProblem};
pub use spec::{
    FrontAsk, FrontReport, MapAsk, MeasuredSource, StudyFront, StudyMap, StudyRoad, StudySpec,
};
pub use surrogate::SurrogateRequest;
