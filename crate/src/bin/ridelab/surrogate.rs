//! `ridelab surrogate`: a surrogate fitted to HiFi samples and validated on a HiFi grid.

use crate::args::{
    car_and_road, car_loads_road_of, json, AdaptiveArgs, BoxArgs, CarRoad, ObjectiveArgs,
};
use crate::road::shaped_road;
use clap::Args;
use ridelab::analysis::ModelKind;
use ridelab::design::DesignBox;
use ridelab::error::{Result, RideError};
use ridelab::road_profile::{MeasuredModel, MeasuredRoad, RoadScenario};
use ridelab::study::{SurrogateReport, SurrogateRequest};
use ridelab::surrogate::VALIDATION_LEVELS;
use ridelab::surrogate::{PlanSpec, Setting, SurrogateSpec};

#[derive(Args)]
pub(crate) struct SurrogateArgs {
    /// The surrogate, e.g. rba-mul-rbf-mq, vba-qts, pba-smts.
    #[arg(long)]
    pub(crate) approach: SurrogateSpec,
    /// Its HiFi sampling plan: ae:N or grid:n.
    #[arg(long, default_value = "ae:10")]
    pub(crate) plan: PlanSpec,
    /// Validate on a grid:N HiFi grid instead of 20 x 20 and print the predictions.
    #[arg(long, value_name = "grid:N", value_parser = predict_grid)]
    pub(crate) predict: Option<usize>,
    #[command(flatten)]
    pub(crate) design_box: BoxArgs,
    #[command(flatten)]
    pub(crate) adaptive: AdaptiveArgs,
    /// What the adaptive loop's fronts judge designs by (with `--adaptive` only).
    #[command(flatten)]
    pub(crate) objectives: ObjectiveArgs,
    #[command(flatten)]
    pub(crate) car: CarRoad,
    /// The whole fit as JSON (SI units, with a `units` object) instead of the text summary.
    #[arg(long)]
    pub(crate) json: bool,
}

/// `grid:N` of `--predict`: a grid plan's side.
pub(crate) fn predict_grid(s: &str) -> Result<usize> {
    match PlanSpec::parse(s) {
        Ok(PlanSpec::Grid(n)) => Ok(n),
        _ => Err(RideError::field("", format!("'{s}' is not grid:N"))),
    }
}

pub(crate) fn surrogate_cmd(a: SurrogateArgs) -> Result<String> {
    let r = match a.car.road.as_deref() {
        Some(path) => measured_surrogate(&a, path),
        None => iso_surrogate(&a),
    }
    .map_err(|e| match e {
        RideError::Field { field, reason } if field == "predict-grid" => {
            RideError::field("predict", reason)
        }
        other => other,
    })?;
    if a.json {
        json(&r)
    } else {
        ridelab::finite::check(&r)?;
        Ok(crate::text::surrogate_text(&r))
    }
}

/// The request of the options: errors name the box, an objective given without
/// `--adaptive` (a plain fit judges no designs) or an invalid one.
fn request(a: &SurrogateArgs) -> Result<SurrogateRequest> {
    let adaptive = a.adaptive.options();
    if adaptive.is_none() {
        a.objectives.refuse(
            "a plain fit judges no designs; the objectives apply to the adaptive loop's fronts (--adaptive K)",
        )?;
    }
    Ok(SurrogateRequest {
        design_box: a.design_box.design_box()?,
        predict_grid: a.predict,
        adaptive,
        objectives: a.objectives.objectives()?,
        ..SurrogateRequest::new(a.approach, a.plan)
    })
}

/// The surrogate on an ISO class, plain or adaptive.
fn iso_surrogate(a: &SurrogateArgs) -> Result<SurrogateReport> {
    let (car, road) = car_and_road(&a.car)?;
    request(a)?.report(&car, &road)
}

/// `surrogate --road FILE`: the surrogate's HiFi samples and validation grid are the full
/// car on the measured road, its LoFi the quarter car on that road (both by the exact
/// route with the road's shaping filters); `--adaptive K` adds K HiFi runs there one at a
/// time as on an ISO class. One scenario: a car file's load cases are refused naming
/// them; the HiFi runs (plan, adaptive runs and validation grid) are bounded by
/// [`ridelab::budget::MAX_MEASURED_RUNS`].
fn measured_surrogate(a: &SurrogateArgs, path: &str) -> Result<SurrogateReport> {
    let (car, loads, _) = car_loads_road_of(&a.car)?;
    if !loads.is_empty() {
        return Err(RideError::field(
            "road",
            "a measured road is one scenario: a car file's load_cases take ISO classes (--class)",
        ));
    }
    let req = request(a)?;
    let design_box: DesignBox = req.design_box;
    let plan = a.plan.plan()?;
    let levels = a.predict.unwrap_or(VALIDATION_LEVELS) as u64;
    ridelab::budget::check_measured(
        plan.points(&design_box).len() as u64
            + req.adaptive.map_or(0, |o| o.runs as u64)
            + levels * levels,
        "plan",
        "the plan, the adaptive runs and the validation grid",
        "the plan's size, --adaptive or --predict",
    )?;
    let (shaped, tracks) = shaped_road(&a.car, path)?;
    let about = MeasuredRoad::of(path, &shaped, tracks);
    let setting = Setting::measured(&car, shaped.clone(), &design_box)?;
    let hifi = MeasuredModel::new(ModelKind::Full, &car, shaped);
    let mut r = req.report_on(&car, &setting, hifi)?;
    r.road = RoadScenario::Measured(about);
    Ok(r)
}
