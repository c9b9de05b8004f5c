//! Time domain: a seeded ISO 8608 road realisation and the response of a model to it.
//!
//! The road is a periodic sum of sinusoids on the grid `f_k = k / T` with amplitudes
//! `A_k = sqrt(2 G(f_k) df)` (one-sided PSD `G`, `df = 1 / T`) and seeded random phases,
//! built by one inverse FFT per (track, delay); a delay `tau` is the exact phase shift
//! `-2 pi f_k tau`, so rear wheels see exactly the front profile, `tau` later.
//!
//! A linear model is discretised exactly for a piecewise-linear road (first-order hold):
//! with `r(t_k + s) = r_k + s v_k`, `v_k = (r_{k+1} - r_k) / h`,
//! `x_{k+1} = Phi x_k + G0 (Bd r_k + Bv v_k) + G1 Bd v_k`, where `Phi = e^{A h}`,
//! `G0 = int_0^h e^{A s} ds`, `G1 = int_0^h e^{A s} (h - s) ds` are read off one matrix
//! exponential (Van Loan). A front damper law ([`Damper`]: bump and rebound rates, a
//! digressive knee) makes the model nonlinear; it is integrated by classical
//! Runge-Kutta (RK4) at the same step, on the same piecewise-linear road.
//!
//! Every recorded quantity comes from the forces applied at that step: the
//! accelerations `q'' = M^-1 (-K q - C_lin q' + Kr r + Cr r' - sum_front d f(d . q'))`
//! and the outputs `y = Yq q + Yv q' + Ya q'' + Yr r` from the model's output rows, so
//! BAcc is the body's acceleration, DTL `kt (zu - zr)` and SWS `zs - zu` of the record.

mod damper;

pub use damper::{Damper, Knee, MAX_KNEE_VELOCITY};

use crate::analysis::ModelKind;
use crate::car::Car;
use crate::error::{Result, RideError};
use crate::math;
use crate::model::{LinearModel, N_OUT};
use crate::road::Road;
use nalgebra::{DMatrix, DVector};
use num_complex::Complex64 as C64;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// Highest road frequency realised unless the step is too coarse for it, Hz.
const DEFAULT_F_MAX: f64 = 200.0;
/// Most time steps in one run (duration / dt).
pub const MAX_STEPS: f64 = 4.0e6;
/// Most samples a run records (duration / dt / decimate).
pub(crate) const MAX_SAMPLES: f64 = 5.0e5;

/// Settings of a time-domain run.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
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
    /// The front dampers' law; `None`: the car's linear damper (exact discretisation).
    /// With a law the design's Cs is its equivalent linear rate (see [`Damper`]).
    pub damper: Option<Damper>,
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
            f_max: DEFAULT_F_MAX,
            damper: None,
            decimate: 1,
        }
    }
}

impl TimeOptions {
    /// These options with time step `dt` and the highest road frequency lowered to
    /// `0.4 / dt` (80 % of Nyquist) where [`DEFAULT_F_MAX`] would not fit the step.
    pub fn with_step(self, dt: f64) -> TimeOptions {
        TimeOptions {
            dt,
            f_max: DEFAULT_F_MAX.min(0.4 / dt),
            ..self
        }
    }

