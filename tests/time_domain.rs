//! The time domain checked against itself and against physics: records that agree with
//! their own outputs (BAcc is the body's acceleration, DTL and SWS its deflections),
//! the nonlinear integrator against the exact discretisation, the energy balance of a
//! nonlinear run, the damper-rate rule, seeds, delays and decimation.

use ridelab::car::Car;
use ridelab::model::LinearModel;
use ridelab::road::{Road, Tracks};
use ridelab::time_domain::{simulate, Damper, Knee, TimeOptions, TimeResponse};
use ridelab::ModelKind;

/// 10 s at 0.5 ms, every sample kept: the run of issue #12's report.
fn options(damper: Option<Damper>) -> TimeOptions {
    TimeOptions {
        duration: 10.0,
        seed: 3,
        decimate: 1,
        damper,
        ..TimeOptions::default().with_step(5e-4)
    }
}

fn rms(x: impl Iterator<Item = f64>) -> f64 {
    let (mut s, mut n) = (0.0, 0usize);
    for v in x {
        s += v * v;
        n += 1;
    }
    (s / n as f64).sqrt()
}

/// The laws the checks run on: soft bump / hard rebound (as in the issue), the reverse,
/// and a digressive damper (knee at 0.1 m/s, slopes halved above it).
fn laws() -> [Damper; 3] {
    [
        Damper::asymmetric(500.0, 2500.0),
        Damper::asymmetric(2500.0, 500.0),
        Damper {
            bump: 800.0,
            rebound: 2400.0,
            knee: Some(Knee {
                velocity: 0.1,
                bump: 400.0,
                rebound: 1200.0,
            }),
        },
    ]
}

/// The design model of a run (the car with the run's front Cs).
fn model_of(kind: ModelKind, car: &Car, r: &TimeResponse) -> LinearModel {
    kind.build(&car.with_front(car.front.spring, r.damper_rate).unwrap())
}

/// The body point above the front-right wheel, from the positions record.
fn body_above_front(model: &LinearModel, r: &TimeResponse) -> Vec<f64> {
    let d = &model.front_corners[0];
    (0..r.t.len())
        .map(|i| (0..model.n_body).map(|k| d[k] * r.positions[k][i]).sum())
        .collect()
}

#[test]
fn nonlinear_outputs_are_the_records_own_motion() {
    let car = Car::datum();
    let road = Road::default();
    for kind in [ModelKind::Quarter, ModelKind::Full] {
        for law in laws() {
            let r = simulate(kind, &car, &road, &options(Some(law))).unwrap();
            let model = model_of(kind, &car, &r);
            let h = 5e-4;
            let zs = body_above_front(&model, &r);
            let n = zs.len();
            // BAcc against the second difference of the body position: the difference
            // is O(h^2 z'''') (about 1e-4 of the RMS at the wheel-hop frequency).
            let diff = rms((1..n - 1)
                .map(|i| (zs[i + 1] - 2.0 * zs[i] + zs[i - 1]) / (h * h) - r.outputs[0][i]));
            assert!(
                diff < 1e-3 * r.rms[0],
                "{kind:?} {law:?}: BAcc vs second difference {diff:e} (RMS {})",
                r.rms[0]
            );
            // DTL is kt (zu - zr) and SWS zs - zu of the same record, to rounding.
            let u = model.n_body; // the front-right wheel's coordinate
            let kt = car.front.tire_stiffness;
            for (i, &zs) in zs.iter().enumerate() {
                let zu = r.positions[u][i];
                let dtl = kt * (zu - r.road[i]);
                assert!(
                    (r.outputs[1][i] - dtl).abs() <= 1e-9 * r.rms[1],
                    "{kind:?} DTL at {i}"
                );
                let sws = zs - zu;
                assert!(
                    (r.outputs[2][i] - sws).abs() <= 1e-12,
                    "{kind:?} SWS at {i}"
                );
            }
            // The body accelerations are the records' too.
            let acc = rms((1..n - 1).map(|i| {
                let p = &r.positions[0];
                (p[i + 1] - 2.0 * p[i] + p[i - 1]) / (h * h) - r.accelerations[0][i]
            }));
            assert!(
                acc < 1e-3 * rms(r.accelerations[0].iter().copied()),
                "{kind:?} heave"
            );
        }
    }
}

