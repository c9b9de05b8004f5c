//! `ridelab map`: the design criteria and objective maps over a Ks x Cs grid.

use crate::args::{
    count, json, study_of, svg_target, write_svg, CarRoad, CasesArgs, ObjectiveArgs,
};
use clap::Args;
use ridelab::chart::{map_chart_svg, map_report_charts};
use ridelab::comfort::Comfort;
use ridelab::design::DesignBox;
use ridelab::error::Result;
use ridelab::gpu::Compute;
use ridelab::maps::{Axis, Grid, Scale};
use ridelab::study::{map_csv, EvaluatorSpec, MapAsk, MapReport, StudySpec};
use ridelab::surrogate::PlanSpec;
use std::path::{Path, PathBuf};

#[derive(Args)]
pub(crate) struct MapArgs {
    /// quarter (LoFi), full (HiFi) or a surrogate name (see `ridelab surrogate`), fitted
    /// to the HiFi at --plan's points over the grid's box.
    #[arg(long, value_parser = |s: &str| EvaluatorSpec::parse("model", s))]
    pub(crate) model: EvaluatorSpec,
    /// A surrogate's HiFi sampling plan: ae:N or grid:n.
    #[arg(long, default_value = "ae:10")]
    pub(crate) plan: PlanSpec,
    /// The Ks range a surrogate is fitted over, min:max (N/m) [default: the grid's].
    #[arg(long, value_name = "MIN:MAX", allow_hyphen_values = true, value_parser = |s: &str| DesignBox::parse_range("fit-ks-range", s))]
    pub(crate) fit_ks_range: Option<(f64, f64)>,
    /// The Cs range a surrogate is fitted over, min:max (N s/m) [default: the grid's].
    #[arg(long, value_name = "MIN:MAX", allow_hyphen_values = true, value_parser = |s: &str| DesignBox::parse_range("fit-cs-range", s))]
    pub(crate) fit_cs_range: Option<(f64, f64)>,
    /// Ks axis, min:max:points (N/m).
    #[arg(long, default_value = "10000:40000:41", allow_hyphen_values = true, value_parser = |s: &str| Axis::parse("ks-range", s))]
    pub(crate) ks_range: Axis,
    /// Cs axis, min:max:points (N s/m).
    #[arg(long, default_value = "500:4000:41", allow_hyphen_values = true, value_parser = |s: &str| Axis::parse("cs-range", s))]
    pub(crate) cs_range: Axis,
    /// Criteria relative to the datum car's.
    #[arg(long)]
    pub(crate) relative: bool,
    /// The comfort field: bacc (RMS body acceleration) or wk (ISO 2631-1 Wk-weighted),
    /// m/s^2; the JSON's `comfort` says "wk" when it is weighted.
    #[arg(long, default_value = "bacc")]
    pub(crate) comfort: Comfort,
    /// Where the HiFi map is computed: gpu, cpu, or auto (a hardware GPU when there is
    /// one, else the CPU); the JSON's `compute` says which ran.
    #[arg(long, default_value = "auto")]
    pub(crate) compute: Compute,
    #[command(flatten)]
    pub(crate) car: CarRoad,
    #[command(flatten)]
    pub(crate) cases: CasesArgs,
    /// The map of case K alone (its loaded car on its road, its own datum) instead of
    /// the robust map; cases are numbered load-case-major from 0.
    #[arg(long, value_name = "K", value_parser = count, allow_negative_numbers = true)]
    pub(crate) case: Option<usize>,
    /// The whole map as JSON (SI units, with a `units` object) instead of the text summary.
    #[arg(long, conflicts_with = "csv")]
    pub(crate) json: bool,
    /// One row per grid point (CSV) instead of the text summary.
    #[arg(long)]
    pub(crate) csv: bool,
    /// Also write PREFIX-bacc.svg, PREFIX-dtl.svg and PREFIX-sws.svg.
    #[arg(long, value_name = "PREFIX")]
    pub(crate) svg: Option<String>,
    #[command(flatten)]
    pub(crate) objectives: ObjectiveArgs,
}

pub(crate) fn map_cmd(a: MapArgs) -> Result<String> {
    let svg = svg_target(a.svg.as_deref())?;
    let base = study_of(&a.car, Some(&a.cases))?;
    let grid = Grid::new(a.ks_range, a.cs_range)?;
    let study = StudySpec {
        design_box: fit_box(&a, &grid),
        objectives: a.objectives.objectives()?,
        comfort: a.comfort,
        compute: Some(a.compute),
        ..base
    };
    let ask = MapAsk {
        model: a.model,
        plan: a.plan,
        grid,
        scale: if a.relative {
            Scale::Relative
        } else {
            Scale::Absolute
        },
        case: a.case,
    };
    let r = study.map(&ask)?;
    let text = if a.json { json(&r)? } else { String::new() };
    map_output(&a, svg, r.into_map(), text)
}

/// The box a surrogate is fitted over: `--fit-ks-range` and `--fit-cs-range`, each the
/// grid's where not given.
fn fit_box(a: &MapArgs, grid: &Grid) -> DesignBox {
    let (ks, cs) = (
        a.fit_ks_range.unwrap_or((grid.ks.min, grid.ks.max)),
        a.fit_cs_range.unwrap_or((grid.cs.min, grid.cs.max)),
    );
    DesignBox {
        ks_min: ks.0,
        ks_max: ks.1,
        cs_min: cs.0,
        cs_max: cs.1,
    }
}

/// Writes the SVGs (`--svg`) and returns the CSV, the JSON or the text of `r`.
fn map_output(
    a: &MapArgs,
    svg: Option<PathBuf>,
    r: MapReport,
    json_text: String,
) -> Result<String> {
    if let Some(prefix) = svg {
        ridelab::finite::check(&r)?;
        let prefix = prefix.to_string_lossy();
        let prefix = prefix.strip_suffix(".svg").unwrap_or(&prefix);
        for (key, chart) in map_report_charts(&r) {
            write_svg(
                Path::new(&format!("{prefix}-{key}.svg")),
                &map_chart_svg(&chart)?,
            )?;
        }
    }
    if a.csv {
        ridelab::finite::check(&r)?;
        Ok(map_csv(&r))
    } else if a.json {
        Ok(json_text)
    } else {
        ridelab::finite::check(&r)?;
        Ok(crate::text::map_text(&r))
    }
}
