//! The exact route on a shaped road: the model's state augmented with the shaping
//! filters, the variances from Lyapunov equations with the front-rear delay exact.
//!
//! Write the filter of a source as `F(s) = F0 + s Ft(s)`, `F0 = F(0)`,
//! `Ft(s) = (F(s) - F0) / s = C_f (sI - A_f)^-1 A_f^-1 B_f` (strictly proper, stable). The
//! road displacement of wheel group `g` (the source's wheels with delay `tau_g`, weighted
//! sums of their input columns) is then `r_g = F0 R(t - tau_g) + C_f xt_g`, with `R` the
//! integral of the white noise `w` (ISO's random walk, scaled) and `xt_g` a copy of the
//! filter state driven by the delayed noise, `xt_g' = A_f xt_g + Bt w(t - tau_g)`,
//! `Bt = A_f^-1 B_f`: a finite state cannot hold the filter's state `tau` ago, but a copy
//! driven by the delayed noise is exactly that state in stationarity. With
//! `E_g = -A^-1 Bd_g` and the shifted state `z = x - sum_g E_g F0 R_g` (as in
//! `criteria::exact`), the augmented state `X = [z; xt_1; ...; xt_G]` obeys
//!
//! ```text
//! X' = A_aug X + sum_g B_g w(t - tau_g)
//! A_aug = [ A   (Bd_g C_f + Bv_g C_f A_f)_g ]     B_g = [ Bv_g D_f - E_g F0 ]
//!         [ 0   diag(A_f, ..., A_f)         ]           [ Bt in block g     ]
//! y = [Cy, (Dr_g C_f)_g] X + sum_g G_g F0 R(t - tau_g),   G_g = Cy E_g + Dr_g
//! ```
//!
//! which is the white-noise form of `criteria::exact` with unit intensity: the variance
//! is `sum_{g,l} c X_gl exp(A_aug^T (tau_g - tau_l)) c^T` with `A X_gl + X_gl A^T + B_g B_l^T = 0`
//! (`tau_g >= tau_l`), the box-exponential terms `-2 F0 G_g c A^-1 (exp(A dt) - I) B_l` and
//! the box terms `F0^2 G_g G_l min(tau_g, tau_l)`, needing `sum_g G_g = 0` (else a road
//! warp). Independent sources add their variances. A constant filter (`F0 = D_f`, no
//! states) reduces this to `criteria::exact` exactly.

use super::lyap::Lyapunov;
use super::shaped::ShapedRoad;
use crate::criteria::{append_wk, static_gain};
use crate::error::{Result, RideError};
use crate::evaluate::Criteria;
use crate::model::{LinearModel, N_OUT};
use nalgebra::{DMatrix, DVector};

/// A wheel group of one source in the augmented form.
struct Group {
    tau: f64,
    b: DVector<f64>,
    /// Box gains `F0 G_g`.
    g: [f64; N_OUT],
}

/// The augmented white-noise form of one source.
struct Form {
    a: DMatrix<f64>,
    cy: DMatrix<f64>,
    groups: Vec<Group>,
}

/// Exact RMS `[BAcc, DTL, SWS]` of `model` on the shaped road (see the module doc).
///
/// Refuses, like [`crate::criteria::criteria_exact`], a white feed-through into an
/// output and a road warp (a source whose static gains do not cancel: independent
/// tracks with unequal front and rear track widths).
pub fn criteria_shaped(model: &LinearModel, road: &ShapedRoad) -> Result<Criteria> {
    let mut var = [0.0; N_OUT];
    for form in forms(model, road)? {
        let v = variances(&form)?;
        for o in 0..N_OUT {
            var[o] += v[o];
        }
    }
    if var.iter().any(|v| !v.is_finite() || *v < 0.0) {
        return Err(RideError::Numerical(
            "variance is not finite: is the model stable?".into(),
        ));
    }
    Ok(Criteria::from_array(var.map(f64::sqrt)))
}

