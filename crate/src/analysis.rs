//! The LoFi and HiFi evaluators over the design variables, and the full analysis
//! report of one design (criteria by both routes, modes, ride properties).

use crate::car::Car;
use crate::criteria::{criteria_exact, criteria_spectral, quarter_car_rms};
use crate::error::{Result, RideError};
use crate::evaluate::{Criteria, Evaluator};
use crate::model::{full_car, quarter_car, LinearModel};
use crate::modes::Mode;
use crate::road::Road;
use serde::{Deserialize, Serialize};

/// Relative tolerance of the HiFi frequency route used by maps and optimisers
/// (on the variance; the achieved RMS error is far smaller, see the tests).
pub const HIFI_RTOL: f64 = 1e-6;

/// Which vehicle model.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ModelKind {
    /// LoFi: 2-DOF quarter car of the front corner.
    Quarter,
    /// HiFi: 7-DOF full car.
    Full,
}

impl ModelKind {
    /// Parses "quarter" or "full".
    pub fn parse(s: &str) -> Result<ModelKind> {
        match s.trim().to_ascii_lowercase().as_str() {
            "quarter" | "lofi" => Ok(ModelKind::Quarter),
            "full" | "hifi" => Ok(ModelKind::Full),
            _ => Err(RideError::field(
                "model",
                format!("'{s}' is not 'quarter' or 'full'"),
            )),
        }
    }

    /// The linear model of `car` for this kind.
    pub fn build(self, car: &Car) -> LinearModel {
        match self {
            ModelKind::Quarter => quarter_car(&car.quarter()),
            ModelKind::Full => full_car(car),
        }
    }
}

/// LoFi evaluator: the front quarter car of `car` on `road` with the front spring and
/// damper replaced. Closed forms for an undamped tyre, the exact Lyapunov route otherwise.
#[derive(Debug, Clone, PartialEq)]
pub struct LoFi {
    /// The car (rear and masses fixed).
    pub car: Car,
    /// The road.
    pub road: Road,
}

impl Evaluator for LoFi {
    fn evaluate(&self, ks: f64, cs: f64) -> Result<Criteria> {
        let mut q = self.car.quarter();
        q.ks = ks;
        q.cs = cs;
        q.validate()?;
        if q.ct == 0.0 {
            Ok(quarter_car_rms(&q, self.road.intensity()))
        } else {
            criteria_exact(&quarter_car(&q), &self.road)
        }
    }
    fn name(&self) -> String {
        "quarter".into()
    }
}

/// HiFi evaluator: the full car with both front corners set to `(ks, cs)`, by the
/// frequency route at [`HIFI_RTOL`] (the ISO low cutoff applies for a road warp).
#[derive(Debug, Clone, PartialEq)]
pub struct HiFi {
    /// The car.
    pub car: Car,
    /// The road.
    pub road: Road,
}

impl Evaluator for HiFi {
    fn evaluate(&self, ks: f64, cs: f64) -> Result<Criteria> {
        let car = self.car.with_front(ks, cs)?;
        Ok(criteria_spectral(&full_car(&car), &self.road, HIFI_RTOL)?.criteria)
    }
    fn name(&self) -> String {
        "full".into()
    }
}

/// Everything `ridelab eval` reports about one design.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Report {
    /// Model kind.
    pub model: ModelKind,
    /// Car name.
    pub car: String,
    /// Road scenario.
    pub road: Road,
    /// Front spring rate, N/m.
    pub ks: f64,
    /// Front damper rate, N s/m.
    pub cs: f64,
    /// RMS body acceleration above the front wheel, m/s^2.
    pub bacc: f64,
    /// RMS dynamic tyre load, N.
    pub dtl: f64,
    /// RMS suspension working space, m.
    pub sws: f64,
    /// RMS DTL relative to the static front wheel load, -.
    pub dtl_relative: f64,
    /// Which route gave `bacc`, `dtl`, `sws`: "exact" or "spectral".
    pub route: &'static str,
    /// The frequency route's values, for comparison.
    pub spectral: Criteria,
    /// Largest relative difference between the routes.
    pub route_difference: f64,
    /// Lower band limit, Hz, when the response needs ISO 8608's low cutoff (road warp).
    pub low_cutoff_hz: Option<f64>,
    /// Natural frequencies and damping ratios.
    pub modes: Vec<Mode>,
    /// Front body-bounce frequency on the ride rate, Hz.
    pub body_bounce_hz: f64,
    /// Front critical damping `2 sqrt(ks ms)`, N s/m.
    pub critical_damping: f64,
    /// Front damping ratio `cs / (2 sqrt(ks ms))`, -.
    pub damping_ratio: f64,
    /// Front wheel (ride) rate `Kw = ks kt / (ks + kt)`, N/m.
    pub wheel_rate: f64,
    /// Static front wheel load, N.
    pub static_wheel_load: f64,
}

/// Analyses one design of `car` (front spring and damper as in the car) on `road`.
pub fn report(kind: ModelKind, car: &Car, road: &Road) -> Result<Report> {
    car.validate()?;
    road.validate()?;
    let model = kind.build(car);
    let spectral = criteria_spectral(&model, road, 1e-10)?;
    let (values, route) = match criteria_exact(&model, road) {
        Ok(c) => (c, "exact"),
        Err(RideError::Numerical(_)) if spectral.low_cutoff_hz.is_some() => {
            (spectral.criteria, "spectral")
        }
        Err(e) => return Err(e),
    };
    let diff = values
        .to_array()
        .iter()
        .zip(spectral.criteria.to_array())
        .map(|(a, b)| (a / b - 1.0).abs())
        .fold(0.0, f64::max);
    let q = car.quarter();
    Ok(Report {
        model: kind,
        car: car.name.clone(),
        road: *road,
        ks: q.ks,
        cs: q.cs,
        bacc: values.bacc,
        dtl: values.dtl,
        sws: values.sws,
        dtl_relative: values.dtl / car.front_wheel_load(),
        route,
        spectral: spectral.criteria,
        route_difference: diff,
        low_cutoff_hz: spectral.low_cutoff_hz,
        modes: model.modes()?,
        body_bounce_hz: q.bounce_frequency(),
        critical_damping: q.critical_damping(),
        damping_ratio: crate::dos::damping_ratio(q.ks, q.cs, q.ms),
        wheel_rate: q.wheel_rate(),
        static_wheel_load: car.front_wheel_load(),
    })
}
