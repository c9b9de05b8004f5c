//! Modes of a linear model: natural frequency and damping ratio of each eigenvalue
//! pair of the state matrix, labelled by the coordinate that dominates its shape, one
//! coordinate per oscillatory mode (see [`modes`]), and [`LinearModel::modes`], which
//! asks a model for them.

use super::LinearModel;
use crate::error::{Result, RideError};
use crate::math;
use nalgebra::DMatrix;
use num_complex::Complex64 as C64;
use serde::Serialize;
use std::f64::consts::PI;

/// One mode of vibration.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Mode {
    /// Undamped natural frequency `|lambda| / (2 pi)`, Hz.
    pub frequency: f64,
    /// Damped frequency `|Im lambda| / (2 pi)`, Hz (0 for an overdamped root).
    pub damped_frequency: f64,
    /// Damping ratio `-Re lambda / |lambda|`, -.
    pub damping_ratio: f64,
    /// The generalised coordinate the mode is assigned to (its kinetic-energy share, one
    /// coordinate per oscillatory mode, see [`modes`]); wheel pairs say "in phase" or
    /// "anti-phase".
    pub label: String,
}

/// Modes of `model`, sorted by natural frequency. Complex pairs appear once;
/// overdamped real roots appear singly.
///
/// Labels: each mode's shape `phi` (the coordinate part of its eigenvector) gives the
/// kinetic-energy share of every coordinate, `p_i = m_ii |phi_i|^2 / sum_j m_jj |phi_j|^2`
/// (the mass matrices of the models are diagonal, and the share needs no length scale to
/// compare rotations with displacements). The oscillatory modes (at most one per
/// coordinate) are labelled one-to-one: the assignment of distinct coordinates to them
/// that maximises the sum of their shares, so two modes never get the same label (a stiff
/// front couples heave and pitch until heave dominates both modes' shapes). An overdamped
/// real root takes its largest share's coordinate.
pub fn modes(model: &LinearModel) -> Result<Vec<Mode>> {
    let ss = model.state_space()?;
    let n = model.n();
    let eig = ss.a.complex_eigenvalues();
    let ac: DMatrix<C64> = ss.a.map(|v| C64::new(v, 0.0));
    let mut roots: Vec<(C64, Vec<C64>, Vec<f64>)> = Vec::new();
    for lam in eig.iter() {
        if lam.im < -1e-12 * math::cabs(*lam) {
            continue; // the conjugate of a pair already listed
        }
        if lam.re.is_nan() || lam.re >= 0.0 {
            return Err(RideError::Numerical(
                "model is not asymptotically stable".into(),
            ));
        }
        let shape = eigenvector(&ac, *lam)?;
        let share = energy_shares(model, &shape);
        roots.push((*lam, shape, share));
    }
    let oscillatory: Vec<usize> = (0..roots.len())
        .filter(|&k| roots[k].0.im > 1e-12 * math::cabs(roots[k].0))
        .collect();
    let shares: Vec<&[f64]> = oscillatory.iter().map(|&k| &roots[k].2[..]).collect();
    let mut coordinate: Vec<usize> = roots.iter().map(|r| dominant(&r.2)).collect();
    for (&k, j) in oscillatory.iter().zip(assign_one_to_one(&shares, n)) {
        coordinate[k] = j;
    }
    let mut out: Vec<Mode> = roots
        .iter()
        .zip(coordinate)
        .map(|((lam, shape, _), j)| {
            let wn = math::cabs(*lam);
            Mode {
                frequency: wn / (2.0 * PI),
                damped_frequency: lam.im.abs() / (2.0 * PI),
                damping_ratio: -lam.re / wn,
                label: label_of(model, shape, j),
            }
        })
        .collect();
    crate::order::sort_by_f64_key(&mut out, |m| m.frequency);
    Ok(out)
}

impl LinearModel {
    /// Natural frequencies and damping ratios of the model (eigenvalues of `A`).
    pub fn modes(&self) -> Result<Vec<Mode>> {
        modes(self)
    }
}