#[test]
fn equal_bump_and_rebound_rates_reproduce_the_exact_linear_run() {
    let car = Car::datum();
    let road = Road::default();
    let cs = car.front.damper;
    for kind in [ModelKind::Quarter, ModelKind::Full] {
        let lin = simulate(kind, &car, &road, &options(None)).unwrap();
        // RK4 with Csb = Csr = Cs: an independent integration of the same linear model.
        let rk = simulate(
            kind,
            &car,
            &road,
            &options(Some(Damper::asymmetric(cs, cs))),
        )
        .unwrap();
        for o in 0..3 {
            let d = rms((0..lin.t.len()).map(|i| lin.outputs[o][i] - rk.outputs[o][i]));
            // RK4's global error is O(h^4): about 1e-6 of the RMS at h = 0.5 ms.
            assert!(
                d < 1e-4 * lin.rms[o],
                "{kind:?} output {o}: {:e}",
                d / lin.rms[o]
            );
        }
        assert_eq!(rk.damper_rate, cs);
        assert!((rk.equivalent_rate / cs - 1.0).abs() < 1e-12);
    }
}

#[test]
fn the_design_cs_of_a_nonlinear_run_is_the_mean_rate() {
    let road = Road::default();
    let law = Damper::asymmetric(900.0, 2100.0); // mean 1500, the datum car has 1290
    for kind in [ModelKind::Quarter, ModelKind::Full] {
        let datum = Car::datum();
        let soft = datum.with_front(datum.front.spring, 600.0).unwrap();
        let hard = datum.with_front(datum.front.spring, 4000.0).unwrap();
        // Whatever Cs the car carried, the run is the law's: no linear damper is left over.
        let a = simulate(kind, &soft, &road, &options(Some(law))).unwrap();
        let b = simulate(kind, &hard, &road, &options(Some(law))).unwrap();
        assert_eq!(a.outputs, b.outputs, "{kind:?}");
        assert_eq!(a.damper_rate, 1500.0);
        // A symmetric law of rate c is the linear car with Cs = c, not the car's Cs.
        let c = 2000.0;
        let rk = simulate(kind, &soft, &road, &options(Some(Damper::asymmetric(c, c)))).unwrap();
        let lin = simulate(
            kind,
            &datum.with_front(datum.front.spring, c).unwrap(),
            &road,
            &options(None),
        )
        .unwrap();
        for o in 0..3 {
            assert!((rk.rms[o] / lin.rms[o] - 1.0).abs() < 1e-4, "{kind:?} {o}");
        }
    }
}

#[test]
fn a_harder_rebound_packs_the_suspension_down() {
    // With Csr > Csb the damper lets the suspension compress faster than it extends:
    // the mean deflection zs - zu goes negative (the car sits lower); swapping the rates
    // raises it. The linear damper has a mean of zero (to the record's noise).
    let car = Car::datum();
    let road = Road::default();
    let mean = |r: &TimeResponse| r.outputs[2].iter().sum::<f64>() / r.outputs[2].len() as f64;
    for kind in [ModelKind::Quarter, ModelKind::Full] {
        let lin = mean(&simulate(kind, &car, &road, &options(None)).unwrap());
        let down = simulate(
            kind,
            &car,
            &road,
            &options(Some(Damper::asymmetric(500.0, 2500.0))),
        )
        .unwrap();
        let up = simulate(
            kind,
            &car,
            &road,
            &options(Some(Damper::asymmetric(2500.0, 500.0))),
        )
        .unwrap();
        let (down, up) = (mean(&down), mean(&up));
        assert!(
            down < -0.1 * down.abs().max(up.abs()) && down < lin,
            "{kind:?}: {down:e}"
        );
        assert!(
            up > 0.1 * down.abs().max(up.abs()) && up > lin,
            "{kind:?}: {up:e}"
        );
        // Both shifts are a sizeable part of the SWS RMS (about 7 mm), not rounding.
        assert!(down.abs() > 2e-4 && up.abs() > 2e-4, "{down:e} {up:e}");
    }
}

