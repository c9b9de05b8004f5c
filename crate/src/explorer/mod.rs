//! The explorer's logic behind the page, in plain Rust (the wasm shell in `crate::web`
//! only converts to and from JS): the state a view is defined by, design maps of any
//! model, fronts with their HiFi re-check, spectra, time responses and the fitted
//! surrogate. Everything here builds and is tested natively.

pub mod maps;
pub mod state;
pub mod studies;
pub mod surrogate;
#[cfg(test)]
mod tests;

pub use maps::{lofi_map, map_of, MapModel};
pub use state::{dos_context, model_map, ModelMap, Scenario, State, MAX_GRID, STATE_FIELDS};
pub use studies::{front, spectra, time_response, FrontModel, FrontResult, Spectra, TimeResult};
pub use surrogate::{fit_report, fitted, FittedSurrogate};