/// The ISO 2631-1 Wk-weighted RMS body acceleration above the front wheel of `model` on
/// the shaped road, m/s^2: each source's augmented form (module doc) with the Wk filter
/// appended, driven by BAcc (as [`crate::criteria::bacc_wk_exact`] on an ISO road; BAcc
/// has no static gain from the road, and Wk none at 0 Hz, so the weighted output has no
/// box terms), by the same Lyapunov equations.
pub(crate) fn bacc_wk_shaped(model: &LinearModel, road: &ShapedRoad) -> Result<f64> {
    let mut var = 0.0;
    for form in forms(model, road)? {
        let scale = form.cy.row(0).amax().max(1.0);
        if form.groups.iter().any(|g| g.g[0].abs() > 1e-9 * scale) {
            return Err(static_gain());
        }
        let (a, weighted) = append_wk(&form.a, &form.cy.row(0).clone_owned());
        let n = a.nrows();
        // Only the weighted acceleration is asked for: the other rows stay zero.
        let mut cy = DMatrix::zeros(N_OUT, n);
        cy.row_mut(0).copy_from(&weighted);
        let groups = form
            .groups
            .into_iter()
            .map(|g| Group {
                tau: g.tau,
                b: g.b.resize_vertically(n, 0.0),
                g: [0.0; N_OUT],
            })
            .collect();
        var += variances(&Form { a, cy, groups })?[0];
    }
    if !var.is_finite() || var < 0.0 {
        return Err(RideError::Numerical(
            "weighted variance is not finite: is the model stable?".into(),
        ));
    }
    Ok(var.sqrt())
}

/// The augmented forms of every source that drives a wheel of `model`.
fn forms(model: &LinearModel, road: &ShapedRoad) -> Result<Vec<Form>> {
    road.validate()?;
    let ss = model.state_space()?;
    let scale = ss.dr.amax().max(1.0);
    if ss.dw.amax() > 1e-12 * scale {
        return Err(RideError::Numerical(
            "an output feeds through the road velocity: its RMS is unbounded".into(),
        ));
    }
    let nx = ss.a.nrows();
    let lu = ss.a.clone().lu();
    let e = -lu
        .solve(&ss.bd)
        .ok_or_else(|| RideError::Numerical("state matrix is singular".into()))?;
    let gain = &ss.cy * &e + &ss.dr;
    let mut out = Vec::new();
    for src in &road.sources {
        // Wheel groups: (delay, weighted Bd, Bv, E, Dr, G).
        struct Raw {
            tau: f64,
            bd: DVector<f64>,
            bv: DVector<f64>,
            e: DVector<f64>,
            dr: [f64; N_OUT],
            g: [f64; N_OUT],
        }
        let mut raw: Vec<Raw> = Vec::new();
        for (j, wheel) in model.wheels.iter().enumerate() {
            let w = src.weights[wheel.track.min(1)];
            if w == 0.0 {
                continue;
            }
            let tau = wheel.behind / road.speed;
            let idx = match raw
                .iter()
                .position(|r| (r.tau - tau).abs() <= 1e-12 * (1.0 + tau))
            {
                Some(i) => i,
                None => {
                    raw.push(Raw {
                        tau,
                        bd: DVector::zeros(nx),
                        bv: DVector::zeros(nx),
                        e: DVector::zeros(nx),
                        dr: [0.0; N_OUT],
                        g: [0.0; N_OUT],
                    });
                    raw.len() - 1
                }
            };
            let r = &mut raw[idx];
            r.bd += ss.bd.column(j) * w;
            r.bv += ss.bv.column(j) * w;
            r.e += e.column(j) * w;
            for o in 0..N_OUT {
                r.dr[o] += ss.dr[(o, j)] * w;
                r.g[o] += gain[(o, j)] * w;
            }
        }
        if raw.is_empty() {
            continue;
        }
        crate::order::sort_by_f64_key(&mut raw, |r| r.tau);
        check_stationary(raw.iter().map(|r| r.g), scale)?;
        let (af, bf, cf, df) = src.filter.state_space();
        let nf = af.nrows();
        let (bt, f0) = if nf > 0 {
            let bt = af
                .clone()
                .lu()
                .solve(&bf)
                .ok_or_else(|| RideError::Numerical("shaping filter has a pole at 0".into()))?;
            let f0 = df - cf.dot(&bt);
            (bt, f0)
        } else {
            (DVector::zeros(0), df)
        };
        let ng = raw.len();
        let n = nx + ng * nf;
        let mut a = DMatrix::zeros(n, n);
        a.view_mut((0, 0), (nx, nx)).copy_from(&ss.a);
        let mut cy = DMatrix::zeros(N_OUT, n);
        cy.view_mut((0, 0), (N_OUT, nx)).copy_from(&ss.cy);
        let cfa = af.transpose() * &cf; // (C_f A_f)^T
        let mut groups = Vec::with_capacity(ng);
        for (gi, r) in raw.iter().enumerate() {
            let o = nx + gi * nf;
            let mut b = DVector::zeros(n);
            b.rows_mut(0, nx).copy_from(&(&r.bv * df - &r.e * f0));
            if nf > 0 {
                a.view_mut((o, o), (nf, nf)).copy_from(&af);
                a.view_mut((0, o), (nx, nf))
                    .copy_from(&(&r.bd * cf.transpose() + &r.bv * cfa.transpose()));
                b.rows_mut(o, nf).copy_from(&bt);
                for out_i in 0..N_OUT {
                    for k in 0..nf {
                        cy[(out_i, o + k)] = r.dr[out_i] * cf[k];
                    }
                }
            }
            groups.push(Group {
                tau: r.tau,
                b,
                g: r.g.map(|v| v * f0),
            });
        }
        out.push(Form { a, cy, groups });
    }
    Ok(out)
}

