//! The browser shell (wasm32 only): a thin JS API over the core, exported with
//! wasm-bindgen. Every entry returns `Result<_, JsValue>`; an error is a JS `Error`
//! whose message is the core's [`RideError`] text and whose `field` property names the
//! state field at fault (`"speed"`, `"ks"`, `"car"`, ...), so the page can show it
//! next to that field. Nothing here panics on bad input, and nothing touches the DOM:
//! the same module runs in a Web Worker.
//!
//! State objects (see [`State`]) are plain JS objects in SI units:
//! `{car, carJson?, ks, cs, class, speed, tracks, ksMin?, ksMax?, csMin?, csMax?, swsLimit?,
//! bounceBand?, dampingBand?, noWorse?, dtlMargin?, travel?, surrogate?, plan?}`. The page
//! keeps one [`Explorer`] session per thread and moves it with small setters; the free
//! functions here need no state. The logic behind every entry is in [`crate::explorer`].

mod charts;
mod explorer;
#[cfg(feature = "gpu")]
mod gpu;
#[cfg(feature = "on-demand")]
mod on_demand;
#[cfg(feature = "on-demand")]
mod road;
mod screen;
pub use explorer::{check_state, Explorer};
#[cfg(feature = "gpu")]
pub use gpu::GpuMaps;
#[cfg(feature = "on-demand")]
pub use on_demand::AdaptiveRun;
#[cfg(feature = "on-demand")]
pub use road::{describe_road, design_on_road, road_front, road_map, use_road};
pub use screen::{draw_line_chart_js, draw_map_frame_js};

use crate::car::{Car, PRESETS};
use crate::chart::ColourMap;
use crate::error::RideError;
use crate::explorer::{ui_field, State, STATE_FIELDS};
use crate::road::RoadClass;
use crate::robust::{CarFile, LoadCase};
use js_sys::{Float64Array, Object, Reflect, Uint8Array};
use serde::Serialize;
use wasm_bindgen::prelude::*;

/// Converts a core error to a JS `Error` with a `field` property.
fn js_error(e: RideError) -> JsValue {
    let field = match &e {
        RideError::Field { field, .. } | RideError::Infeasible { field, .. } => ui_field(field),
        // The only JSON the core parses is a car file.
        RideError::Json(_) => "car".into(),
        _ => String::new(),
    };
    // The page shows spring and damper rates in kN/m and kNs/m.
    let err = js_sys::Error::new(&crate::domain::page_units(&e.to_string()));
    // Setting a property on a fresh Error object cannot fail.
    let _ = Reflect::set(&err, &"field".into(), &field.into());
    err.into()
}

/// A core error as a JS `Error` whose `field` is the core's own field name, unmapped
/// (the damper law's `bump`, `rebound`, `knee.velocity`, ...: the page has a field each).
fn js_error_verbatim(e: RideError) -> JsValue {
    let field = match &e {
        RideError::Field { field, .. } => field.clone(),
        _ => String::new(),
    };
    let err = js_sys::Error::new(&e.to_string());
    let _ = Reflect::set(&err, &"field".into(), &field.into());
    err.into()
}

/// `v` as a JS value, once every number in it is known to be finite
/// ([`crate::finite::check`]: no NaN or infinity reaches the screen).
fn to_js<T: Serialize>(v: &T) -> Result<JsValue, JsValue> {
    crate::finite::check(v).map_err(js_error)?;
    v.serialize(&serde_wasm_bindgen::Serializer::json_compatible())
        .map_err(|e| js_sys::Error::new(&format!("serialisation: {e}")).into())
}

fn state_error(msg: String) -> JsValue {
    let err = js_sys::Error::new(&format!("state: {msg}"));
    let _ = Reflect::set(&err, &"field".into(), &"state".into());
    err.into()
}

/// The state object as a [`State`]. serde-wasm-bindgen reads only the fields it knows,
/// so unknown (misspelt) keys are refused here first.
fn parse_state(state: JsValue) -> Result<State, JsValue> {
    if let Some(obj) = state.dyn_ref::<Object>() {
        for key in Object::keys(obj).iter() {
            let key = key.as_string().unwrap_or_default();
            if !STATE_FIELDS.contains(&key.as_str()) {
                return Err(state_error(format!(
                    "unknown field `{key}`, expected one of {}",
                    STATE_FIELDS.join(", ")
                )));
            }
        }
    } else {
        return Err(state_error("must be an object".into()));
    }
    serde_wasm_bindgen::from_value(state).map_err(|e| state_error(e.to_string()))
}