/// Kinetic-energy share of each coordinate in a mode shape, `m_ii |phi_i|^2` normalised
/// to sum 1 (the coordinate part of the state eigenvector `[phi; lambda phi]`).
fn energy_shares(model: &LinearModel, shape: &[C64]) -> Vec<f64> {
    let n = model.n();
    let e: Vec<f64> = (0..n)
        .map(|i| model.m[(i, i)].abs() * shape[i].norm_sqr())
        .collect();
    let total: f64 = e.iter().sum();
    if total > 0.0 {
        e.iter().map(|v| v / total).collect()
    } else {
        e
    }
}

/// The index of the largest share (the first on ties).
fn dominant(share: &[f64]) -> usize {
    (0..share.len())
        .max_by(|&i, &j| share[i].total_cmp(&share[j]).then(j.cmp(&i)))
        .unwrap_or(0)
}

/// Distinct coordinates for the modes `shares[k]` (`shares.len() <= n`) maximising the sum
/// of the chosen shares: exact dynamic programming over the subsets of used coordinates
/// (`2^n` states; the models here have `n <= 7`), greedy by largest share above 16.
fn assign_one_to_one(shares: &[&[f64]], n: usize) -> Vec<usize> {
    let m = shares.len();
    if m > n || n > 16 {
        // Unreachable for the vehicle models; keep each mode's own best coordinate.
        return shares.iter().map(|s| dominant(s)).collect();
    }
    let size = 1usize << n;
    let mut best = vec![f64::NEG_INFINITY; size];
    let mut from = vec![(0usize, 0usize); size];
    best[0] = 0.0;
    // Every subset is reached from a smaller one, so increasing masks see final values.
    for mask in 0..size {
        let k = mask.count_ones() as usize;
        if k >= m || best[mask] == f64::NEG_INFINITY {
            continue;
        }
        for j in (0..n).filter(|j| mask & (1 << j) == 0) {
            let next = mask | (1 << j);
            let v = best[mask] + shares[k][j];
            if v > best[next] {
                best[next] = v;
                from[next] = (mask, j);
            }
        }
    }
    let mut mask = (0..size)
        .filter(|mask| mask.count_ones() as usize == m)
        .max_by(|&a, &b| best[a].total_cmp(&best[b]).then(b.cmp(&a)))
        .unwrap_or(0);
    let mut out = vec![0; m];
    for k in (0..m).rev() {
        let (prev, j) = from[mask];
        out[k] = j;
        mask = prev;
    }
    out
}

/// Unit eigenvector of `a` for eigenvalue `lam`: the right singular vector of `a - lam I`
/// for its least singular value. (Inverse iteration from a fixed start vector can miss a
/// mode the start vector is blind to: a start linear in the index has no component along
/// a warp mode, wheels moving +, -, -, +.)
fn eigenvector(a: &DMatrix<C64>, lam: C64) -> Result<Vec<C64>> {
    let n = a.nrows();
    let shifted = a - DMatrix::identity(n, n) * lam;
    let svd = shifted.svd(false, true);
    let v_t = svd.v_t.ok_or_else(|| {
        RideError::Numerical("eigenvector: singular value decomposition failed".into())
    })?;
    let k = (0..n)
        .min_by(|&i, &j| svd.singular_values[i].total_cmp(&svd.singular_values[j]))
        .ok_or_else(|| RideError::Numerical("eigenvector of an empty model".into()))?;
    Ok((0..n).map(|i| v_t[(k, i)].conj()).collect())
}

