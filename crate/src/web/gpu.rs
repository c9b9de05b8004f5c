//! The GPU path in the page: HiFi maps on the browser's WebGPU.
//!
//! ```js
//! const gpu = await GpuMaps.request();        // rejects: "GPU: no WebGPU adapter ..."
//! gpu.adapter;                                // e.g. "SwiftShader Device (Subzero)"
//! const m = await gpu.hifiMap(state, 160, 120);
//! // m = {nx, ny, values: Float64Array(3 nx ny), adapter, path: "gpu", nodes}
//! ```
//!
//! `values` has the layout of `lofiMap`: BAcc (m/s^2), DTL (N), SWS (m) planes, each
//! row-major with Cs slow on the cell-centre grid of the state's design box. Every value
//! is the GPU route's (f32, within 1e-4 of the CPU HiFi, `tests/gpu.rs`). Without WebGPU
//! (no `navigator.gpu`, no adapter) `request` rejects with an `Error`; nothing panics.

use super::{js_error, parse_state};
use crate::error::RideError;
use crate::gpu::{GpuMapper, MapInput};
use crate::maps::Grid;
use js_sys::{Float64Array, Object, Promise, Reflect};
use std::rc::Rc;
use wasm_bindgen::prelude::*;
use wasm_bindgen_futures::future_to_promise;

/// The page's GPU: a WebGPU device with the HiFi kernel compiled.
#[wasm_bindgen]
pub struct GpuMaps {
    mapper: Rc<GpuMapper>,
}

#[wasm_bindgen]
impl GpuMaps {
    /// Resolves to the GPU path, or rejects with an `Error` when the browser has no
    /// WebGPU adapter (the page then stays on the CPU path and says so).
    pub async fn request() -> Result<GpuMaps, JsValue> {
        match GpuMapper::request().await.map_err(js_error)? {
            Some(m) => Ok(GpuMaps { mapper: Rc::new(m) }),
            None => Err(js_error(RideError::Gpu(
                "no WebGPU adapter in this browser: the HiFi maps use the CPU path".into(),
            ))),
        }
    }

    /// The adapter's name (what the footer shows).
    #[wasm_bindgen(getter)]
    pub fn adapter(&self) -> String {
        self.mapper.adapter_name().to_string()
    }

    /// The HiFi map of the state's car and road on its design box, `nx` x `ny` cell
    /// centres (2..=1001 each; errors name `nx` or `ny`): a promise of
    /// `{nx, ny, values, adapter, path, nodes}` (see the module doc).
    #[wasm_bindgen(js_name = hifiMap)]
    pub fn hifi_map(&self, state: JsValue, nx: usize, ny: usize) -> Promise {
        self.run(state, move |b| Grid::cells(b, nx, ny))
    }

    /// The HiFi criteria of the objective plane's STM starting grid (the design box's
    /// `STM_GRID x STM_GRID` nodes, corners included: `Grid::over_box`), for
    /// `Explorer.hifiFront`: a promise of `{nx, ny, values, adapter, path, nodes}` with
    /// `values` in the map layout.
    #[wasm_bindgen(js_name = stmGrid)]
    pub fn stm_grid(&self, state: JsValue) -> Promise {
        let n = crate::explorer::studies::STM_GRID;
        self.run(state, move |b| Grid::over_box(b, n, n))
    }

    /// Runs the kernel on the grid `grid_of` makes of the state's design box.
    fn run(
        &self,
        state: JsValue,
        grid_of: impl FnOnce(&crate::design::DesignBox) -> crate::error::Result<Grid>,
    ) -> Promise {
        let mapper = Rc::clone(&self.mapper);
        let input = parse_state(state).and_then(|s| {
            let sc = s.scenario().map_err(js_error)?;
            let grid = grid_of(&sc.dbox).map_err(js_error)?;
            MapInput::new(&sc.datum, &sc.road, &grid)
                .map(|input| (input, grid))
                .map_err(js_error)
        });
        future_to_promise(async move {
            let (input, grid) = input?;
            let values = mapper.run(&input).await.map_err(js_error)?;
            let n = values.len();
            let mut planes = vec![0.0; 3 * n];
            for (k, c) in values.iter().enumerate() {
                planes[k] = c.bacc;
                planes[n + k] = c.dtl;
                planes[2 * n + k] = c.sws;
            }
            let out = Object::new();
            Reflect::set(&out, &"nx".into(), &(grid.ks.n as f64).into())?;
            Reflect::set(&out, &"ny".into(), &(grid.cs.n as f64).into())?;
            Reflect::set(
                &out,
                &"values".into(),
                &Float64Array::from(planes.as_slice()).into(),
            )?;
            Reflect::set(&out, &"adapter".into(), &mapper.adapter_name().into())?;
            Reflect::set(&out, &"path".into(), &"gpu".into())?;
            Reflect::set(&out, &"nodes".into(), &(input.rule.len() as f64).into())?;
            Ok(out.into())
        })
    }
}