/// `W_road - D - (E(T) - E(0))` and `D` over a record: the road's work on the tyres,
/// the dampers' dissipation and the mechanical energy (kinetic plus elastic, tyres
/// included), by the trapezoidal rule on the records (tyre damping zero).
fn energy_balance(model: &LinearModel, law: &Damper, r: &TimeResponse, h: f64) -> (f64, f64) {
    let n = r.t.len();
    let nq = model.n();
    let q = |i: usize| nalgebra::DVector::from_fn(nq, |d, _| r.positions[d][i]);
    let qd = |i: usize| nalgebra::DVector::from_fn(nq, |d, _| r.velocities[d][i]);
    let road = |i: usize| nalgebra::DVector::from_fn(model.kr.ncols(), |j, _| r.wheel_road[j][i]);
    // Tyre rate of each wheel: its column of Kr holds it once.
    let kt: Vec<f64> = (0..model.kr.ncols())
        .map(|j| model.kr.column(j).sum())
        .collect();
    let mut c_lin = model.c.clone();
    for d in &model.front_corners {
        c_lin -= r.damper_rate * d * d.transpose();
    }
    let energy = |i: usize| {
        let (q, qd, zr) = (q(i), qd(i), road(i));
        let kin = 0.5 * qd.dot(&(&model.m * &qd));
        let tyre_road: f64 = (0..kt.len()).map(|j| 0.5 * kt[j] * zr[j] * zr[j]).sum();
        let el = 0.5 * q.dot(&(&model.k * &q)) - q.dot(&(&model.kr * &zr)) + tyre_road;
        kin + el
    };
    let dissipation = |i: usize| {
        let v = qd(i);
        let front: f64 = model
            .front_corners
            .iter()
            .map(|d| {
                let s = d.dot(&v);
                s * law.force(s)
            })
            .sum();
        v.dot(&(&c_lin * &v)) + front
    };
    // Force of each tyre on its wheel, kt (zr - zu): the road pushes with it.
    let tyre = |i: usize| {
        let (q, zr) = (q(i), road(i));
        let kq = model.kr.transpose() * q;
        nalgebra::DVector::from_fn(kt.len(), |j, _| kt[j] * zr[j] - kq[j])
    };
    let (mut work, mut diss) = (0.0, 0.0);
    for i in 0..n - 1 {
        // The road velocity is constant over a step (piecewise-linear road).
        let v = (road(i + 1) - road(i)) / h;
        work += 0.5 * h * (tyre(i) + tyre(i + 1)).dot(&v);
        diss += 0.5 * h * (dissipation(i) + dissipation(i + 1));
    }
    (work - diss - (energy(n - 1) - energy(0)), diss)
}

#[test]
fn nonlinear_runs_balance_their_energy() {
    let car = Car::datum();
    let h = 5e-4;
    for kind in [ModelKind::Quarter, ModelKind::Full] {
        for tracks in [Tracks::Correlated, Tracks::Independent] {
            let road = Road {
                tracks,
                ..Road::default()
            };
            for law in laws() {
                let opt = TimeOptions {
                    duration: 4.0,
                    ..options(Some(law))
                };
                let r = simulate(kind, &car, &road, &opt).unwrap();
                let model = model_of(kind, &car, &r);
                let (residual, dissipated) = energy_balance(&model, &law, &r, h);
                // Trapezoidal rule on a record with content up to the wheel hop (~10 Hz):
                // O((2 pi f h)^2 / 12), about 1e-4 of the dissipated energy.
                assert!(
                    residual.abs() < 1e-3 * dissipated,
                    "{kind:?} {tracks:?} {law:?}: residual {residual:e} J of {dissipated:e} J"
                );
            }
            if kind == ModelKind::Quarter {
                break;
            }
        }
    }
}

#[test]
fn a_seed_gives_one_record_and_the_rear_wheels_follow_the_front() {
    let car = Car::datum();
    // tau = L / v = 0.14 s, exactly 280 steps of 0.5 ms.
    let road = Road {
        speed: car.wheelbase() / 0.14,
        ..Road::default()
    };
    let opt = TimeOptions {
        duration: 2.0,
        ..options(None)
    };
    let a = simulate(ModelKind::Full, &car, &road, &opt).unwrap();
    let b = simulate(ModelKind::Full, &car, &road, &opt).unwrap();
    assert_eq!(a, b);
    let other = simulate(
        ModelKind::Full,
        &car,
        &road,
        &TimeOptions { seed: 4, ..opt },
    )
    .unwrap();
    assert!(
        rms((0..a.t.len()).map(|i| a.road[i] - other.road[i])) > 0.5 * rms(a.road.iter().copied())
    );
    // Wheels 0, 2: front-right and rear-right (same track); the record is periodic.
    let scale = rms(a.road.iter().copied());
    let n = a.t.len();
    for i in 0..n {
        let front = a.wheel_road[0][(i + n - 280) % n];
        assert!(
            (a.wheel_road[2][i] - front).abs() < 1e-12 * scale.max(1e-3),
            "at {i}"
        );
    }
    assert_eq!(
        a.wheel_road[0], a.wheel_road[1],
        "correlated tracks: both sides alike"
    );
}

