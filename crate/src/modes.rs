//! Modes of a linear model: natural frequency and damping ratio of each eigenvalue
//! pair of the state matrix, labelled by the coordinate that dominates its shape.

use crate::error::{Result, RideError};
use crate::model::LinearModel;
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
    /// The generalised coordinate with the largest share of the mode shape.
    pub label: String,
}

/// Modes of `model`, sorted by natural frequency. Complex pairs appear once;
/// overdamped real roots appear singly.
pub fn modes(model: &LinearModel) -> Result<Vec<Mode>> {
    let ss = model.state_space()?;
    let n = model.n();
    let eig = ss.a.complex_eigenvalues();
    let ac: DMatrix<C64> = ss.a.map(|v| C64::new(v, 0.0));
    // Length scales that make rotations comparable with displacements (m per rad).
    let scale: Vec<f64> = (0..n)
        .map(|i| {
            let d = model.outputs[2]
                .q
                .iter()
                .map(|v| v.abs())
                .fold(0.0, f64::max)
                .max(1.0);
            if model.dof_names[i].contains("pitch") || model.dof_names[i].contains("roll") {
                d
            } else {
                1.0
            }
        })
        .collect();
    let mut out = Vec::new();
    for lam in eig.iter() {
        if lam.im < -1e-12 * lam.norm() {
            continue; // the conjugate of a pair already listed
        }
        if lam.re.is_nan() || lam.re >= 0.0 {
            return Err(RideError::Numerical(
                "model is not asymptotically stable".into(),
            ));
        }
        let shape = eigenvector(&ac, *lam)?;
        let dom = (0..n)
            .max_by(|&i, &j| (shape[i].norm() * scale[i]).total_cmp(&(shape[j].norm() * scale[j])))
            .unwrap_or(0);
        let wn = lam.norm();
        let label = label_of(model, &shape, dom);
        out.push(Mode {
            frequency: wn / (2.0 * PI),
            damped_frequency: lam.im.abs() / (2.0 * PI),
            damping_ratio: -lam.re / wn,
            label,
        });
    }
    out.sort_by(|a, b| a.frequency.total_cmp(&b.frequency));
    Ok(out)
}

/// Unit eigenvector of `a` for eigenvalue `lam` by two steps of shifted inverse iteration.
fn eigenvector(a: &DMatrix<C64>, lam: C64) -> Result<Vec<C64>> {
    let n = a.nrows();
    let shift = lam + C64::new(1e-10, 1e-10) * lam.norm().max(1.0);
    let lu = (a - DMatrix::identity(n, n) * shift).lu();
    let mut x = nalgebra::DVector::from_fn(n, |i, _| {
        C64::new(1.0 + 0.1 * i as f64, 0.3 - 0.05 * i as f64)
    });
    for _ in 0..2 {
        x = lu
            .solve(&x)
            .ok_or_else(|| RideError::Numerical("eigenvector iteration failed".into()))?;
        let nx = x.norm();
        x /= C64::new(nx, 0.0);
    }
    Ok(x.iter().copied().collect())
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
    if ratio.norm() < 0.5 {
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
