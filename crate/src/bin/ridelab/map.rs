//! `ridelab map`: the design criteria and objective maps over a Ks x Cs grid.

use crate::args::{
    car_loads_road_of, count, json, svg_target, write_svg, CarRoad, CasesArgs, ObjectiveArgs,
};
use crate::road::{one_scenario, shaped_road};
use clap::Args;
use ridelab::car::Car;
use ridelab::chart::{map_chart_svg, map_report_charts};
use ridelab::comfort::Comfort;
use ridelab::design::DesignBox;
use ridelab::error::{Result, RideError};
use ridelab::gpu::Compute;
use ridelab::maps::{Axis, Grid, Scale};
use ridelab::robust::LoadCase;
use ridelab::robust::{CaseSet, Combine};
use ridelab::study::{map_csv, EvaluatorSpec, MapReport, MapRequest, MapSettings};
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
    let (car, loads, road) = car_loads_road_of(&a.car)?;
    let settings = MapSettings {
        grid: Grid::new(a.ks_range, a.cs_range)?,
        scale: if a.relative {
            Scale::Relative
        } else {
            Scale::Absolute
        },
        objectives: a.objectives.objectives()?,
        comfort: a.comfort,
        ..MapSettings::default()
    };
    if let Some(path) = a.car.road.as_deref() {
        let r = measured_map(&a, &car, &loads, &settings, path)?;
        let text = if a.json { json(&r)? } else { String::new() };
        return map_output(&a, svg, r, text);
    }
    let set = a.cases.set(&car, &loads, &road)?;
    if set.is_some() && a.compute == Compute::Gpu {
        return Err(RideError::field(
            "compute",
            "gpu: the robust maps' cases are evaluated on the CPU; use --compute cpu or auto",
        ));
    }
    let request = MapRequest {
        compute: a.compute,
        plan: a.plan,
        fit_box: fit_box(&a, &settings),
        ..MapRequest::new(a.model, &car, &road, settings)
    };
    let (r, json_text) = match (set, a.case) {
        (None, None) => {
            let r = request.run()?;
            let text = if a.json { json(&r)? } else { String::new() };
            (r, text)
        }
        (set, Some(k)) => {
            let set = match set {
                Some(s) => s,
                None => CaseSet::new(&car, &road, &[], &[], Combine::Worst)?,
            };
            let r = request.run_case(&set, k)?;
            let text = if a.json { json(&r)? } else { String::new() };
            (r.map, text)
        }
        (Some(set), None) => {
            let r = request.run_robust(&set)?;
            let text = if a.json { json(&r)? } else { String::new() };
            (r.map, text)
        }
    };
    map_output(&a, svg, r, json_text)
}

/// The map on the measured road of `--road FILE`: one scenario, so `--cases`, `--case`,
/// a car file's load cases and `--compute gpu` are refused naming them; `--comfort wk`
/// weights BAcc by the modal route with the road's filters and Wk's. A point costs more
/// here than on an ISO class (the exact route with the road's filters), so the grid is
/// bounded by [`ridelab::budget::MAX_MEASURED_RUNS`] points.
fn measured_map(
    a: &MapArgs,
    car: &Car,
    loads: &[LoadCase],
    settings: &MapSettings,
    path: &str,
) -> Result<MapReport> {
    one_scenario(
        a.cases.cases.is_some() || a.case.is_some() || !loads.is_empty(),
        a.compute == Compute::Gpu,
    )?;
    let g = &settings.grid;
    ridelab::budget::check_measured(
        (g.ks.n as u64) * (g.cs.n as u64),
        "ks-range",
        &format!("a {} x {} map", g.ks.n, g.cs.n),
        "the points of --ks-range or --cs-range",
    )?;
    let (shaped, tracks) = shaped_road(&a.car, path)?;
    // The ISO road is only recorded: the measured one replaces it.
    let iso = ridelab::road::Road::default();
    let request = MapRequest {
        plan: a.plan,
        fit_box: fit_box(a, settings),
        ..MapRequest::new(a.model, car, &iso, settings.clone())
    };
    ridelab::study::measured::measured_map(&request, &shaped, path, tracks)
}

/// The box of `--fit-ks-range` and `--fit-cs-range`, each the grid's where not given
/// (`None` when neither is).
fn fit_box(a: &MapArgs, settings: &MapSettings) -> Option<DesignBox> {
    if a.fit_ks_range.is_none() && a.fit_cs_range.is_none() {
        return None;
    }
    let g = &settings.grid;
    let (ks, cs) = (
        a.fit_ks_range.unwrap_or((g.ks.min, g.ks.max)),
        a.fit_cs_range.unwrap_or((g.cs.min, g.cs.max)),
    );
    Some(DesignBox {
        ks_min: ks.0,
        ks_max: ks.1,
        cs_min: cs.0,
        cs_max: cs.1,
    })
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