/// Runs once when the module is instantiated (page and workers): a panic, should one
/// ever happen, then names itself and its place in the console instead of "unreachable".
#[wasm_bindgen(start)]
pub fn start() {
    console_error_panic_hook::set_once();
}

/// The crate version.
#[wasm_bindgen]
pub fn version() -> String {
    env!("CARGO_PKG_VERSION").into()
}

/// The default state: the datum car at its own front spring and damper, class B at
/// 20 m/s, correlated tracks, the default design box and the 7 mm SWS limit.
#[wasm_bindgen(js_name = defaultState)]
pub fn default_state() -> Result<JsValue, JsValue> {
    to_js(&State::default())
}

#[derive(Serialize)]
struct PresetInfo {
    name: &'static str,
    label: String,
    json: &'static str,
    ks: f64,
    cs: f64,
}

/// The shipped car presets: `[{name, label, json, ks, cs}]` (`ks`, `cs`: the preset's
/// own front spring and damper, the datum design).
#[wasm_bindgen]
pub fn presets() -> Result<JsValue, JsValue> {
    let mut out = Vec::with_capacity(PRESETS.len());
    for (name, json) in PRESETS {
        let car = Car::from_json(json).map_err(js_error)?;
        out.push(PresetInfo {
            name,
            label: car.name.clone(),
            json,
            ks: car.front.spring,
            cs: car.front.damper,
        });
    }
    to_js(&out)
}

/// The 256 colours of a map colour scale (`name`: "viridis", "cividis" or "diverging")
/// as 768 bytes, `r, g, b` per entry: the page paints its map images with the colours
/// the core's charts use (see [`crate::chart::colour`]).
#[wasm_bindgen(js_name = colourTable)]
pub fn colour_table(name: &str) -> Result<Uint8Array, JsValue> {
    let map: ColourMap = serde_wasm_bindgen::from_value(JsValue::from_str(name)).map_err(|_| {
        js_error(RideError::field(
            "colourMap",
            format!("'{name}' is not 'viridis', 'cividis' or 'diverging'"),
        ))
    })?;
    let mut rgb = Vec::with_capacity(3 * 256);
    for k in 0..=255u8 {
        let c = map.entry(k);
        rgb.extend([c.0, c.1, c.2]);
    }
    Ok(Uint8Array::from(rgb.as_slice()))
}

/// Contour lines of a map plane for the page's canvas, by the core's marching squares
/// (`maps::contour`, the one the exported charts draw: a node is above a level when
/// `f >= level`, cells with a non-finite corner are skipped). `field` is one plane of
/// `nx x ny` cell-centre values (row-major, Cs rows); returns one `Float64Array` per
/// level of segments `[x0, y0, x1, y1, ...]` in grid coordinates (cell `i` at `x = i`,
/// row `j` at `y = j`). Errors name `field`, `nx` or `level`.
#[wasm_bindgen(js_name = contourSegments)]
pub fn contour_segments_js(
    field: &[f64],
    nx: usize,
    ny: usize,
    levels: &[f64],
) -> Result<js_sys::Array, JsValue> {
    use crate::maps::{contour, Axis, Grid};
    // Axes 1..=n (an axis must be positive): a vertex at 1 + x is grid coordinate x.
    let axis = |name: &str, n: usize| Axis::new(name, 1.0, n as f64, n).map_err(js_error);
    let grid = Grid::new(axis("nx", nx)?, axis("ny", ny)?).map_err(js_error)?;
    let out = js_sys::Array::new();
    for &level in levels {
        let c = contour(&grid, field, level).map_err(js_error)?;
        let mut seg = Vec::new();
        for line in &c.polylines {
            for w in line.points.windows(2) {
                seg.extend([w[0][0] - 1.0, w[0][1] - 1.0, w[1][0] - 1.0, w[1][1] - 1.0]);
            }
        }
        out.push(&Float64Array::from(seg.as_slice()));
    }
    Ok(out)
}

