//! SVG export of the page's charts (the spec readers are shared with `web::screen`): `lineChartSvg(spec)` and `mapChartSvg(spec)` take a
//! plain JS object (a [`LineChart`] or [`MapChart`] spec, camelCase keys) and return the
//! SVG document as a string, or throw a JS `Error` whose `field` names the spec field at
//! fault (`series[1].points[7]`, `values`, an unknown key's own path such as `xlabel`;
//! `spec` for the object as a whole).
//!
//! **Main thread only.** On wasm32, plotters 0.3.7 measures text through the DOM
//! (`style/font/web.rs`: `window().unwrap().document().unwrap().body().unwrap()`, then a
//! `<span>` is appended to the body, measured and removed). Without a window (a Web
//! Worker), a document or a body, or in a document where a new `<span>` is not an HTML
//! element, those `unwrap`s would panic, and a panic aborts the module. So every entry
//! checks all of that first ([`text_measurable`]) and throws an error instead; the worker
//! must not list these methods.

use crate::chart::MapChart;
use crate::error::RideError;
use js_sys::{Array, ArrayBuffer, Float64Array, Object, Reflect};
use serde::de::DeserializeOwned;
use wasm_bindgen::prelude::*;
use wasm_bindgen::JsCast;

/// A chart error as a JS `Error` with `field` set to the spec field (the core's field
/// path verbatim: these are not state fields, so the state's field mapping does not apply).
pub(super) fn chart_error(e: RideError) -> JsValue {
    let field = match &e {
        RideError::Field { field, .. } => field.clone(),
        _ => String::new(),
    };
    let err = js_sys::Error::new(&e.to_string());
    // Setting a property on a fresh Error object cannot fail.
    let _ = Reflect::set(&err, &"field".into(), &field.into());
    err.into()
}

/// Refuses keys of the object `value` (at `path`, "" for the spec) not in `allowed`:
/// serde-wasm-bindgen reads only the keys a struct knows, so a misspelt optional key
/// would be dropped without a word. Non-objects are left to serde.
pub(super) fn check_keys(value: &JsValue, path: &str, allowed: &[&str]) -> Result<(), JsValue> {
    if Array::is_array(value) || ArrayBuffer::is_view(value) {
        return Ok(());
    }
    let Some(obj) = value.dyn_ref::<Object>() else {
        return Ok(());
    };
    for key in Object::keys(obj).iter() {
        let key = key.as_string().unwrap_or_default();
        if !allowed.contains(&key.as_str()) {
            let field = if path.is_empty() {
                key.clone()
            } else {
                format!("{path}.{key}")
            };
            return Err(chart_error(RideError::field(
                field,
                format!(
                    "unknown field `{key}`, expected one of {}",
                    allowed.join(", ")
                ),
            )));
        }
    }
    Ok(())
}

/// [`check_keys`] on each object of the array at `value[key]`, as `key[k]`.
pub(super) fn check_items(value: &JsValue, key: &str, allowed: &[&str]) -> Result<(), JsValue> {
    let items = Reflect::get(value, &key.into()).unwrap_or(JsValue::UNDEFINED);
    if let Some(items) = items.dyn_ref::<Array>() {
        for (k, item) in items.iter().enumerate() {
            check_keys(&item, &format!("{key}[{k}]"), allowed)?;
        }
    }
    Ok(())
}

/// Reads a spec; a bad value is reported at its path (`width`, `series[0].size`).
///
/// serde-wasm-bindgen's errors carry no path. Rather than track one on every read
/// (serde_path_to_error, which compiles each spec type's reader a second time: 5.6 KB of
/// the first-screen module gzipped, about 28 ms on a slow school network, issue #29),
/// a failed read is located afterwards by [`locate`], which reads the spec again without
/// one key at a time (the same reader: nothing more is compiled). Unknown keys are
/// refused before the read ([`check_keys`]), colours and values after it (the charts'
/// `layout`), each with its own path.
pub(super) fn read_spec<T: DeserializeOwned>(spec: JsValue) -> Result<T, JsValue> {
    serde_wasm_bindgen::from_value(spec.clone()).map_err(|e| {
        let message = e.to_string();
        let read = |v| {
            serde_wasm_bindgen::from_value::<T>(v)
                .err()
                .map(|e| e.to_string())
        };
        let field = locate(&spec, &message, &read).unwrap_or_else(|| "spec".to_string());
        chart_error(RideError::field(field, message))
    })
}