/// The dominant coordinate's name; for a wheel whose mirror wheel moves as much
/// (a symmetric car), the pair's name and whether they move in or out of phase.
fn label_of(model: &LinearModel, shape: &[C64], dom: usize) -> String {
    let name = model.dof_names[dom];
    let Some(side) = ["right", "left"].into_iter().find(|s| name.ends_with(s)) else {
        return name.to_string();
    };
    let mirror_name = if side == "right" {
        name.replace("right", "left")
    } else {
        name.replace("left", "right")
    };
    let Some(mirror) = model.dof_names.iter().position(|n| *n == mirror_name) else {
        return name.to_string();
    };
    let ratio = shape[mirror] / shape[dom];
    if math::cabs(ratio) < 0.5 {
        return name.to_string();
    }
    let base = name.trim_end_matches(side).trim_end_matches('-');
    let phase = if ratio.re > 0.0 {
        "in phase"
    } else {
        "anti-phase"
    };
    format!("{base} ({phase})")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::car::{Axle, Car, QuarterCar};
    use crate::model::{full_car, quarter_car};

    /// The root `lambda = omega_n (-zeta + i sqrt(1 - zeta^2))` a listed mode stands for.
    fn root_of(m: &Mode) -> C64 {
        let wn = 2.0 * PI * m.frequency;
        C64::new(
            -m.damping_ratio * wn,
            wn * (1.0 - m.damping_ratio.powi(2)).max(0.0).sqrt(),
        )
    }

    /// The quarter car's characteristic polynomial `det(M s^2 + C s + K)` at `s`, divided by
    /// its leading term `ms mu |s|^4` so that a root gives a number at rounding level.
    fn quarter_residual(q: &QuarterCar, s: C64) -> f64 {
        let body = s * s * q.ms + s * q.cs + q.ks;
        let wheel = s * s * q.mu + s * (q.cs + q.ct) + q.ks + q.kt;
        let couple = s * q.cs + q.ks;
        (body * wheel - couple * couple).norm() / (q.ms * q.mu * s.norm_sqr().powi(2))
    }

    /// Undamped natural frequencies of the quarter car, Hz, from the quadratic in omega^2
    /// `ms mu w^4 - (ms (ks + kt) + mu ks) w^2 + ks kt = 0`.
    fn undamped_quarter_hz(q: &QuarterCar) -> [f64; 2] {
        let b = q.ms * (q.ks + q.kt) + q.mu * q.ks;
        let disc = (b * b - 4.0 * q.ms * q.mu * q.ks * q.kt).sqrt();
        let w2 = [(b - disc), (b + disc)].map(|x| x / (2.0 * q.ms * q.mu));
        w2.map(|w| w.sqrt() / (2.0 * PI))
    }

    #[test]
    fn quarter_car_modes_match_the_closed_form() {
        // Light damping: the natural frequencies |lambda| / 2 pi differ from the undamped ones
        // only at second order in the damping, about zeta^2 (1e-5 at cs = 20 N s/m).
        let light = QuarterCar {
            cs: 20.0,
            ..Car::datum().quarter()
        };
        let m = quarter_car(&light).modes().unwrap();
        assert_eq!(m.len(), 2);
        for (mode, f) in m.iter().zip(undamped_quarter_hz(&light)) {
            let d = (mode.frequency / f - 1.0).abs();
            assert!(
                d < 1e-4,
                "{}: {} vs {f} Hz ({d:e})",
                mode.label,
                mode.frequency
            );
        }
        // The quadratic against the uncoupled estimates of the datum: the body on the ride
        // rate, sqrt(Kw / ms) / 2 pi = 0.985 Hz, the wheel between spring and tyre,
        // sqrt((ks + kt) / mu) / 2 pi = 11.13 Hz; they differ at order mu / ms (< 0.5 %).
        let q = Car::datum().quarter();
        let [fb, fw] = undamped_quarter_hz(&q);
        let body = (q.wheel_rate() / q.ms).sqrt() / (2.0 * PI);
        let wheel = ((q.ks + q.kt) / q.mu).sqrt() / (2.0 * PI);
        assert!((fb / body - 1.0).abs() < 5e-3, "{fb} vs {body}");
        assert!((fw / wheel - 1.0).abs() < 5e-3, "{fw} vs {wheel}");
        assert!((body - 0.985).abs() < 1e-3 && (wheel - 11.13).abs() < 1e-2);
        // Any damping: each listed root solves the characteristic quartic (relative residual
        // at rounding level, 1e-9 for eigenvalues of a 4 x 4 matrix with entries up to 4e3),
        // the damped frequency is omega_n sqrt(1 - zeta^2), and the labels say which is which.
        for q in [
            light,
            Car::datum().quarter(),
            QuarterCar {
                cs: 3_500.0,
                ct: 200.0,
                ..Car::datum().quarter()
            },
        ] {
            let m = quarter_car(&q).modes().unwrap();
            assert_eq!(m.len(), 2);
            for mode in &m {
                let r = quarter_residual(&q, root_of(mode));
                assert!(r < 1e-9, "{}: residual {r:e}", mode.label);
                let fd = mode.frequency * (1.0 - mode.damping_ratio.powi(2)).sqrt();
                assert!((mode.damped_frequency - fd).abs() < 1e-12 * fd);
            }
            assert_eq!(m[0].label, "body heave zs");
            assert_eq!(m[1].label, "wheel hop zu");
        }
    }

    /// Olley's flat-ride symmetry: with a = b, equal axles and equal tracks, heave, pitch,
    /// roll and warp decouple. Each body motion with its wheels is a quarter car with
    /// `ms = M / 4` (heave), `Iyy / (4 a^2)` (pitch), `Ixx / t^2` (roll), and the warp of the
    /// wheels (FR, FL, RR, RL moving +, -, -, +) leaves the body still:
    /// `mu s^2 + cs s + ks + kt = 0`.
    #[test]
    fn decoupled_full_car_modes_and_labels_by_hand() {
        let axle = Axle {
            unsprung_mass: 40.0,
            spring: 20_000.0,
            damper: 1_500.0,
            tire_stiffness: 180_000.0,
            tire_damping: 0.0,
        };
        let car = Car {
            name: "decoupled".into(),
            source: "test".into(),
            sprung_mass: 1_300.0,
            pitch_inertia: 2_000.0,
            roll_inertia: 500.0,
            a: 1.35,
            b: 1.35,
            track_front: 1.5,
            track_rear: 1.5,
            front: axle,
            rear: axle,
        };
        let quarter = |ms: f64| QuarterCar {
            ms,
            mu: axle.unsprung_mass,
            ks: axle.spring,
            cs: axle.damper,
            kt: axle.tire_stiffness,
            ct: 0.0,
        };
        let heave = quarter(car.sprung_mass / 4.0);
        let pitch = quarter(car.pitch_inertia / (4.0 * car.a * car.a));
        let roll = quarter(car.roll_inertia / car.track_front.powi(2));
        let warp = |s: C64| {
            (s * s * axle.unsprung_mass + s * axle.damper + axle.spring + axle.tire_stiffness)
                .norm()
                / (axle.unsprung_mass * s.norm_sqr())
        };
        let m = full_car(&car).modes().unwrap();
        assert_eq!(m.len(), 7, "{m:?}");
        // Each mode solves its own hand-derived characteristic polynomial to rounding level
        // (1e-9 relative, as for the quarter car), and only that one (1e-3: the polynomials
        // of the other motions are far from zero there, the three body roots differ by > 10 %).
        let residuals = |mode: &Mode| {
            let s = root_of(mode);
            [
                quarter_residual(&heave, s),
                quarter_residual(&pitch, s),
                quarter_residual(&roll, s),
                warp(s),
            ]
        };
        let mut seen = [0usize; 4];
        for mode in &m {
            let r = residuals(mode);
            let k = (0..4).min_by(|&i, &j| r[i].total_cmp(&r[j])).unwrap();
            assert!(r[k] < 1e-9, "{mode:?}: residuals {r:?}");
            for (i, ri) in r.iter().enumerate() {
                assert!(
                    i == k || *ri > 1e-3,
                    "{mode:?} also solves motion {i}: {r:?}"
                );
            }
            seen[k] += 1;
            let body = mode.frequency < 3.0;
            let want = match (k, body) {
                (0, true) => "body heave z",
                (1, true) => "body pitch theta",
                (2, true) => "body roll phi",
                // Wheels of the heave and pitch motions move left and right together; of
                // the roll and warp motions, left against right.
                (0 | 1, false) => "(in phase)",
                (2 | 3, false) => "(anti-phase)",
                _ => unreachable!("warp has no body mode"),
            };
            if body {
                assert_eq!(mode.label, want, "{mode:?}");
            } else {
                assert!(
                    mode.label.starts_with("wheel hop ") && mode.label.ends_with(want),
                    "{mode:?}: want {want}"
                );
            }
        }
        assert_eq!(seen, [2, 2, 2, 1], "{m:?}");
    }

    /// Kinetic-energy shares of a mode computed without this module: the null vector of
    /// `M s^2 + C s + K` at the listed root (smallest singular value).
    fn shares_by_svd(model: &LinearModel, s: C64) -> Vec<f64> {
        let n = model.n();
        let z = DMatrix::from_fn(n, n, |i, j| {
            s * s * model.m[(i, j)] + s * model.c[(i, j)] + model.k[(i, j)]
        });
        let svd = z.svd(false, true);
        let v_t = svd.v_t.unwrap();
        let k = (0..n)
            .min_by(|&i, &j| svd.singular_values[i].total_cmp(&svd.singular_values[j]))
            .unwrap();
        let e: Vec<f64> = (0..n)
            .map(|i| model.m[(i, i)] * v_t[(k, i)].norm_sqr())
            .collect();
        let total: f64 = e.iter().sum();
        e.iter().map(|x| x / total).collect()
    }

    /// Issue #11: at Ks 40 kN/m, Cs 4 kNs/m the stiff front couples heave and pitch until
    /// heave dominates the shapes of both body modes; the table listed "body heave z" twice.
    #[test]
    fn stiff_front_body_modes_get_distinct_labels() {
        let car = Car::datum().with_front(40_000.0, 4_000.0).unwrap();
        let model = full_car(&car);
        let m = model.modes().unwrap();
        let labels: Vec<&str> = m.iter().map(|x| x.label.as_str()).collect();
        for name in ["body heave z", "body pitch theta", "body roll phi"] {
            let count = labels.iter().filter(|l| **l == name).count();
            assert_eq!(count, 1, "{name}: {labels:?}");
        }
        let mut labels_sorted = labels.clone();
        labels_sorted.sort_unstable();
        labels_sorted.dedup();
        assert_eq!(labels_sorted.len(), m.len(), "{labels:?}");
        // Correct, not only distinct: of the two heave-pitch modes, the one named heave has
        // the larger heave share and the one named pitch the larger pitch share (shares by
        // an independent SVD of the quadratic eigenproblem).
        let share = |name: &str| {
            let mode = m.iter().find(|x| x.label == name).unwrap();
            shares_by_svd(&model, root_of(mode))
        };
        let (h, p) = (share("body heave z"), share("body pitch theta"));
        eprintln!("heave-named mode shares {h:.3?}\npitch-named mode shares {p:.3?}");
        assert!(h[0] > p[0] && p[1] > h[1], "heave {h:?} pitch {p:?}");
        // The old rule named both modes heave: it compared the amplitude of z with that of
        // theta times the largest lever arm, max(a, t / 2, 1 m) = 1.011 m. Amplitudes from the
        // shares: |z| = sqrt(p_z / M), |theta| = sqrt(p_theta / Iyy).
        let arm = car.a.max(car.track_front / 2.0).max(1.0);
        for (name, sh) in [("heave", &h), ("pitch", &p)] {
            let z = (sh[0] / car.sprung_mass).sqrt();
            let theta = (sh[1] / car.pitch_inertia).sqrt();
            assert!(
                z > arm * theta,
                "{name}-named mode: |z| {z} vs {arm} |theta| {theta}"
            );
        }
    }

    #[test]
    fn assignment_gives_distinct_coordinates_with_the_largest_total_share() {
        // Both modes have most of their share in coordinate 0; giving mode 0 coordinate 0
        // and mode 1 coordinate 1 sums 0.6 + 0.45 = 1.05 > 0.4 + 0.55.
        let a: &[f64] = &[0.6, 0.4, 0.0];
        let b: &[f64] = &[0.55, 0.45, 0.0];
        assert_eq!(assign_one_to_one(&[a, b], 3), [0, 1]);
        assert_eq!(assign_one_to_one(&[b, a], 3), [1, 0]);
        // Three modes: taking each mode's best free coordinate in turn (0, then 2, then 1)
        // sums 0.5 + 0.4 + 0.1 = 1.0; the best total 0.45 + 0.5 + 0.9 = 1.85 gives mode 0
        // coordinate 1.
        let m0: &[f64] = &[0.5, 0.45, 0.05];
        let m1: &[f64] = &[0.5, 0.1, 0.4];
        let m2: &[f64] = &[0.0, 0.1, 0.9];
        assert_eq!(assign_one_to_one(&[m0, m1, m2], 3), [1, 0, 2]);
        // Fewer modes than coordinates.
        assert_eq!(assign_one_to_one(&[m2], 3), [2]);
        assert_eq!(dominant(&[0.2, 0.7, 0.1]), 1);
    }
}
