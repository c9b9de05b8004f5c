//! `ridelab surrogate`: a surrogate fitted to HiFi samples and validated on a HiFi grid.

use crate::args::{json, study_of, AdaptiveArgs, BoxArgs, CarRoad, ObjectiveArgs};
use clap::Args;
use ridelab::error::{Result, RideError};
use ridelab::study::StudySpec;
use ridelab::surrogate::{PlanSpec, SurrogateSpec};

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
    let base = study_of(&a.car, None)?;
    let adaptive = a.adaptive.options();
    if adaptive.is_none() {
        a.objectives.refuse(
            "a plain fit judges no designs; the objectives apply to the adaptive loop's fronts (--adaptive K)",
        )?;
    }
    let study = StudySpec {
        design_box: a.design_box.design_box()?,
        objectives: a.objectives.objectives()?,
        ..base
    };
    let r = study
        .surrogate(a.approach, a.plan, a.predict, adaptive)
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
