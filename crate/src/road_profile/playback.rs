//! Playback: a profile as the road under each wheel of a time-domain run.
//!
//! At speed `v` the front axle starts `L_max` (the largest `behind` of any wheel) into the
//! profile, so that every wheel is on it from the start, and at time `t_k = k dt` wheel `j`
//! (`behind_j` metres behind the front axle, on track `t_j`) is at distance
//! `x = start + L_max + v t_k - behind_j`: a rear wheel sees the front's road `behind / v`
//! later. The elevation there is the linear interpolation of the track's samples; with
//! `dt = dx / (v k)` (integer `k`, [`Profile::playback_step`]) the samples the run takes
//! are the profile's own or on its straight segments, so a first-order-hold run (as
//! `time_domain`'s exact discretisation) sees exactly the profile's piecewise-linear
//! interpolant. Track 0 (right) plays `elevation_right_m`, track 1 (left) `elevation_m`;
//! a one-track profile plays on both (correlated tracks).

use super::profile::Profile;
use crate::error::{Result, RideError};
use crate::model::Wheel;
use crate::time_domain::MAX_STEPS;

/// The road under each wheel, sampled every `dt`.
#[derive(Debug, Clone, PartialEq)]
pub struct WheelRoad {
    /// Time step, s.
    pub dt: f64,
    /// Distance of the front axle at `t = 0`, m.
    pub front_start: f64,
    /// Road displacement under each wheel (model's wheel order) at `k dt`, m.
    pub wheels: Vec<Vec<f64>>,
}

impl WheelRoad {
    /// Number of time samples.
    pub fn len(&self) -> usize {
        self.wheels.first().map_or(0, Vec::len)
    }

