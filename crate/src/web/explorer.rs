//! The page's session: `new Explorer(state)`, a JS class over [`Session`] that owns the
//! view's scenario, its fitted surrogate and the kept maps. The page moves it with
//! `setState(state)` (the session re-parses only what changed: on a slider move, the
//! design) and asks it; a setter that fails leaves it at its last good state. Its `tags`
//! say what each result belongs to (`describe` and `designStep` carry them).
//! Every method's numbers are [`Session`]'s, which the native tests check. A state is
//! checked here too (`checkState`, [`check_state`]): by the scenario a session would build.

use super::{js_error, parse_state, to_js};
use crate::analysis::ModelKind;
use crate::car::Car;
use crate::explorer::{Model, ModelMap, RoadResolver, Scenario, Session, State, Tags};
use crate::gpu::ComputePath;
use js_sys::{Float64Array, Object, Reflect, Uint8Array};
use serde::Serialize;
use wasm_bindgen::prelude::*;

/// The measured roads a session here can be on: the profiles `useRoad` registered on
/// this thread (the workers' module), none in the first-screen module, which leaves the
/// shaped routes out (the page sends a state on a measured road to its on-demand module).
pub(super) fn roads() -> Option<RoadResolver> {
    #[cfg(feature = "on-demand")]
    return Some(std::rc::Rc::new(super::road::resolve));
    #[cfg(not(feature = "on-demand"))]
    None
}

/// The scenario of `state`, its `roadProfile` resolved by [`roads`]; errors name the
/// field at fault.
pub(super) fn scenario_of(state: &State) -> crate::error::Result<Scenario> {
    match roads() {
        Some(r) => state.scenario_on(&r),
        None => state.scenario(),
    }
}

/// Checks a state; returns the normalised state or an error naming the field.
#[wasm_bindgen(js_name = checkState)]
pub fn check_state(state: JsValue) -> Result<JsValue, JsValue> {
    let s = parse_state(state)?;
    scenario_of(&s).map_err(js_error)?;
    to_js(&s)
}

/// The explorer session (see the module documentation).
#[wasm_bindgen]
pub struct Explorer(pub(super) Session);

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
    /// The robust cases' names ("<load case> / <class> at <speed> m/s"), case order;
    /// absent without cases.
    #[serde(skip_serializing_if = "Option::is_none")]
    cases: Option<Vec<String>>,
    /// Worst case or weighted mean, with cases.
    #[serde(skip_serializing_if = "Option::is_none")]
    combine: Option<crate::robust::Combine>,
    /// The measured road in place of the class (file, speed, tracks, band, filter
    /// error); absent on an ISO class.
    #[serde(skip_serializing_if = "Option::is_none")]
    measured_road: Option<crate::road::MeasuredRoad>,
    /// The session's tags (what the page keys its results by).
    tags: Tags,
}

/// A map as `{nx, ny, values: Float64Array, feasible: Uint8Array, broken: Uint8Array,
/// feasibleCount, datum: {bacc, dtl, sws}}` (`datum`: the map's datum criteria, m/s^2, N,
/// m; of a robust map the robust datum, case 0's): `values` the BAcc (m/s^2), DTL (N) and SWS (m) planes in that order,
/// each row-major with Cs slow (row 0 at the lowest Cs) and Ks fast, index
/// `c nx ny + j nx + i` at the cell centre `ks_i = ks_min + (i + 1/2) (ks_max - ks_min) / nx`;
/// `broken` the objectives each cell breaks as a bitmask (bit 0 SWS limit, 1 bounce band,
/// 2 damping band, 3..5 BAcc/DTL/SWS no worse than datum, 6 DTL margin, 7 travel).
fn map_js(m: &ModelMap) -> Result<JsValue, JsValue> {
    let out = Object::new();
    let set = |k: &str, v: JsValue| Reflect::set(&out, &k.into(), &v);
    set("nx", (m.grid().ks.n as f64).into())?;
    set("ny", (m.grid().cs.n as f64).into())?;
    let planes = m.planes();
    if planes.iter().any(|v| !v.is_finite()) {
        return Err(js_error(crate::error::RideError::Numerical(
            "internal: a map holds a value that is not finite; it is not drawn (please report this with the page's link)".into(),
        )));
    }
    set("values", Float64Array::from(planes.as_slice()).into())?;
    set("feasible", Uint8Array::from(m.feasible().as_slice()).into())?;
    set("broken", Uint8Array::from(m.broken()).into())?;
    set("feasibleCount", (m.dos.summary.feasible as f64).into())?;
    set("datum", to_js(&m.values.datum.criteria)?)?;
    Ok(out.into())
}

