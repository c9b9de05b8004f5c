//! ISO 8608 random road: classes, speed, front-rear delay and track correlation.
//!
//! Displacement PSD `Gd(n) = Gd(n0) (n / n0)^-2`, `n0 = 0.1` cycle/m. At speed `v` the
//! one-sided temporal PSD is `G(f) = Gd(f / v) / v`, so the road *velocity* is white with
//! one-sided PSD `Gv = (2 pi n0)^2 Gd(n0) v` (m^2/s^2 per Hz).

use crate::error::{parse_choice, Result, RideError};
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;
use strum::{EnumIter, EnumProperty, IntoStaticStr, VariantNames};

/// Reference spatial frequency of ISO 8608, cycle/m.
pub(crate) const N0: f64 = 0.1;
/// Lowest spatial frequency of ISO 8608's classification band, cycle/m.
pub(crate) const N_MIN: f64 = 0.011;

/// ISO 8608 road class.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum RoadClass {
    A,
    B,
    C,
    D,
    E,
    F,
    G,
    H,
}

impl RoadClass {
    /// All classes, best to worst.
    pub const ALL: [RoadClass; 8] = [
        RoadClass::A,
        RoadClass::B,
        RoadClass::C,
        RoadClass::D,
        RoadClass::E,
        RoadClass::F,
        RoadClass::G,
        RoadClass::H,
    ];

    /// `Gd(n0)`, m^3: 16e-6 for A, times 4 per class up to 262144e-6 for H.
    pub fn gd_n0(self) -> f64 {
        16e-6 * 4f64.powi(self as i32)
    }

    /// Parses "A".."H" (case-insensitive).
    pub fn parse(s: &str) -> Result<RoadClass> {
        let t = s.trim().to_ascii_uppercase();
        RoadClass::ALL
            .iter()
            .copied()
            .find(|c| format!("{c:?}") == t)
            .ok_or_else(|| {
                RideError::field("class", format!("'{s}' is not an ISO 8608 class A..H"))
            })
    }
}

/// Whether the left and right wheel tracks see the same profile.
#[derive(
    Debug,
    Clone,
    Copy,
    PartialEq,
    Eq,
    Serialize,
    Deserialize,
    EnumIter,
    EnumProperty,
    IntoStaticStr,
    VariantNames,
)]
#[serde(rename_all = "lowercase")]
#[strum(serialize_all = "lowercase")]
#[strum()]
pub enum Tracks {
    /// Left and right profiles identical (no road roll).
    Correlated,
    /// Left and right profiles independent, each with the class PSD.
    Independent,
}

impl std::str::FromStr for Tracks {
    type Err = RideError;
    fn from_str(s: &str) -> Result<Tracks> {
        Tracks::parse(s)
    }
}

impl std::str::FromStr for RoadClass {
    type Err = RideError;
    fn from_str(s: &str) -> Result<RoadClass> {
        RoadClass::parse(s)
    }
}

impl Tracks {
    /// Parses "correlated" or "independent" (any case; errors name `tracks`).
    pub fn parse(s: &str) -> Result<Tracks> {
        parse_choice("tracks", s)
    }
}

/// A road scenario: class, vehicle speed and track correlation.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Road {
    /// ISO 8608 class.
    pub class: RoadClass,
    /// Vehicle speed, m/s.
    pub speed: f64,
    /// Left/right correlation.
    pub tracks: Tracks,
}

impl Default for Road {
    /// The default scenario: class B at 20 m/s, correlated tracks.
    fn default() -> Self {
        Road {
            class: RoadClass::B,
            speed: 20.0,
            tracks: Tracks::Correlated,
        }
    }
}

impl Road {
    /// Checks the speed: a finite number > 0 in its physical range
    /// ([`crate::domain::SPEED`], 1..100 m/s).
    pub fn validate(&self) -> Result<()> {
        if !(self.speed.is_finite() && self.speed > 0.0) {
            return Err(RideError::field(
                "speed",
                "must be a finite number > 0 (m/s)",
            ));
        }
        crate::domain::SPEED.check("speed", self.speed)
    }

    /// One-sided PSD of the road velocity, `Gv = (2 pi n0)^2 Gd(n0) v`, m^2/s^2 per Hz.
    pub fn velocity_psd(&self) -> f64 {
        (2.0 * PI * N0).powi(2) * self.class.gd_n0() * self.speed
    }

