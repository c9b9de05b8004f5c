//! The `units` object of every JSON output (issue #32): the unit of every numeric field,
//! by field name, in SI as the page's JSON and CSV use (display units such as kN/m and
//! mm belong to the text, SVG and page views).
//!
//! A field's unit is set by its name wherever it sits in the output (`ks` is N/m in a
//! pick, a sample or a datum); arrays of numbers take their field's name. A report that
//! brings its own `units` (the maps: relative fields are ratios) keeps its entries.

use ridelab::error::{Result, RideError};
use serde_json::{Map, Value};
use std::collections::BTreeMap;

/// Unit of a numeric field by name, `None` for a name this table does not know (the
/// CLI tests run every command and fail on such a name).
pub(crate) fn unit_of(key: &str) -> Option<&'static str> {
    let unit = match key {
        // Design, car and road.
        "ks" | "spring" | "tire_stiffness" | "ks_min" | "ks_max" | "ks_values" | "wheel_rate"
        | "kt" => "N/m",
        "cs" | "damper" | "tire_damping" | "cs_min" | "cs_max" | "cs_values" | "damper_rate"
        | "equivalent_rate" | "bump" | "rebound" | "bump_high" | "rebound_high"
        | "critical_damping" | "ct" => "N s/m",
        "speed" | "velocity" | "knee" => "m/s",
        "sprung_mass" | "unsprung_mass" | "mass" | "quarter_mass" | "ms" | "mu" => "kg",
        "pitch_inertia" | "roll_inertia" => "kg m^2",
        "x" | "y" | "z" | "a" | "b" | "track_front" | "track_rear" | "wheelbase" | "spacing_m"
        | "length_m" | "segment_m" => "m",
        "gd_n0" | "gd" | "gd_right" => "m^3",
        "n" | "n_min" | "n_max" | "resolution" => "cycle/m",
        // Criteria and their limits.
        "bacc" | "bacc_wk" | "spectral_bacc_wk" | "wk" => "m/s^2",
        "dtl" | "static_load" | "static_wheel_load" => "N",
        "sws" | "sws_limit" | "road" => "m",
        "t" | "dt" | "duration" | "sample_interval" | "seconds" | "render_seconds"
        | "total_seconds" => "s",
        "frequency" | "damped_frequency" | "body_bounce_hz" | "band_hz" | "low_cutoff_hz"
        | "bounce" | "wheel_hop" => "Hz",
        "hypervolume" | "ehvi" | "value" => "(m/s^2) N",
        "reference_point" => "[m/s^2, N]",
        // A front's pick as a design pair (the adaptive study's rows).
        "pick" => "[N/m, N s/m]",
        k if k.ends_with("_percent") => "%",
        // Dimensionless: ratios, weights, errors relative to a value, normalised
        // coordinates; and counts, indices, seeds and bit masks.
        "damping_ratio"
        | "ratio"
        | "weight"
        | "weights"
        | "probability"
        | "score"
        | "mass_ratio"
        | "dynamic_index"
        | "roll_index"
        | "waviness"
        | "dtl_margin"
        | "dtl_relative"
        | "route_difference"
        | "spectral_error_estimate"
        | "fit_error"
        | "residual"
        | "r2"
        | "min_r2"
        | "cost"
        | "pseudo_weights"
        | "distance"
        | "min_distance"
        | "probability_feasible"
        | "relative_std"
        | "energy"
        | "min_gap"
        | "unit"
        | "gamma2"
        | "overlap"
        | "hypervolume_ratio"
        | "eta_c"
        | "eta_m"
        | "crossover_probability"
        | "mutation_probability"
        | "stop_below" => "-",
        "points"
        | "poly"
        | "level"
        | "levels"
        | "seed"
        | "grid"
        | "population"
        | "generations"
        | "evaluations"
        | "hifi_evaluations"
        | "hifi_runs"
        | "runs"
        | "run"
        | "total"
        | "feasible"
        | "broken"
        | "bit"
        | "mask"
        | "index"
        | "case"
        | "decimate"
        | "validation_levels"
        | "iterations"
        | "starts"
        | "best_start"
        | "candidates"
        | "samples"
        | "segments"
        | "segment_samples"
        | "tracks"
        | "front_points"
        | "order"
        | "initial"
        | "min_runs"
        | "max_runs"
        | "hifi_feasible_points" => "-",
        _ => return None,
    };
    Some(unit)
}

