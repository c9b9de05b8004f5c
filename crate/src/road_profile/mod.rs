//! Your own road: measured road profiles in, described and judged exactly and fast (#31).
//!
//! A profile is a CSV file `distance_m,elevation_m[,elevation_right_m]` ([`Profile`]).
//! From it this module computes:
//!
//! - **a description** ([`describe`], [`RoadDescription`]): the displacement PSD
//!   `Gd(n)` (m^3, one-sided, over spatial frequency `n` in cycle/m) by Welch's method, the
//!   ISO 8608 fit `Gd(n) = Gd(n0) (n / n0)^-w` (class A..H, waviness `w`) and, with two
//!   tracks, their coherence;
//! - **a shaped road at a speed** ([`ShapedRoad`]): at speed `v` the one-sided road
//!   *velocity* PSD is `Gv(f) = (2 pi f)^2 Gd(f / v) / v` (m^2/s^2 per Hz), measured over a
//!   band [`BAND_HZ`] (clipped to what the profile resolves) and extended as ISO 8608's
//!   default (white velocity, `w = 2`) outside it ([`VelocityPsd`]); a small stable
//!   rational filter ([`ShapingFilter`]) driven by unit white noise reproduces it with a
//!   stated error;
//! - **the criteria by two routes**: exact ([`criteria_shaped_fast`](modal::criteria_shaped_fast): the modal route
//!   [`criteria_shaped_modal`], the model's modes times the filters' partial fractions, and
//!   where it declines [`criteria_shaped`], Lyapunov equations of the model augmented with
//!   the filter, the front-rear delay exact through `exp(A tau)`; the quarter car's
//!   closed form [`ShapedQuarter`] and the full car's residue route
//!   [`crate::criteria::ShapedResidueRoute`] for maps and optimisers) and
//!   in frequency ([`criteria_shaped_spectral`]: `|H(f)|^2 Gv(f)` integrated on the raw
//!   Welch PSD, the delays as exact phase factors);
//! - **playback** ([`playback`]): the profile itself as the wheels' road input of a
//!   time-domain run, rear wheels `L / v` later.
//!
//! Synthetic profiles ([`synthesize`]) from an ISO class of any waviness, optionally with
//! the joints of a slab concrete road, serve the tests and the shipped examples.

// Index loops over small matrices read like the equations they implement.
#![allow(clippy::needless_range_loop)]

mod describe;
mod exact;
mod lyap;
mod measured;
mod modal;
mod playback;
mod profile;
mod shaped;
mod shaping;
mod spectral;
mod synth;
mod welch;

pub use crate::road::{MeasuredRoad, RoadScenario};
pub use describe::{describe, CoherenceSeries, IsoFit, PsdSeries, RoadDescription, WelchInfo};
pub use exact::criteria_shaped;
pub use measured::{
    road_error, DesignOnRoad, MeasuredModel, QuarterRoute, ShapedQuarter, WkOnRoad,
};
pub(crate) use modal::bacc_wk_shaped_fast;
pub use modal::criteria_shaped_modal;
pub use playback::{playback, WheelRoad};
pub use profile::{Profile, MAX_BYTES};
pub use shaped::{ProfileTracks, ShapedRoad, ShapedSource};
pub use shaping::{Extension, ShapingFilter, VelocityPsd};
pub use spectral::{criteria_shaped_spectral, ShapedSpectrum};
pub use synth::{shipped_examples, synthesize, Slabs, Synthesis, EXAMPLE_DECIMALS};

/// The temporal band, Hz, over which a profile's measured velocity PSD is used at a speed
/// (clipped to what the profile resolves there): from below the body modes (about 1 Hz)
/// to past the wheel hop (about 10 Hz) and far enough into the tyre-deflection tail that
/// the white extension above it carries only a few per cent of var(DTL) (2.7 % above
/// 100 Hz for the datum car, METHOD.md).
pub(crate) const BAND_HZ: [f64; 2] = [0.3, 100.0];

/// [`describe`]'s Welch segments are about `1 / SEGMENT_DIVISOR` of the profile (about 15
/// averaged segments at 50 % overlap), for the resolution ISO 8608's band needs.
pub(crate) const SEGMENT_DIVISOR: usize = 8;

/// A [`ShapedRoad`]'s Welch segments are as long as its band needs at its speed (the
/// lowest frequency [`LOWEST_BIN`] bins up), and a profile must hold at least this many of
/// them (50 % overlap).
pub(crate) const MIN_SEGMENTS: usize = 8;

/// The lowest Welch bin trusted, in units of the bin spacing `dn` (the first bins carry
/// the linear detrend's and the Hann window's leakage).
pub(crate) const LOWEST_BIN: f64 = 3.0;

/// The highest spatial frequency trusted, as a fraction of the Nyquist frequency
/// `1 / (2 dx)` (measured profiles are anti-alias filtered below Nyquist).
pub(crate) const NYQUIST_FRACTION: f64 = 0.5;

#[cfg(test)]
mod tests;
