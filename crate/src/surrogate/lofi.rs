//! The LoFi a surrogate tunes: the front quarter car of the car on an ISO 8608 class
//! (closed forms, or the exact route with a damped tyre) or on a measured road (the closed
//! form with the road's shaping filters, [`ShapedQuarter`]), so that every
//! approach fits and predicts on the road its HiFi samples were taken on.

use crate::analysis::{front_quarter, quarter_criteria};
use crate::car::{Car, QuarterCar};
use crate::error::Result;
use crate::evaluate::{Criteria, Evaluator};
use crate::road::Road;
use crate::road_profile::ShapedQuarter;
use std::sync::Arc;

/// The LoFi of a surrogate: `car`'s front quarter car with the front spring and damper
/// replaced, on `measured` when there is one, else on `road`.
#[derive(Debug, Clone, PartialEq)]
pub struct SurrogateLoFi {
    /// The car (rear and masses fixed).
    pub car: Car,
    /// The ISO road; on a measured road, ISO 8608's default class at that road's speed
    /// and tracks, which no value uses.
    pub road: Road,
    /// The quarter car's route on the measured road, shaped at its speed (shared by every
    /// fitted surrogate).
    pub measured: Option<Arc<ShapedQuarter>>,
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
