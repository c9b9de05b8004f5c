//! HiFi: the 7-DOF full car, `q = [z, theta, phi, zu1, zu2, zu3, zu4]`.
//!
//! Axes x forward, y left, z up. Corner i at `(x_i, y_i)`: 1 front-right `(a, -tf/2)`,
//! 2 front-left `(a, tf/2)`, 3 rear-right `(-b, -tr/2)`, 4 rear-left `(-b, tr/2)`.
//! Body point above corner i: `z_si = z - x_i theta + y_i phi` (theta > 0 nose down).
//!
//! ```text
//! F_i = -ks_i (z_si - z_ui) - cs_i (z_si' - z_ui')
//! M z'' = sum F_i,  Iyy theta'' = sum (-x_i) F_i,  Ixx phi'' = sum y_i F_i
//! mu_i z_ui'' = -F_i - kt_i (z_ui - zr_i) - ct_i (z_ui' - zr_i')
//! ```
//! Outputs at corner 1: BAcc = z_s1'', DTL = kt_1 (z_u1 - zr_1), SWS = z_s1 - z_u1.
//! M, C and K are assembled as sums of rank-one terms `k d d^T` over the springs and
//! dampers, with `d` the deflection vector of each element.

use super::{LinearModel, OutputRow, Wheel};
use crate::car::Car;
use nalgebra::{DMatrix, DVector};

const N: usize = 7;

/// Builds the full-car [`LinearModel`] (three body coordinates, four wheels).
pub fn full_car(car: &Car) -> LinearModel {
    let (a, b) = (car.a, car.b);
    let (tf, tr) = (car.track_front, car.track_rear);
    let corners = [
        (a, -tf / 2.0, &car.front),
        (a, tf / 2.0, &car.front),
        (-b, -tr / 2.0, &car.rear),
        (-b, tr / 2.0, &car.rear),
    ];
    let mut m = DMatrix::zeros(N, N);
    m[(0, 0)] = car.sprung_mass;
    m[(1, 1)] = car.pitch_inertia;
    m[(2, 2)] = car.roll_inertia;
    let mut k = DMatrix::zeros(N, N);
    let mut c = DMatrix::zeros(N, N);
    let mut kr = DMatrix::zeros(N, 4);
    let mut cr = DMatrix::zeros(N, 4);
    let mut deflection = Vec::with_capacity(4);
    for (i, &(x, y, axle)) in corners.iter().enumerate() {
        let u = 3 + i;
        m[(u, u)] = axle.unsprung_mass;
        // Suspension deflection z_si - z_ui as a row over q.
        let mut d = DVector::zeros(N);
        d[0] = 1.0;
        d[1] = -x;
        d[2] = y;
        d[u] = -1.0;
        k += axle.spring * &d * d.transpose();
        c += axle.damper * &d * d.transpose();
        // Tyre: kt (z_ui - zr_i).
        k[(u, u)] += axle.tire_stiffness;
        c[(u, u)] += axle.tire_damping;
        kr[(u, i)] = axle.tire_stiffness;
        cr[(u, i)] = axle.tire_damping;
        deflection.push(d);
    }
    let zero = DVector::zeros(N);
    let mut body1 = DVector::zeros(N);
    body1.rows_mut(0, 3).copy_from(&deflection[0].rows(0, 3));
    let mut tyre1 = DVector::zeros(N);
    tyre1[3] = car.front.tire_stiffness;
    let mut r_dtl = DVector::zeros(4);
    r_dtl[0] = -car.front.tire_stiffness;
    let l = car.wheelbase();
    LinearModel {
        dof_names: vec![
            "body heave z",
            "body pitch theta",
            "body roll phi",
            "wheel hop front-right",
            "wheel hop front-left",
            "wheel hop rear-right",
            "wheel hop rear-left",
        ],
        m,
        c,
        k,
        kr,
        cr,
        n_body: 3,
        outputs: [
            OutputRow {
                q: zero.clone(),
                v: zero.clone(),
                a: body1,
                r: DVector::zeros(4),
            },
            OutputRow {
                q: tyre1,
                v: zero.clone(),
                a: zero.clone(),
                r: r_dtl,
            },
            OutputRow {
                q: deflection[0].clone(),
                v: zero.clone(),
                a: zero,
                r: DVector::zeros(4),
            },
        ],
        wheels: vec![
            Wheel {
                track: 0,
                behind: 0.0,
            },
            Wheel {
                track: 1,
                behind: 0.0,
            },
            Wheel {
                track: 0,
                behind: l,
            },
            Wheel {
                track: 1,
                behind: l,
            },
        ],
        front_corners: vec![deflection[0].clone(), deflection[1].clone()],
    }
}

