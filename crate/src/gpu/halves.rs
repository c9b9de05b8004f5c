//! The full car split into its two mirror halves, the models the GPU route solves at
//! each frequency.
//!
//! Every car is mirror-symmetric (one [`crate::car::Axle`] per axle), so with wheel inputs
//! `r_i` the response separates into a symmetric half `p = [z, theta, u_f, u_r]`
//! (`q = S_s p`: both wheels of an axle move alike, no roll) driven by `(r_R + r_L) / 2`
//! and an antisymmetric half `p = [phi, -, w_f, w_r]` (right wheels `+w`, left `-w`)
//! driven by `(r_R - r_L) / 2`, each the Galerkin projection `S^T M S`, `S^T C S`,
//! `S^T K S` of the 7-DOF model of [`crate::model::full_car`]. Corner 1's outputs are the
//! sum of the two halves' outputs.
//!
//! - Correlated tracks: `r_L = r_R`, only the symmetric half moves, weight 1.
//! - Independent tracks: the two halves' inputs are uncorrelated with half the track PSD
//!   each, so `var = (var_s + var_a) / 2`, each computed with the full PSD.
//!
//! The antisymmetric half has one body coordinate (roll); its second body slot is a
//! decoupled placeholder with `Z = 1 + i w` (never singular, never driven), so both halves
//! share one shape: two body coordinates, two unsprung ones. The unsprung block is
//! diagonal and the matrices symmetric, so the kernel eliminates the wheels and solves
//! a 2 x 2 complex system per frequency and wheel group.

use crate::car::Car;
use crate::error::{Result, RideError};
use crate::model::{full_car, LinearModel, N_OUT};
use crate::road::Tracks;
use nalgebra::DMatrix;

/// Coordinates of a half: two body, two unsprung (front, rear).
pub(crate) const N_COORD: usize = 4;
/// The nine distinct entries of a half's symmetric matrices: body `(0,0)`, `(0,1)`,
/// `(1,1)`, coupling `(0,2)`, `(0,3)`, `(1,2)`, `(1,3)`, unsprung `(2,2)`, `(3,3)`.
pub(crate) const SLOTS: [(usize, usize); 9] = [
    (0, 0),
    (0, 1),
    (1, 1),
    (0, 2),
    (0, 3),
    (1, 2),
    (1, 3),
    (2, 2),
    (3, 3),
];

/// One half: `Z(w) = K0 + ks dK - w^2 M + i w (C0 + cs dC)` on the nine [`SLOTS`], the
/// road input of each wheel group (front, rear) and the output rows of corner 1.
#[derive(Debug, Clone, PartialEq)]
pub struct Half {
    /// Share of the variance: 1 (correlated), 1/2 (each half, independent tracks).
    pub weight: f64,
    /// Mass entries, kg, kg m^2 (coupling slots are zero).
    pub m: [f64; 9],
    /// Stiffness without the front springs, N/m, N m/rad, N/rad.
    pub k0: [f64; 9],
    /// Stiffness per unit front spring rate, -.
    pub dk: [f64; 9],
    /// Damping without the front dampers.
    pub c0: [f64; 9],
    /// Damping per unit front damper rate, -.
    pub dc: [f64; 9],
    /// Generalised force per unit road displacement of each group `[front, rear]`.
    pub kr: [[f64; N_COORD]; 2],
    /// Generalised force per unit road velocity of each group.
    pub cr: [[f64; N_COORD]; 2],
    /// Output feed-through per unit road displacement of each group `[BAcc, DTL, SWS]`.
    pub yr: [[f64; N_OUT]; 2],
    /// Output coefficients on `p` (`[BAcc, DTL, SWS]` rows).
    pub out_q: [[f64; N_COORD]; N_OUT],
    /// Output coefficients on `p'`.
    pub out_v: [[f64; N_COORD]; N_OUT],
    /// Output coefficients on `p''`.
    pub out_a: [[f64; N_COORD]; N_OUT],
}

/// The halves of `car` (front spring and damper free) for `tracks`.
pub(crate) fn halves(car: &Car, tracks: Tracks) -> Result<Vec<Half>> {
    car.validate()?;
    let mut base_car = car.clone();
    base_car.front.spring = 0.0;
    base_car.front.damper = 0.0;
    let mut unit_car = base_car.clone();
    unit_car.front.spring = 1.0;
    unit_car.front.damper = 1.0;
    let base = full_car(&base_car);
    let unit = full_car(&unit_car);
    let sym = (symmetric_projection(), [1.0, 1.0, 1.0, 1.0], false);
    let anti = (antisymmetric_projection(), [1.0, -1.0, 1.0, -1.0], true);
    match tracks {
        Tracks::Correlated => Ok(vec![project(&base, &unit, &sym, 1.0)?]),
        Tracks::Independent => Ok(vec![
            project(&base, &unit, &sym, 0.5)?,
            project(&base, &unit, &anti, 0.5)?,
        ]),
    }
}

