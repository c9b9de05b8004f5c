//! `ridelab study`: the fidelity study, or the adaptive study of one surrogate.

use crate::args::{car_and_road, car_loads_road_of, count, json, BoxArgs, CarRoad, ObjectiveArgs};
use crate::road::shaped_road;
use clap::Args;
use ridelab::analysis::ModelKind;
use ridelab::car::Car;
use ridelab::error::{Result, RideError};
use ridelab::optimize::StmParams;
use ridelab::road_profile::{MeasuredModel, MeasuredRoad, RoadScenario};
use ridelab::study::adaptive::{adaptive_study, adaptive_study_on, AdaptiveStudy, StudyOptions};
use ridelab::study::spec::one_scenario;
use ridelab::study::{study, study_on, StudyReport};
use ridelab::surrogate::Setting;
use ridelab::surrogate::SurrogateSpec;

#[derive(Args)]
pub(crate) struct StudyArgs {
    /// The adaptive study of this surrogate instead of the fidelity study: for every
    /// total of HiFi runs, Audze-Eglais + adaptive runs against an Audze-Eglais plan of
    /// that size, judged on the HiFi.
    #[arg(long, value_name = "SURROGATE")]
    pub(crate) adaptive: Option<SurrogateSpec>,
    /// Audze-Eglais points of the adaptive study's initial plan, 2.. [default: 5].
    #[arg(long, value_parser = count, requires = "adaptive", allow_negative_numbers = true)]
    pub(crate) initial: Option<usize>,
    /// Smallest total of HiFi runs of the adaptive study [default: 6].
    #[arg(long, value_parser = count, requires = "adaptive", allow_negative_numbers = true)]
    pub(crate) min_runs: Option<usize>,
    /// Largest total of HiFi runs of the adaptive study, ..100 [default: 20].
    #[arg(long, value_parser = count, requires = "adaptive", allow_negative_numbers = true)]
    pub(crate) max_runs: Option<usize>,
    /// STM grid points per variable of every front of the adaptive study (the HiFi's own
    /// included), 2..2001 [default: 201].
    #[arg(long, value_parser = count, requires = "adaptive", allow_negative_numbers = true)]
    pub(crate) grid: Option<usize>,
    /// The box every plan, validation grid and front spans.
    #[command(flatten)]
    pub(crate) design_box: BoxArgs,
    /// What the adaptive study's fronts judge designs by (with `--adaptive` only).
    #[command(flatten)]
    pub(crate) objectives: ObjectiveArgs,
    #[command(flatten)]
    pub(crate) car: CarRoad,
    /// The whole study as JSON (SI units, with a `units` object) instead of the text table.
    #[arg(long, conflicts_with = "markdown")]
    pub(crate) json: bool,
    /// The study as a Markdown table instead of the text table.
    #[arg(long)]
    pub(crate) markdown: bool,
}

pub(crate) fn study_cmd(a: StudyArgs) -> Result<String> {
    if a.adaptive.is_none() {
        a.objectives.refuse(
            "the fidelity study judges fits, not designs; the objectives apply to the adaptive study's fronts (--adaptive SURROGATE)",
        )?;
    }
    if let Some(path) = a.car.road.as_deref() {
        if let Some(spec) = a.adaptive {
            let r = measured_adaptive_study(&a, path, spec)?;
            return output(&a, &r, r.to_markdown());
        }
        let r = measured_study(&a, path)?;
        return output(&a, &r, r.to_markdown());
    }
    let (car, road) = car_and_road(&a.car)?;
    if let Some(spec) = a.adaptive {
        let r = adaptive_study(&car, &road, spec, &study_options(&a)?).map_err(option_name)?;
        return output(&a, &r, r.to_markdown());
    }
    let r = study(&car, &road, &a.design_box.design_box()?)?;
    output(&a, &r, r.to_markdown())
}

/// The adaptive study's settings from the options (the defaults where left out); errors
/// name the box or an objective.
fn study_options(a: &StudyArgs) -> Result<StudyOptions> {
    let d = StudyOptions::default();
    Ok(StudyOptions {
        initial: a.initial.unwrap_or(d.initial),
        min_runs: a.min_runs.unwrap_or(d.min_runs),
        max_runs: a.max_runs.unwrap_or(d.max_runs),
        stm: StmParams {
            grid: a.grid.unwrap_or(d.stm.grid),
            ..d.stm.clone()
        },
        design_box: a.design_box.design_box()?,
        objectives: a.objectives.objectives()?,
        ..d
    })
}

/// An error's field as the option that sets it (`min_runs` -> `min-runs`).
fn option_name(e: RideError) -> RideError {
    match e {
        RideError::Field { field, reason } => RideError::field(field.replace('_', "-"), reason),
        other => other,
    }
}

/// A study as `--json`, `--markdown` or the text table of its Markdown.
fn output<T: serde::Serialize>(a: &StudyArgs, r: &T, markdown: String) -> Result<String> {
    if a.json {
        json(r)
    } else if a.markdown {
        Ok(markdown)
    } else {
        Ok(crate::text::plain_table(&markdown))
    }
}

/// `study --road FILE`: the fidelity study on the measured road (its HiFi samples and
/// validation grid the full car there, the surrogates' LoFi the quarter car there, as
/// `surrogate --road`), in the options' design box. Fixed work (every plan of the study
/// and the 20 x 20 grid: about 3 s on the shipped slab road). One scenario: a car file's
/// load cases exit 2 naming `road`.
fn measured_study(a: &StudyArgs, path: &str) -> Result<StudyReport> {
    let (car, setting, hifi, road) = measured_scenario(a, path)?;
    study_on(&car, &setting, hifi, road)
}

/// `study --road FILE --adaptive SURROGATE`: the adaptive study on the measured road, its
/// HiFi runs (the loop's, the Audze-Eglais plans', every front's re-check) the full car
/// there and the surrogates' LoFi the quarter car there. Bounded as on an ISO class
/// (`--max-runs` <= 100, the fronts' STM grid by the work budget).
fn measured_adaptive_study(
    a: &StudyArgs,
    path: &str,
    spec: SurrogateSpec,
) -> Result<AdaptiveStudy> {
    let (car, setting, hifi, road) = measured_scenario(a, path)?;
    adaptive_study_on(&car, &setting, &hifi, road, spec, &study_options(a)?).map_err(option_name)
}

/// The car, the surrogates' setting, the full car and the road's description of a study
/// on the profile `path` at the options' speed and tracks.
fn measured_scenario(
    a: &StudyArgs,
    path: &str,
) -> Result<(Car, Setting, MeasuredModel, RoadScenario)> {
    let (car, loads, _) = car_loads_road_of(&a.car)?;
    one_scenario(!loads.is_empty(), false)?;
    let (shaped, tracks) = shaped_road(&a.car, path)?;
    let about = MeasuredRoad::of(path, &shaped, tracks);
    let setting = Setting::measured(&car, shaped.clone(), &a.design_box.design_box()?)?;
    let hifi = MeasuredModel::new(ModelKind::Full, &car, shaped);
    Ok((car, setting, hifi, RoadScenario::Measured(about)))
}
