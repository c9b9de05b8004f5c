//! The browser shell (wasm32 only): a thin JS API over the core, exported with
//! wasm-bindgen. Every entry returns `Result<_, JsValue>`; an error is a JS `Error`
//! whose message is the core's [`RideError`] text and whose `field` property names the
//! state field at fault (`"speed"`, `"ks"`, `"car"`, ...), so the page can show it
//! next to that field. Nothing here panics on bad input, and nothing touches the DOM:
//! the same module runs in a Web Worker.
//!
//! State objects (see [`State`]) are plain JS objects in SI units:
//! `{car, carJson?, ks, cs, class, speed, tracks, ksMin?, ksMax?, csMin?, csMax?, swsLimit?,
//! bounceBand?, dampingBand?, noWorse?, surrogate?, plan?}`. The logic behind every entry
//! is in [`crate::explorer`].

mod charts;
#[cfg(feature = "gpu")]
mod gpu;
mod screen;
pub use charts::{line_chart_svg_js, map_chart_svg_js};
#[cfg(feature = "gpu")]
pub use gpu::GpuMaps;
pub use screen::{draw_line_chart_js, draw_map_frame_js};

use crate::analysis::ModelKind;
use crate::car::{Car, PRESETS};
use crate::chart::ColourMap;
use crate::error::RideError;
use crate::explorer::{
    ui_field, EvaluatorKind, FrontModel, MapModel, ModelMap, Session, State, STATE_FIELDS,
};
use crate::road::RoadClass;
use js_sys::{Float64Array, Object, Reflect, Uint8Array};
use serde::Serialize;
use std::cell::RefCell;
use wasm_bindgen::prelude::*;

