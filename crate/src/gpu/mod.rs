//! The GPU route: HiFi criteria (7-DOF full car, front corner: BAcc, DTL, SWS) on every
//! cell of a Ks x Cs grid by the frequency route, one GPU invocation per cell, in f32.
//!
//! ```text
//! var_o = Gv sum_halves weight int_{f_lo}^inf |T_f,o(w) + T_r,o(w) e^{-i w L/v}|^2 / w^2 df
//! ```
//!
//! - [`halves`]: the car as its symmetric half (correlated tracks) or both mirror halves
//!   (independent tracks, each with weight 1/2), each a 2 x 2 complex solve per
//!   frequency after eliminating the wheels.
//! - [`quadrature`]: one fixed [`FrequencyRule`] per map, graded by the poles of every
//!   design of the map, Filon weights for the front-rear cross term, the `f^-2` tails
//!   integrated in `1/f`. `f_lo` is 0, or ISO 8608's lowest frequency `0.011 v` where the
//!   CPU HiFi uses it (a road warp: independent tracks, unequal track widths).
//! - [`cell`]: the kernel's arithmetic on the CPU, in f64 (the route) or f32 (emulating
//!   the GPU); `kernel.wgsl`: the same on the GPU.
//!
//! Every value is checked against the CPU HiFi ([`crate::HiFi`], the exact modal route)
//! in `tests/gpu.rs`: within 1e-4 relative on every cell.

pub mod cell;
mod compute;
#[cfg(feature = "gpu")]
mod device;
pub mod halves;
pub mod quadrature;

pub use compute::{Compute, ComputePath, HiFiGrid};
#[cfg(feature = "gpu")]
pub use device::{kernel_source, GpuMapper};

use crate::car::Car;
use crate::criteria::criteria_spectral;
use crate::error::{Result, RideError};
use crate::evaluate::Criteria;
use crate::maps::Grid;
use crate::math;
use crate::model::{full_car, N_OUT};
use crate::road::{Road, Tracks};
#[cfg(test)]
use cell::cell_variances;
use cell::{pack_half, pack_node, HALF_STRIDE};
use halves::Half;
use num_traits::Float;
pub use quadrature::{FrequencyRule, PoleBand};
use std::f64::consts::PI;

/// Designs per axis at which the poles are sampled to grade the rule.
const POLE_SAMPLES: usize = 7;

/// Everything the kernel needs for one map: the grid, the car's halves, the rule and the
/// road's velocity PSD.
#[derive(Debug, Clone, PartialEq)]
pub struct MapInput {
    /// The grid (Cs rows, Ks columns).
    pub grid: Grid,
    /// The halves of the car.
    pub halves: Vec<Half>,
    /// The frequency rule.
    pub rule: FrequencyRule,
    /// One-sided road velocity PSD `Gv`, m^2/s^2 per Hz.
    pub gv: f64,
    /// ISO 8608's lower band limit, Hz, where the road warps (as the CPU HiFi).
    pub low_cutoff_hz: Option<f64>,
}

impl MapInput {
    /// Prepares the map of `car` (front spring and damper set per cell) on `road` over `grid`.
    pub fn new(car: &Car, road: &Road, grid: &Grid) -> Result<MapInput> {
        car.validate()?;
        road.validate()?;
        grid.validate()?;
        let halves = halves::halves(car, road.tracks)?;
        // Where the HiFi evaluator takes the frequency route (a road warp), it starts at
        // the frequency route's own cutoff: ask that route, at any design of the map.
        let low_cutoff_hz = match road.tracks {
            Tracks::Correlated => None,
            Tracks::Independent => {
                let (ks, cs) = grid.point(0, 0);
                criteria_spectral(&full_car(&car.with_front(ks, cs)?), road, 1e-3)?.low_cutoff_hz
            }
        };
        let bands = pole_bands(car, grid)?;
        let rule = FrequencyRule::new(
            &bands,
            low_cutoff_hz.unwrap_or(0.0),
            road.delay(car.wheelbase()),
        )?;
        Ok(MapInput {
            grid: *grid,
            halves,
            rule,
            gv: road.velocity_psd(),
            low_cutoff_hz,
        })
    }

    /// The halves packed for the kernel, in `F`.
    pub fn packed_halves<F: Float>(&self) -> Vec<[F; HALF_STRIDE]> {
        self.halves.iter().map(|h| pack_half(h).map(cast)).collect()
    }

    /// The combined and split nodes packed for the kernel, in `F`.
    pub fn packed_nodes<F: Float>(&self) -> (Vec<[F; 4]>, Vec<[F; 4]>) {
        let pack = |v: &[quadrature::Node]| v.iter().map(|n| pack_node(n).map(cast)).collect();
        (pack(&self.rule.combined), pack(&self.rule.split))
    }

    /// The criteria of every cell (row-major, Cs rows) computed on the CPU in `F`
    /// (f64: the route; f32: what the GPU computes).
    #[cfg(test)]
    pub fn map_cpu<F: Float>(&self) -> Result<Vec<Criteria>> {
        let halves = self.packed_halves::<F>();
        let (combined, split) = self.packed_nodes::<F>();
        (0..self.grid.len())
            .map(|k| {
                let (i, j) = self.grid.indices(k);
                let (ks, cs) = self.grid.point(i, j);
                let var = cell_variances(&halves, &combined, &split, cast(ks), cast(cs));
                self.criteria(k, var.map(|v| v.to_f64().unwrap_or(f64::NAN)))
            })
            .collect()
    }

