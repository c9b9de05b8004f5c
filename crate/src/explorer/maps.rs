//! Design maps of any model for the explorer: LoFi, HiFi, the fitted surrogate, and the
//! surrogate's error against the HiFi.
//!
//! A map's values depend on the car, road, design box and (for the surrogate) its fit,
//! not on the design objectives, which only judge them. Editing an objective (the SWS
//! limit dragged, a band typed) is the commonest edit, so the last values of each model
//! and grid are kept per thread and only the objective mask is recomputed: a 240 x 180
//! LoFi map then costs its mask (about 1 ms in the page) instead of 43 200 evaluations.

use super::state::{broken_mask, check_grid, dos_context, map_values, ModelMap, Scenario};
use super::surrogate::{fitted, FitKey};
use crate::error::{Result, RideError};
use crate::evaluate::Evaluator;
use std::cell::RefCell;
use std::rc::Rc;

/// Which model a map shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MapModel {
    /// The quarter car.
    LoFi,
    /// The full car.
    HiFi,
    /// The fitted surrogate.
    Surrogate,
    /// The surrogate's signed relative error against the HiFi, %.
    SurrogateError,
}

impl MapModel {
    /// Parses "lofi", "hifi", "surrogate" or "error" (errors name `model`).
    pub fn parse(s: &str) -> Result<MapModel> {
        match s {
            "lofi" => Ok(MapModel::LoFi),
            "hifi" => Ok(MapModel::HiFi),
            "surrogate" => Ok(MapModel::Surrogate),
            "error" => Ok(MapModel::SurrogateError),
            _ => Err(RideError::field(
                "model",
                format!("'{s}' is not one of lofi, hifi, surrogate, error"),
            )),
        }
    }
}

/// What a map's values depend on.
#[derive(Debug, Clone, PartialEq)]
struct ValuesKey {
    model: MapModel,
    fit: FitKey,
    nx: usize,
    ny: usize,
}

/// Maps kept: one per model and grid in use (the page shows one model at 240 x 180, its
/// objective plane uses the surrogate at 120 x 90, the worker the HiFi at 41 x 41).
const KEPT_MAPS: usize = 6;

thread_local! {
    static LAST_VALUES: RefCell<Vec<(ValuesKey, Rc<Vec<f64>>)>> = const { RefCell::new(Vec::new()) };
}

/// The values of `model` on the grid, from the cache or from `compute`.
fn values(
    s: &Scenario,
    model: MapModel,
    nx: usize,
    ny: usize,
    compute: impl FnOnce() -> Result<Vec<f64>>,
) -> Result<Rc<Vec<f64>>> {
    let key = ValuesKey {
        model,
        fit: FitKey::of(s),
        nx,
        ny,
    };
    let hit = LAST_VALUES.with_borrow(|kept| {
        kept.iter()
            .find(|(k, _)| *k == key)
            .map(|(_, v)| Rc::clone(v))
    });
    if let Some(v) = hit {
        return Ok(v);
    }
    let v = Rc::new(compute()?);
    LAST_VALUES.with_borrow_mut(|kept| {
        kept.retain(|(k, _)| !(k.model == model && k.nx == nx && k.ny == ny));
        if kept.len() >= KEPT_MAPS {
            kept.remove(0);
        }
        kept.push((key, Rc::clone(&v)));
    });
    Ok(v)
}

/// The map of `model` with its objectives judged against `model`'s own datum.
fn judged<E: Evaluator + ?Sized>(
    s: &Scenario,
    kind: MapModel,
    model: &E,
    nx: usize,
    ny: usize,
) -> Result<ModelMap> {
    let v = values(s, kind, nx, ny, || map_values(s, model, nx, ny))?;
    let ctx = dos_context(&s.datum, model)?;
    Ok(ModelMap {
        nx,
        ny,
        broken: broken_mask(s, &ctx, &v, nx, ny),
        values: v.as_ref().clone(),
    })
}

/// The map of `model` over the scenario's design box. For [`MapModel::SurrogateError`]
/// the planes hold `100 (surrogate / HiFi - 1)`, %, and the objectives are the HiFi's.
pub fn map_of(s: &Scenario, model: MapModel, nx: usize, ny: usize) -> Result<ModelMap> {
    check_grid(nx, ny)?;
    match model {
        MapModel::LoFi => judged(s, model, &s.lofi(), nx, ny),
        MapModel::HiFi => judged(s, model, &s.hifi()?, nx, ny),
        MapModel::Surrogate => judged(s, model, &*fitted(s)?.model, nx, ny),
        MapModel::SurrogateError => {
            let hifi = s.hifi()?;
            let h = values(s, MapModel::HiFi, nx, ny, || map_values(s, &hifi, nx, ny))?;
            let e = values(s, model, nx, ny, || {
                let p = map_values(s, &*fitted(s)?.model, nx, ny)?;
                Ok(p.iter()
                    .zip(h.iter())
                    .map(|(p, h)| 100.0 * (p - h) / h)
                    .collect())
            })?;
            let ctx = dos_context(&s.datum, &hifi)?;
            Ok(ModelMap {
                nx,
                ny,
                broken: broken_mask(s, &ctx, &h, nx, ny),
                values: e.as_ref().clone(),
            })
        }
    }
}

/// The LoFi map of `scenario` on an `nx` x `ny` grid.
pub fn lofi_map(s: &Scenario, nx: usize, ny: usize) -> Result<ModelMap> {
    map_of(s, MapModel::LoFi, nx, ny)
}