    /// Checks every field; messages name the field.
    pub(crate) fn validate(&self) -> Result<()> {
        if !(self.duration.is_finite() && self.duration > 0.0 && self.duration <= 3600.0) {
            return Err(RideError::field("duration", "must be in (0, 3600] s"));
        }
        if !(self.dt.is_finite() && self.dt > 0.0 && self.dt <= 0.01) {
            return Err(RideError::field("dt", "must be in (0, 0.01] s"));
        }
        if self.duration / self.dt > MAX_STEPS {
            return Err(RideError::field(
                "dt",
                format!("too many steps (duration / dt > {MAX_STEPS:e})"),
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
        if let Some(d) = &self.damper {
            d.validate().map_err(|e| match e {
                RideError::Field { field, reason } => {
                    RideError::field(format!("damper.{field}"), reason)
                }
                e => e,
            })?;
        }
        if self.decimate == 0 {
            return Err(RideError::field("decimate", "must be >= 1"));
        }
        if self.duration / self.dt / self.decimate as f64 > MAX_SAMPLES {
            return Err(RideError::field(
                "decimate",
                format!(
                    "the record would hold more than {MAX_SAMPLES:e} samples (duration / dt / decimate): keep fewer"
                ),
            ));
        }
        Ok(())
    }
}

/// A recorded response (every `decimate`-th step).
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
    /// Their rates (m/s, rad/s); not in the JSON (kept for checks such as energy balances).
    #[serde(skip)]
    pub velocities: Vec<Vec<f64>>,
    /// Their accelerations from the forces applied at each step (m/s^2, rad/s^2).
    pub accelerations: Vec<Vec<f64>>,
    /// Road displacement under each wheel, m, in the model's wheel order; not in the JSON.
    #[serde(skip)]
    pub wheel_road: Vec<Vec<f64>>,
    /// RMS of each output over the whole record (every sample, before decimation).
    pub rms: [f64; N_OUT],
    /// The design's front Cs of the run, N s/m: the car's, or the law's equivalent
    /// linear rate `(Csb + Csr) / 2`.
    pub damper_rate: f64,
    /// The energy-equivalent linear rate of the front-right damper over the run,
    /// `sum f(v) v / sum v^2` (every step), N s/m: the rate a linear damper dissipating
    /// the same energy at the same velocities would have.
    pub equivalent_rate: f64,
}

/// Road profile samples `x(n dt - tau)`, `n = 0..N-1`, of one track (periodic, length N;
/// the PSD kept within the band `(f_min, f_max)`, Hz),
/// by `dft` (planned for length N once per run: a run realises every wheel's track).
fn road_profile(
    dft: &mut crate::fft::Dft,
    road: &Road,
    n: usize,
    dt: f64,
    (f_min, f_max): (f64, f64),
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
        let z = math::cpolar(0.5 * amp, ph - 2.0 * PI * f * tau);
        spec[k] = z;
        spec[n - k] = z.conj();
    }
    dft.inverse(&mut spec);
    spec.into_iter().map(|c| c.re).collect()
}

/// Simulates the design `car` with model `kind` on a seeded realisation of `road`: the
/// one entry point of the page and the CLI.
///
/// With `opt.damper` set, the front dampers follow that law (RK4) and the design's
/// front Cs is the law's equivalent linear rate `(Csb + Csr) / 2` (the rule of
/// [`Damper`]), whatever `car.front.damper` is: the linear part of the model is built with
/// that rate and exactly that rate is taken out again, so no linear front damper is left
/// over. Without it the car's linear damper runs on the exact discretisation.
pub fn simulate(
    kind: ModelKind,
    car: &Car,
    road: &Road,
    opt: &TimeOptions,
) -> Result<TimeResponse> {
    opt.validate()?;
    let rate = opt.damper.map_or(car.front.damper, |law| law.linear_rate());
    let design = car.with_front(car.front.spring, rate)?;
    run(&kind.build(&design), road, opt, rate)
}

/// The time loop. `rate`: the linear rate the model's front dampers were built with
/// (taken out of `C` again when `opt.damper` gives a law).
fn run(model: &LinearModel, road: &Road, opt: &TimeOptions, rate: f64) -> Result<TimeResponse> {
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
    let mut dft = crate::fft::Dft::new(n);
    for src in &exc.sources {
        // All wheels of a source share its phases (the first wheel's track).
        let track = model.wheels[src.channels[0].0].track;
        for &(j, tau) in &src.channels {
            r_wheel[j] = road_profile(
                &mut dft,
                road,
                n,
                h,
                (opt.f_min, opt.f_max),
                &phases[track],
                tau,
            );
        }
    }
    let warm = ((20.0f64.min(opt.duration)) / h).round() as usize;
    integrate(model, opt, rate, h, warm, warm + n, |k, j| {
        r_wheel[j][(k + n - warm % n) % n]
    })
}

/// Simulates the design `car` with model `kind` on a measured profile played back
/// (`wheels[j][k]`: the road under the model's wheel `j` at `k dt`, m, as
/// `crate::road_profile::playback` samples it for the model's wheels), from
/// rest at the profile's start: no warm-up (the profile is not periodic), so the record
/// and its RMS include the start's transient. `opt.dt` and `opt.duration` are the
/// playback's; `opt.seed` is not used.
pub fn simulate_playback(
    kind: ModelKind,
    car: &Car,
    dt: f64,
    wheels: &[Vec<f64>],
    opt: &TimeOptions,
) -> Result<TimeResponse> {
    let rate = opt.damper.map_or(car.front.damper, |law| law.linear_rate());
    let design = car.with_front(car.front.spring, rate)?;
    let model = kind.build(&design);
    let n = wheels.first().map_or(0, Vec::len);
    if n < 17 || wheels.len() != model.kr.ncols() || wheels.iter().any(|w| w.len() != n) {
        return Err(RideError::field(
            "road",
            format!(
                "the playback needs one record of at least 17 samples per wheel ({} wheels, {n} samples)",
                wheels.len()
            ),
        ));
    }
    let opt = TimeOptions {
        dt,
        duration: (n - 1) as f64 * dt,
        f_max: DEFAULT_F_MAX.min(0.4 / dt),
        ..*opt
    };
    opt.validate()?;
    integrate(&model, &opt, rate, dt, 0, n - 1, |k, j| wheels[j][k])
}

/// The time loop over `total` steps of `h` s from rest, recording (and taking the RMS
/// over) the steps from `warm` on; `road(k, j)`: the road displacement under wheel `j`
/// at step `k`, m (`k` up to `total`). `rate`: the linear rate the model's front dampers
/// were built with (taken out of `C` again when `opt.damper` gives a law).
fn integrate(
    model: &LinearModel,
    opt: &TimeOptions,
    rate: f64,
    h: f64,
    warm: usize,
    total: usize,
    road: impl Fn(usize, usize) -> f64,
) -> Result<TimeResponse> {
    let n = total - warm;
    let wheels = model.kr.ncols();
    let dynamics = Dynamics::new(model, opt.damper.map(|law| (law, rate)))?;
    let stepper = Stepper::new(model, h, &dynamics)?;
    let nq = model.n();
    let r_at = |k: usize| -> DVector<f64> { DVector::from_fn(wheels, |j, _| road(k, j)) };
    let mut x = DVector::zeros(2 * nq);
    let keep = opt.decimate;
    let cap = n / keep + 1;
    let series = |count: usize| vec![Vec::with_capacity(cap); count];
    let mut out = TimeResponse {
        t: Vec::with_capacity(cap),
        road: Vec::with_capacity(cap),
        outputs: std::array::from_fn(|_| Vec::with_capacity(cap)),
        positions: series(nq),
        velocities: series(nq),
        accelerations: series(nq),
        wheel_road: series(wheels),
        rms: [0.0; N_OUT],
        damper_rate: rate,
        equivalent_rate: 0.0,
    };
    let mut sumsq = [0.0; N_OUT];
    // Front-right damper: sum of f(v) v and of v^2 over the record.
    let (mut power, mut vsq) = (0.0, 0.0);
    let mut r_now = r_at(0);
    for k in 0..total {
        let r_next = r_at(k + 1);
        let v = (&r_next - &r_now) / h;
        if k >= warm {
            let i = k - warm;
            // The accelerations and outputs from the forces applied at this step.
            let q = x.rows(0, nq);
            let qd = x.rows(nq, nq);
            let qdd = dynamics.acceleration(&x, &r_now, &v);
            let y = model
                .outputs
                .each_ref()
                .map(|o| o.q.dot(&q) + o.v.dot(&qd) + o.a.dot(&qdd) + o.r.dot(&r_now));
            for o in 0..N_OUT {
                sumsq[o] += y[o] * y[o];
            }
            let rate = model.front_corners[0].dot(&qd);
            power += dynamics.front_force(rate, out.damper_rate) * rate;
            vsq += rate * rate;
            if i.is_multiple_of(keep) {
                out.t.push(i as f64 * h);
                out.road.push(r_now[0]);
                for (record, value) in out.outputs.iter_mut().zip(y) {
                    record.push(value);
                }
                for d in 0..nq {
                    out.positions[d].push(q[d]);
                    out.velocities[d].push(qd[d]);
                    out.accelerations[d].push(qdd[d]);
                }
                for (j, w) in out.wheel_road.iter_mut().enumerate() {
                    w.push(r_now[j]);
                }
            }
        }
        x = stepper.step(&dynamics, &x, &r_now, &v);
        r_now = r_next;
    }
    out.rms = sumsq.map(|s| (s / n as f64).sqrt());
    out.equivalent_rate = if vsq > 0.0 {
        power / vsq
    } else {
        out.damper_rate
    };
    if out.rms.iter().any(|v| !v.is_finite()) {
        // The step check keeps every linear mode stable; a law's knee can still excite
        // more than it: the step is the cause a user can change.
        return Err(RideError::field(
            "dt",
            format!(
                "the response grew without bound at {} s steps: give a shorter step",
                crate::domain::num(h)
            ),
        ));
    }
    Ok(out)
}

/// `M q'' = -K q - C_lin q' + Kr r + Cr r' - sum_front d f(d . q')`: the equations of
/// motion with the front dampers' law (`C_lin = C` and no law for a linear run).
struct Dynamics {
    minv: DMatrix<f64>,
    k: DMatrix<f64>,
    c_lin: DMatrix<f64>,
    kr: DMatrix<f64>,
    cr: DMatrix<f64>,
    corners: Vec<DVector<f64>>,
    law: Option<Damper>,
}

impl Dynamics {
    fn new(model: &LinearModel, law: Option<(Damper, f64)>) -> Result<Dynamics> {
        let minv = model
            .m
            .clone()
            .try_inverse()
            .ok_or_else(|| RideError::Numerical("mass matrix is singular".into()))?;
        let mut c_lin = model.c.clone();
        if let Some((_, rate)) = law {
            // The model's front dampers carry `rate`: take exactly that out.
            for d in &model.front_corners {
                c_lin -= rate * d * d.transpose();
            }
        }
        Ok(Dynamics {
            minv,
            k: model.k.clone(),
            c_lin,
            kr: model.kr.clone(),
            cr: model.cr.clone(),
            corners: model.front_corners.clone(),
            law: law.map(|(l, _)| l),
        })
    }

