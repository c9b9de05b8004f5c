//! Which path computes a HiFi grid (`--compute gpu|cpu|auto`), and the grid's values
//! as an [`Evaluator`], so maps and STM take them like any evaluator.

use crate::analysis::HiFi;
use crate::error::{parse_choice, Result, RideError};
use crate::evaluate::{Criteria, Evaluator};
use crate::maps::Grid;
use serde::{Deserialize, Serialize};
use strum::{EnumIter, EnumProperty, IntoStaticStr, VariantNames};

/// The path a caller asks for.
#[derive(
    Debug,
    Clone,
    Copy,
    PartialEq,
    Eq,
    Default,
    Serialize,
    Deserialize,
    EnumIter,
    EnumProperty,
    IntoStaticStr,
    VariantNames,
)]
#[serde(rename_all = "lowercase")]
#[strum(serialize_all = "lowercase")]
#[strum()]
pub enum Compute {
    /// The GPU when a hardware adapter is there, else the CPU. A software adapter
    /// (lavapipe, SwiftShader) is slower than the CPU path and is only used on request.
    #[default]
    Auto,
    /// The GPU, any adapter; an error when there is none.
    Gpu,
    /// The CPU HiFi (the reference).
    Cpu,
}

impl std::str::FromStr for Compute {
    type Err = RideError;
    fn from_str(s: &str) -> Result<Compute> {
        Compute::parse(s)
    }
}

impl Compute {
    /// Parses "auto", "gpu" or "cpu" (any case; errors name `compute`).
    pub fn parse(s: &str) -> Result<Compute> {
        parse_choice("compute", s)
    }
}

/// The path that ran: serialises as `"gpu"` or `"cpu"` (the JSON's `compute` field).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ComputePath {
    /// The GPU route (f32 frequency route, within 1e-4 of the CPU HiFi).
    Gpu,
    /// The CPU HiFi.
    Cpu,
}

/// The mapper `compute` asks for: none for `Cpu`, a hardware adapter's for `Auto` (none
/// without one), any adapter's for `Gpu` (an error naming `compute` without one).
#[cfg(all(feature = "gpu", not(target_arch = "wasm32")))]
fn gpu_mapper(compute: Compute) -> Result<Option<super::GpuMapper>> {
    use super::GpuMapper;
    match compute {
        Compute::Cpu => Ok(None),
        Compute::Auto => Ok(GpuMapper::new()?.filter(|m| !m.is_software())),
        Compute::Gpu => GpuMapper::new()?.map(Some).ok_or_else(|| {
            RideError::field(
                "compute",
                "gpu: no GPU adapter (natively a Vulkan, Metal or DX12 driver; on Debian \
                 without a GPU: apt-get install mesa-vulkan-drivers), use --compute cpu or auto",
            )
        }),
    }
}

/// HiFi criteria precomputed on a grid: a grid point returns its stored value, any
/// other design (the datum, STM's refinements) is evaluated by the CPU HiFi.
#[derive(Debug, Clone)]
pub struct HiFiGrid {
    hifi: HiFi,
    grid: Grid,
    values: Vec<Criteria>,
    path: ComputePath,
    adapter: Option<String>,
}

impl HiFiGrid {
    /// `hifi` over `grid` on the path `compute` asks for, with `threads` threads on the
    /// CPU path. `Compute::Gpu` without an adapter (or in a build without the `gpu`
    /// feature) is an error naming `compute`.
    pub fn compute(hifi: HiFi, grid: &Grid, compute: Compute, threads: usize) -> Result<HiFiGrid> {
        if let Some(g) = HiFiGrid::on_gpu(&hifi, grid, compute)? {
            return Ok(g);
        }
        let values = crate::maps::evaluate_grid(&hifi, grid, threads)?;
        Ok(HiFiGrid::from_values(hifi, *grid, values, ComputePath::Cpu))
    }

    /// `hifi` over `grid` on the GPU when `compute` takes it there: `None` for `Cpu`, and
    /// for `Auto` without a hardware adapter or where the route cannot run (a mode damped
    /// too weakly for its rule, a device failure), so the caller's CPU path runs; `Gpu`
    /// without an adapter, or failing, is an error (naming `compute` when there is no
    /// adapter or no GPU path in this build). The grid off the GPU's points evaluates on
    /// a copy of `hifi` (the HiFi is prepared once by the caller).
    // `hifi` is read on the native GPU path only.
    #[cfg_attr(
        not(all(feature = "gpu", not(target_arch = "wasm32"))),
        allow(unused_variables)
    )]
    pub(crate) fn on_gpu(hifi: &HiFi, grid: &Grid, compute: Compute) -> Result<Option<HiFiGrid>> {
        grid.validate()?;
        #[cfg(all(feature = "gpu", not(target_arch = "wasm32")))]
        if let Some(m) = gpu_mapper(compute)? {
            match super::MapInput::new(hifi.car(), hifi.road(), grid)
                .and_then(|input| m.map(&input))
            {
                Ok(values) => {
                    return Ok(Some(HiFiGrid {
                        hifi: hifi.clone(),
                        grid: *grid,
                        values,
                        path: ComputePath::Gpu,
                        adapter: Some(m.adapter_name().to_string()),
                    }))
                }
                Err(e) if compute == Compute::Gpu => return Err(e),
                Err(_) => {}
            }
        }
        // The page awaits the GPU (`web::GpuMaps`); this blocking path is native only.
        #[cfg(not(all(feature = "gpu", not(target_arch = "wasm32"))))]
        if compute == Compute::Gpu {
            return Err(RideError::field(
                "compute",
                "gpu: this build has no GPU path (build with --features gpu), \
                 use --compute cpu or auto",
            ));
        }
        Ok(None)
    }

    /// Wraps values already computed on `grid` (row-major, Cs rows) by `path`.
    pub(crate) fn from_values(
        hifi: HiFi,
        grid: Grid,
        values: Vec<Criteria>,
        path: ComputePath,
    ) -> HiFiGrid {
        HiFiGrid {
            hifi,
            grid,
            values,
            path,
            adapter: None,
        }
    }

    /// The path that computed the grid.
    pub fn path(&self) -> ComputePath {
        self.path
    }

    /// The GPU adapter's name when the GPU computed the grid.
    pub fn adapter(&self) -> Option<&str> {
        self.adapter.as_deref()
    }

    /// The values, row-major (Cs rows, Ks columns).
    pub fn values(&self) -> &[Criteria] {
        &self.values
    }

    /// The grid index of `v` on `axis` when it is a grid value (to 1e-9 of a step).
    fn index_on(axis: &crate::maps::Axis, v: f64) -> Option<usize> {
        let t = (v - axis.min) / axis.step();
        let k = t.round();
        let ok = (0.0..axis.n as f64).contains(&k) && (t - k).abs() <= 1e-9;
        ok.then_some(k as usize)
    }
}

impl Evaluator for HiFiGrid {
    fn evaluate(&self, ks: f64, cs: f64) -> Result<Criteria> {
        match (
            HiFiGrid::index_on(&self.grid.ks, ks),
            HiFiGrid::index_on(&self.grid.cs, cs),
        ) {
            (Some(i), Some(j)) if self.values.len() == self.grid.len() => {
                Ok(self.values[self.grid.index(i, j)])
            }
            _ => self.hifi.evaluate(ks, cs),
        }
    }
    fn name(&self) -> String {
        "full".into()
    }
}