/// `"gpu"` or `"cpu"`: the path that made HiFi values, as the page names it.
pub(super) fn path_name(path: ComputePath) -> &'static str {
    match path {
        ComputePath::Gpu => "gpu",
        ComputePath::Cpu => "cpu",
    }
}

#[wasm_bindgen]
impl Explorer {
    /// A session on `state`; errors name the field at fault.
    #[wasm_bindgen(constructor)]
    pub fn new(state: JsValue) -> Result<Explorer, JsValue> {
        Session::with_roads(parse_state(state)?, roads())
            .map(Explorer)
            .map_err(js_error)
    }

    /// Moves to `state`, re-parsing only what changed (a custom car's file is read again
    /// only when it changes); the fit and the kept maps go when what they depend on does.
    #[wasm_bindgen(js_name = setState)]
    pub fn set_state(&mut self, state: JsValue) -> Result<(), JsValue> {
        self.0.set_state(parse_state(state)?).map_err(js_error)
    }

    /// The current state, normalised.
    pub fn state(&self) -> Result<JsValue, JsValue> {
        to_js(self.0.state())
    }

    /// What the page shows about the scenario besides the criteria: `{car, quarter,
    /// datumKs, datumCs, staticWheelLoad, road, velocityPsd, delay, designBox, swsLimit}`
    /// (N/m, N s/m, N, m^2/s^2/Hz, s, m), its `tags` ([`Explorer::tags`]), and with robust
    /// cases `cases` (their names) and `combine` ("worst" or "mean").
    pub fn describe(&self) -> Result<JsValue, JsValue> {
        let s = self.0.scenario();
        to_js(&Description {
            quarter: s.datum.quarter(),
            datum_ks: s.datum.front.spring,
            datum_cs: s.datum.front.damper,
            static_wheel_load: s.datum.front_wheel_load(),
            road: s.road,
            velocity_psd: s.road.velocity_psd(),
            delay: s.road.delay(s.datum.wheelbase()),
            design_box: s.dbox,
            sws_limit: s.objectives.sws_limit,
            cases: s
                .cases
                .as_ref()
                .map(|c| c.cases.iter().map(|k| k.name.clone()).collect()),
            combine: s.cases.as_ref().map(|c| c.combine),
            measured_road: s.measured.as_ref().map(|m| m.0.summary().clone()),
            car: s.datum.clone(),
            tags: self.0.tags(),
        })
    }

    /// The session's tags `{design, datum, fit, scenario}` ([`Tags`]): whole numbers, each
    /// a hash of the state fields one kind of result depends on (equal for equal states
    /// in every session), which the page keys its results by.
    pub fn tags(&self) -> Result<JsValue, JsValue> {
        to_js(&self.0.tags())
    }

    /// The full analysis report of the design by one model, `model` "lofi" or "hifi"
    /// ("quarter", "full" also read): the same report as `ridelab eval`.
    pub fn analyse(&self, model: &str) -> Result<JsValue, JsValue> {
        let kind = ModelKind::parse(model).map_err(js_error)?;
        to_js(&self.0.report(kind).map_err(js_error)?)
    }

    /// The readout of the design by one model (`model` as in `analyse`): the report's
    /// criteria, Wk-weighted comfort, modes and ride properties without its frequency-route
    /// check (about 0.1 ms for the full car against 1.9 ms): what a slider move shows.
    pub fn readout(&self, model: &str) -> Result<JsValue, JsValue> {
        let kind = ModelKind::parse(model).map_err(js_error)?;
        to_js(&self.0.readout(kind).map_err(js_error)?)
    }

    /// A slider step in one call (`Session::design_step`): `{lofi, surrogate, plane,
    /// hifi, tags}`, the design's LoFi report, surrogate criteria, criteria on the objective
    /// plane's model `plane` (null when that is "surrogate") and with `withHifi` its HiFi
    /// readout (null when it fails).
    #[wasm_bindgen(js_name = designStep)]
    pub fn design_step(&mut self, plane: &str, with_hifi: bool) -> Result<JsValue, JsValue> {
        let kind = Model::parse_among("model", plane, Model::CRITERIA).map_err(js_error)?;
        to_js(&self.0.design_step(kind, with_hifi).map_err(js_error)?)
    }

