//! `ridelab study`: the fidelity study, or the adaptive study of one surrogate.

use crate::args::{count, json, study_of, BoxArgs, CarRoad, ObjectiveArgs};
use clap::Args;
use ridelab::error::{Result, RideError};
use ridelab::optimize::StmParams;
use ridelab::study::adaptive::StudyOptions;
use ridelab::study::StudySpec;
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
    let base = study_of(&a.car, None)?;
    let study = StudySpec {
        design_box: a.design_box.design_box()?,
        objectives: a.objectives.objectives()?,
        ..base
    };
    if let Some(spec) = a.adaptive {
        let r = study
            .adaptive_study(spec, &study_options(&a))
            .map_err(option_name)?;
        return output(&a, &r, r.to_markdown());
    }
    let r = study.fidelity()?;
    output(&a, &r, r.to_markdown())
}

/// The adaptive study's settings from the options (the defaults where left out; the
/// box and objectives are the study's).
fn study_options(a: &StudyArgs) -> StudyOptions {
    let d = StudyOptions::default();
    StudyOptions {
        initial: a.initial.unwrap_or(d.initial),
        min_runs: a.min_runs.unwrap_or(d.min_runs),
        max_runs: a.max_runs.unwrap_or(d.max_runs),
        stm: StmParams {
            grid: a.grid.unwrap_or(d.stm.grid),
            ..d.stm.clone()
        },
        ..d
    }
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
