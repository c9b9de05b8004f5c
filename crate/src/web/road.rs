//! A dropped road profile (issue #31): `describeRoad(bytes)` as `ridelab road FILE --json`;
//! `designOnRoad(state, bytes, file)`, the state's design and datum on that road by both
//! models, each number as `ridelab eval --road FILE`; `roadMap` and `roadFront`, the maps
//! and the Pareto front on that road as `ridelab map --road FILE` and `ridelab optimize
//! --road FILE` compute them. Errors are JS `Error`s whose `field` is `road` (the message
//! names the file's column and row), `speed`, or the state's or call's field at fault.

use super::{js_error, parse_state, to_js};
use crate::analysis::ModelKind;
use crate::error::{parse_choice, RideError};
use crate::explorer::Scenario;
use crate::explorer::{OnRoad, RoadSource};
use crate::maps::{Grid, Scale};
use crate::optimize::{Method, PickRule};
use crate::road::{Road, Tracks};
use crate::road_profile::{
    describe, road_error, DesignOnRoad, MeasuredModel, MeasuredRoad, Profile, ProfileTracks,
    ShapedRoad,
};
use crate::study::measured::{measured_map, optimize_measured};
use crate::study::{EvaluatorSpec, MapRequest, MapSettings, OptimizeRequest};
use js_sys::{Float64Array, Object, Reflect, Uint8Array};
use std::cell::RefCell;
use std::hash::{Hash, Hasher};
use wasm_bindgen::prelude::*;

/// `e` as a JS error whose `field` is `road` or `speed` (the page's two fields for it).
fn road_js_error(e: RideError) -> JsValue {
    let err = js_error(e.clone());
    let field = match &e {
        RideError::Field { field, .. } if field == "speed" => "speed",
        _ => "road",
    };
    let _ = js_sys::Reflect::set(&err, &"field".into(), &field.into());
    err
}

fn profile(bytes: &[u8]) -> Result<Profile, JsValue> {
    Profile::from_csv_bytes(bytes).map_err(|e| road_js_error(road_error(e)))
}

/// The profile file's bytes described: the Welch PSD, the ISO 8608 fit (class, `gd_n0`
/// m^3, waviness), the band means and, with two tracks, their coherence
/// ([`crate::road_profile::RoadDescription`], field names as the CLI's JSON).
#[wasm_bindgen(js_name = describeRoad)]
pub fn describe_road(bytes: &[u8]) -> Result<JsValue, JsValue> {
    let d = describe(&profile(bytes)?).map_err(|e| road_js_error(road_error(e)))?;
    to_js(&d).inspect_err(|e| {
        let _ = js_sys::Reflect::set(e, &"field".into(), &"road".into());
    })
}

/// The state's design and its datum on the profile (named `file`) at the state's speed,
/// by the quarter and the full car ([`DesignOnRoad`]). One track drives both wheels as the
/// state's `tracks` says (as `ridelab eval --road FILE --tracks ...`); two tracks keep
/// their measured coherence (the CLI's default for them).
#[wasm_bindgen(js_name = designOnRoad)]
pub fn design_on_road(state: JsValue, bytes: &[u8], file: &str) -> Result<JsValue, JsValue> {
    let scenario = panel_scenario(state)?;
    let (road, tracks) = shaped(bytes, file, &scenario)?;
    let q = scenario.design.quarter();
    let on = DesignOnRoad::on_shaped(&scenario.datum, q.ks, q.cs, &road, file, tracks)
        .map_err(road_js_error)?;
    to_js(&on)
}

/// The scenario of `state` for the road panel, which judges the dropped file itself: the
/// state's own road choice (`roadProfile`, the road menu's) is not used.
fn panel_scenario(state: JsValue) -> Result<Scenario, JsValue> {
    let mut s = parse_state(state)?;
    s.road_profile = None;
    s.scenario().map_err(js_error)
}

/// The profile `bytes` (named `file`) shaped at the scenario's speed with its tracks, by
/// the profiles and roads this thread keeps ([`use_road`], [`resolve`]: the panel's map,
/// front and judgement ask for the same road in a row, and shaping it costs more than a
/// map's runs on a short profile); errors name `road` or `speed`.
fn shaped(
    bytes: &[u8],
    file: &str,
    scenario: &Scenario,
) -> Result<(ShapedRoad, ProfileTracks), JsValue> {
    let key = use_road(bytes, file)?;
    let on = kept_road(&key, scenario.road.speed, scenario.road.tracks).map_err(road_js_error)?;
    Ok((on.road().clone(), on.tracks()))
}

/// `"lofi"` or `"quarter"` (the quarter car), `"hifi"` or `"full"` (the full car); errors
/// name `model`.
fn model_kind(model: &str) -> Result<ModelKind, JsValue> {
    parse_choice("model", model).map_err(js_error)
}

