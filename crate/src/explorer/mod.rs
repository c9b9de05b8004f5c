//! The explorer's logic behind the page, in plain Rust (the wasm shell in `crate::web`
//! only converts to and from JS): the state a view is defined by, and the [`Session`]
//! that owns it with its parsed scenario, fitted surrogate and kept maps, giving design
//! maps of any model, fronts with their HiFi re-check, spectra and time responses.
//! Everything here builds and is tested natively.

pub mod adaptive;
pub mod fields;
pub mod hifi_front;
pub mod maps;
pub mod model;
pub mod road_source;
pub mod session;
pub mod state;
pub mod studies;
pub mod surrogate;
pub mod tags;
#[cfg(test)]
mod tests;
#[cfg(test)]
mod tests_criteria;
#[cfg(test)]
mod tests_hifi_front;
#[cfg(test)]
mod tests_measured;
#[cfg(test)]
mod tests_robust;

pub use adaptive::{PageLoop, PageStep, PageUncertainty, MAX_CHECK_LEVELS};
pub use fields::ui_field;
pub use hifi_front::{HifiFrontView, PlaneCheck};
pub use maps::ModelMap;
pub use model::Model;
pub use road_source::{OnRoad, RoadSource};
pub use session::{DesignStep, Session};
pub use state::{Measured, RoadResolver, Scenario, State, FIT_FIELDS, REPORT_FIELDS, STATE_FIELDS};
pub use studies::{FrontResult, Spectra, TimeResult};
pub use surrogate::{fit, fit_report, FitKey, FitRecord, FittedSurrogate};
pub use tags::Tags;
