//! `ridelab road FILE`: a measured road profile described (Welch PSD, ISO 8608 fit,
//! coherence), and the measured road of `eval --road FILE` (issue #31).

use crate::args::{json, CarRoad};
use clap::Args;
use ridelab::analysis::ModelKind;
use ridelab::car::Car;
use ridelab::comfort::Comfort;
use ridelab::criteria::comfort_label;
use ridelab::error::{Result, RideError};
use ridelab::evaluate::{Criteria, Evaluator};
use ridelab::road::Tracks;
use ridelab::road_profile::{
    criteria_shaped_spectral, describe, road_error, MeasuredModel, Profile, ProfileTracks,
    RoadDescription, ShapedRoad, ShapedSpectrum,
};
use serde::Serialize;

#[derive(Args)]
pub(crate) struct RoadArgs {
    /// The profile: CSV with the header distance_m,elevation_m[,elevation_right_m].
    #[arg(value_name = "FILE")]
    pub(crate) file: String,
    /// The description as JSON (SI units, with a `units` object) instead of the text.
    #[arg(long)]
    pub(crate) json: bool,
}

/// Reads and checks a profile file; every error names `road` with the file's own
/// column and row.
pub(crate) fn read_profile(path: &str) -> Result<Profile> {
    let bytes = std::fs::read(path)
        .map_err(|e| RideError::field("road", format!("cannot read '{path}': {e}")))?;
    Profile::from_csv_bytes(&bytes).map_err(road_error)
}

pub(crate) fn road_cmd(a: RoadArgs) -> Result<String> {
    let profile = read_profile(&a.file)?;
    let d = describe(&profile)?;
    if a.json {
        json(&d)
    } else {
        ridelab::finite::check(&d)?;
        Ok(road_text(&a.file, &d))
    }
}

fn road_text(file: &str, d: &RoadDescription) -> String {
    let f = &d.iso8608;
    let mut s = format!(
        "{file}: {} samples every {:.4} m, {:.1} m, {} track{}\n\
         ISO 8608 fit over {:.3}..{:.3} cycle/m: class {:?}, Gd(n0 = 0.1 cycle/m) {:.3e} m^3, waviness {:.2} (residual {:.3} in log10)\n",
        d.samples,
        d.spacing_m,
        d.length_m,
        d.tracks,
        if d.tracks == 2 { "s" } else { "" },
        f.band[0],
        f.band[1],
        f.class,
        f.gd_n0,
        f.waviness,
        f.residual,
    );
    if let Some(c) = &d.coherence {
        let mean = c.gamma2.iter().sum::<f64>() / c.gamma2.len().max(1) as f64;
        s += &format!(
            "tracks' coherence: mean {mean:.3} over {} bins\n",
            c.gamma2.len()
        );
    }
    s += &format!("PSD: {}\n", d.method);
    for n in &d.notes {
        s += &format!("note: {n}\n");
    }
    s + "--json for the PSD, its band means and the coherence\n"
}

/// The measured road of `--road FILE` at the options' `--speed` (default 20 m/s) with
/// their `--tracks` (default: the file's own, measured when it has two); errors name
/// `road` (with the file's column and row) or `speed`.
pub(crate) fn shaped_road(o: &CarRoad, path: &str) -> Result<(ShapedRoad, ProfileTracks)> {
    let (profile, speed, tracks) = profile_at(o, path)?;
    let shaped = ShapedRoad::from_profile(&profile, speed, tracks).map_err(road_error)?;
    Ok((shaped, tracks))
}

/// The profile of `path`, the speed (`--speed`, checked) and how its tracks drive the car:
/// `--tracks`, or as the file says (one column: both tracks see it; two: measured).
pub(crate) fn profile_at(o: &CarRoad, path: &str) -> Result<(Profile, f64, ProfileTracks)> {
    let profile = read_profile(path)?;
    let speed = o.speed.unwrap_or(ridelab::road::Road::default().speed);
    ridelab::domain::SPEED.check("speed", speed)?;
    let tracks = match o.tracks {
        None => ProfileTracks::default_for(&profile),
        Some(Tracks::Correlated) => ProfileTracks::Correlated,
        Some(Tracks::Independent) => ProfileTracks::Independent,
    };
    Ok((profile, speed, tracks))
}