/// The maps of `model` ("lofi" or "hifi") on the profile (named `file`) at the state's
/// speed and tracks over the `nx` x `ny` cell-centre grid of the state's design box, with
/// the state's design objectives and comfort measure: `{nx, ny, values, feasible, broken,
/// feasibleCount, datum, ksValues, csValues, road, designBox, datumKs, datumCs, swsLimit}` (the
/// page's map data, the planes BAcc m/s^2 | DTL N | SWS m row-major with Cs rows, `datum`
/// the datum design's criteria; `road` what the CLI's JSON says of it),
/// each value as `ridelab map --road FILE` computes it on that grid. The grid is bounded
/// by [`crate::budget::MAX_MEASURED_RUNS`] points (errors name `nx`).
#[wasm_bindgen(js_name = roadMap)]
pub fn road_map(
    state: JsValue,
    bytes: &[u8],
    file: &str,
    model: &str,
    nx: usize,
    ny: usize,
) -> Result<JsValue, JsValue> {
    let kind = model_kind(model)?;
    let scenario = panel_scenario(state)?;
    let grid = Grid::cells(&scenario.dbox, nx, ny).map_err(js_error)?;
    crate::budget::check_measured(
        (nx as u64) * (ny as u64),
        "nx",
        &format!("a {nx} x {ny} map"),
        "the map's cells",
    )
    .map_err(js_error)?;
    let (road, tracks) = shaped(bytes, file, &scenario)?;
    let settings = MapSettings {
        grid,
        scale: Scale::Absolute,
        objectives: scenario.objectives.clone(),
        contour_levels: 0,
        comfort: scenario.comfort,
    };
    // The ISO road is only recorded: the measured one replaces it.
    let iso = Road::default();
    let request = MapRequest::new(kind, &scenario.datum, &iso, settings);
    let r = measured_map(&request, &road, file, tracks).map_err(road_js_error)?;
    crate::finite::check(&r).map_err(js_error)?;
    let planes: Vec<f64> = [&r.bacc, &r.dtl, &r.sws]
        .into_iter()
        .flatten()
        .copied()
        .collect();
    let feasible: Vec<u8> = r
        .feasibility
        .mask
        .iter()
        .map(|&m| u8::from(m == 0))
        .collect();
    let out = Object::new();
    let set = |k: &str, v: JsValue| Reflect::set(&out, &k.into(), &v);
    set("nx", (nx as f64).into())?;
    set("ny", (ny as f64).into())?;
    set("values", Float64Array::from(planes.as_slice()).into())?;
    set("feasible", Uint8Array::from(feasible.as_slice()).into())?;
    set(
        "broken",
        Uint8Array::from(r.feasibility.mask.as_slice()).into(),
    )?;
    set(
        "feasibleCount",
        (r.feasibility.summary.feasible as f64).into(),
    )?;
    set("datum", to_js(&r.datum.criteria)?)?;
    set(
        "ksValues",
        Float64Array::from(r.ks_values.as_slice()).into(),
    )?;
    set(
        "csValues",
        Float64Array::from(r.cs_values.as_slice()).into(),
    )?;
    set("road", to_js(&r.road)?)?;
    set("designBox", to_js(&scenario.dbox)?)?;
    set("datumKs", r.datum.ks.into())?;
    set("datumCs", r.datum.cs.into())?;
    set(
        "swsLimit",
        scenario
            .objectives
            .sws_limit
            .map_or(JsValue::NULL, JsValue::from),
    )?;
    Ok(out.into())
}

/// The Pareto front of comfort (the state's measure) and DTL on `model` ("lofi" or
/// "hifi") on the profile (named `file`) at the state's speed and tracks, by STM with the
/// objective plane's settings (a 61-point grid refined twice: 4 591 runs on the shipped
/// slab road, a tenth of `ridelab optimize`'s default, so the heavy worker is free again
/// in under 0.3 s even with the Wk-weighted comfort) over the state's design box with its objectives, the
/// pick by the state's rule and re-checked on the full car there: the JSON of `ridelab
/// optimize --road FILE --evaluator quarter|full --grid 61 --levels 2` (its `road`
/// included).
#[wasm_bindgen(js_name = roadFront)]
pub fn road_front(
    state: JsValue,
    bytes: &[u8],
    file: &str,
    model: &str,
) -> Result<JsValue, JsValue> {
    let kind = model_kind(model)?;
    let scenario = panel_scenario(state)?;
    let method = crate::explorer::studies::method("stm").map_err(js_error)?;
    if let Method::Stm(stm) = &method {
        crate::budget::check_measured(
            crate::budget::stm_runs(stm.grid, stm.levels),
            "grid",
            "the front",
            "the front's grid",
        )
        .map_err(js_error)?;
    }
    let (road, tracks) = shaped(bytes, file, &scenario)?;
    let car = &scenario.datum;
    let hifi =
        MeasuredModel::new(ModelKind::Full, car, road.clone()).with_comfort(scenario.comfort);
    // The request's ISO road is not used: the models are on the measured one.
    let unused = Road::default();
    let request = OptimizeRequest {
        evaluator: EvaluatorSpec::Model(kind),
        comfort: scenario.comfort,
        ..OptimizeRequest::new(
            car,
            &unused,
            scenario.dbox,
            method,
            scenario.objectives.clone(),
        )
    };
    let (mut out, _) = optimize_measured(&request, &hifi, None).map_err(road_js_error)?;
    if scenario.pick != PickRule::MinMax {
        out.repick_on(scenario.pick, &hifi, &scenario.dbox)
            .map_err(js_error)?;
    }
    crate::finite::check(&out).map_err(js_error)?;
    let v = to_js(&out)?;
    Reflect::set(
        &v,
        &"road".into(),
        &to_js(&MeasuredRoad::of(file, &road, tracks))?,
    )?;
    Ok(v)
}