/// `q = S p` for `p = [z, theta, u_f, u_r]`.
fn symmetric_projection() -> DMatrix<f64> {
    let mut s = DMatrix::zeros(7, N_COORD);
    s[(0, 0)] = 1.0;
    s[(1, 1)] = 1.0;
    s[(3, 2)] = 1.0;
    s[(4, 2)] = 1.0;
    s[(5, 3)] = 1.0;
    s[(6, 3)] = 1.0;
    s
}

/// `q = S p` for `p = [phi, placeholder, w_f, w_r]` (right wheels `+w`, left `-w`).
fn antisymmetric_projection() -> DMatrix<f64> {
    let mut s = DMatrix::zeros(7, N_COORD);
    s[(2, 0)] = 1.0;
    s[(3, 2)] = 1.0;
    s[(4, 2)] = -1.0;
    s[(5, 3)] = 1.0;
    s[(6, 3)] = -1.0;
    s
}

fn slots(m: &DMatrix<f64>) -> [f64; 9] {
    SLOTS.map(|(i, j)| m[(i, j)])
}

/// Projects the model pair onto one half; `signs` are the wheels' shares of the half's
/// input, `placeholder` marks the unused second body slot.
fn project(
    base: &LinearModel,
    unit: &LinearModel,
    (s, signs, placeholder): &(DMatrix<f64>, [f64; 4], bool),
    weight: f64,
) -> Result<Half> {
    let st = s.transpose();
    let p = |m: &DMatrix<f64>| &st * m * s;
    let mut m = p(&base.m);
    let (mut k0, dk) = (p(&base.k), p(&unit.k) - p(&base.k));
    let (mut c0, dc) = (p(&base.c), p(&unit.c) - p(&base.c));
    if *placeholder {
        m[(1, 1)] = 0.0;
        k0[(1, 1)] = 1.0;
        c0[(1, 1)] = 1.0;
    }
    for mat in [&m, &k0, &dk, &c0, &dc] {
        let scale = mat.amax().max(1.0);
        let off_slots = (0..N_COORD).any(|i| {
            (0..N_COORD).any(|j| {
                let listed = SLOTS.contains(&(i.min(j), i.max(j)));
                (mat[(i, j)] - mat[(j, i)]).abs() > 1e-12 * scale || (!listed && mat[(i, j)] != 0.0)
            })
        });
        if off_slots {
            return Err(RideError::Numerical(
                "GPU route: a half's matrices are not symmetric with a diagonal unsprung block"
                    .into(),
            ));
        }
    }
    if (0..2).any(|b| (2..4).any(|u| m[(b, u)] != 0.0)) {
        return Err(RideError::Numerical(
            "GPU route: mass coupling between body and wheels".into(),
        ));
    }
    let groups = [[0usize, 1], [2, 3]];
    let mut kr = [[0.0; N_COORD]; 2];
    let mut cr = [[0.0; N_COORD]; 2];
    let mut yr = [[0.0; N_OUT]; 2];
    for (g, wheels) in groups.iter().enumerate() {
        for &j in wheels {
            let skr = &st * base.kr.column(j);
            let scr = &st * base.cr.column(j);
            for i in 0..N_COORD {
                kr[g][i] += signs[j] * skr[i];
                cr[g][i] += signs[j] * scr[i];
            }
            for (y, out) in yr[g].iter_mut().zip(&base.outputs) {
                *y += signs[j] * out.r[j];
            }
        }
    }
    let row = |v: &nalgebra::DVector<f64>| -> [f64; N_COORD] {
        let r = &st * v;
        std::array::from_fn(|i| r[i])
    };
    Ok(Half {
        weight,
        m: slots(&m),
        k0: slots(&k0),
        dk: slots(&dk),
        c0: slots(&c0),
        dc: slots(&dc),
        kr,
        cr,
        yr,
        out_q: std::array::from_fn(|o| row(&base.outputs[o].q)),
        out_v: std::array::from_fn(|o| row(&base.outputs[o].v)),
        out_a: std::array::from_fn(|o| row(&base.outputs[o].a)),
    })
}
