//! RideLab: surrogate-based passenger-car suspension design.
//!
//! Data flows one way: car + road -> model -> criteria -> maps / surrogate -> optimize.
//! The core is plain Rust; `web` (wasm only) and the `ridelab` binary are thin shells.
//!
//! What the binary, the tests, the benchmarks and the examples do not use is `pub(crate)`
//! (issue #28), so that the compiler sees dead code; the documentation still names those
//! items where they explain a public one (`cargo doc --document-private-items` links them).
#![allow(rustdoc::private_intra_doc_links)]

pub mod analysis;
pub mod budget;
pub mod car;
pub mod chart;
pub mod comfort;
pub mod criteria;
pub mod design;
pub mod doe;
pub mod domain;
pub mod dos;
pub mod error;
pub mod evaluate;
pub mod explorer;
pub(crate) mod fft;
pub mod finite;
pub mod gpu;
pub(crate) mod json_path;
pub mod maps;
pub mod math;
pub mod model;
pub mod optimize;
pub mod order;
pub mod report;
pub mod road;
pub mod road_profile;
pub mod robust;
pub mod study;
pub mod surrogate;
pub mod time_domain;
#[cfg(target_arch = "wasm32")]
pub mod web;

pub use analysis::{HiFi, LoFi, ModelKind};
pub use car::{Car, QuarterCar};
pub use comfort::Comfort;
pub use design::DesignBox;
pub use error::{Result, RideError};
pub use evaluate::{Criteria, Evaluator};
pub use road::{Road, RoadClass, Tracks};
