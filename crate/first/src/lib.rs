//! The page's first-screen wasm (issue #29): the `ridelab` crate linked without its
//! `on-demand` feature, so this cdylib exports the core's page API (`ridelab::web`: the
//! `Explorer` session, presets, state checks, colour tables, contours, canvas charts)
//! without the parts the page loads on demand. It adds no code of its own: the exports
//! are the core's `#[wasm_bindgen]` items, which a cdylib keeps from its dependencies.

pub use ridelab;
