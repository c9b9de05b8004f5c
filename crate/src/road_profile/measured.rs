//! A LoFi or HiFi model of a car on a measured road, as an [`Evaluator`]: what lets every
//! design map and optimiser run on a profile file (`--road FILE`) as on an ISO class.

use super::modal::{bacc_wk_shaped_fast, criteria_shaped_fast};
#[cfg(test)]
use super::profile::Profile;
use super::shaped::{ProfileTracks, ShapedRoad, ShapedSource};
use crate::analysis::{half_family, Half, ModelKind};
use crate::car::{Car, DesignDomain, QuarterCar};
use crate::comfort::Comfort;
use crate::criteria::{comfort_label, quarter_shaped, PoleZeroFilter, ShapedResidueRoute};
use crate::error::{Result, RideError};
use crate::evaluate::{Criteria, Evaluator};
use crate::model::{quarter_car, LinearModel};
use crate::road::MeasuredRoad;
use crate::road::Road;
use serde::Serialize;

/// The quarter car on a shaped road, the LoFi of every measured-road map, surrogate and
/// adaptive loop: the closed form of its transfer ([`quarter_shaped`], about a
/// microsecond) where it applies, the modal route with the road's filters (and the
/// Lyapunov route behind it, [`criteria_shaped_fast`]) where it declines.
#[derive(Debug, Clone, PartialEq)]
pub struct ShapedQuarter {
    road: ShapedRoad,
    /// Each source's weight on the quarter car's wheel (on the right track, as
    /// [`crate::model::quarter_car`]'s) with its filter; `None` where a filter's partial
    /// fractions cancel.
    sources: Option<Vec<(f64, PoleZeroFilter)>>,
}

impl ShapedQuarter {
    /// The quarter car's route on `road`.
    pub fn new(road: ShapedRoad) -> ShapedQuarter {
        let sources = road
            .sources
            .iter()
            .map(|s| Some((s.weights[0], s.filter.pole_zero()?)))
            .collect();
        ShapedQuarter { road, sources }
    }

    /// Exact RMS `[BAcc m/s^2, DTL N, SWS m]` of the (valid) quarter car `q` on the road.
    pub fn criteria(&self, q: &QuarterCar) -> Result<Criteria> {
        match self.sources.as_deref().and_then(|s| quarter_shaped(q, s)) {
            Some(c) => Ok(c),
            None => criteria_shaped_fast(&quarter_car(q), &self.road),
        }
    }
}

/// The quarter car's exact criteria on a road that is not an ISO class: a measured road
/// shaped at its speed ([`ShapedQuarter`]). The surrogates' LoFi holds it as a trait
/// object ([`crate::surrogate::SurrogateLoFi`]), so that a build that never makes one (the
/// page's first-screen wasm, issue #29) carries none of the shaped routes' code.
pub trait QuarterRoute: std::fmt::Debug + Send + Sync {
    /// Exact RMS `[BAcc m/s^2, DTL N, SWS m]` of the (valid) quarter car `q` on the road.
    fn criteria(&self, q: &QuarterCar) -> Result<Criteria>;

    /// The shaped road.
    fn road(&self) -> &ShapedRoad;
}

impl QuarterRoute for ShapedQuarter {
    fn criteria(&self, q: &QuarterCar) -> Result<Criteria> {
        ShapedQuarter::criteria(self, q)
    }

    fn road(&self) -> &ShapedRoad {
        &self.road
    }
}

/// `kind`'s model of `car` with the front spring and damper replaced, on `road`: RMS
/// `[BAcc m/s^2, DTL N, SWS m]` by the exact routes at each design: for the full car the
/// residue route with the road's filters ([`ShapedResidueRoute`]: the car's two halves,
/// the sum of the tracks driving one and their difference the other) where it
/// certifies the point, else the modal route with the filters, else the Lyapunov
/// equations of the model augmented with them ([`criteria_shaped_fast`]); for the quarter
/// car the closed form of its transfer with the filters ([`ShapedQuarter`]), those two
/// behind it. With
/// [`Comfort::Wk`] ([`MeasuredModel::with_comfort`]) the comfort slot holds the ISO 2631-1
/// Wk-weighted RMS body acceleration, m/s^2, by the modal route with the road's filters
/// and Wk's, the Lyapunov equations behind it ([`bacc_wk_shaped_fast`]), as
/// [`crate::comfort::WkComfort`] does on an ISO road.
#[derive(Debug, Clone)]
pub struct MeasuredModel {
    kind: ModelKind,
    /// The Wk route when the comfort slot holds Wk: set only by
    /// [`MeasuredModel::with_comfort`], so that a build that never asks for Wk on a
    /// measured road (the page's) does not carry it.
    wk: Option<WkRoute>,
    car: Car,
    /// The car's design domain: a design inside it needs no more checks.
    domain: DesignDomain,
    road: ShapedRoad,
    residue: Option<ShapedResidueRoute>,
    /// The quarter car's closed form (the LoFi only).
    quarter: Option<ShapedQuarter>,
}

