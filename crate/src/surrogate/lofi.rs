//! The LoFi a surrogate tunes: the front quarter car of the car on an ISO 8608 class
//! (closed forms, or the exact route with a damped tyre) or on a measured road (the closed
//! form with the road's shaping filters, [`crate::road_profile::ShapedQuarter`]), so that
//! every approach fits and predicts on the road its HiFi samples were taken on.

use crate::analysis::{front_quarter, quarter_criteria};
use crate::car::{Car, QuarterCar};
use crate::error::Result;
use crate::evaluate::{Criteria, Evaluator};
use crate::road::Road;
use crate::road_profile::QuarterRoute;
use serde::{Deserialize, Serialize};
use std::sync::Arc;

/// The LoFi of a surrogate: `car`'s front quarter car with the front spring and damper
/// replaced, on `measured` when there is one, else on `road`.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct SurrogateLoFi {
    /// The car (rear and masses fixed).
    pub car: Car,
    /// The ISO road; on a measured road, ISO 8608's default class at that road's speed
    /// and tracks, which no value uses.
    pub road: Road,
    /// The quarter car's route on the measured road, shaped at its speed (shared by every
    /// fitted surrogate). Not data: a surrogate on a measured road has no record
    /// ([`super::Guarded::record`]).
    #[serde(skip)]
    pub measured: Option<Arc<dyn QuarterRoute>>,
}

impl PartialEq for SurrogateLoFi {
    /// Equal car, ISO road and measured road (by its shaped road).
    fn eq(&self, other: &SurrogateLoFi) -> bool {
        self.car == other.car
            && self.road == other.road
            && match (&self.measured, &other.measured) {
                (None, None) => true,
                (Some(a), Some(b)) => a.road() == b.road(),
                _ => false,
            }
    }
}

impl SurrogateLoFi {
    /// RMS `[BAcc m/s^2, DTL N, SWS m]` of any quarter car `q` on this LoFi's road.
    pub fn quarter_criteria(&self, q: &QuarterCar) -> Result<Criteria> {
        match &self.measured {
            None => quarter_criteria(q, &self.road),
            Some(road) => {
                q.validate()?;
                road.criteria(q)
            }
        }
    }
}

impl Evaluator for SurrogateLoFi {
    fn evaluate(&self, ks: f64, cs: f64) -> Result<Criteria> {
        self.quarter_criteria(&front_quarter(&self.car, ks, cs)?)
    }

    fn name(&self) -> String {
        "quarter".into()
    }
}
