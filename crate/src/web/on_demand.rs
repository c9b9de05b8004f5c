//! The page's on-demand parts (issue #29), in the wasm the workers load (the crate's
//! `on-demand` feature): the HiFi front, spectra, time responses, the fit's validation,
//! the study report, the GPU path's kept maps, the adaptive loop, road profiles and the
//! SVG charts. The main thread's first screen loads the small wasm without them
//! (`crate/first`); its sliders, maps, objective plane and readout need none of them.

use super::explorer::path_name;
use super::{js_error, parse_state, state_error, to_js, Explorer};
use crate::analysis::ModelKind;
use crate::error::RideError;
use crate::explorer::Model;
use js_sys::Float64Array;
use wasm_bindgen::prelude::*;

#[wasm_bindgen]
impl Explorer {
    /// With robust cases, the robust front of `ridelab optimize --cases` on `model`
    /// ("lofi" or "robust"; "surrogate" is refused naming `cases`) by `method` ("stm" or
    /// "nsga2"), as `front` gives a front, with `robust: {combine, normalisation, cases}`
    /// (each case's pick as that command's JSON `cases`). Without cases an error naming
    /// `cases`. In the workers' module only: the first screen needs no robust optimiser.
    #[wasm_bindgen(js_name = robustFront)]
    pub fn robust_front(&self, method: &str, model: Option<String>) -> Result<JsValue, JsValue> {
        let on = Model::parse_among(
            "frontModel",
            model.as_deref().unwrap_or("lofi"),
            Model::FRONT,
        )
        .map_err(js_error)?;
        to_js(&self.0.robust_front(method, on).map_err(js_error)?)
    }

    /// Offers this session a fit another thread made (`fitRecord`'s bytes): a scenario
    /// with the fit's inputs takes it instead of fitting again. Errors name `fit`.
    #[wasm_bindgen(js_name = offerFit)]
    pub fn offer_fit(&mut self, record: &[u8]) -> Result<(), JsValue> {
        let record = crate::explorer::FitRecord::from_bytes(record).map_err(js_error)?;
        self.0.offer_fit(record);
        Ok(())
    }

    /// Keeps HiFi values computed on the GPU (`GpuMaps.hifiMap`'s `values`, the map
    /// layout) for the `nx` x `ny` HiFi and error maps of the current scenario; errors
    /// name `values`, `nx` or `ny`.
    #[wasm_bindgen(js_name = keepHifiMap)]
    pub fn keep_hifi_map(&mut self, nx: usize, ny: usize, values: &[f64]) -> Result<(), JsValue> {
        self.0.keep_hifi_planes(nx, ny, values).map_err(js_error)
    }

    /// `"gpu"` or `"cpu"`: the path that made the kept HiFi values on the `nx` x `ny`
    /// grid; undefined when none are kept.
    #[wasm_bindgen(js_name = hifiPath)]
    pub fn hifi_path(&self, nx: usize, ny: usize) -> Option<String> {
        self.0.hifi_path(nx, ny).map(|p| path_name(p).to_string())
    }

    /// The HiFi's own Pareto front (STM on the full car, the plane's settings) with its
    /// pick, and the objective plane's front judged on the HiFi against it (both
    /// hypervolumes against the HiFi front's reference point, the HiFi runs each took):
    /// `{front, hifiRuns, compute, plane: {model, hifiRuns, frontPoints,
    /// hifiFeasiblePoints, hypervolume, hypervolumeOnHifi, hypervolumeRatio,
    /// pickGapPercent}}` (`front` as `front`'s). `values`: STM's starting grid from
    /// `GpuMaps.stmGrid` (then `compute` is "gpu"), or undefined for the CPU HiFi. About
    /// 5000 HiFi runs: the page asks its worker.
    #[wasm_bindgen(js_name = hifiFront)]
    pub fn hifi_front(&mut self, values: Option<Vec<f64>>) -> Result<JsValue, JsValue> {
        to_js(&self.0.hifi_front(values.as_deref()).map_err(js_error)?)
    }

    /// |H| from road displacement and the output PSDs of the design by the LoFi, the HiFi
    /// and the surrogate at `nfreq` log-spaced frequencies from 0.1 to 100 Hz:
    /// `{f, lofi: {frf, psd}, hifi, surrogate}`, each `[bacc, dtl, sws]` (1/s^2, N/m, m/m;
    /// (m/s^2)^2/Hz, N^2/Hz, m^2/Hz).
    pub fn spectra(&mut self, nfreq: usize) -> Result<JsValue, JsValue> {
        to_js(&self.0.spectra(nfreq).map_err(js_error)?)
    }