    /// Intensity of the white road velocity, `W = Gv / 2 = 2 pi^2 Gd(n0) n0^2 v`, m^2/s
    /// (`E[w(t) w(s)] = W delta(t - s)`), the weight of the Lyapunov equation.
    pub fn intensity(&self) -> f64 {
        self.velocity_psd() / 2.0
    }

    /// One-sided temporal displacement PSD `G(f) = Gd(n0) n0^2 v / f^2`, m^2/Hz.
    pub fn displacement_psd(&self, f: f64) -> f64 {
        self.class.gd_n0() * N0 * N0 * self.speed / (f * f)
    }

    /// Front-to-rear delay `tau = L / v`, s, for wheelbase `l` (m).
    pub fn delay(&self, l: f64) -> f64 {
        l / self.speed
    }

    /// ISO 8608's lowest temporal frequency `N_MIN v`, Hz.
    pub(crate) fn lowest_frequency(&self) -> f64 {
        N_MIN * self.speed
    }
}

/// How a profile's tracks drive the wheels (see `crate::road_profile::ShapedRoad`): one track, or both with their coherence.
#[derive(
    Debug,
    Clone,
    Copy,
    PartialEq,
    Eq,
    Serialize,
    Deserialize,
    EnumIter,
    EnumProperty,
    IntoStaticStr,
    VariantNames,
)]
#[serde(rename_all = "lowercase")]
#[strum(serialize_all = "lowercase")]
#[strum()]
pub enum ProfileTracks {
    /// Both tracks see the same profile.
    Correlated,
    /// The tracks are independent.
    Independent,
    /// Two measured tracks, their coherence kept (sum and difference sources).
    Measured,
}

impl std::str::FromStr for ProfileTracks {
    type Err = RideError;
    fn from_str(s: &str) -> Result<ProfileTracks> {
        parse_choice("tracks", s)
    }
}

/// What a report says of the measured road it was computed on (JSON `road`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MeasuredRoad {
    /// The profile file as given.
    pub file: String,
    /// Speed, m/s.
    pub speed: f64,
    /// How its tracks drive the wheels.
    pub tracks: ProfileTracks,
    /// Temporal band where the measured PSD is used, Hz.
    pub band_hz: [f64; 2],
    /// The shaping filters' largest relative PSD error over the band, -.
    pub fit_error: f64,
}

/// The road of a report: an ISO 8608 class (JSON as [`Road`], unchanged) or a measured
/// profile.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(untagged)]
pub enum RoadScenario {
    /// An ISO 8608 class at a speed.
    Iso(Road),
    /// A measured profile at a speed.
    Measured(MeasuredRoad),
}

impl RoadScenario {
    /// In words: "class B at 20 m/s" or "road.csv at 20 m/s".
    pub fn words(&self) -> String {
        match self {
            RoadScenario::Iso(r) => format!("class {:?} at {} m/s", r.class, r.speed),
            RoadScenario::Measured(m) => format!("{} at {} m/s", m.file, m.speed),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn class_values_follow_iso_8608() {
        assert_eq!(RoadClass::A.gd_n0(), 16e-6);
        assert!((RoadClass::C.gd_n0() - 256e-6).abs() < 1e-18);
        assert!((RoadClass::H.gd_n0() - 262_144e-6).abs() < 1e-12);
        assert_eq!(RoadClass::parse("c").unwrap(), RoadClass::C);
        assert!(RoadClass::parse("Z")
            .unwrap_err()
            .to_string()
            .starts_with("class"));
    }

    #[test]
    fn velocity_psd_is_displacement_psd_times_omega_squared() {
        let r = Road::default();
        for f in [0.3, 1.0, 17.0] {
            let gv = (2.0 * PI * f).powi(2) * r.displacement_psd(f);
            assert!((gv / r.velocity_psd() - 1.0).abs() < 1e-12);
        }
        // Gv = (2 pi 0.1)^2 * 64e-6 * 20 = 5.0532e-4 m^2/s^2/Hz
        assert!((r.velocity_psd() - 5.053_2e-4).abs() < 1e-7);
    }
}
