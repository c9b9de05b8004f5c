//! A road at a speed as independent shaped sources: each a velocity PSD, its shaping
//! filter, and the weights with which it drives the right and left tracks.
//!
//! - [`ProfileTracks::Correlated`]: one source drives both tracks (weights `[1, 1]`), with the
//!   mean of the tracks' PSDs (the only track's with one);
//! - [`ProfileTracks::Independent`]: one source per track (`[1, 0]` right, `[0, 1]` left),
//!   each with its track's PSD (the only track's for both with one);
//! - [`ProfileTracks::Measured`] (two tracks): the sum `s = (r + l) / 2` (weights `[1, 1]`) and
//!   the difference `d = (r - l) / 2` (weights `[1, -1]`), each with its own Welch PSD,
//!   so that `r = s + d`, `l = s - d` keep the measured coherence. Treating `s` and `d` as
//!   independent assumes the tracks have equal PSDs and a real cross PSD (a road
//!   statistically the same seen from either side); their cross PSD is then zero.
//!
//! A wheel on track `t` (0 right, 1 left, as in [`crate::model::Wheel`]) `behind` metres
//! behind the front axle sees each source times its weight, `behind / v` later.

use super::describe::N_MAX_ISO;
use super::profile::Profile;
use super::shaping::{ShapingFilter, VelocityPsd};
use super::welch::welch;
use super::{BAND_HZ, LOWEST_BIN, NYQUIST_FRACTION};
use crate::error::{Result, RideError};
pub use crate::road::ProfileTracks;
#[cfg(test)]
use crate::road::Road;
use crate::road::Tracks;
use serde::Serialize;

impl ProfileTracks {
    /// The natural choice for a profile: measured with two tracks, correlated with one.
    pub fn default_for(profile: &Profile) -> ProfileTracks {
        if profile.tracks() == 2 {
            ProfileTracks::Measured
        } else {
            ProfileTracks::Correlated
        }
    }

    /// How `profile`'s tracks drive the car when the page's state says `tracks`: two
    /// tracks keep their measured coherence (the CLI's default for them); one drives both
    /// wheels as `tracks` says (as `ridelab ... --road FILE --tracks ...`).
    pub fn on_page(profile: &Profile, tracks: Tracks) -> ProfileTracks {
        match (profile.tracks(), tracks) {
            (2, _) => ProfileTracks::Measured,
            (_, Tracks::Correlated) => ProfileTracks::Correlated,
            (_, Tracks::Independent) => ProfileTracks::Independent,
        }
    }
}

/// One independent road source.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ShapedSource {
    /// "both tracks", "right", "left", "sum" or "difference".
    pub label: &'static str,
    /// Weights on the right and left tracks.
    pub weights: [f64; 2],
    /// Its velocity PSD (measured, with the white extension).
    pub psd: VelocityPsd,
    /// Its shaping filter.
    pub filter: ShapingFilter,
}

/// A road at a speed, as shaped sources (see the module doc).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ShapedRoad {
    /// Speed, m/s.
    pub speed: f64,
    /// Temporal band where the PSD is measured, Hz.
    pub band_hz: [f64; 2],
    /// The independent sources.
    pub sources: Vec<ShapedSource>,
    /// What was clipped or assumed, in words.
    pub notes: Vec<String>,
}