/// A Wk-weighted BAcc route on a shaped road, m/s^2.
type WkRoute = fn(&LinearModel, &ShapedRoad) -> Result<f64>;

impl MeasuredModel {
    /// The model of `car` (its front design is the datum) on the shaped `road`.
    pub fn new(kind: ModelKind, car: &Car, road: ShapedRoad) -> MeasuredModel {
        let (residue, quarter) = match kind {
            ModelKind::Full => (residue_route(car, &road), None),
            ModelKind::Quarter => (None, Some(ShapedQuarter::new(road.clone()))),
        };
        MeasuredModel {
            kind,
            wk: None,
            car: car.clone(),
            domain: car.design_domain(),
            road,
            residue,
            quarter,
        }
    }

    /// The model with `comfort` in the comfort slot.
    pub fn with_comfort(self, comfort: Comfort) -> MeasuredModel {
        let wk: Option<WkRoute> = match comfort {
            Comfort::Bacc => None,
            Comfort::Wk => Some(bacc_wk_shaped_fast),
        };
        MeasuredModel { wk, ..self }
    }

    /// The shaped road (speed, band, sources and their filters).
    pub(crate) fn road(&self) -> &ShapedRoad {
        &self.road
    }
}

/// The full car's residue route on `road` where its sources split over the car's halves:
/// one source on both tracks (the symmetric half), the tracks' sum and difference (both
/// halves, weight 1), or independent tracks with one filter (both halves, weight 1/2:
/// each half sees half the power); `None` otherwise, or where a family cannot be built.
pub(super) fn residue_route(car: &Car, road: &ShapedRoad) -> Option<ShapedResidueRoute> {
    let iso = Road {
        speed: road.speed,
        ..Road::default()
    };
    let part = |half: Half, weight: f64, source: &ShapedSource| {
        Some((
            half_family(car, &iso, half).ok()?,
            weight,
            source.filter.pole_zero()?,
        ))
    };
    let parts = match road.sources.as_slice() {
        [s] if s.weights == [1.0, 1.0] => vec![part(Half::Symmetric, 1.0, s)?],
        [s, d] if s.weights == [1.0, 1.0] && d.weights == [1.0, -1.0] => vec![
            part(Half::Symmetric, 1.0, s)?,
            part(Half::Antisymmetric, 1.0, d)?,
        ],
        [r, l] if r.weights == [1.0, 0.0] && l.weights == [0.0, 1.0] && r.filter == l.filter => {
            vec![
                part(Half::Symmetric, 0.5, r)?,
                part(Half::Antisymmetric, 0.5, r)?,
            ]
        }
        _ => return None,
    };
    ShapedResidueRoute::new(parts).ok()
}

