//! Time domain: a seeded ISO 8608 road realisation and the response of a model to it.
//!
//! The road is a periodic sum of sinusoids on the grid `f_k = k / T` with amplitudes
//! `A_k = sqrt(2 G(f_k) df)` (one-sided PSD `G`, `df = 1 / T`) and seeded random phases,
//! built by one inverse FFT per (track, delay); a delay `tau` is the exact phase shift
//! `-2 pi f_k tau`, so rear wheels see exactly the front profile, `tau` later.
//!
//! The linear model is discretised exactly for a piecewise-linear road (first-order hold):
//! with `r(t_k + s) = r_k + s v_k`, `v_k = (r_{k+1} - r_k) / h`,
//! `x_{k+1} = Phi x_k + G0 (Bd r_k + Bv v_k) + G1 Bd v_k`, where `Phi = e^{A h}`,
//! `G0 = int_0^h e^{A s} ds`, `G1 = int_0^h e^{A s} (h - s) ds` are read off one matrix
//! exponential (Van Loan). An asymmetric front damper (bump rate `Csb` for compression,
//! rebound rate `Csr` for extension) makes the model nonlinear; it is integrated by
//! classical Runge-Kutta (RK4) at the same step.

use crate::error::{Result, RideError};
use crate::model::{LinearModel, N_OUT};
use crate::road::Road;
use nalgebra::{DMatrix, DVector};
use num_complex::Complex64 as C64;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// Settings of a time-domain run.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct TimeOptions {
    /// Length of the recorded (periodic) road, s.
    pub duration: f64,
    /// Time step, s.
    pub dt: f64,
    /// Seed of the random phases.
    pub seed: u64,
    /// Lowest road frequency realised, Hz.
    pub f_min: f64,
    /// Highest road frequency realised, Hz (at most the Nyquist frequency).
    pub f_max: f64,
    /// Asymmetric front damper `(Csb bump, Csr rebound)`, N s/m; `None` = linear.
    pub asymmetric: Option<(f64, f64)>,
    /// Keep every `decimate`-th sample in the returned record.
    pub decimate: usize,
}

impl Default for TimeOptions {
    fn default() -> Self {
        TimeOptions {
            duration: 20.0,
            dt: 1e-3,
            seed: 1,
            f_min: 0.1,
            f_max: 200.0,
            asymmetric: None,
            decimate: 1,
        }
    }
}

impl TimeOptions {
    /// Checks every field; messages name the field.
    pub fn validate(&self) -> Result<()> {
        if !(self.duration.is_finite() && self.duration > 0.0 && self.duration <= 3600.0) {
            return Err(RideError::field("duration", "must be in (0, 3600] s"));
        }
        if !(self.dt.is_finite() && self.dt > 0.0 && self.dt <= 0.01) {
            return Err(RideError::field("dt", "must be in (0, 0.01] s"));
        }
        if self.duration / self.dt > 4.0e6 {
            return Err(RideError::field(
                "dt",
                "too many steps (duration / dt > 4e6)",
            ));
        }
        if !(self.f_min.is_finite()
            && self.f_min > 0.0
            && self.f_max.is_finite()
            && self.f_min < self.f_max)
        {
            return Err(RideError::field("f_min", "needs finite 0 < f_min < f_max"));
        }
        if self.f_max > 0.5 / self.dt {
            return Err(RideError::field(
                "f_max",
                "must not exceed the Nyquist frequency 1 / (2 dt)",
            ));
        }
        if let Some((b, r)) = self.asymmetric {
            if !(b.is_finite() && r.is_finite() && b > 0.0 && r > 0.0) {
                return Err(RideError::field(
                    "asymmetric",
                    "bump and rebound rates must be finite and > 0",
                ));
            }
        }
        if self.decimate == 0 {
            return Err(RideError::field("decimate", "must be >= 1"));
        }
        Ok(())
    }
}

/// A recorded response.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TimeResponse {
    /// Sample times, s.
    pub t: Vec<f64>,
    /// Road displacement under the front-right wheel, m.
    pub road: Vec<f64>,
    /// Outputs `[BAcc m/s^2, DTL N, SWS m]` per sample.
    pub outputs: [Vec<f64>; N_OUT],
    /// Generalised coordinates per sample (m, rad), in the model's order.
    pub positions: Vec<Vec<f64>>,
    /// RMS of each output over the whole record (every sample, before decimation).
    pub rms: [f64; N_OUT],
}

