//! The ride criteria BAcc, DTL and SWS (RMS over the whole band, front corner),
//! each by two independent routes: exact (closed forms, Lyapunov with the delay)
//! and spectral (frequency-domain integration with the exact delay factor).

mod closed_form;
mod exact;
mod spectral;

pub use closed_form::quarter_car_rms;
pub use exact::criteria_exact;
pub use spectral::{criteria_spectral, SpectralCriteria, Spectrum};
