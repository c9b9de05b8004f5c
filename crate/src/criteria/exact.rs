//! The exact route: RMS criteria from Lyapunov equations, with the front-rear delay
//! entering exactly through `exp(A tau)`.
//!
//! With `x = [q; q']`, `x' = A x + Bd r + Bv r'` and `E = -A^-1 Bd`, the shifted state
//! `z = x - E r` obeys `z' = A z + (Bv - E) r'`, driven only by the white road velocity,
//! and `y = Cy z + G r` with the static gain `G = Cy E + Dr`. For a source `w` feeding
//! wheel groups `g` with delays `tau_g` (velocity input `b_g`, gain `G_g`), stationarity
//! needs `sum_g G_g = 0`, and then the impulse response of an output to `w` is
//!
//! ```text
//! h(u) = sum_g [ 1(u >= tau_g) c exp(A (u - tau_g)) b_g - G_g 1(u < tau_g) ]
//! var(y) = W int_0^inf h(u)^2 du
//! ```
//!
//! whose terms are closed forms: `c X_gl exp(A^T (tau_g - tau_l)) c^T` with
//! `A X_gl + X_gl A^T + b_g b_l^T = 0` (tau_g >= tau_l), box-exponential terms
//! `-2 G_g c A^-1 (exp(A (tau_g - tau_l)) - I) b_l` (tau_l < tau_g) and
//! `G_g G_l min(tau_g, tau_l)`.
//! The Lyapunov/Sylvester equations are solved in Kronecker form
//! `(I (x) A + A (x) I) vec X = -vec(b_g b_l^T)` with one LU for all right-hand sides:
//! exact to rounding and robust to repeated eigenvalues (which a modal solution is not).

use crate::error::{Result, RideError};
use crate::evaluate::Criteria;
use crate::model::{LinearModel, N_OUT};
use crate::road::Road;
use nalgebra::{DMatrix, DVector};

/// A group of wheels of one source that share a delay.
pub(super) struct Group {
    /// Delay behind the front axle, s.
    pub tau: f64,
    /// Velocity input of the shifted state `z` (sum over the group's wheels).
    pub b: DVector<f64>,
    /// Static gain of each output from the group's road displacement.
    pub g: [f64; N_OUT],
}

/// The white-noise form of a model on a road: state space, wheel groups per source.
pub(super) struct WhiteForm {
    pub a: DMatrix<f64>,
    pub lu_a: nalgebra::LU<f64, nalgebra::Dyn, nalgebra::Dyn>,
    pub cy: DMatrix<f64>,
    pub sources: Vec<Vec<Group>>,
    pub intensity: f64,
}

impl WhiteForm {
    /// Builds the form; fails when an output is unbounded (white feed-through or road warp).
    pub(crate) fn new(model: &LinearModel, road: &Road) -> Result<WhiteForm> {
        road.validate()?;
        let ss = model.state_space()?;
        let scale = ss.dr.amax().max(1.0);
        if ss.dw.amax() > 1e-12 * scale {
            return Err(RideError::Numerical(
                "an output feeds through the white road velocity: its RMS is unbounded".into(),
            ));
        }
        let lu_a = ss.a.clone().lu();
        let e = -lu_a
            .solve(&ss.bd)
            .ok_or_else(|| RideError::Numerical("state matrix is singular".into()))?;
        let bw = &ss.bv - &e;
        let gain = &ss.cy * &e + &ss.dr;
        let exc = model.excitation(road);
        let mut sources = Vec::with_capacity(exc.sources.len());
        for src in &exc.sources {
            let mut groups: Vec<Group> = Vec::new();
            for &(j, tau) in &src.channels {
                let g: [f64; N_OUT] = std::array::from_fn(|i| gain[(i, j)]);
                match groups
                    .iter_mut()
                    .find(|gr| (gr.tau - tau).abs() <= 1e-12 * (1.0 + tau))
                {
                    Some(gr) => {
                        gr.b += bw.column(j);
                        for i in 0..N_OUT {
                            gr.g[i] += g[i];
                        }
                    }
                    None => groups.push(Group {
                        tau,
                        b: bw.column(j).into_owned(),
                        g,
                    }),
                }
            }
            crate::order::sort_by_f64_key(&mut groups, |g| g.tau);
            check_stationary(groups.iter().map(|gr| gr.g), scale)?;
            sources.push(groups);
        }
        Ok(WhiteForm {
            a: ss.a,
            lu_a,
            cy: ss.cy,
            sources,
            intensity: exc.intensity,
        })
    }