/// Road profile samples `x(n dt - tau)`, `n = 0..N-1`, of one track (periodic, length N).
pub fn road_profile(
    road: &Road,
    n: usize,
    dt: f64,
    f_min: f64,
    f_max: f64,
    phases: &[f64],
    tau: f64,
) -> Vec<f64> {
    let t_total = n as f64 * dt;
    let df = 1.0 / t_total;
    let mut spec = vec![C64::new(0.0, 0.0); n];
    for (k, &ph) in phases.iter().enumerate().take(n / 2).skip(1) {
        let f = k as f64 * df;
        if f < f_min || f > f_max {
            continue;
        }
        let amp = (2.0 * road.displacement_psd(f) * df).sqrt();
        let z = C64::from_polar(0.5 * amp, ph - 2.0 * PI * f * tau);
        spec[k] = z;
        spec[n - k] = z.conj();
    }
    let mut planner = rustfft::FftPlanner::new();
    planner.plan_fft_inverse(n).process(&mut spec);
    spec.into_iter().map(|c| c.re).collect()
}

/// Simulates `model` on a seeded realisation of `road`.
pub fn simulate(model: &LinearModel, road: &Road, opt: &TimeOptions) -> Result<TimeResponse> {
    road.validate()?;
    opt.validate()?;
    let n = (opt.duration / opt.dt).round() as usize;
    if n < 16 {
        return Err(RideError::field(
            "duration",
            "must hold at least 16 time steps",
        ));
    }
    let h = opt.dt;
    let exc = model.excitation(road);
    let wheels = model.kr.ncols();
    // One phase set per track; every wheel gets its track's profile shifted by its delay.
    let mut rng = ChaCha8Rng::seed_from_u64(opt.seed);
    let n_tracks = model.wheels.iter().map(|w| w.track).max().unwrap_or(0) + 1;
    let phases: Vec<Vec<f64>> = (0..n_tracks)
        .map(|_| {
            (0..n / 2)
                .map(|_| rng.random_range(0.0..2.0 * PI))
                .collect()
        })
        .collect();
    let mut r_wheel: Vec<Vec<f64>> = vec![Vec::new(); wheels];
    for src in &exc.sources {
        // All wheels of a source share its phases (the first wheel's track).
        let track = model.wheels[src.channels[0].0].track;
        for &(j, tau) in &src.channels {
            r_wheel[j] = road_profile(road, n, h, opt.f_min, opt.f_max, &phases[track], tau);
        }
    }
    let ss = model.state_space()?;
    let ns = ss.a.nrows();
    let warm = ((20.0f64.min(opt.duration)) / h).round() as usize;
    let total = warm + n;
    let r_at = |k: usize| -> DVector<f64> {
        DVector::from_fn(wheels, |j, _| r_wheel[j][(k + n - warm % n) % n])
    };
    let mut x = DVector::zeros(ns);
    let keep = opt.decimate;
    let mut out = TimeResponse {
        t: Vec::with_capacity(n / keep + 1),
        road: Vec::with_capacity(n / keep + 1),
        outputs: std::array::from_fn(|_| Vec::with_capacity(n / keep + 1)),
        positions: vec![Vec::with_capacity(n / keep + 1); model.n()],
        rms: [0.0; N_OUT],
    };
    let mut sumsq = [0.0; N_OUT];
    let stepper = Stepper::new(model, &ss, h, opt.asymmetric)?;
    let mut r_now = r_at(0);
    for k in 0..total {
        let r_next = r_at(k + 1);
        let v = (&r_next - &r_now) / h;
        if k >= warm {
            let i = k - warm;
            let y = &ss.cy * &x + &ss.dr * &r_now + &ss.dw * &v;
            for o in 0..N_OUT {
                sumsq[o] += y[o] * y[o];
            }
            if i.is_multiple_of(keep) {
                out.t.push(i as f64 * h);
                out.road.push(r_now[0]);
                for o in 0..N_OUT {
                    out.outputs[o].push(y[o]);
                }
                for (d, p) in out.positions.iter_mut().enumerate() {
                    p.push(x[d]);
                }
            }
        }
        x = stepper.step(&x, &r_now, &v);
        r_now = r_next;
    }
    out.rms = sumsq.map(|s| (s / n as f64).sqrt());
    if out.rms.iter().any(|v| !v.is_finite()) {
        return Err(RideError::Numerical("time-domain response diverged".into()));
    }
    Ok(out)
}

/// One step of the state over `h` with a linear road ramp.
enum Stepper {
    /// Exact first-order-hold discretisation.
    Linear {
        phi: DMatrix<f64>,
        g0: DMatrix<f64>,
        g1: DMatrix<f64>,
        bd: DMatrix<f64>,
        bv: DMatrix<f64>,
    },
    /// RK4 on the model with asymmetric front dampers.
    Asymmetric(Box<Nonlinear>),
}

