//! The LoFi and HiFi evaluators over the design variables, and the full analysis
//! report of one design (criteria by both routes, modes, ride properties).

use crate::car::{Car, QuarterCar};
use crate::criteria::{criteria_exact, criteria_fast_exact, criteria_spectral, quarter_car_rms};
use crate::error::{Result, RideError};
use crate::evaluate::{Criteria, Evaluator};
use crate::model::Mode;
use crate::model::{full_car, quarter_car, symmetric_half, LinearModel};
use crate::road::{Road, Tracks};
use serde::{Deserialize, Serialize};

/// Which vehicle model.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ModelKind {
    /// LoFi: 2-DOF quarter car of the front corner.
    Quarter,
    /// HiFi: 7-DOF full car.
    Full,
}

impl std::str::FromStr for ModelKind {
    type Err = RideError;
    fn from_str(s: &str) -> Result<ModelKind> {
        ModelKind::parse(s)
    }
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

impl LoFi {
    /// The LoFi evaluator of `car` on `road`.
    pub fn new(car: &Car, road: &Road) -> LoFi {
        LoFi {
            car: car.clone(),
            road: *road,
        }
    }
}

/// LoFi criteria of any quarter car on `road`: the closed forms for an undamped tyre,
/// the exact Lyapunov route otherwise.
pub fn quarter_criteria(q: &QuarterCar, road: &Road) -> Result<Criteria> {
    q.validate()?;
    if q.ct == 0.0 {
        Ok(quarter_car_rms(q, road.intensity()))
    } else {
        criteria_exact(&quarter_car(q), road)
    }
}

impl Evaluator for LoFi {
    fn evaluate(&self, ks: f64, cs: f64) -> Result<Criteria> {
        let mut q = self.car.quarter();
        q.ks = ks;
        q.cs = cs;
        quarter_criteria(&q, &self.road)
    }
    fn name(&self) -> String {
        "quarter".into()
    }
}

/// HiFi evaluator: the full car with both front corners set to `(ks, cs)`, by the
/// exact modal route (Kronecker route as fallback). With correlated tracks it works on
/// the left-right symmetric half (8 states, exact for mirror-symmetric cars).
///
/// The model is affine in the design: `K = K0 + ks dK`, `C = C0 + cs dC`, so it is
/// assembled once and each evaluation only adds two scaled matrices.
#[derive(Debug, Clone, PartialEq)]
pub struct HiFi {
    car: Car,
    road: Road,
    base: LinearModel,
    dk: nalgebra::DMatrix<f64>,
    dc: nalgebra::DMatrix<f64>,
}

impl HiFi {
    /// Prepares the HiFi evaluator of `car` on `road`.
    pub fn new(car: &Car, road: &Road) -> Result<HiFi> {
        car.validate()?;
        road.validate()?;
        let model_at = |ks: f64, cs: f64| {
            let mut c = car.clone();
            c.front.spring = ks;
            c.front.damper = cs;
            let full = full_car(&c);
            match road.tracks {
                Tracks::Correlated => symmetric_half(&full),
                Tracks::Independent => full,
            }
        };
        let base = model_at(0.0, 0.0);
        let unit = model_at(1.0, 1.0);
        Ok(HiFi {
            car: car.clone(),
            road: *road,
            dk: &unit.k - &base.k,
            dc: &unit.c - &base.c,
            base,
        })
    }

    /// The car.
    pub fn car(&self) -> &Car {
        &self.car
    }

    /// The road.
    pub fn road(&self) -> &Road {
        &self.road
    }
}

impl Evaluator for HiFi {
    fn evaluate(&self, ks: f64, cs: f64) -> Result<Criteria> {
        let mut front = self.car.front;
        front.spring = ks;
        front.damper = cs;
        crate::car::check_design(ks, cs)?;
        front.validate("front")?;
        let mut m = self.base.clone();
        m.k += ks * &self.dk;
        m.c += cs * &self.dc;
        match criteria_fast_exact(&m, &self.road) {
            Ok(c) => Ok(c),
            // A road warp: the frequency route with ISO 8608's low cutoff.
            Err(RideError::Numerical(msg)) if msg.starts_with("road warp") => {
                Ok(criteria_spectral(&m, &self.road, 1e-8)?.criteria)
            }
            Err(e) => Err(e),
        }
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
    let spectral = criteria_spectral(&model, road, 1e-8)?;
    let (values, route) = match criteria_fast_exact(&model, road) {
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