    /// The force of one front damper at extension rate `v`, N: its law's, or `rate v`
    /// for the linear damper of a linear run.
    fn front_force(&self, v: f64, rate: f64) -> f64 {
        self.law.map_or(rate * v, |l| l.force(v))
    }

    /// `q''` at state `x = [q; q']`, road displacement `r` and velocity `v`.
    fn acceleration(&self, x: &DVector<f64>, r: &DVector<f64>, v: &DVector<f64>) -> DVector<f64> {
        let n = self.k.nrows();
        let q = x.rows(0, n);
        let qd = x.rows(n, n);
        let mut f = -(&self.k * q) - &self.c_lin * qd + &self.kr * r + &self.cr * v;
        if let Some(law) = &self.law {
            for d in &self.corners {
                f -= d * law.force(d.dot(&qd));
            }
        }
        &self.minv * f
    }

    /// `x' = [q'; q'']`.
    fn derivative(&self, x: &DVector<f64>, r: &DVector<f64>, v: &DVector<f64>) -> DVector<f64> {
        let n = self.k.nrows();
        let mut dx = DVector::zeros(2 * n);
        dx.rows_mut(0, n).copy_from(&x.rows(n, n));
        dx.rows_mut(n, n).copy_from(&self.acceleration(x, r, v));
        dx
    }
}

/// Largest `|lambda| h` of the explicit RK4 steps a damper law runs with: RK4 is stable
/// for `|lambda h|` up to about 2.6 to 2.8 around the left half-plane, so 2.5 keeps every
/// mode inside.
const RK4_REACH: f64 = 2.5;

/// Refuses a step `h` (s) too long for RK4 with `law`: the model with its front dampers at
/// the law's steepest slope has an eigenvalue `lambda` (1/s) with `|lambda| h > 2.5`, and
/// the run would diverge. The error names `dt` and the step that works.
fn check_explicit_step(dynamics: &Dynamics, law: &Damper, h: f64) -> Result<()> {
    let slopes = [law.bump, law.rebound]
        .into_iter()
        .chain(law.knee.iter().flat_map(|k| [k.bump, k.rebound]));
    let steepest = slopes.fold(0.0f64, f64::max);
    let n = dynamics.k.nrows();
    let mut c = dynamics.c_lin.clone();
    for d in &dynamics.corners {
        c += steepest * d * d.transpose();
    }
    let mut a = DMatrix::zeros(2 * n, 2 * n);
    a.view_mut((0, n), (n, n)).fill_with_identity();
    a.view_mut((n, 0), (n, n))
        .copy_from(&(-(&dynamics.minv * &dynamics.k)));
    a.view_mut((n, n), (n, n))
        .copy_from(&(-(&dynamics.minv * c)));
    let fastest = a
        .complex_eigenvalues()
        .iter()
        .map(|l| math::cabs(*l))
        .fold(0.0f64, f64::max);
    if fastest * h <= RK4_REACH {
        return Ok(());
    }
    let limit = RK4_REACH / fastest;
    // A round step below the limit: 1, 2 or 5 times a power of ten.
    let decade = math::powf(10f64, math::log10(limit).floor());
    let suggest = [5.0, 2.0, 1.0]
        .into_iter()
        .map(|m| m * decade)
        .find(|s| *s <= limit)
        .unwrap_or(decade);
    Err(RideError::field(
        "dt",
        format!(
            "{} s steps are too long for the damper law: at its steepest slope ({} N s/m) the car has a mode of {} 1/s, and the explicit steps a nonlinear damper needs stay stable only below {} s; give a step of {} s or less (or soften the law)",
            crate::domain::num(h),
            crate::domain::num(steepest),
            crate::domain::num(fastest),
            crate::domain::num(limit),
            crate::domain::num(suggest)
        ),
    ))
}

/// One step of the state over `h` with a linear road ramp.
enum Stepper {
    /// Exact first-order-hold discretisation of a linear model.
    Linear {
        phi: DMatrix<f64>,
        g0: DMatrix<f64>,
        g1: DMatrix<f64>,
        bd: DMatrix<f64>,
        bv: DMatrix<f64>,
    },
    /// Classical Runge-Kutta (RK4) on [`Dynamics`] with a damper law.
    RungeKutta { h: f64 },
}

impl Stepper {
    fn new(model: &LinearModel, h: f64, dynamics: &Dynamics) -> Result<Stepper> {
        if let Some(law) = dynamics.law {
            check_explicit_step(dynamics, &law, h)?;
            return Ok(Stepper::RungeKutta { h });
        }
        let ss = model.state_space()?;
        let ns = ss.a.nrows();
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
            bd: ss.bd,
            bv: ss.bv,
        })
    }

    fn step(
        &self,
        dynamics: &Dynamics,
        x: &DVector<f64>,
        r: &DVector<f64>,
        v: &DVector<f64>,
    ) -> DVector<f64> {
        match self {
            Stepper::Linear {
                phi,
                g0,
                g1,
                bd,
                bv,
            } => phi * x + g0 * (bd * r + bv * v) + g1 * (bd * v),
            &Stepper::RungeKutta { h } => {
                let r_half = r + v * (0.5 * h);
                let r_end = r + v * h;
                let k1 = dynamics.derivative(x, r, v);
                let k2 = dynamics.derivative(&(x + &k1 * (0.5 * h)), &r_half, v);
                let k3 = dynamics.derivative(&(x + &k2 * (0.5 * h)), &r_half, v);
                let k4 = dynamics.derivative(&(x + &k3 * h), &r_end, v);
                x + (k1 + k2 * 2.0 + k3 * 2.0 + k4) * (h / 6.0)
            }
        }
    }
}