    /// The box-box terms `W sum_gl G_g G_l min(tau_g, tau_l)` of every output.
    fn box_terms(&self) -> [f64; N_OUT] {
        let mut var = [0.0; N_OUT];
        for groups in &self.sources {
            for g in groups {
                for l in groups {
                    for (i, v) in var.iter_mut().enumerate() {
                        *v += self.intensity * g.g[i] * l.g[i] * g.tau.min(l.tau);
                    }
                }
            }
        }
        var
    }
}

/// Refuses a source whose static gains do not sum to zero: the output then follows the
/// road displacement itself (a random walk: road warp) and its RMS is unbounded.
pub(super) fn check_stationary(
    gains: impl Iterator<Item = [f64; N_OUT]> + Clone,
    scale: f64,
) -> Result<()> {
    for i in 0..N_OUT {
        let sum: f64 = gains.clone().map(|g| g[i]).sum();
        let size: f64 = gains.clone().map(|g| g[i].abs()).sum();
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

/// Square roots of the variances, refusing anything not finite and non-negative.
pub(super) fn rms_of(var: [f64; N_OUT]) -> Result<Criteria> {
    if var.iter().any(|v| !v.is_finite() || *v < 0.0) {
        return Err(RideError::Numerical(
            "variance is not finite: is the model stable?".into(),
        ));
    }
    Ok(Criteria::from_array(var.map(f64::sqrt)))
}

/// Exact RMS `[BAcc, DTL, SWS]` of `model` on `road`.
///
/// Fails with a message when the response is unbounded: a white road-velocity
/// feed-through into an output, or a road warp (independent tracks with unequal
/// front and rear track widths) that makes the static deflection a random walk.
pub fn criteria_exact(model: &LinearModel, road: &Road) -> Result<Criteria> {
    rms_of(variances(&WhiteForm::new(model, road)?)?)
}

/// The output variances of a white-noise form (the sum of the closed-form terms above).
pub(super) fn variances(wf: &WhiteForm) -> Result<[f64; N_OUT]> {
    let ns = wf.a.nrows();
    // Kronecker operator of the Lyapunov/Sylvester equation, factorised once.
    let eye = DMatrix::<f64>::identity(ns, ns);
    let lu_k = (eye.kronecker(&wf.a) + wf.a.kronecker(&eye)).lu();
    let mut var = wf.box_terms();
    for groups in &wf.sources {
        for (gi, g) in groups.iter().enumerate() {
            for (li, l) in groups.iter().enumerate().take(gi + 1) {
                let dt = g.tau - l.tau;
                let rhs = -(&g.b * l.b.transpose());
                let xv = lu_k
                    .solve(&DVector::from_column_slice(rhs.as_slice()))
                    .ok_or_else(|| RideError::Numerical("Lyapunov operator is singular".into()))?;
                let x = DMatrix::from_column_slice(ns, ns, xv.as_slice());
                let ex = if dt > 0.0 {
                    (&wf.a * dt).exp()
                } else {
                    eye.clone()
                };
                let xe = &x * ex.transpose();
                // Box-exponential term, needs A^-1 (exp(A dt) - I) b_l.
                let box_exp = if dt > 0.0 {
                    wf.lu_a.solve(&((&ex - &eye) * &l.b))
                } else {
                    None
                };
                for (i, v) in var.iter_mut().enumerate() {
                    let c = wf.cy.row(i);
                    let mut t = (c * &xe * c.transpose())[(0, 0)];
                    if gi != li {
                        t *= 2.0; // the (l, g) ordered pair gives the same value
                    }
                    if let Some(bx) = &box_exp {
                        t -= 2.0 * g.g[i] * (c * bx)[(0, 0)];
                    }
                    *v += wf.intensity * t;
                }
            }
        }
    }
    Ok(var)
}