impl ShapedRoad {
    /// The road of `profile` at `speed` (m/s) with `tracks`: Welch PSDs as in
    /// [`super::describe`] but with segments as long as the band needs at this speed
    /// ([`Profile::segment_at`], so that as many as possible average), the band [`BAND_HZ`]
    /// clipped to what the profile resolves (refused when the profile is too short:
    /// [`Profile::check_length`]), a filter fitted per source.
    pub fn from_profile(
        profile: &Profile,
        speed: f64,
        tracks: ProfileTracks,
    ) -> Result<ShapedRoad> {
        profile.check_length(speed)?;
        let seg = profile.segment_at(speed);
        let n_lo = LOWEST_BIN / (seg as f64 * profile.spacing);
        let n_hi = NYQUIST_FRACTION * 0.5 / profile.spacing;
        let band = [BAND_HZ[0].max(n_lo * speed), BAND_HZ[1].min(n_hi * speed)];
        let mut notes = Vec::new();
        if band[1] < 4.0 * band[0] {
            return Err(RideError::field(
                "distance_m",
                format!(
                    "at {speed} m/s the profile's spacing {} m resolves only up to {:.2} Hz",
                    profile.spacing, band[1]
                ),
            ));
        }
        if band[1] < BAND_HZ[1] {
            notes.push(format!(
                "at {speed} m/s the profile resolves up to {:.1} Hz (half its Nyquist \
                 frequency): above that the velocity PSD keeps its last octave's slope for \
                 two octaves, then is white",
                band[1]
            ));
        }
        if n_hi < N_MAX_ISO {
            notes.push(format!(
                "the spacing {} m resolves wavelengths down to {:.2} m, longer than ISO \
                 8608's shortest (0.35 m)",
                profile.spacing,
                1.0 / n_hi
            ));
        }
        let right = profile.elevation_right.as_deref();
        let s = welch(&profile.elevation, right, profile.spacing, seg);
        let source = |label, weights, gd: &[f64]| -> Result<ShapedSource> {
            let psd = VelocityPsd::from_spatial(&s.n, gd, speed, band)?;
            let filter = ShapingFilter::fit(&psd)?;
            Ok(ShapedSource {
                label,
                weights,
                psd,
                filter,
            })
        };
        let left = &s.pxx;
        let sources = match (tracks, &s.pyy, &s.pxy) {
            (ProfileTracks::Correlated, None, _) => vec![source("both tracks", [1.0, 1.0], left)?],
            (ProfileTracks::Correlated, Some(r), _) => {
                let mean: Vec<f64> = left.iter().zip(r).map(|(a, b)| 0.5 * (a + b)).collect();
                vec![source("both tracks", [1.0, 1.0], &mean)?]
            }
            (ProfileTracks::Independent, r, _) => vec![
                source("right", [1.0, 0.0], r.as_deref().unwrap_or(left))?,
                source("left", [0.0, 1.0], left)?,
            ],
            (ProfileTracks::Measured, Some(r), Some(x)) => {
                // (r + l)/2 and (r - l)/2 from the auto and cross PSDs (Welch is quadratic).
                let sum: Vec<f64> = (0..left.len())
                    .map(|j| 0.25 * (left[j] + r[j] + 2.0 * x[j].re))
                    .collect();
                let diff: Vec<f64> = (0..left.len())
                    .map(|j| 0.25 * (left[j] + r[j] - 2.0 * x[j].re))
                    .collect();
                notes.push(
                    "measured tracks: the sum and difference of the tracks are taken as \
                     independent sources (equal track PSDs, real cross PSD)"
                        .into(),
                );
                vec![
                    source("sum", [1.0, 1.0], &sum)?,
                    source("difference", [1.0, -1.0], &diff)?,
                ]
            }
            (ProfileTracks::Measured, _, _) => {
                return Err(RideError::field(
                    "tracks",
                    "'measured' needs two tracks: a file with the column elevation_right_m",
                ))
            }
        };
        Ok(ShapedRoad {
            speed,
            band_hz: band,
            sources,
            notes,
        })
    }

    /// The ISO 8608 road `road` with waviness `w` over [`BAND_HZ`] (white outside): with
    /// `w = 2` exactly the road of [`crate::criteria::criteria_exact`] (constant filters).
    #[cfg(test)]
    pub(crate) fn iso(road: &Road, waviness: f64) -> Result<ShapedRoad> {
        road.validate()?;
        if !(waviness.is_finite() && (0.5..=5.0).contains(&waviness)) {
            return Err(RideError::field("waviness", "must be in [0.5, 5]"));
        }
        let psd = VelocityPsd::iso(road.class.gd_n0(), waviness, road.speed, BAND_HZ);
        let filter = ShapingFilter::fit(&psd)?;
        let one = |label, weights| ShapedSource {
            label,
            weights,
            psd: psd.clone(),
            filter: filter.clone(),
        };
        let sources = match road.tracks {
            Tracks::Correlated => vec![one("both tracks", [1.0, 1.0])],
            Tracks::Independent => vec![one("right", [1.0, 0.0]), one("left", [0.0, 1.0])],
        };
        Ok(ShapedRoad {
            speed: road.speed,
            band_hz: BAND_HZ,
            sources,
            notes: Vec::new(),
        })
    }

    /// The largest filter error of the sources, in the band and outside it
    /// ([`ShapingFilter::error`]), -.
    pub fn fit_error(&self) -> f64 {
        self.sources
            .iter()
            .map(|s| s.filter.error())
            .fold(0.0, f64::max)
    }

    /// Checks the speed.
    pub(super) fn validate(&self) -> Result<()> {
        if !(self.speed.is_finite() && self.speed > 0.0 && self.speed <= 100.0) {
            return Err(RideError::field("speed", "must be in (0, 100] m/s"));
        }
        Ok(())
    }
}
