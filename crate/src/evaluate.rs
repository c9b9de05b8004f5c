//! One way to evaluate anything: the LoFi model, the HiFi model and every
//! surrogate implement [`Evaluator`], so maps, optimisers and the page take any of them.

use crate::error::Result;
use serde::{Deserialize, Serialize};

/// The three ride criteria at the front corner, RMS over the whole band.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Criteria {
    /// RMS body vertical acceleration above the front wheel, m/s^2.
    pub bacc: f64,
    /// RMS dynamic tyre load `kt (zu - zr)`, N.
    pub dtl: f64,
    /// RMS suspension working space `zs - zu`, m.
    pub sws: f64,
}

impl Criteria {
    /// The criteria as an array `[bacc, dtl, sws]`.
    pub fn to_array(self) -> [f64; 3] {
        [self.bacc, self.dtl, self.sws]
    }

    /// Builds criteria from an array `[bacc, dtl, sws]`.
    pub fn from_array(a: [f64; 3]) -> Self {
        Criteria {
            bacc: a[0],
            dtl: a[1],
            sws: a[2],
        }
    }
}

/// Names of the criteria in the order of [`Criteria::to_array`].
pub(crate) const CRITERIA_NAMES: [&str; 3] = ["bacc", "dtl", "sws"];

/// Anything that maps a front design (spring rate `ks`, N/m; damper rate `cs`, N s/m)
/// to the three criteria.
pub trait Evaluator {
    /// Criteria at one design point.
    fn evaluate(&self, ks: f64, cs: f64) -> Result<Criteria>;

    /// A short name for reports ("quarter", "full", "vba-qts", ...).
    fn name(&self) -> String;
}

impl<E: Evaluator + ?Sized> Evaluator for &E {
    fn evaluate(&self, ks: f64, cs: f64) -> Result<Criteria> {
        (**self).evaluate(ks, cs)
    }
    fn name(&self) -> String {
        (**self).name()
    }
}

impl<E: Evaluator + ?Sized> Evaluator for Box<E> {
    fn evaluate(&self, ks: f64, cs: f64) -> Result<Criteria> {
        (**self).evaluate(ks, cs)
    }
    fn name(&self) -> String {
        (**self).name()
    }
}