/// The design objectives in mask-bit order, as a map's `broken` mask numbers them:
/// `[{bit, name, label, family}]` (`bit` the mask value `1 << b`, `name` as serialised,
/// `label` for messages, `family` "limit", "band" or "datum": see `Objective::family`).
#[wasm_bindgen]
pub fn objectives() -> Result<JsValue, JsValue> {
    use crate::maps::{objective_bit, objective_name, OBJECTIVE_BITS};
    #[derive(Serialize)]
    struct O {
        bit: u8,
        name: &'static str,
        label: &'static str,
        family: &'static str,
    }
    let v: Vec<O> = OBJECTIVE_BITS
        .iter()
        .map(|&o| O {
            bit: objective_bit(o),
            name: objective_name(o),
            label: o.label(),
            family: o.family(),
        })
        .collect();
    to_js(&v)
}

/// The ISO 8608 classes with `Gd(n0)` in m^3: `[{name, gd}]`.
#[wasm_bindgen(js_name = roadClasses)]
pub fn road_classes() -> Result<JsValue, JsValue> {
    #[derive(Serialize)]
    struct C {
        name: String,
        gd: f64,
    }
    let v: Vec<C> = RoadClass::ALL
        .iter()
        .map(|c| C {
            name: format!("{c:?}"),
            gd: c.gd_n0(),
        })
        .collect();
    to_js(&v)
}

/// Parses and validates a car file (as `ridelab --car FILE`: its `load_cases` too);
/// returns `{car, ks, cs, loadCases}` (`loadCases`: the file's load cases as a cases
/// file lists them, empty when it lists none) or an error naming the field.
#[wasm_bindgen(js_name = parseCar)]
pub fn parse_car(json: &str) -> Result<JsValue, JsValue> {
    #[derive(Serialize)]
    struct Parsed {
        car: Car,
        ks: f64,
        cs: f64,
        #[serde(rename = "loadCases")]
        load_cases: Vec<LoadCase>,
    }
    let file = CarFile::from_json(json).map_err(js_error)?;
    let car = file.car;
    let (ks, cs) = (car.front.spring, car.front.damper);
    let load_cases = file.load_cases;
    to_js(&Parsed {
        car,
        ks,
        cs,
        load_cases,
    })
}

/// The surrogate names the state's `surrogate` field takes (`ridelab surrogate` names).
#[wasm_bindgen]
pub fn surrogates() -> Result<JsValue, JsValue> {
    let names: Vec<String> = crate::surrogate::SurrogateSpec::all()
        .iter()
        .map(|s| s.name())
        .collect();
    to_js(&names)
}

/// The front damper law's force-velocity line, for the page's chart: `damper` is
/// `{bump, rebound, knee: {velocity, bump, rebound} | null}` (N s/m and m/s, as in
/// [`time_response_js`]'s options) and `v_max` the largest speed drawn either way, m/s.
/// Returns `{points: [[v, f]], linearRate}`: the law's corners and ends (m/s, N; `v > 0`
/// is rebound) and the equivalent linear rate `(bump + rebound) / 2` the maps use, N s/m.
/// Errors name the law's field (`bump`, `rebound`, `knee.velocity`, ...) or `vMax`.
#[wasm_bindgen(js_name = damperCurve)]
pub fn damper_curve_js(damper: JsValue, v_max: f64) -> Result<JsValue, JsValue> {
    use crate::time_domain::{Damper, MAX_KNEE_VELOCITY};
    #[derive(Serialize)]
    #[serde(rename_all = "camelCase")]
    struct Curve {
        points: Vec<(f64, f64)>,
        linear_rate: f64,
    }
    // Through JSON text: serde_json honours the law's deny_unknown_fields (a misspelt
    // key is refused, not dropped).
    let bad = |why: String| js_error_verbatim(RideError::field("damper", why));
    let text = js_sys::JSON::stringify(&damper)
        .ok()
        .and_then(|t| t.as_string())
        .ok_or_else(|| bad("must be an object {bump, rebound, knee}".into()))?;
    let law: Damper = serde_json::from_str(&text).map_err(|e| bad(e.to_string()))?;
    law.validate().map_err(js_error_verbatim)?;
    if !(v_max.is_finite() && v_max > 0.0 && v_max <= MAX_KNEE_VELOCITY) {
        return Err(js_error_verbatim(RideError::field(
            "vMax",
            format!("must be in (0, {MAX_KNEE_VELOCITY}] m/s (got {v_max})"),
        )));
    }
    to_js(&Curve {
        points: law.curve(v_max),
        linear_rate: law.linear_rate(),
    })
}