/// The path of the key of `spec` that makes `read` fail with `message`: the first key
/// without which the read fails otherwise (or not at all), and within an array of
/// objects at that key the item, then the item's key, found the same way (`series[1]`,
/// `series[1].size`); `None` when no key changes it (a spec that is not an object).
fn locate(
    spec: &JsValue,
    message: &str,
    read: &dyn Fn(JsValue) -> Option<String>,
) -> Option<String> {
    let changes = |v: JsValue| read(v).as_deref() != Some(message);
    let obj = spec
        .dyn_ref::<Object>()
        .filter(|_| !Array::is_array(spec))?;
    let key = Object::keys(obj)
        .iter()
        .find(|k| changes(without(obj, k)))?;
    let name = key.as_string().unwrap_or_default();
    let value = Reflect::get(obj, &key).unwrap_or(JsValue::UNDEFINED);
    let Some(items) = value.dyn_ref::<Array>() else {
        return Some(name);
    };
    // With `obj[key]` replaced by `items`, the spec read again.
    let with = |items: &Array| {
        let copy = Object::assign(&Object::new(), obj);
        // Setting a key of a plain object just made cannot fail.
        let _ = Reflect::set(&copy, &key, items);
        JsValue::from(copy)
    };
    for (i, item) in items.iter().enumerate() {
        let others = items
            .slice(0, i as u32)
            .concat(&items.slice(i as u32 + 1, items.length()));
        if !changes(with(&others)) {
            continue;
        }
        let Some(item_obj) = item.dyn_ref::<Object>().filter(|_| !Array::is_array(&item)) else {
            return Some(format!("{name}[{i}]"));
        };
        for k in Object::keys(item_obj).iter() {
            let one = items.slice(0, items.length());
            one.set(i as u32, without(item_obj, &k));
            if changes(with(&one)) {
                return Some(format!("{name}[{i}].{}", k.as_string().unwrap_or_default()));
            }
        }
        return Some(format!("{name}[{i}]"));
    }
    Some(name)
}

/// A copy of `obj` without `key`.
fn without(obj: &Object, key: &JsValue) -> JsValue {
    let copy = Object::assign(&Object::new(), obj);
    // Deleting a key of a plain object just made cannot fail.
    let _ = Reflect::delete_property(&copy, key);
    copy.into()
}

/// Reads a [`MapChart`] spec. A `values` given as a `Float64Array` is copied in one go
/// (serde-wasm-bindgen reads typed arrays element by element: about 9 ms for the
/// page's 160 x 120 map, where the copy takes microseconds); anything else goes through
/// serde like the rest of the spec.
pub(super) fn read_map_spec(spec: JsValue) -> Result<MapChart, JsValue> {
    let values = Reflect::get(&spec, &"values".into()).unwrap_or(JsValue::UNDEFINED);
    let Some(typed) = values.dyn_ref::<Float64Array>() else {
        return read_spec(spec);
    };
    let copy = Object::assign(&Object::new(), spec.unchecked_ref());
    // Deleting a key of a plain object just made cannot fail.
    let _ = Reflect::delete_property(&copy, &"values".into());
    let mut chart: MapChart = read_spec(copy.into())?;
    chart.values = typed.to_vec();
    Ok(chart)
}

/// Ok when plotters can measure text here (see the module documentation).
pub(super) fn text_measurable() -> Result<(), JsValue> {
    let fail = |why: &str| {
        Err(chart_error(RideError::field(
            "chart",
            format!("SVG charts measure their text in the page's document, so they run on the main thread only: {why}"),
        )))
    };
    let Some(window) = web_sys::window() else {
        return fail("there is no window here (a Web Worker?)");
    };
    let Some(document) = window.document() else {
        return fail("the window has no document");
    };
    if document.body().is_none() {
        return fail("the document has no body yet");
    }
    match document.create_element("span") {
        Ok(el) if el.is_instance_of::<web_sys::HtmlElement>() => Ok(()),
        _ => fail("the document is not an HTML document"),
    }
}

/// The exports, in the page's on-demand wasm (the main thread loads it at the first
/// export; its first-screen wasm leaves them out, issue #29).
#[cfg(feature = "on-demand")]
mod export {
    use super::{chart_error, check_items, check_keys, read_map_spec, read_spec, text_measurable};
    use crate::chart::{line_chart_svg, map_chart_svg, LineChart, MapChart, MapMarker, Series};
    use js_sys::Reflect;
    use wasm_bindgen::prelude::*;

    /// A line or scatter chart as an SVG string (see [`LineChart`]): `{title, xLabel,
    /// yLabel, xLog, yLog, xRange, yRange, width, height, legend, series: [{name, colour,
    /// points: [[x, y], ...], style: "line" | "dots" | {markers: shape}, size, stroke,
    /// opacity}]}`.
    #[wasm_bindgen(js_name = lineChartSvg)]
    pub fn line_chart_svg_js(spec: JsValue) -> Result<String, JsValue> {
        check_keys(&spec, "", &LineChart::FIELDS)?;
        check_items(&spec, "series", &Series::FIELDS)?;
        let chart: LineChart = read_spec(spec)?;
        chart.layout().map_err(chart_error)?;
        text_measurable()?;
        line_chart_svg(&chart).map_err(chart_error)
    }

    /// A design map as an SVG string (see [`MapChart`]): `{title, unit, nx, ny, values,
    /// sampling, designBox: {ks_min, ks_max, cs_min, cs_max}, colourMap, range, feasible,
    /// contours: {auto: n} | {levels: [...]}, markers: [{label, ks, cs, shape, colour, size}],
    /// width, height, legend}`; `values` and `feasible` may be typed arrays.
    #[wasm_bindgen(js_name = mapChartSvg)]
    pub fn map_chart_svg_js(spec: JsValue) -> Result<String, JsValue> {
        check_keys(&spec, "", &MapChart::FIELDS)?;
        check_items(&spec, "markers", &MapMarker::FIELDS)?;
        let design_box = Reflect::get(&spec, &"designBox".into()).unwrap_or(JsValue::UNDEFINED);
        check_keys(&design_box, "designBox", &MapChart::BOX_FIELDS)?;
        let chart = read_map_spec(spec)?;
        chart.layout().map_err(chart_error)?;
        text_measurable()?;
        map_chart_svg(&chart).map_err(chart_error)
    }
}
