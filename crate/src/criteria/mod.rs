//! The ride criteria BAcc, DTL and SWS (RMS over the whole band, front corner),
//! each by two independent routes: exact (closed forms; Lyapunov with the delay, in
//! Kronecker or modal form) and spectral (frequency-domain integration with the exact
//! delay factor).

// Index loops over small fixed-size arrays read like the equations they implement.
#![allow(clippy::needless_range_loop)]
// Quadrature nodes are quoted to the digits of their published tables.
#![allow(clippy::excessive_precision)]

mod closed_form;
mod exact;
mod hqr;
mod iso2631;
mod modal;
mod poly;
mod residue;
mod spectral;

pub use closed_form::quarter_car_rms;
pub use exact::criteria_exact;
pub(crate) use iso2631::{add_wk_variance, append_wk, static_gain, wk_gain};
pub use iso2631::{bacc_wk, bacc_wk_exact, bacc_wk_spectral, comfort_label};
pub(crate) use modal::{add_source_variances, expand_sources, inverse_sums, Channel};
pub use modal::{criteria_fast_exact, criteria_modal};
pub use residue::RESIDUE_TOLERANCE;
pub(crate) use residue::{
    quarter_shaped, Certified, PoleZeroFilter, ResidueFamily, ResidueRoads, ResidueRoute,
    ShapedResidueRoute,
};
pub use spectral::{criteria_spectral, SpectralCriteria, Spectrum};