impl Evaluator for MeasuredModel {
    fn evaluate(&self, ks: f64, cs: f64) -> Result<Criteria> {
        // A design in the domain is valid (a few comparisons); outside it, building the
        // car names the fault.
        if !self.domain.contains(ks, cs) {
            self.car.with_front(ks, cs)?;
        }
        let residue = self.residue.as_ref().map(|r| r.criteria(ks, cs));
        let plain = match (&self.quarter, residue) {
            (Some(quarter), _) => quarter.criteria(&QuarterCar {
                ks,
                cs,
                ..self.car.quarter()
            })?,
            (None, Some(Ok(Some(c)))) => c,
            (None, Some(Err(e))) => return Err(e),
            _ => criteria_shaped_fast(&self.kind.build(&self.car.with_front(ks, cs)?), &self.road)?,
        };
        Ok(match self.wk {
            None => plain,
            Some(wk) => Criteria {
                bacc: wk(&self.kind.build(&self.car.with_front(ks, cs)?), &self.road)?,
                ..plain
            },
        })
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

/// `e` with its field named as the road's (`road: column elevation_m, row 17`), as every
/// reader of a profile file reports it.
pub fn road_error(e: RideError) -> RideError {
    match e {
        RideError::Field { field, reason } => RideError::field(format!("road: {field}"), reason),
        other => RideError::field("road", other.to_string()),
    }
}

/// A design and its datum judged on a measured road by both models, RMS `[BAcc m/s^2,
/// DTL N, SWS m]` by the exact routes of [`MeasuredModel`]: what the page shows for a
/// dropped profile file, each number equal to `ridelab eval --road FILE --model quarter`
/// (or `full`) at that design, speed and tracks.
#[derive(Debug, Clone, Serialize)]
pub struct DesignOnRoad {
    /// The road (file, speed, tracks, band, the shaping filters' error).
    pub road: MeasuredRoad,
    /// The quarter car (LoFi) at the design.
    pub quarter: Criteria,
    /// The full car (HiFi) at the design.
    pub full: Criteria,
    /// The quarter car at the datum (the car's own front spring and damper).
    pub datum_quarter: Criteria,
    /// The full car at the datum.
    pub datum_full: Criteria,
    /// The ISO 2631-1 Wk-weighted RMS body acceleration of the same four, m/s^2
    /// (`eval --road`'s `bacc_wk`), with Annex C's words for the full car's.
    pub bacc_wk: WkOnRoad,
    /// Notes from shaping the road at this speed (band clipped, resampling, ...).
    pub notes: Vec<String>,
}

/// [`DesignOnRoad`]'s Wk-weighted BAcc, m/s^2, by [`MeasuredModel::with_comfort`]'s
/// exact route (the model with the road's filters and Wk's).
#[derive(Debug, Clone, Serialize)]
pub struct WkOnRoad {
    /// The quarter car at the design.
    pub quarter: f64,
    /// The full car at the design.
    pub full: f64,
    /// The quarter car at the datum.
    pub datum_quarter: f64,
    /// The full car at the datum.
    pub datum_full: f64,
    /// ISO 2631-1 Annex C's words for `full` (`eval --road --model full`'s `comfort`).
    pub comfort: &'static str,
    /// The same for `datum_full`.
    pub datum_comfort: &'static str,
}

impl DesignOnRoad {
    /// `datum` with its front spring `ks` (N/m) and damper `cs` (N s/m), and `datum`
    /// itself, on `profile` (named `file`) at `speed` (m/s) with `tracks`; errors name
    /// `road: ...` (the profile's column and row, or what the speed needs of it), `ks` or
    /// `cs`.
    #[cfg(test)]
    pub(crate) fn compute(
        datum: &Car,
        ks: f64,
        cs: f64,
        profile: &Profile,
        file: &str,
        speed: f64,
        tracks: ProfileTracks,
    ) -> Result<DesignOnRoad> {
        crate::domain::SPEED.check("speed", speed)?;
        let shaped = ShapedRoad::from_profile(profile, speed, tracks).map_err(road_error)?;
        DesignOnRoad::on_shaped(datum, ks, cs, &shaped, file, tracks)
    }

    /// `DesignOnRoad::compute` on the profile already shaped at its speed (`shaped`,
    /// from the profile `file` with `tracks`): what the page asks again after a design
    /// move, with the road it keeps; errors name `ks` or `cs`.
    pub fn on_shaped(
        datum: &Car,
        ks: f64,
        cs: f64,
        shaped: &ShapedRoad,
        file: &str,
        tracks: ProfileTracks,
    ) -> Result<DesignOnRoad> {
        datum.with_front(ks, cs)?;
        let (quarter, full) = (
            MeasuredModel::new(ModelKind::Quarter, datum, shaped.clone()),
            MeasuredModel::new(ModelKind::Full, datum, shaped.clone()),
        );
        let (k0, c0) = (datum.front.spring, datum.front.damper);
        let (on, at_datum) = (
            [quarter.evaluate(ks, cs)?, full.evaluate(ks, cs)?],
            [quarter.evaluate(k0, c0)?, full.evaluate(k0, c0)?],
        );
        let (quarter_wk, full_wk) = (
            quarter.with_comfort(Comfort::Wk),
            full.with_comfort(Comfort::Wk),
        );
        let (wk_full, wk_datum_full) = (
            full_wk.evaluate(ks, cs)?.bacc,
            full_wk.evaluate(k0, c0)?.bacc,
        );
        Ok(DesignOnRoad {
            road: MeasuredRoad::of(file, shaped, tracks),
            quarter: on[0],
            full: on[1],
            datum_quarter: at_datum[0],
            datum_full: at_datum[1],
            bacc_wk: WkOnRoad {
                quarter: quarter_wk.evaluate(ks, cs)?.bacc,
                full: wk_full,
                datum_quarter: quarter_wk.evaluate(k0, c0)?.bacc,
                datum_full: wk_datum_full,
                comfort: comfort_label(wk_full),
                datum_comfort: comfort_label(wk_datum_full),
            },
            notes: shaped.notes.clone(),
        })
    }
}
