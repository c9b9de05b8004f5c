//! A LoFi or HiFi model of a car on a measured road, as an [`Evaluator`]: what lets every
//! design map and optimiser run on a profile file (`--road FILE`) as on an ISO class.

use super::exact::criteria_shaped;
use super::shaped::{ProfileTracks, ShapedRoad};
use crate::analysis::ModelKind;
use crate::car::Car;
use crate::error::Result;
use crate::evaluate::{Criteria, Evaluator};
use crate::road::Road;
use serde::Serialize;

/// `kind`'s model of `car` with the front spring and damper replaced, on `road`: RMS
/// `[BAcc m/s^2, DTL N, SWS m]` by the exact route ([`criteria_shaped`]: Lyapunov
/// equations of the model augmented with the road's shaping filters) at each design.
#[derive(Debug, Clone)]
pub struct MeasuredModel {
    kind: ModelKind,
    car: Car,
    road: ShapedRoad,
}

impl MeasuredModel {
    /// The model of `car` (its front design is the datum) on the shaped `road`.
    pub fn new(kind: ModelKind, car: &Car, road: ShapedRoad) -> MeasuredModel {
        MeasuredModel {
            kind,
            car: car.clone(),
            road,
        }
    }

    /// The shaped road (speed, band, sources and their filters).
    pub fn road(&self) -> &ShapedRoad {
        &self.road
    }
}

impl Evaluator for MeasuredModel {
    fn evaluate(&self, ks: f64, cs: f64) -> Result<Criteria> {
        let car = self.car.with_front(ks, cs)?;
        criteria_shaped(&self.kind.build(&car), &self.road)
    }

    /// `"quarter"` or `"full"`, as on an ISO road.
    fn name(&self) -> String {
        match self.kind {
            ModelKind::Quarter => "quarter",
            ModelKind::Full => "full",
        }
        .into()
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

impl MeasuredRoad {
    /// The summary of `road`, shaped from the profile `file` with `tracks`.
    pub fn of(file: &str, road: &ShapedRoad, tracks: ProfileTracks) -> MeasuredRoad {
        MeasuredRoad {
            file: file.to_string(),
            speed: road.speed,
            tracks,
            band_hz: road.band_hz,
            fit_error: road.fit_error(),
        }
    }
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