/// `value` as pretty JSON with a top-level `units` object naming the unit of every
/// numeric field in it, once every number is known to be finite. A top-level array
/// (`presets`) becomes `{"items": [...], "units": {...}}`.
pub(crate) fn json_with_units<T: serde::Serialize>(value: &T) -> Result<String> {
    ridelab::finite::check(value)?;
    let v = serde_json::to_value(value)
        .map_err(|e| RideError::Numerical(format!("cannot write JSON: {e}")))?;
    let mut top = match v {
        Value::Object(map) => map,
        other => Map::from_iter([("items".to_string(), other)]),
    };
    let own = match top.remove("units") {
        Some(Value::Object(own)) => own,
        _ => Map::new(),
    };
    let own_unit = |k: &str| own.get(k).and_then(Value::as_str).map(str::to_string);
    let mut units = BTreeMap::new();
    let mut path = Vec::new();
    for (k, item) in &top {
        path.push(k.clone());
        collect(item, &mut path, &own_unit, &mut units);
        path.pop();
    }
    let mut merged: Map<String, Value> = units
        .into_iter()
        .map(|(k, u)| (k, Value::String(u)))
        .collect();
    merged.extend(own.clone());
    top.insert("units".to_string(), Value::Object(merged));
    serde_json::to_string_pretty(&Value::Object(top))
        .map(|s| s + "\n")
        .map_err(|e| RideError::Numerical(format!("cannot write JSON: {e}")))
}

fn collect(
    v: &Value,
    path: &mut Vec<String>,
    own: &dyn Fn(&str) -> Option<String>,
    units: &mut BTreeMap<String, String>,
) {
    match v {
        Value::Number(_) => {
            if let Some((key, unit)) = resolve(path, own) {
                units.insert(key, unit);
            }
        }
        // The numbers of an array share its path, so its first names their unit (a
        // map's 19 200 values cost one lookup, not 19 200).
        Value::Array(items) => {
            let mut numbers = items.iter().filter(|i| i.is_number());
            if let Some(first) = numbers.next() {
                collect(first, path, own, units);
            }
            items
                .iter()
                .filter(|i| !i.is_number())
                .for_each(|i| collect(i, path, own, units));
        }
        Value::Object(map) => {
            for (k, item) in map {
                path.push(k.clone());
                collect(item, path, own, units);
                path.pop();
            }
        }
        _ => {}
    }
}

/// The `units` entry of the number at `path` (object keys from the top): by its own name,
/// or where the name alone does not say, by its parent too (`positions.body_pitch_theta`
/// is rad; `sws.rmse` is m, or the report's own unit of `sws` when it has one: a
/// relative map's ratio).
pub(crate) fn resolve(
    path: &[String],
    own: &dyn Fn(&str) -> Option<String>,
) -> Option<(String, String)> {
    let leaf = path.last()?.as_str();
    let parent = path.len().checked_sub(2).map(|i| path[i].as_str());
    let angle = leaf.contains("pitch") || leaf.contains("roll");
    let fixed = |u: &str| Some(u.to_string());
    let unit = match (parent, leaf) {
        (Some("positions"), _) => fixed(if angle { "rad" } else { "m" }),
        (Some("accelerations"), _) => fixed(if angle { "rad/s^2" } else { "m/s^2" }),
        (Some(c @ ("bacc" | "dtl" | "sws")), "rmse" | "max_abs_error" | "level") => {
            own(c).or_else(|| unit_of(c).map(str::to_string))
        }
        (Some("ks"), "min" | "max") => fixed("N/m"),
        (Some("cs"), "min" | "max") => fixed("N s/m"),
        (Some("ks" | "cs"), "n") => fixed("-"),
        (Some("polylines"), "points") => fixed("[N/m, N s/m] pairs (Ks, Cs)"),
        (Some("outline"), "level") => fixed("- (feasible 1, infeasible 0)"),
        (Some("tuning"), "value") => fixed("- (unless the parameter's name says otherwise)"),
        (Some("options" | "method"), _) => fixed("-"),
        _ => None,
    };
    match (unit, parent) {
        (Some(u), Some(p)) => Some((format!("{p}.{leaf}"), u)),
        _ => unit_of(leaf).map(|u| (leaf.to_string(), u.to_string())),
    }
}
