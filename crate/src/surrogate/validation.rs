//! The common yardstick of surrogates: HiFi values on an `n x n` grid over the design box.

use super::metrics::{metrics_by_criterion, ByCriterion, Metrics};
use crate::design::DesignBox;
use crate::doe::full_factorial;
use crate::error::{Result, RideError};
use crate::evaluate::{Criteria, Evaluator};

/// Levels per axis of the default validation grid (`20 x 20` points).
pub const VALIDATION_LEVELS: usize = 20;

/// HiFi values on an `n x n` grid over the design box, the common yardstick of surrogates.
#[derive(Debug, Clone, PartialEq)]
pub struct ValidationSet {
    /// Levels per axis.
    pub levels: usize,
    /// Grid points `(ks N/m, cs N s/m)`, Ks level outer.
    pub points: Vec<(f64, f64)>,
    /// HiFi criteria at the points.
    pub hifi: Vec<Criteria>,
}

impl ValidationSet {
    /// Evaluates `hifi` on the `levels x levels` grid over `design_box`.
    pub fn new<E: Evaluator>(hifi: &E, design_box: &DesignBox, levels: usize) -> Result<Self> {
        let grid = full_factorial(levels)
            .map_err(|e| RideError::field("validation-grid", e.to_string()))?;
        let points: Vec<(f64, f64)> = grid
            .unit
            .iter()
            .map(|p| design_box.scale(p[0], p[1]))
            .collect();
        let hifi = points
            .iter()
            .map(|&(ks, cs)| hifi.evaluate(ks, cs))
            .collect::<Result<_>>()?;
        Ok(ValidationSet {
            levels,
            points,
            hifi,
        })
    }

    /// The predictions of `model` at the points.
    pub fn predict<E: Evaluator + ?Sized>(&self, model: &E) -> Result<Vec<Criteria>> {
        self.points
            .iter()
            .map(|&(ks, cs)| model.evaluate(ks, cs))
            .collect()
    }

    /// R^2, RMSE, MAE and RTE of `predicted` (at the points) per criterion.
    pub fn metrics(&self, predicted: &[Criteria]) -> Result<ByCriterion<Metrics>> {
        metrics_by_criterion(&self.hifi, predicted)
    }
}
