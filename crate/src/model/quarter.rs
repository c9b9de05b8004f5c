//! LoFi: the 2-DOF quarter car of the front corner, `q = [zs, zu]`.
//!
//! ```text
//! ms zs'' = -ks (zs - zu) - cs (zs' - zu')
//! mu zu'' =  ks (zs - zu) + cs (zs' - zu') - kt (zu - zr) - ct (zu' - zr')
//! ```
//! Outputs: BAcc = zs'', DTL = kt (zu - zr), SWS = zs - zu.

use super::{LinearModel, OutputRow, Wheel};
use crate::car::QuarterCar;
use nalgebra::{dmatrix, dvector};

/// Builds the quarter-car [`LinearModel`] (one body coordinate, one wheel).
pub fn quarter_car(p: &QuarterCar) -> LinearModel {
    let QuarterCar {
        ms,
        mu,
        ks,
        cs,
        kt,
        ct,
    } = *p;
    LinearModel {
        dof_names: vec!["body heave zs", "wheel hop zu"],
        m: dmatrix![ms, 0.0; 0.0, mu],
        c: dmatrix![cs, -cs; -cs, cs + ct],
        k: dmatrix![ks, -ks; -ks, ks + kt],
        kr: dmatrix![0.0; kt],
        cr: dmatrix![0.0; ct],
        n_body: 1,
        outputs: [
            OutputRow {
                q: dvector![0.0, 0.0],
                v: dvector![0.0, 0.0],
                a: dvector![1.0, 0.0],
                r: dvector![0.0],
            },
            OutputRow {
                q: dvector![0.0, kt],
                v: dvector![0.0, 0.0],
                a: dvector![0.0, 0.0],
                r: dvector![-kt],
            },
            OutputRow {
                q: dvector![1.0, -1.0],
                v: dvector![0.0, 0.0],
                a: dvector![0.0, 0.0],
                r: dvector![0.0],
            },
        ],
        wheels: vec![Wheel {
            track: 0,
            behind: 0.0,
        }],
        front_corners: vec![dvector![1.0, -1.0]],
    }
}
