//! Linear vehicle models from one description: mass, damping and stiffness matrices,
//! road input matrices and the three output rows. Both the quarter car (LoFi) and the
//! full car (HiFi) are built as a [`LinearModel`]; every analysis works on that.
//!
//! Equations of motion, generalised coordinates `q` (m, rad), wheel road displacements `r` (m):
//!
//! ```text
//! M q'' + C q' + K q = Kr r + Cr r'
//! y = Yq q + Yv q' + Ya q'' + Yr r          (y = [BAcc, DTL, SWS])
//! ```
//!
//! The first `n_body` coordinates are the body; the others are unsprung masses, each
//! coupled only to the body (their blocks of M, C and K are diagonal), which the
//! frequency route exploits.

mod full;
pub mod modes;
mod quarter;

pub(crate) use full::antisymmetric_half;
pub use full::{full_car, symmetric_half};
pub use modes::Mode;
pub use quarter::quarter_car;

use crate::error::{Result, RideError};
use crate::road::{Road, Tracks};
use nalgebra::{DMatrix, DVector};

/// Number of outputs: BAcc, DTL, SWS.
pub(crate) const N_OUT: usize = 3;

/// One output as a linear form of `q`, `q'`, `q''` and `r`.
#[derive(Debug, Clone, PartialEq)]
pub struct OutputRow {
    /// Coefficients on `q`.
    pub q: DVector<f64>,
    /// Coefficients on `q'`.
    pub v: DVector<f64>,
    /// Coefficients on `q''`.
    pub a: DVector<f64>,
    /// Coefficients on the wheel road displacements `r`.
    pub r: DVector<f64>,
}

/// A wheel's place on the road: which track it runs on and its delay behind the front axle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Wheel {
    /// 0 = right track, 1 = left track.
    pub track: usize,
    /// Distance behind the front axle, m (0 for front wheels, L for rear wheels).
    pub behind: f64,
}

/// A linear vehicle model.
#[derive(Debug, Clone, PartialEq)]
pub struct LinearModel {
    /// Names of the generalised coordinates.
    pub dof_names: Vec<&'static str>,
    /// Mass matrix, kg and kg m^2.
    pub m: DMatrix<f64>,
    /// Damping matrix.
    pub c: DMatrix<f64>,
    /// Stiffness matrix.
    pub k: DMatrix<f64>,
    /// Road displacement to generalised force (n x wheels).
    pub kr: DMatrix<f64>,
    /// Road velocity to generalised force (n x wheels).
    pub cr: DMatrix<f64>,
    /// Number of body coordinates (the first ones).
    pub n_body: usize,
    /// Output rows `[BAcc, DTL, SWS]`.
    pub outputs: [OutputRow; N_OUT],
    /// Where each wheel runs.
    pub wheels: Vec<Wheel>,
    /// Deflection vectors `d` (`d . q = z_s - z_u`) of the front suspension corners, whose
    /// dampers are the design variable (the time domain's asymmetric damper acts there).
    pub front_corners: Vec<DVector<f64>>,
}

/// One independent white road-velocity source and the wheels it drives.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Source {
    /// `(wheel index, delay s)` pairs.
    pub channels: Vec<(usize, f64)>,
}

/// How the road drives a model: independent white velocity sources of intensity
/// `W` (m^2/s, `E[w(t) w(s)] = W delta(t-s)`), each feeding some wheels with delays.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Excitation {
    /// The sources (one for correlated tracks, one per track otherwise).
    pub sources: Vec<Source>,
    /// Two-sided intensity of each source's velocity, m^2/s.
    pub intensity: f64,
}

impl LinearModel {
    /// Number of generalised coordinates.
    pub fn n(&self) -> usize {
        self.m.nrows()
    }

    /// The road excitation of this model on `road`: wheels on the same track share a
    /// source (all wheels share one when the tracks are correlated), delayed by `behind / v`.
    pub(crate) fn excitation(&self, road: &Road) -> Excitation {
        let n_src = match road.tracks {
            Tracks::Correlated => 1,
            Tracks::Independent => 2,
        };
        let mut sources = vec![
            Source {
                channels: Vec::new()
            };
            n_src
        ];
        for (j, w) in self.wheels.iter().enumerate() {
            let s = if n_src == 1 { 0 } else { w.track };
            sources[s].channels.push((j, road.delay(w.behind)));
        }
        sources.retain(|s| !s.channels.is_empty());
        Excitation {
            sources,
            intensity: road.intensity(),
        }
    }

    /// First-order form with `x = [q; q']`:
    /// `x' = A x + Bd r + Bv r'`, `y = Cy x + Dr r + Dw r'`.
    pub(crate) fn state_space(&self) -> Result<StateSpace> {
        let n = self.n();
        let minv = self
            .m
            .clone()
            .try_inverse()
            .ok_or_else(|| RideError::Numerical("mass matrix is singular".into()))?;
        let mk = &minv * &self.k;
        let mc = &minv * &self.c;
        let wheels = self.kr.ncols();
        let mut a = DMatrix::zeros(2 * n, 2 * n);
        a.view_mut((0, n), (n, n))
            .copy_from(&DMatrix::identity(n, n));
        a.view_mut((n, 0), (n, n)).copy_from(&(-&mk));
        a.view_mut((n, n), (n, n)).copy_from(&(-&mc));
        let mut bd = DMatrix::zeros(2 * n, wheels);
        bd.view_mut((n, 0), (n, wheels))
            .copy_from(&(&minv * &self.kr));
        let mut bv = DMatrix::zeros(2 * n, wheels);
        bv.view_mut((n, 0), (n, wheels))
            .copy_from(&(&minv * &self.cr));
        let mut cy = DMatrix::zeros(N_OUT, 2 * n);
        let mut dr = DMatrix::zeros(N_OUT, wheels);
        let mut dw = DMatrix::zeros(N_OUT, wheels);
        for (i, o) in self.outputs.iter().enumerate() {
            // q'' = M^-1 (-K q - C q' + Kr r + Cr r') folded into the row.
            let at = o.a.transpose();
            cy.view_mut((i, 0), (1, n))
                .copy_from(&(o.q.transpose() - &at * &mk));
            cy.view_mut((i, n), (1, n))
                .copy_from(&(o.v.transpose() - &at * &mc));
            dr.row_mut(i)
                .copy_from(&(o.r.transpose() + &at * &minv * &self.kr));
            dw.row_mut(i).copy_from(&(&at * &minv * &self.cr));
        }
        Ok(StateSpace {
            a,
            bd,
            bv,
            cy,
            dr,
            dw,
        })
    }
}

/// State-space matrices of a [`LinearModel`] (see [`LinearModel::state_space`]).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct StateSpace {
    /// State matrix (2n x 2n).
    pub a: DMatrix<f64>,
    /// Road displacement input (2n x wheels).
    pub bd: DMatrix<f64>,
    /// Road velocity input (2n x wheels).
    pub bv: DMatrix<f64>,
    /// Output matrix (3 x 2n).
    pub cy: DMatrix<f64>,
    /// Direct road displacement feed-through (3 x wheels).
    pub dr: DMatrix<f64>,
    /// Direct road velocity feed-through (3 x wheels); must be zero for finite RMS.
    pub dw: DMatrix<f64>,
}