    /// Whether no samples were taken.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

impl Profile {
    /// The largest step at most `max_dt` (s) that divides the sample interval `dx / v`
    /// into whole steps, s: `dx / (v ceil(dx / (v max_dt)))`.
    pub fn playback_step(&self, speed: f64, max_dt: f64) -> f64 {
        let t = self.spacing / speed;
        t / (t / max_dt).ceil().max(1.0)
    }
}

/// The road under `wheels` when `profile` is driven at `speed` (m/s), sampled every `dt`
/// (s), for as long as every wheel is on the profile (see the module doc).
pub fn playback(profile: &Profile, wheels: &[Wheel], speed: f64, dt: f64) -> Result<WheelRoad> {
    if !(speed.is_finite() && speed > 0.0 && speed <= 100.0) {
        return Err(RideError::field("speed", "must be in (0, 100] m/s"));
    }
    if !(dt.is_finite() && dt > 0.0 && dt <= 0.1) {
        return Err(RideError::field("dt", "must be in (0, 0.1] s"));
    }
    if wheels
        .iter()
        .any(|w| !(w.behind.is_finite() && w.behind >= 0.0))
    {
        return Err(RideError::field(
            "wheels",
            "each wheel must be 0 or more m behind the front axle",
        ));
    }
    let l_max = wheels.iter().map(|w| w.behind).fold(0.0, f64::max);
    let span = profile.length() - l_max;
    if span <= 0.0 {
        return Err(RideError::field(
            "distance_m",
            format!(
                "the profile ({:.1} m) is shorter than the wheelbase ({l_max} m)",
                profile.length()
            ),
        ));
    }
    let steps = (span / (speed * dt) * (1.0 + 1e-12)).floor() + 1.0;
    if steps > MAX_STEPS {
        return Err(RideError::field(
            "dt",
            format!("{steps:.0} steps: at most {MAX_STEPS:e} (take a longer step)"),
        ));
    }
    let steps = steps as usize;
    let h = profile.spacing;
    let out = wheels
        .iter()
        .map(|w| {
            let z = if w.track == 0 {
                profile.right()
            } else {
                profile.left()
            };
            let last = z.len() - 1;
            (0..steps)
                .map(|k| {
                    // Position in samples, from the profile's first sample.
                    let u = ((l_max - w.behind) + speed * dt * k as f64) / h;
                    let i = (u.floor() as usize).min(last - 1);
                    cubic(z, i, (u - i as f64).clamp(0.0, 1.0))
                })
                .collect()
        })
        .collect();
    Ok(WheelRoad {
        dt,
        front_start: profile.start + l_max,
        wheels: out,
    })
}

/// Catmull-Rom (Keys, `a = -1/2`) interpolation of `z` between samples `i` and `i + 1` at
/// fraction `t`: through the samples, continuous slope, exact for quadratics; its gain
/// stays within 1 % up to a quarter of the sampling frequency (where linear interpolation
/// has lost 19 %). The end intervals use linearly extrapolated neighbours.
fn cubic(z: &[f64], i: usize, t: f64) -> f64 {
    let p1 = z[i];
    let p2 = z[i + 1];
    let p0 = if i > 0 { z[i - 1] } else { 2.0 * p1 - p2 };
    let p3 = if i + 2 < z.len() {
        z[i + 2]
    } else {
        2.0 * p2 - p1
    };
    0.5 * (2.0 * p1
        + t * (p2 - p0)
        + t * t * (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3)
        + t * t * t * (3.0 * (p1 - p2) + p3 - p0))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::car::Car;
    use crate::model::{full_car, quarter_car, LinearModel, N_OUT};
    use crate::road_profile::{criteria_shaped, synthesize, ProfileTracks, ShapedRoad, Synthesis};
    use nalgebra::{DMatrix, DVector};

    /// A test oracle: the model's response to the wheel road by the exact first-order-hold
    /// discretisation (`time_domain`'s, restated here because its stepper is private), RMS of
    /// each output from `warm` seconds on.
    fn rms_response(model: &LinearModel, road: &WheelRoad, warm: f64) -> [f64; N_OUT] {
        let ss = model.state_space().unwrap();
        let ns = ss.a.nrows();
        let h = road.dt;
        let mut big = DMatrix::zeros(3 * ns, 3 * ns);
        big.view_mut((0, 0), (ns, ns)).copy_from(&(&ss.a * h));
        big.view_mut((0, ns), (ns, ns))
            .copy_from(&(DMatrix::identity(ns, ns) * h));
        big.view_mut((ns, 2 * ns), (ns, ns))
            .copy_from(&(DMatrix::identity(ns, ns) * h));
        let e = big.exp();
        let phi = e.view((0, 0), (ns, ns)).into_owned();
        let g0 = e.view((0, ns), (ns, ns)).into_owned();
        let g1 = e.view((0, 2 * ns), (ns, ns)).into_owned();
        let nw = road.wheels.len();
        let r_at = |k: usize| DVector::from_fn(nw, |j, _| road.wheels[j][k]);
        // Start from the static equilibrium on the first sample: x = -A^-1 Bd r.
        let mut x = -ss.a.clone().lu().solve(&(&ss.bd * r_at(0))).unwrap();
        let skip = (warm / h).round() as usize;
        let mut sum = [0.0; N_OUT];
        let mut count = 0usize;
        for k in 0..road.len() - 1 {
            let r = r_at(k);
            let v = (r_at(k + 1) - &r) / h;
            if k >= skip {
                let y = &ss.cy * &x + &ss.dr * &r + &ss.dw * &v;
                for o in 0..N_OUT {
                    sum[o] += y[o] * y[o];
                }
                count += 1;
            }
            x = &phi * &x + &g0 * (&ss.bd * &r + &ss.bv * &v) + &g1 * (&ss.bd * &v);
        }
        sum.map(|s| (s / count as f64).sqrt())
    }

    /// Each wheel plays the profile at its own distance: the rear wheels on the samples
    /// (the step divides the sample interval), the front wheels `L` further on; the
    /// interpolant goes through the samples and is exact for a quadratic (inside the end
    /// intervals).
    #[test]
    fn rear_wheels_see_the_front_road_later() {
        let p = synthesize(&Synthesis {
            length: 100.0,
            ..Synthesis::default()
        })
        .unwrap();
        let car = Car::datum();
        let model = full_car(&car);
        let v = 20.0;
        let dt = p.playback_step(v, 1e-3);
        let k = p.spacing / (v * dt);
        assert!((k - k.round()).abs() < 1e-9 && v * dt <= 1e-3 * v + 1e-12);
        let road = playback(&p, &model.wheels, v, dt).unwrap();
        assert_eq!(road.front_start, car.wheelbase());
        let l = car.wheelbase();
        let k = k.round() as usize;
        for m in [0usize, 37, 1000] {
            // Rear right (wheel 2) on sample m; front right (wheel 0) at m dx + L.
            assert!((road.wheels[2][m * k] - p.right()[m]).abs() < 1e-12);
            let u = (m as f64 * p.spacing + l) / p.spacing;
            let i = u.floor() as usize;
            let expect = cubic(p.right(), i, u - i as f64);
            assert!((road.wheels[0][m * k] - expect).abs() < 1e-12);
        }
        let q: Vec<f64> = (0..10).map(|i| 0.3 * (i * i) as f64 - i as f64).collect();
        for (i, t) in [(1usize, 0.3), (4, 0.0), (4, 0.71), (7, 0.5)] {
            let x = i as f64 + t;
            assert!(
                (cubic(&q, i, t) - (0.3 * x * x - x)).abs() < 1e-12,
                "{i} {t}"
            );
        }
        assert!(playback(&p, &model.wheels, 0.0, dt).is_err());
        assert!(playback(&p, &model.wheels, v, 0.0).is_err());
    }

    /// The profile played back through the quarter and the full car at three speeds: the
    /// RMS after the start-up transient is within 3 % of the filter route on the same
    /// profile.
    #[test]
    fn playback_agrees_with_the_filter_route() {
        let p = synthesize(&Synthesis {
            gd_n0: 256e-6,
            waviness: 2.5,
            length: 3000.0,
            spacing: 0.05,
            seed: 8,
            ..Synthesis::default()
        })
        .unwrap();
        let car = Car::datum();
        for speed in [10.0, 20.0, 30.0] {
            let shaped = ShapedRoad::from_profile(&p, speed, ProfileTracks::Correlated).unwrap();
            for model in [quarter_car(&car.quarter()), full_car(&car)] {
                let road = playback(&p, &model.wheels, speed, p.spacing / speed).unwrap();
                let td = rms_response(&model, &road, 5.0);
                let ex = criteria_shaped(&model, &shaped).unwrap().to_array();
                for o in 0..N_OUT {
                    let d = td[o] / ex[o] - 1.0;
                    eprintln!(
                        "v {speed} n {} out {o}: time {:.5e} filter {:.5e} ({:+.2} %), fit error {:.3}",
                        model.n(),
                        td[o],
                        ex[o],
                        100.0 * d,
                        shaped.fit_error()
                    );
                    assert!(
                        d.abs() < 0.03,
                        "v {speed} output {o}: {} vs {}",
                        td[o],
                        ex[o]
                    );
                }
            }
        }
    }
}