/// Most profiles a thread keeps for the road panel and the road menu (each at most
/// [`crate::road_profile::MAX_BYTES`] as a file): the newest replace the oldest.
const KEPT_PROFILES: usize = 4;

/// Most shaped roads a thread keeps for the road panel and the road menu (a profile at a
/// few speeds).
const KEPT_ROADS: usize = 8;

/// A profile registered by [`use_road`].
#[derive(Clone)]
struct KeptProfile {
    /// `"<file>#<content>"`, the state's `roadProfile`.
    key: String,
    file: String,
    /// A hash of the file's bytes ([`content_hash`]).
    content: u64,
    profile: std::sync::Arc<Profile>,
}

thread_local! {
    /// The profiles `useRoad` registered on this thread, oldest first.
    static PROFILES: RefCell<Vec<KeptProfile>> = const { RefCell::new(Vec::new()) };
    /// The roads the session asked for, oldest first, by [`OnRoad`]'s key.
    static ROADS: RefCell<Vec<std::sync::Arc<OnRoad>>> = const { RefCell::new(Vec::new()) };
}

/// A hash of a profile file's bytes (two files of one name are two roads).
fn content_hash(bytes: &[u8]) -> u64 {
    let mut h = std::collections::hash_map::DefaultHasher::new();
    bytes.hash(&mut h);
    h.finish()
}

/// Registers the profile `bytes` (named `file`) for the road panel and menu on this thread and
/// returns its key, `"<file>#<hash>"`: a state whose `roadProfile` is that key is on the
/// profile (shaped at the state's speed with its tracks) in place of its ISO class. The
/// page registers a road on each of its threads. Errors name `road` (the column and row).
#[wasm_bindgen(js_name = useRoad)]
pub fn use_road(bytes: &[u8], file: &str) -> Result<String, JsValue> {
    let content = content_hash(bytes);
    let key = format!("{file}#{content:016x}");
    let known = PROFILES.with_borrow(|p| p.iter().any(|k| k.key == key));
    if !known {
        let kept = KeptProfile {
            key: key.clone(),
            file: file.to_string(),
            content,
            profile: std::sync::Arc::new(profile(bytes)?),
        };
        PROFILES.with_borrow_mut(|all| {
            if all.len() >= KEPT_PROFILES {
                all.remove(0);
            }
            all.push(kept);
        });
    }
    Ok(key)
}

/// The session's road resolver ([`crate::explorer::RoadResolver`]): [`kept_road`].
pub(super) fn resolve(
    key: &str,
    speed: f64,
    tracks: Tracks,
) -> crate::error::Result<std::sync::Arc<dyn RoadSource>> {
    Ok(kept_road(key, speed, tracks)?)
}

/// The registered profile `key` shaped at `speed` with the page's `tracks`, kept for the
/// next ask; errors name `road` (a key not registered here, or what the speed needs of
/// the file) or `speed`.
fn kept_road(
    key: &str,
    speed: f64,
    tracks: Tracks,
) -> crate::error::Result<std::sync::Arc<OnRoad>> {
    let Some(kept) = PROFILES.with_borrow(|kept| kept.iter().find(|k| k.key == key).cloned())
    else {
        return Err(RideError::field(
            "road",
            format!("the measured road '{key}' is not loaded on this thread: drop its file on the Car & road tab again"),
        ));
    };
    let t = ProfileTracks::on_page(&kept.profile, tracks);
    let want = OnRoad::key_of(&kept.file, kept.content, speed, t);
    if let Some(r) = ROADS.with_borrow(|roads| roads.iter().find(|r| r.key() == want).cloned()) {
        return Ok(r);
    }
    crate::domain::SPEED.check("speed", speed)?;
    let road = ShapedRoad::from_profile(&kept.profile, speed, t).map_err(road_error)?;
    let on = std::sync::Arc::new(OnRoad::new(&kept.file, kept.content, kept.profile, road, t));
    ROADS.with_borrow_mut(|roads| {
        if roads.len() >= KEPT_ROADS {
            roads.remove(0);
        }
        roads.push(on.clone());
    });
    Ok(on)
}
