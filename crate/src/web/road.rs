//! A dropped road profile (issue #31): `describeRoad(bytes)` as `ridelab road FILE --json`,
//! and `designOnRoad(state, bytes, file)`, the state's design and datum on that road by
//! both models, each number as `ridelab eval --road FILE`. Errors are JS `Error`s whose
//! `field` is `road` (the message names the file's column and row) or `speed`.

use super::{js_error, parse_state, to_js};
use crate::error::RideError;
use crate::road::Tracks;
use crate::road_profile::{describe, road_error, DesignOnRoad, Profile, ProfileTracks};
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
    let scenario = parse_state(state)?.scenario().map_err(js_error)?;
    let p = profile(bytes)?;
    let tracks = match (p.tracks(), scenario.road.tracks) {
        (2, _) => ProfileTracks::Measured,
        (_, Tracks::Correlated) => ProfileTracks::Correlated,
        (_, Tracks::Independent) => ProfileTracks::Independent,
    };
    let q = scenario.design.quarter();
    let on = DesignOnRoad::compute(
        &scenario.datum,
        q.ks,
        q.cs,
        &p,
        file,
        scenario.road.speed,
        tracks,
    )
    .map_err(road_js_error)?;
    to_js(&on)
}
