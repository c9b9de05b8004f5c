//! Design maps of any model for the explorer: LoFi, HiFi, the fitted surrogate, and the
//! surrogate's error against the HiFi, on the cell-centre grid of the design box
//! ([`Grid::cells`]). They go through the one map pipeline of [`crate::maps`], as the CLI's
//! maps do: [`Dcs`] computes the criteria, [`DosMap`] judges the design objectives.

use crate::maps::{Dcs, DosMap, Grid};
use std::rc::Rc;

/// A design map of one model: the criteria on the grid and the objectives judged there.
#[derive(Debug, Clone, PartialEq)]
pub struct ModelMap {
    /// The model's criteria (kept between objective edits, hence shared). For
    /// [`Model::SurrogateError`], the fields hold `100 (surrogate / HiFi - 1)`, %.
    pub values: Rc<Dcs>,
    /// The design objectives on it; for the error map, the HiFi's.
    pub dos: DosMap,
}

impl ModelMap {
    /// The grid.
    pub fn grid(&self) -> &Grid {
        &self.values.grid
    }

    /// `[bacc plane, dtl plane, sws plane]` in one vector: index `c nx ny + j nx + i`
    /// (the page's layout; each plane is the [`Dcs`] field, Cs rows, Ks columns).
    pub fn planes(&self) -> Vec<f64> {
        let v = &self.values;
        [v.bacc.as_slice(), &v.dtl, &v.sws].concat()
    }

    /// The objectives each cell breaks as a bitmask ([`crate::maps::OBJECTIVE_BITS`]);
    /// 0 where the design is feasible.
    pub fn broken(&self) -> &[u8] {
        &self.dos.mask
    }

    /// 1 where the cell meets every active objective, 0 where not.
    pub fn feasible(&self) -> Vec<u8> {
        self.dos.mask.iter().map(|&b| u8::from(b == 0)).collect()
    }
}

/// The error map's fields, `100 (surrogate / HiFi - 1)` %, on the HiFi map's grid.
pub(crate) fn error_values(surrogate: &Dcs, hifi: &Dcs) -> Dcs {
    let pct = |p: &[f64], h: &[f64]| -> Vec<f64> {
        p.iter().zip(h).map(|(p, h)| 100.0 * (p - h) / h).collect()
    };
    Dcs {
        evaluator: format!("{} error vs {}", surrogate.evaluator, hifi.evaluator),
        bacc: pct(&surrogate.bacc, &hifi.bacc),
        dtl: pct(&surrogate.dtl, &hifi.dtl),
        sws: pct(&surrogate.sws, &hifi.sws),
        ..hifi.clone()
    }
}