/// `M q'' = -K q - C_lin q' + Kr r + Cr r' - sum_i d_i f(d_i . q')` with the front damper
/// law `f(v) = Csb v` in bump (`v < 0`) and `Csr v` in rebound.
struct Nonlinear {
    n: usize,
    h: f64,
    minv: DMatrix<f64>,
    k: DMatrix<f64>,
    c_lin: DMatrix<f64>,
    kr: DMatrix<f64>,
    cr: DMatrix<f64>,
    corners: Vec<DVector<f64>>,
    bump: f64,
    rebound: f64,
}

impl Stepper {
    fn new(
        model: &LinearModel,
        ss: &crate::model::StateSpace,
        h: f64,
        asym: Option<(f64, f64)>,
    ) -> Result<Stepper> {
        let ns = ss.a.nrows();
        match asym {
            None => {
                let mut big = DMatrix::zeros(3 * ns, 3 * ns);
                big.view_mut((0, 0), (ns, ns)).copy_from(&(&ss.a * h));
                big.view_mut((0, ns), (ns, ns))
                    .copy_from(&(DMatrix::identity(ns, ns) * h));
                big.view_mut((ns, 2 * ns), (ns, ns))
                    .copy_from(&(DMatrix::identity(ns, ns) * h));
                let e = big.exp();
                // exp([[A, I, 0], [0, 0, I], [0, 0, 0]] h) has top row [Phi, G0, G1].
                Ok(Stepper::Linear {
                    phi: e.view((0, 0), (ns, ns)).into_owned(),
                    g0: e.view((0, ns), (ns, ns)).into_owned(),
                    g1: e.view((0, 2 * ns), (ns, ns)).into_owned(),
                    bd: ss.bd.clone(),
                    bv: ss.bv.clone(),
                })
            }
            Some((bump, rebound)) => {
                // The model's front dampers carry the mean rate (Csb + Csr) / 2: remove them.
                let mean = 0.5 * (bump + rebound);
                let mut c_lin = model.c.clone();
                for d in &model.front_corners {
                    c_lin -= mean * d * d.transpose();
                }
                let minv = model
                    .m
                    .clone()
                    .try_inverse()
                    .ok_or_else(|| RideError::Numerical("mass matrix is singular".into()))?;
                Ok(Stepper::Asymmetric(Box::new(Nonlinear {
                    n: model.n(),
                    h,
                    minv,
                    k: model.k.clone(),
                    c_lin,
                    kr: model.kr.clone(),
                    cr: model.cr.clone(),
                    corners: model.front_corners.clone(),
                    bump,
                    rebound,
                })))
            }
        }
    }

    fn step(&self, x: &DVector<f64>, r: &DVector<f64>, v: &DVector<f64>) -> DVector<f64> {
        match self {
            Stepper::Linear {
                phi,
                g0,
                g1,
                bd,
                bv,
            } => phi * x + g0 * (bd * r + bv * v) + g1 * (bd * v),
            Stepper::Asymmetric(nl) => nl.rk4(x, r, v),
        }
    }
}

impl Nonlinear {
    /// State derivative at road displacement `r` and road velocity `v`.
    fn deriv(&self, x: &DVector<f64>, r: &DVector<f64>, v: &DVector<f64>) -> DVector<f64> {
        let n = self.n;
        let q = x.rows(0, n);
        let qd = x.rows(n, n);
        let mut f = -(&self.k * q) - &self.c_lin * qd + &self.kr * r + &self.cr * v;
        for d in &self.corners {
            let rate = d.dot(&qd);
            let c = if rate < 0.0 { self.bump } else { self.rebound };
            f -= d * (c * rate);
        }
        let acc = &self.minv * f;
        let mut dx = DVector::zeros(2 * n);
        dx.rows_mut(0, n).copy_from(&qd);
        dx.rows_mut(n, n).copy_from(&acc);
        dx
    }

    fn rk4(&self, x: &DVector<f64>, r: &DVector<f64>, v: &DVector<f64>) -> DVector<f64> {
        let h = self.h;
        let r_half = r + v * (0.5 * h);
        let r_end = r + v * h;
        let k1 = self.deriv(x, r, v);
        let k2 = self.deriv(&(x + &k1 * (0.5 * h)), &r_half, v);
        let k3 = self.deriv(&(x + &k2 * (0.5 * h)), &r_half, v);
        let k4 = self.deriv(&(x + &k3 * h), &r_end, v);
        x + (k1 + k2 * 2.0 + k3 * 2.0 + k4) * (h / 6.0)
    }
}