    /// Criteria of cell `k` from its variances over `Gv`; errors name the cell when a
    /// value is not finite and positive.
    pub fn criteria(&self, k: usize, var: [f64; N_OUT]) -> Result<Criteria> {
        if var.iter().all(|v| v.is_finite() && *v > 0.0) {
            Ok(Criteria::from_array(var.map(|v| (v * self.gv).sqrt())))
        } else {
            let (i, j) = self.grid.indices(k);
            let (ks, cs) = self.grid.point(i, j);
            Err(RideError::Numerical(format!(
                "GPU route: no finite variance at ks = {ks} N/m, cs = {cs} N s/m"
            )))
        }
    }
}

fn cast<F: Float>(v: f64) -> F {
    F::from(v).unwrap_or_else(F::nan)
}

/// The poles of the full car over the grid's box: eigenvalues `lambda` of the state
/// matrix at `POLE_SAMPLES^2` designs (corners included), as points `f = lambda / (2 pi i)`
/// of the complex frequency plane, each joined to the nearest pole of the neighbouring
/// designs (in Ks and in Cs) by a band, so a pole's path between samples is covered.
fn pole_bands(car: &Car, grid: &Grid) -> Result<Vec<PoleBand>> {
    let b = grid.design_box();
    let n = POLE_SAMPLES;
    let mut poles: Vec<Vec<(f64, f64)>> = Vec::with_capacity(n * n);
    for j in 0..n {
        for i in 0..n {
            let t = |k: usize| k as f64 / (n - 1) as f64;
            let (ks, cs) = b.scale(t(i), t(j));
            let a = full_car(&car.with_front(ks, cs)?).state_space()?.a;
            let p: Vec<(f64, f64)> = a
                .complex_eigenvalues()
                .iter()
                .filter(|l| l.im >= 0.0)
                .map(|l| (l.im / (2.0 * PI), -l.re / (2.0 * PI)))
                .collect();
            if p.iter().any(|&(re, im)| !(re.is_finite() && im > 0.0)) {
                return Err(RideError::Numerical(format!(
                    "GPU route: the full car is not asymptotically stable at ks = {ks} N/m, cs = {cs} N s/m"
                )));
            }
            poles.push(p);
        }
    }
    let mut bands = Vec::new();
    let mut join = |a: &[(f64, f64)], b: &[(f64, f64)]| {
        for &(re, im) in a {
            let near = b
                .iter()
                .min_by(|x, y| {
                    let d = |p: &&(f64, f64)| math::hypot(p.0 - re, p.1 - im);
                    d(x).total_cmp(&d(y))
                })
                .copied()
                .unwrap_or((re, im));
            bands.push(PoleBand {
                lo: re.min(near.0),
                hi: re.max(near.0),
                decay: im.min(near.1),
            });
        }
    };
    for j in 0..n {
        for i in 0..n {
            let here = &poles[j * n + i];
            join(here, here);
            if i + 1 < n {
                join(here, &poles[j * n + i + 1]);
            }
            if j + 1 < n {
                join(here, &poles[(j + 1) * n + i]);
            }
        }
    }
    Ok(bands)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::design::DesignBox;
    use crate::maps::evaluate_grid;
    use crate::HiFi;

    fn max_rel(a: &[Criteria], b: &[Criteria]) -> f64 {
        a.iter()
            .zip(b)
            .flat_map(|(x, y)| {
                x.to_array()
                    .into_iter()
                    .zip(y.to_array())
                    .map(|(p, q)| (p / q - 1.0).abs())
            })
            .fold(0.0, f64::max)
    }

    /// The route without a GPU: in f64 it is the CPU HiFi to 1e-6 (the rule's error), in
    /// f32 (what the kernel computes, operation for operation) to 1e-4; the datum car on
    /// correlated tracks and with a road warp on independent ones, slow and fast.
    #[test]
    fn the_route_in_f64_and_f32_equals_the_cpu_hifi() {
        let mut warp = Car::datum();
        warp.track_rear = warp.track_front - 0.05;
        let grid = Grid::over_box(&DesignBox::default(), 4, 4).unwrap();
        for (car, tracks) in [
            (Car::datum(), Tracks::Correlated),
            (warp, Tracks::Independent),
        ] {
            for speed in [5.0, 40.0] {
                let road = Road {
                    speed,
                    tracks,
                    ..Road::default()
                };
                let cpu = evaluate_grid(&HiFi::new(&car, &road).unwrap(), &grid, 1).unwrap();
                let input = MapInput::new(&car, &road, &grid).unwrap();
                let e64 = max_rel(&input.map_cpu::<f64>().unwrap(), &cpu);
                let e32 = max_rel(&input.map_cpu::<f32>().unwrap(), &cpu);
                assert!(e64 <= 1e-6, "{tracks:?} {speed} m/s: f64 {e64:.2e}");
                assert!(e32 <= 1e-4, "{tracks:?} {speed} m/s: f32 {e32:.2e}");
            }
        }
    }

    /// The symmetric half's mass is the full car's, `S^T M S`: the body and all four
    /// wheels (each unsprung slot holds an axle's two).
    #[test]
    fn the_symmetric_half_carries_the_whole_mass() {
        let car = Car::datum();
        let h = &halves::halves(&car, Tracks::Correlated).unwrap()[0];
        let unsprung = 2.0 * (car.front.unsprung_mass + car.rear.unsprung_mass);
        let total = h.m[0] + h.m[7] + h.m[8];
        assert!((total - car.sprung_mass - unsprung).abs() <= 1e-9 * total);
    }
}