#[test]
fn rms_is_taken_over_every_step_before_decimation() {
    let car = Car::datum();
    let road = Road::default();
    let every = simulate(ModelKind::Quarter, &car, &road, &options(None)).unwrap();
    let tenth = simulate(
        ModelKind::Quarter,
        &car,
        &road,
        &TimeOptions {
            decimate: 10,
            ..options(None)
        },
    )
    .unwrap();
    assert_eq!(every.rms, tenth.rms);
    assert_eq!(tenth.t.len(), every.t.len().div_ceil(10));
    for o in 0..3 {
        for (i, v) in tenth.outputs[o].iter().enumerate() {
            assert_eq!(*v, every.outputs[o][10 * i]);
        }
        // The kept samples alone give another number: the RMS is not theirs.
        assert_ne!(rms(tenth.outputs[o].iter().copied()), tenth.rms[o]);
    }
}

#[test]
fn bad_time_options_name_their_field() {
    let car = Car::datum();
    let road = Road::default();
    let err = |opt: TimeOptions| {
        simulate(ModelKind::Quarter, &car, &road, &opt)
            .unwrap_err()
            .to_string()
    };
    assert!(err(options(Some(Damper::asymmetric(0.0, 1000.0)))).starts_with("damper.bump:"));
    let knee = Damper {
        knee: Some(Knee {
            velocity: -1.0,
            bump: 1.0,
            rebound: 1.0,
        }),
        ..Damper::asymmetric(1000.0, 1000.0)
    };
    assert!(err(options(Some(knee))).starts_with("damper.knee.velocity:"));
    assert!(err(TimeOptions {
        decimate: 0,
        ..options(None)
    })
    .starts_with("decimate:"));
    assert!(err(TimeOptions {
        duration: 1000.0,
        dt: 1e-3,
        decimate: 1,
        ..options(None)
    })
    .starts_with("decimate:"));
    assert!(err(TimeOptions {
        dt: 0.0,
        ..options(None)
    })
    .starts_with("dt:"));
}

/// Playback of a measured profile (issue #31) against the closed-form steady state: a
/// sine road `A sin(2 pi x / lambda)` driven at `v` excites the quarter car at
/// `f = v / lambda`, where
/// `Zs = K kt R / D`, `Zu = (K - ms w^2) kt R / D`, `K = ks + j w cs`,
/// `D = (K - ms w^2)(K + kt - mu w^2) - K^2`; after the start's transient has died
/// (the last 4 s of a 40 s run) the amplitudes of BAcc `w^2 |Zs|`, SWS `|Zs - Zu|` and
/// DTL `kt |Zu - R|` are the record's peaks to 0.5 %, at three wavelengths around the
/// body and wheel modes. The record starts at rest at the profile's start.
#[test]
fn a_played_back_sine_road_gives_the_closed_form_steady_state() {
    use num_complex::Complex64 as C;
    use ridelab::road_profile::{playback, Profile};
    let car = Car::datum();
    let q = car.quarter();
    let (v, amp) = (20.0, 0.01);
    for lambda in [16.0, 4.0, 1.5] {
        let dx = 0.01;
        let n = (40.0 * v / dx) as usize + 1;
        let x: Vec<f64> = (0..n).map(|i| i as f64 * dx).collect();
        let z: Vec<f64> = x
            .iter()
            .map(|x| amp * (2.0 * std::f64::consts::PI * x / lambda).sin())
            .collect();
        let profile = Profile::from_samples(&x, z, None, 0).unwrap();
        let model = ModelKind::Quarter.build(&car);
        let dt = profile.playback_step(v, 1e-3);
        let road = playback(&profile, &model.wheels, v, dt).unwrap();
        let opt = TimeOptions {
            decimate: 1,
            ..TimeOptions::default()
        };
        let r = ridelab::time_domain::simulate_playback(
            ModelKind::Quarter,
            &car,
            dt,
            &road.wheels,
            &opt,
        )
        .unwrap();
        let w = 2.0 * std::f64::consts::PI * v / lambda;
        let k = C::new(q.ks, w * q.cs);
        let d = (k - q.ms * w * w) * (k + q.kt - q.mu * w * w) - k * k;
        let zs = k * q.kt * amp / d;
        let zu = (k - q.ms * w * w) * q.kt * amp / d;
        let want = [
            w * w * zs.norm(),
            q.kt * (zu - amp).norm(),
            (zs - zu).norm(),
        ];
        let tail =
            r.t.iter()
                .position(|&t| t >= r.t.last().unwrap() - 4.0)
                .unwrap();
        for (o, name) in ["bacc", "dtl", "sws"].iter().enumerate() {
            let peak = r.outputs[o][tail..]
                .iter()
                .fold(0.0f64, |m, y| m.max(y.abs()));
            let err = (peak / want[o] - 1.0).abs();
            assert!(
                err < 5e-3,
                "lambda {lambda} m ({:.2} Hz), {name}: peak {peak:e} vs {:e} ({err:e})",
                v / lambda,
                want[o]
            );
        }
    }
}