/// Converts a core error to a JS `Error` with a `field` property.
fn js_error(e: RideError) -> JsValue {
    let field = match &e {
        RideError::Field { field, .. } | RideError::Infeasible { field, .. } => ui_field(field),
        // The only JSON the core parses is a car file.
        RideError::Json(_) => "car".into(),
        _ => String::new(),
    };
    let err = js_sys::Error::new(&e.to_string());
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

fn to_js<T: Serialize>(v: &T) -> Result<JsValue, JsValue> {
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

thread_local! {
    /// The session behind the state-taking functions below: each call moves it to the
    /// call's state (re-parsing only what changed) and asks it. The page's own
    /// [`Explorer`] objects are sessions of their own.
    static SESSION: RefCell<Option<Session>> = const { RefCell::new(None) };
}

/// Runs `f` on the thread's session moved to `state`.
fn with_session<T>(
    state: JsValue,
    f: impl FnOnce(&mut Session) -> crate::error::Result<T>,
) -> Result<T, JsValue> {
    let state = parse_state(state)?;
    SESSION.with_borrow_mut(|slot| {
        match slot {
            Some(s) => s.set_state(state).map_err(js_error)?,
            None => *slot = Some(Session::new(state).map_err(js_error)?),
        }
        // Just set.
        let s = slot
            .as_mut()
            .ok_or_else(|| state_error("no session".into()))?;
        f(s).map_err(js_error)
    })
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

/// Parses and validates a car file; returns `{car, ks, cs}` or an error naming the field.
#[wasm_bindgen(js_name = parseCar)]
pub fn parse_car(json: &str) -> Result<JsValue, JsValue> {
    #[derive(Serialize)]
    struct Parsed {
        car: Car,
        ks: f64,
        cs: f64,
    }
    let car = Car::from_json(json).map_err(js_error)?;
    let (ks, cs) = (car.front.spring, car.front.damper);
    to_js(&Parsed { car, ks, cs })
}

/// Checks a state; returns the normalised state or an error naming the field.
#[wasm_bindgen(js_name = checkState)]
pub fn check_state(state: JsValue) -> Result<JsValue, JsValue> {
    let s = parse_state(state)?;
    s.scenario().map_err(js_error)?;
    to_js(&s)
}

#[derive(Serialize)]
#[serde(rename_all = "camelCase")]
struct Description {
    car: Car,
    quarter: crate::car::QuarterCar,
    datum_ks: f64,
    datum_cs: f64,
    static_wheel_load: f64,
    road: crate::road::Road,
    velocity_psd: f64,
    delay: f64,
    design_box: crate::design::DesignBox,
    sws_limit: Option<f64>,
}

fn description(s: &Session) -> Description {
    let s = s.scenario();
    Description {
        quarter: s.datum.quarter(),
        datum_ks: s.datum.front.spring,
        datum_cs: s.datum.front.damper,
        static_wheel_load: s.datum.front_wheel_load(),
        road: s.road,
        velocity_psd: s.road.velocity_psd(),
        delay: s.road.delay(s.datum.wheelbase()),
        design_box: s.dbox,
        sws_limit: s.objectives.sws_limit,
        car: s.datum.clone(),
    }
}

/// What the page shows about the scenario besides the criteria: the datum car, its
/// quarter car, the datum design `{ks, cs}`, the static front wheel load (N), the road
/// velocity PSD (m^2/s^2/Hz) and the design box.
#[wasm_bindgen]
pub fn describe(state: JsValue) -> Result<JsValue, JsValue> {
    to_js(&with_session(state, |s| Ok(description(s)))?)
}

/// The full analysis report of the state's design by one model: `model` is
/// "quarter" (LoFi) or "full" (HiFi). The same report as `ridelab eval`.
#[wasm_bindgen]
pub fn analyse(state: JsValue, model: &str) -> Result<JsValue, JsValue> {
    let kind = ModelKind::parse(model).map_err(js_error)?;
    to_js(&with_session(state, |s| s.report(kind))?)
}

/// Both reports of the state's design: `{lofi, hifi}` (see [`analyse`]).
#[wasm_bindgen]
pub fn evaluate(state: JsValue) -> Result<JsValue, JsValue> {
    let (lofi, hifi) = with_session(state, |s| {
        Ok((s.report(ModelKind::Quarter)?, s.report(ModelKind::Full)?))
    })?;
    let out = Object::new();
    Reflect::set(&out, &"lofi".into(), &to_js(&lofi)?)?;
    Reflect::set(&out, &"hifi".into(), &to_js(&hifi)?)?;
    Ok(out.into())
}

/// The criteria `{bacc, dtl, sws}` of the state's design by the fast evaluators the
/// maps and optimisers use (`model`: "quarter", "full" or "surrogate", the state's
/// surrogate).
#[wasm_bindgen]
pub fn criteria(state: JsValue, model: &str) -> Result<JsValue, JsValue> {
    let kind = EvaluatorKind::parse(model).map_err(js_error)?;
    to_js(&with_session(state, |s| s.criteria(kind))?)
}

/// The three LoFi criteria over an `nx` x `ny` grid of cell centres of the design box,
/// as one `Float64Array` of `3 nx ny` values: BAcc (m/s^2), DTL (N), SWS (m) planes in
/// that order, each row-major with Cs slow (row 0 at the lowest Cs) and Ks fast:
/// index `c nx ny + j nx + i`, `ks_i = ks_min + (i + 1/2) (ks_max - ks_min) / nx`.
#[wasm_bindgen(js_name = lofiMap)]
pub fn lofi_map_js(state: JsValue, nx: usize, ny: usize) -> Result<Float64Array, JsValue> {
    let m = with_session(state, |s| s.map(MapModel::LoFi, nx, ny))?;
    Ok(Float64Array::from(m.planes().as_slice()))
}

/// A map as `{nx, ny, values: Float64Array, feasible: Uint8Array, broken: Uint8Array,
/// feasibleCount}` (`broken`: the objectives each cell breaks as a bitmask, bit 0 SWS
/// limit, 1 bounce band, 2 damping band, 3..5 BAcc/DTL/SWS no worse than datum).
fn map_js(m: &ModelMap) -> Result<JsValue, JsValue> {
    let out = Object::new();
    Reflect::set(&out, &"nx".into(), &(m.grid().ks.n as f64).into())?;
    Reflect::set(&out, &"ny".into(), &(m.grid().cs.n as f64).into())?;
    Reflect::set(
        &out,
        &"values".into(),
        &Float64Array::from(m.planes().as_slice()).into(),
    )?;
    Reflect::set(
        &out,
        &"feasible".into(),
        &Uint8Array::from(m.feasible().as_slice()).into(),
    )?;
    Reflect::set(&out, &"broken".into(), &Uint8Array::from(m.broken()).into())?;
    Reflect::set(
        &out,
        &"feasibleCount".into(),
        &(m.dos.summary.feasible as f64).into(),
    )?;
    Ok(out.into())
}

/// [`lofi_map_js`] plus the design objectives (see [`map_js`]).
#[wasm_bindgen(js_name = lofiMaps)]
pub fn lofi_maps_js(state: JsValue, nx: usize, ny: usize) -> Result<JsValue, JsValue> {
    map_js(&with_session(state, |s| s.map(MapModel::LoFi, nx, ny))?)
}

/// The map of one model (same layout as [`lofi_maps_js`]): `model` is "lofi", "hifi",
/// "surrogate" (the state's surrogate) or "error" (the surrogate's signed relative error
/// against the HiFi, `100 (S / HiFi - 1)` %, with the HiFi's objectives). The HiFi and
/// error maps cost about 30 us a cell: the page asks the worker for them.
#[wasm_bindgen(js_name = modelMaps)]
pub fn model_maps_js(
    state: JsValue,
    model: &str,
    nx: usize,
    ny: usize,
) -> Result<JsValue, JsValue> {
    let m = MapModel::parse(model).map_err(js_error)?;
    map_js(&with_session(state, |s| s.map(m, nx, ny))?)
}

/// The state's surrogate fitted to HiFi samples over its design box and validated on
/// a `levels x levels` HiFi grid: the `ridelab surrogate` report (samples, tuning,
/// diagnostics, metrics, error map, predictions).
#[wasm_bindgen(js_name = surrogateFit)]
pub fn surrogate_fit_js(state: JsValue, levels: usize) -> Result<JsValue, JsValue> {
    to_js(&with_session(state, |s| s.fit_report(levels))?)
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

/// The Pareto front of BAcc and DTL on `model` ("lofi", the default, or "surrogate")
/// by `method` ("stm", a 61 x 61 grid refined twice, or "nsga2", seeded, 60 x 60), its
/// hypervolume, the min-max pick and the pick re-checked on the HiFi model:
/// `{study: {front, hypervolume, referencePoint, pick, evaluations, ..}, datum,
/// datumHifi, recheck}`. With no feasible design the error names the binding objective.
#[wasm_bindgen]
pub fn front(state: JsValue, method: &str, model: Option<String>) -> Result<JsValue, JsValue> {
    let on = FrontModel::parse(model.as_deref().unwrap_or("lofi")).map_err(js_error)?;
    to_js(&with_session(state, |s| s.front(method, on))?)
}

/// |H| from road displacement and the output PSDs of the design by both models at
/// `nfreq` log-spaced frequencies from 0.1 to 100 Hz: `{f, lofi: {frf, psd}, hifi}`,
/// each `[bacc, dtl, sws]` (1/s^2, N/m, m/m; (m/s^2)^2/Hz, N^2/Hz, m^2/Hz).
#[wasm_bindgen(js_name = spectra)]
pub fn spectra_js(state: JsValue, nfreq: usize) -> Result<JsValue, JsValue> {
    to_js(&with_session(state, |s| s.spectra(nfreq))?)
}

/// Seeded time responses of the design by both models: `options` is
/// `{duration, dt, seed, f_min, f_max, damper: {bump, rebound, knee: {velocity, bump,
/// rebound} | null} | null, decimate}` (s, s, -, Hz, Hz, N s/m and m/s, -; missing fields
/// take the core defaults). With a damper law the run's Cs is its equivalent linear rate
/// `(bump + rebound) / 2`, as in `ridelab simulate --bump --rebound`. Returns
/// `{damper, damperRate, lofi, hifi, a, b}` with `{t, road, outputs, positions,
/// accelerations, rms, damper_rate, equivalent_rate}` per model.
#[wasm_bindgen(js_name = timeResponse)]
pub fn time_response_js(state: JsValue, options: JsValue) -> Result<JsValue, JsValue> {
    let opt: crate::time_domain::TimeOptions = serde_wasm_bindgen::from_value(options)
        .map_err(|e| state_error(format!("time options: {e}")))?;
    to_js(&with_session(state, |s| s.time_response(&opt))?)
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

/// The page's "next HiFi run" (issue #15): `new AdaptiveRun(state, options?)` runs the
/// state's plan on the HiFi and fits its surrogate. Then `propose()` says where the next
/// HiFi run would go and why: `{candidate: {ks, cs, on_front, predicted, relative_std,
/// ehvi, probability_feasible, value, distance}, reason}`. `step()` runs it, refits and
/// returns `{added, step: {hifi_runs, front_points, hypervolume, pick}, recheck}`.
/// `report()` is the loop so far (samples in order with reasons, the `history` of
/// hypervolume and pick per HiFi run, as `ridelab surrogate ... --adaptive K` gives it),
/// `front()` the surrogate's front and `uncertaintyMap(nx, ny)` the estimate, %, in the
/// maps' layout. `options` (optional, the CLI's names): `{criterion: "ehvi-front" |
/// "ehvi", uncertainty: "model" | "loo", candidates, min_distance, seed}`.
#[wasm_bindgen(js_name = AdaptiveRun)]
pub struct AdaptiveRun(crate::explorer::PageLoop);

#[wasm_bindgen(js_class = AdaptiveRun)]
impl AdaptiveRun {
    /// The loop on `state`'s scenario; errors name the field.
    #[wasm_bindgen(constructor)]
    pub fn new(state: JsValue, options: JsValue) -> Result<AdaptiveRun, JsValue> {
        let scenario = parse_state(state)?.scenario().map_err(js_error)?;
        let options: crate::surrogate::adaptive::AdaptiveOptions =
            if options.is_undefined() || options.is_null() {
                Default::default()
            } else {
                serde_wasm_bindgen::from_value(options)
                    .map_err(|e| js_error(RideError::field("adaptive", e.to_string())))?
            };
        crate::explorer::PageLoop::new(&scenario, options)
            .map(AdaptiveRun)
            .map_err(js_error)
    }

    /// Where the next HiFi run would go, and why.
    pub fn propose(&self) -> Result<JsValue, JsValue> {
        to_js(&self.0.propose().map_err(js_error)?)
    }

    /// Runs the HiFi at the proposal, refits, re-checks the new pick on the HiFi.
    pub fn step(&mut self) -> Result<JsValue, JsValue> {
        to_js(&self.0.step().map_err(js_error)?)
    }

    /// The loop so far.
    pub fn report(&self) -> Result<JsValue, JsValue> {
        to_js(&self.0.report())
    }

    /// The surrogate's current feasible front.
    pub fn front(&self) -> Result<JsValue, JsValue> {
        to_js(&self.0.front())
    }

    /// The uncertainty estimate, %, at `nx` x `ny` cell centres: three planes (BAcc,
    /// DTL, SWS), index `k nx ny + j nx + i`.
    #[wasm_bindgen(js_name = uncertaintyMap)]
    pub fn uncertainty_map(&self, nx: usize, ny: usize) -> Result<Float64Array, JsValue> {
        let m = self.0.uncertainty_map(nx, ny).map_err(js_error)?;
        Ok(Float64Array::from(m.as_slice()))
    }
}

/// The study report of the view's scenario (as `ridelab report`, seed 1, the view's
/// surrogate and plan): `{title, html, markdown}`, the HTML one self-contained file.
/// Takes seconds: the page calls it in its worker.
#[wasm_bindgen(js_name = studyReport)]
pub fn study_report_js(state: JsValue) -> Result<JsValue, JsValue> {
    let report = with_session(state, |s| s.study_report())?;
    let docs = report.documents().map_err(js_error)?;
    to_js(&serde_json::json!({
        "title": report.title(),
        "html": docs.html,
        "markdown": docs.markdown,
    }))
}