    /// Seeded time responses of the design by both models: `options` is `{duration, dt,
    /// seed, f_min, f_max, damper: {bump, rebound, knee: {velocity, bump, rebound} | null}
    /// | null, decimate}` (s, s, -, Hz, Hz, N s/m and m/s, -; missing fields take the core
    /// defaults). With a damper law the run's Cs is its equivalent linear rate
    /// `(bump + rebound) / 2`, as in `ridelab simulate --bump --rebound`. Returns
    /// `{damper, damperRate, lofi, hifi, a, b}` with `{t, road, outputs, positions,
    /// accelerations, rms, damper_rate, equivalent_rate}` per model.
    #[wasm_bindgen(js_name = timeResponse)]
    pub fn time_response(&self, options: JsValue) -> Result<JsValue, JsValue> {
        let opt: crate::time_domain::TimeOptions = serde_wasm_bindgen::from_value(options)
            .map_err(|e| state_error(format!("time options: {e}")))?;
        to_js(&self.0.time_response(&opt).map_err(js_error)?)
    }

    /// The surrogate fitted to HiFi samples over the design box and validated on a
    /// `levels x levels` HiFi grid: the `ridelab surrogate` report (samples, tuning,
    /// diagnostics, metrics, error map, predictions), on the session's kept fit. The
    /// validation grid runs the HiFi `levels^2` times: the page asks its worker.
    #[wasm_bindgen(js_name = surrogateFit)]
    pub fn surrogate_fit(&mut self, levels: usize) -> Result<JsValue, JsValue> {
        to_js(&self.0.fit_report(levels).map_err(js_error)?)
    }

    /// The design's full reports by both models, `{lofi, hifi}` (each as `analyse`'s, the
    /// frequency-route check included): what the HiFi worker sends once a slider move
    /// rests, in one call, after the step's readouts.
    #[wasm_bindgen(js_name = designReports)]
    pub fn design_reports(&self) -> Result<JsValue, JsValue> {
        #[derive(serde::Serialize)]
        struct Both {
            lofi: crate::analysis::Report,
            hifi: crate::analysis::Report,
        }
        to_js(&Both {
            lofi: self.0.report(ModelKind::Quarter).map_err(js_error)?,
            hifi: self.0.report(ModelKind::Full).map_err(js_error)?,
        })
    }

    /// The study report of the scenario (as `ridelab report`, seed 1, the view's surrogate
    /// and plan): `{title, html, markdown}`, the HTML one self-contained file. It takes
    /// seconds: the page asks its worker.
    #[wasm_bindgen(js_name = studyReport)]
    pub fn study_report(&self) -> Result<JsValue, JsValue> {
        let report = self.0.study_report().map_err(js_error)?;
        let docs = report.documents().map_err(js_error)?;
        to_js(&serde_json::json!({
            "title": report.title(),
            "html": docs.html,
            "markdown": docs.markdown,
        }))
    }
}

/// The page's "next HiFi run" (issue #15): `new AdaptiveRun(state, options?)` runs the
/// state's plan on the HiFi and fits its surrogate. Then `propose()` says where the next
/// HiFi run would go and why: `{candidate: {ks, cs, on_front, predicted, relative_std,
/// ehvi, probability_feasible, value, distance}, reason}`. `step()` runs it, refits and
/// returns `{added, step: {hifi_runs, front_points, hypervolume, pick}, recheck}`.
/// `report()` is the loop so far (samples in order with reasons, the `history` of
/// hypervolume and pick per HiFi run, as `ridelab surrogate ... --adaptive K` gives it),
/// `front()` the surrogate's front, `uncertaintyMap(nx, ny)` the estimate, %, in the
/// maps' layout, and `uncertaintyCheck(levels)` how well it predicts the true error on a
/// `levels x levels` HiFi grid: `{levels, check: {method, description, pearson,
/// spearman, estimated_mean_percent, true_mean_percent, map_percent}, at_samples_percent}`
/// (by criterion `{bacc, dtl, sws}`; the grid is run on the HiFi once and kept). `options` (optional, the CLI's names): `{criterion: "ehvi-front" |
/// "ehvi", uncertainty: "model" | "loo", candidates, min_distance, seed}`.
#[wasm_bindgen(js_name = AdaptiveRun)]
pub struct AdaptiveRun(crate::explorer::PageLoop);

#[wasm_bindgen(js_class = AdaptiveRun)]
impl AdaptiveRun {
    /// The loop on `state`'s scenario; errors name the field.
    #[wasm_bindgen(constructor)]
    pub fn new(state: JsValue, options: JsValue) -> Result<AdaptiveRun, JsValue> {
        let scenario = super::explorer::scenario_of(&parse_state(state)?).map_err(js_error)?;
        let options: crate::study::adaptive::AdaptiveOptions =
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

    /// How well the estimate predicts the true error on the `levels x levels` HiFi grid
    /// (errors name `levels`).
    #[wasm_bindgen(js_name = uncertaintyCheck)]
    pub fn uncertainty_check(&mut self, levels: usize) -> Result<JsValue, JsValue> {
        to_js(&self.0.uncertainty_check(levels).map_err(js_error)?)
    }
}