/// `eval --road FILE`: the criteria on a measured road by the exact route (the model
/// augmented with the fitted shaping filter) and the frequency route on the raw PSD.
#[derive(Serialize)]
pub(crate) struct MeasuredEval {
    model: ModelKind,
    car: String,
    road_file: String,
    speed: f64,
    tracks: ProfileTracks,
    ks: f64,
    cs: f64,
    bacc: f64,
    dtl: f64,
    sws: f64,
    /// ISO 2631-1 Wk-weighted RMS body acceleration, m/s^2, exact (the model with the
    /// road's filters and Wk's).
    bacc_wk: f64,
    /// ISO 2631-1 Annex C's label of `bacc_wk`.
    comfort: &'static str,
    route: &'static str,
    /// The frequency route on the raw Welch PSD.
    spectral: Criteria,
    /// The same for `bacc_wk`.
    spectral_bacc_wk: f64,
    /// Largest relative difference of the routes (the criteria and `bacc_wk`).
    route_difference: f64,
    /// The shaping filters' largest relative PSD error over the band.
    fit_error: f64,
    band_hz: [f64; 2],
    notes: Vec<String>,
}

/// `car` (its front the design) on the measured road, the model prepared on `datum` (the
/// same car with its own front design).
pub(crate) fn eval_measured(
    kind: ModelKind,
    datum: &Car,
    car: &Car,
    o: &CarRoad,
    path: &str,
) -> Result<MeasuredEval> {
    let (shaped, tracks) = shaped_road(o, path)?;
    let speed = shaped.speed;
    let q = car.quarter();
    let model = MeasuredModel::new(kind, datum, shaped.clone());
    let exact = model.evaluate(q.ks, q.cs)?;
    let bacc_wk = model.with_comfort(Comfort::Wk).evaluate(q.ks, q.cs)?.bacc;
    let spectral = criteria_shaped_spectral(&kind.build(car), &shaped, 1e-8)?.criteria;
    let spectral_bacc_wk = ShapedSpectrum::new(&kind.build(car), &shaped)?.bacc_wk(1e-8)?;
    let diff = exact
        .to_array()
        .iter()
        .chain([&bacc_wk])
        .zip(spectral.to_array().iter().chain([&spectral_bacc_wk]))
        .map(|(a, b)| (a / b - 1.0).abs())
        .fold(0.0, f64::max);
    Ok(MeasuredEval {
        model: kind,
        car: car.name.clone(),
        road_file: path.to_string(),
        speed,
        tracks,
        ks: q.ks,
        cs: q.cs,
        bacc: exact.bacc,
        dtl: exact.dtl,
        sws: exact.sws,
        bacc_wk,
        comfort: comfort_label(bacc_wk),
        route: "exact (shaping filter)",
        spectral,
        spectral_bacc_wk,
        route_difference: diff,
        fit_error: shaped.fit_error(),
        band_hz: shaped.band_hz,
        notes: shaped.notes.clone(),
    })
}

pub(crate) fn measured_text(r: &MeasuredEval) -> String {
    let mut s = format!(
        "{} model, {} on the measured road {} at {} m/s, {} tracks\n{}\n\
         BAcc {:.5} m/s^2 (ISO 2631-1 Wk-weighted {:.5} m/s^2: {})\nDTL  {:.3} N\nSWS  {:.4} mm\n\
         route {}: the frequency route on the raw PSD differs by {:.1e}; the shaping filter's PSD error {:.1e} over {:.2}..{:.1} Hz\n",
        match r.model {
            ModelKind::Quarter => "Quarter-car (LoFi)",
            ModelKind::Full => "Full-car (HiFi)",
        },
        r.car,
        r.road_file,
        r.speed,
        format!("{:?}", r.tracks).to_lowercase(),
        crate::text::design_words(r.ks, r.cs),
        r.bacc,
        r.bacc_wk,
        r.comfort,
        r.dtl,
        1e3 * r.sws,
        r.route,
        r.route_difference,
        r.fit_error,
        r.band_hz[0],
        r.band_hz[1],
    );
    for n in &r.notes {
        s += &format!("note: {n}\n");
    }
    s
}