    /// The criteria `{bacc, dtl, sws}` (m/s^2, N, m) of the design by the fast
    /// evaluators the maps and optimisers use: `model` "lofi", "hifi" or "surrogate" (with
    /// Wk comfort the LoFi's and HiFi's `bacc` is Wk-weighted; the surrogate's never is),
    /// or with robust cases "robust": the LoFi's robust objective as the robust front's
    /// (one LoFi run per case; "lofi" and "hifi" stay the car as given).
    pub fn criteria(&mut self, model: &str) -> Result<JsValue, JsValue> {
        let kind = Model::parse_among("model", model, Model::CRITERIA).map_err(js_error)?;
        to_js(&self.0.criteria(kind).map_err(js_error)?)
    }

    /// The design's criteria as the LoFi or HiFi map (`model` "lofi" or "hifi") shows them
    /// at its point (m/s^2, N, m): the car's, or with robust cases the robust map's (with
    /// `case` K that case's), as `ridelab map --cases` computes the map's cells.
    #[wasm_bindgen(js_name = mapCriteria)]
    pub fn map_criteria(&mut self, model: &str) -> Result<JsValue, JsValue> {
        let kind = ModelKind::parse(model).map_err(js_error)?;
        to_js(&self.0.map_criteria(kind).map_err(js_error)?)
    }

    /// The map of one model on the `nx` x `ny` cell-centre grid of the design box (see
    /// `map_js` for the layout): `model` "lofi", "hifi", "surrogate" or "error" (the
    /// surrogate's signed relative error against the HiFi, `100 (S / HiFi - 1)` %, with the
    /// HiFi's objectives). A HiFi map costs about 3 us a cell: the page asks its worker.
    /// HiFi and error maps also carry `compute`, `"gpu"` or `"cpu"`: the path that made
    /// their HiFi values. With robust cases (the state's `cases`) the LoFi and HiFi maps
    /// are the robust maps of `ridelab map --cases` (or, with `case` K, that case's), and
    /// `model` "robust" is the robust front's problem on the LoFi (the plane's feasible
    /// set); the surrogate and error maps stay on the car as given.
    pub fn maps(&mut self, model: &str, nx: usize, ny: usize) -> Result<JsValue, JsValue> {
        let m = Model::parse_among("model", model, Model::MAP).map_err(js_error)?;
        let out = map_js(&self.0.map(m, nx, ny).map_err(js_error)?)?;
        if matches!(m, Model::HiFi | Model::SurrogateError) {
            if let Some(path) = self.0.hifi_path(nx, ny) {
                Reflect::set(&out, &"compute".into(), &path_name(path).into())?;
            }
        }
        Ok(out)
    }

    /// The Pareto front of comfort (the state's `comfort`: BAcc or Wk-weighted BAcc) and
    /// DTL on `model` ("lofi", the default, or "surrogate", which Wk comfort refuses naming
    /// `comfort`) by `method` ("stm", a 61 x 61 grid refined twice, or "nsga2", seeded,
    /// 60 x 60), its hypervolume, the pick of the state's `pick` rule and the pick re-checked
    /// on the HiFi model: `{study: {front, hypervolume, referencePoint, pick, evaluations,
    /// ..}, datum, datumHifi, recheck, comfort, pseudoWeights}` (`pseudoWeights[k]`: front
    /// point k's `[comfort, road holding]`). With robust cases it is refused naming
    /// `cases`: their front is `robustFront`'s (the workers' module). With no feasible
    /// design the error names the binding objective.
    pub fn front(&mut self, method: &str, model: Option<String>) -> Result<JsValue, JsValue> {
        let on = Model::parse_among(
            "frontModel",
            model.as_deref().unwrap_or("lofi"),
            Model::FRONT,
        )
        .map_err(js_error)?;
        to_js(&self.0.single_front(method, on).map_err(js_error)?)
    }

    /// The surrogate fits this session has made (one per scenario change that needs the
    /// surrogate; tests read it).
    #[wasm_bindgen(js_name = fitCount)]
    pub fn fit_count(&self) -> f64 {
        self.0.fit_count() as f64
    }

    /// The scenario's surrogate fit as bytes (`Uint8Array`; fitted here if not yet), for
    /// another thread's session to adopt (`offerFit`, the workers' module) instead of
    /// fitting again; undefined when the fit has no record. Errors name the field at
    /// fault.
    #[wasm_bindgen(js_name = fitRecord)]
    pub fn fit_record(&mut self) -> Result<Option<Vec<u8>>, JsValue> {
        let record = self.0.fit_record().map_err(js_error)?;
        record.map(|r| r.to_bytes()).transpose().map_err(js_error)
    }
}