/// The left-right symmetric half of a full-car model, `p = [z, theta, u_f, u_r]` with
/// `q = S p`: both front wheels move by `u_f`, both rear wheels by `u_r`, no roll.
///
/// With correlated tracks both wheels of an axle see the same input, and a car whose
/// left and right sides are mirror images (every car file) responds only in this
/// subspace, so the Galerkin projection `S^T M S`, `S^T C S`, `S^T K S`, `S^T Kr`,
/// `S^T Cr` and outputs `row S` reproduce the full model exactly with 8 states instead of 14.
pub fn symmetric_half(full: &LinearModel) -> LinearModel {
    let mut s = DMatrix::zeros(N, 4);
    s[(0, 0)] = 1.0;
    s[(1, 1)] = 1.0;
    s[(3, 2)] = 1.0;
    s[(4, 2)] = 1.0;
    s[(5, 3)] = 1.0;
    s[(6, 3)] = 1.0;
    let st = s.transpose();
    let row = |r: &OutputRow| OutputRow {
        q: &st * &r.q,
        v: &st * &r.v,
        a: &st * &r.a,
        r: r.r.clone(),
    };
    LinearModel {
        dof_names: vec![
            "body heave z",
            "body pitch theta",
            "wheel hop front",
            "wheel hop rear",
        ],
        m: &st * &full.m * &s,
        c: &st * &full.c * &s,
        k: &st * &full.k * &s,
        kr: &st * &full.kr,
        cr: &st * &full.cr,
        n_body: 2,
        outputs: [
            row(&full.outputs[0]),
            row(&full.outputs[1]),
            row(&full.outputs[2]),
        ],
        wheels: full.wheels.clone(),
        front_corners: full.front_corners.iter().map(|d| &st * d).collect(),
    }
}

/// The left-right antisymmetric half of a full-car model, `p = [phi, w_f, w_r]` with
/// `q = S p`: roll, the front wheels moving by `+w_f` (right) and `-w_f` (left), the rear
/// ones by `+w_r` and `-w_r`, no heave or pitch; driven by the antisymmetric road
/// `a = (zr_right - zr_left) / 2`, one input per axle (wheel 0 front, wheel 1 rear at `L`).
///
/// A mirror-symmetric car (every car file) splits exactly into this half and the
/// [`symmetric_half`] (driven by `(zr_right + zr_left) / 2`): with independent tracks
/// of intensity `W` each, both halves see intensity `W / 2` and are uncorrelated, so
/// `var = (var_symmetric + var_antisymmetric) / 2` with each half's variance taken with
/// intensity `W` on one source (correlated tracks). Outputs are those of corner 1
/// (front right), the input weights `+1` right and `-1` left.
pub(crate) fn antisymmetric_half(full: &LinearModel) -> LinearModel {
    let mut s = DMatrix::zeros(N, 3);
    s[(2, 0)] = 1.0;
    s[(3, 1)] = 1.0;
    s[(4, 1)] = -1.0;
    s[(5, 2)] = 1.0;
    s[(6, 2)] = -1.0;
    let st = s.transpose();
    // Wheel inputs: front = right minus left front wheel, rear likewise.
    let mut w = DMatrix::zeros(4, 2);
    w[(0, 0)] = 1.0;
    w[(1, 0)] = -1.0;
    w[(2, 1)] = 1.0;
    w[(3, 1)] = -1.0;
    let wt = w.transpose();
    let row = |r: &OutputRow| OutputRow {
        q: &st * &r.q,
        v: &st * &r.v,
        a: &st * &r.a,
        r: &wt * &r.r,
    };
    let behind = full.wheels[2].behind;
    LinearModel {
        dof_names: vec![
            "body roll phi",
            "wheel hop front, antisymmetric",
            "wheel hop rear, antisymmetric",
        ],
        m: &st * &full.m * &s,
        c: &st * &full.c * &s,
        k: &st * &full.k * &s,
        kr: &st * &full.kr * &w,
        cr: &st * &full.cr * &w,
        n_body: 1,
        outputs: [
            row(&full.outputs[0]),
            row(&full.outputs[1]),
            row(&full.outputs[2]),
        ],
        wheels: vec![
            Wheel {
                track: 0,
                behind: 0.0,
            },
            Wheel { track: 0, behind },
        ],
        front_corners: full.front_corners.iter().map(|d| &st * d).collect(),
    }
}