/// Refuses a source whose static gains do not sum to zero (a road warp).
fn check_stationary(gains: impl Iterator<Item = [f64; N_OUT]> + Clone, scale: f64) -> Result<()> {
    for o in 0..N_OUT {
        let sum: f64 = gains.clone().map(|g| g[o]).sum();
        let size: f64 = gains.clone().map(|g| g[o].abs()).sum();
        if size > 1e-12 * scale && sum.abs() > 1e-9 * size {
            return Err(RideError::RoadWarp(
                "with independent tracks and unequal front and rear track widths the \
                 suspension deflections follow a random walk and their RMS is unbounded"
                    .into(),
            ));
        }
    }
    Ok(())
}

/// The output variances of one augmented form (unit intensity; see the module doc).
fn variances(form: &Form) -> Result<[f64; N_OUT]> {
    let n = form.a.nrows();
    let lyap = Lyapunov::new(&form.a)?;
    let lu = form.a.clone().lu();
    let eye = DMatrix::<f64>::identity(n, n);
    let mut var = [0.0; N_OUT];
    let gs = &form.groups;
    for g in gs {
        for l in gs {
            for (o, v) in var.iter_mut().enumerate() {
                *v += g.g[o] * l.g[o] * g.tau.min(l.tau);
            }
        }
    }
    for (gi, g) in gs.iter().enumerate() {
        for (li, l) in gs.iter().enumerate().take(gi + 1) {
            let dt = g.tau - l.tau;
            let x = lyap.solve(&(&g.b * l.b.transpose()))?;
            let ex = if dt > 0.0 {
                (&form.a * dt).exp()
            } else {
                eye.clone()
            };
            let xe = &x * ex.transpose();
            let box_exp = if dt > 0.0 {
                Some(
                    lu.solve(&((&ex - &eye) * &l.b))
                        .ok_or_else(|| RideError::Numerical("state matrix is singular".into()))?,
                )
            } else {
                None
            };
            for (o, v) in var.iter_mut().enumerate() {
                let c = form.cy.row(o);
                let mut t = (c * &xe * c.transpose())[(0, 0)];
                if gi != li {
                    t *= 2.0;
                }
                if let Some(bx) = &box_exp {
                    t -= 2.0 * g.g[o] * (c * bx)[(0, 0)];
                }
                *v += t;
            }
        }
    }
    Ok(var)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::car::Car;
    use crate::criteria::criteria_exact;
    use crate::model::{full_car, quarter_car};
    use crate::road::{Road, RoadClass, Tracks};

    fn close(a: Criteria, b: Criteria, tol: f64) {
        for (x, y) in a.to_array().iter().zip(b.to_array()) {
            assert!((x / y - 1.0).abs() < tol, "{x} vs {y}");
        }
    }

    /// Waviness 2: constant filters, and the route is `criteria_exact` to 1e-9 on the
    /// quarter car and the full car, correlated and independent tracks, with tyre damping.
    #[test]
    fn waviness_two_is_criteria_exact() {
        let mut car = Car::datum();
        for ct in [0.0, 150.0] {
            car.front.tire_damping = ct;
            car.rear.tire_damping = ct;
            for tracks in [Tracks::Correlated, Tracks::Independent] {
                for (class, speed) in [(RoadClass::B, 20.0), (RoadClass::E, 7.0)] {
                    let road = Road {
                        class,
                        speed,
                        tracks,
                    };
                    let shaped = ShapedRoad::iso(&road, 2.0).unwrap();
                    for model in [quarter_car(&car.quarter()), full_car(&car)] {
                        let a = criteria_shaped(&model, &shaped).unwrap();
                        let b = criteria_exact(&model, &road).unwrap();
                        close(a, b, 1e-9);
                    }
                }
            }
        }
    }

    /// Unequal track widths with independent tracks: a road warp, refused like
    /// `criteria_exact` does.
    #[test]
    fn a_road_warp_is_refused() {
        let mut car = Car::datum();
        car.track_rear = 1.4;
        let road = Road {
            tracks: Tracks::Independent,
            ..Road::default()
        };
        let shaped = ShapedRoad::iso(&road, 2.5).unwrap();
        let e = criteria_shaped(&full_car(&car), &shaped).unwrap_err();
        assert!(matches!(e, RideError::RoadWarp(_)), "{e:?}");
    }
}
