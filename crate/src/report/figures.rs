//! The report's figures as chart specs (drawn to SVG by the core's plotters charts, the
//! same charts as the page and `ridelab map --svg`): FRFs of both models, the maps of
//! both models, the sampling plans and their gap distributions, the chosen surrogate's
//! error maps, and the fronts.

use super::MethodReport;
use crate::chart::{
    front_chart, line_chart_svg, map_chart_svg, map_report_charts, ColourMap, Contours, LineChart,
    MapChart, MarkerShape, Sampling, Series, SeriesStyle,
};
use crate::error::Result;

/// One figure: a file stem (`figures/<key>.svg`), a caption and the SVG document.
#[derive(Debug, Clone, PartialEq)]
pub struct Figure {
    /// File stem, e.g. `frf-bacc`.
    pub key: String,
    /// Caption.
    pub caption: String,
    /// The SVG document.
    pub svg: String,
}

/// The section each figure belongs to, with its figures, in order.
pub fn figures(r: &MethodReport) -> Result<Vec<(usize, Vec<Figure>)>> {
    let line = |key: &str, caption: String, chart: LineChart| -> Result<Figure> {
        Ok(Figure {
            key: key.into(),
            caption,
            svg: line_chart_svg(&chart)?,
        })
    };
    let map = |key: String, caption: String, chart: MapChart| -> Result<Figure> {
        Ok(Figure {
            key,
            caption,
            svg: map_chart_svg(&chart)?,
        })
    };
    // 1: FRFs.
    let v = &r.verification;
    let mut frf = Vec::new();
    for (k, (key, name, unit)) in [
        ("bacc", "BAcc", "1/s^2"),
        ("dtl", "DTL", "N/m"),
        ("sws", "SWS", "m/m"),
    ]
    .into_iter()
    .enumerate()
    {
        let pts = |h: &[f64]| v.frf.f.iter().copied().zip(h.iter().copied()).collect();
        frf.push(line(
            &format!("frf-{key}"),
            format!("|H| of {name} per metre of road displacement (right track), LoFi and HiFi"),
            LineChart {
                title: format!("{name}: frequency response"),
                x_label: "frequency [Hz]".into(),
                y_label: format!("|H| {name} [{unit}]"),
                x_log: true,
                y_log: true,
                series: vec![
                    Series::new("LoFi (quarter car)", "#2563eb", pts(&v.frf.lofi[k])),
                    Series::new("HiFi (full car)", "#c2410c", pts(&v.frf.hifi[k])),
                ],
                ..LineChart::default()
            },
        )?);
    }
    // 2: maps of both models.
    let mut maps = Vec::new();
    for (model, report) in [("lofi", &r.maps.lofi), ("hifi", &r.maps.hifi)] {
        let name = if model == "lofi" { "LoFi" } else { "HiFi" };
        for (key, mut chart) in map_report_charts(report) {
            // A short title: the caption and the section say the car and the road.
            chart.title = format!("{}: {name}", chart.unit);
            maps.push(map(
                format!("map-{model}-{key}"),
                format!(
                    "{} map of {} ({}); hatched: outside the design objective space",
                    key.to_uppercase(),
                    if model == "lofi" {
                        "the LoFi"
                    } else {
                        "the HiFi"
                    },
                    report.evaluator
                ),
                chart,
            )?);
        }
    }
    // 3: sampling plans and gap distributions.
    let colours = ["#2563eb", "#16a34a", "#c2410c", "#9333ea", "#0f766e"];
    let mut plans = Vec::new();
    let mut scatter = Vec::new();
    let mut gaps = Vec::new();
    for (p, colour) in r.sampling.iter().zip(colours) {
        scatter.push(
            Series::new(
                &format!("{} points", p.points),
                colour,
                p.design
                    .iter()
                    .map(|&(ks, cs)| (ks / 1e3, cs / 1e3))
                    .collect(),
            )
            .with_style(SeriesStyle::Markers(MarkerShape::Circle)),
        );
        // The histogram as a step line over the bin edges.
        let mut steps = Vec::new();
        for &(lo, hi, count) in &p.gaps {
            steps.push((lo, count as f64));
            steps.push((hi, count as f64));
        }
        gaps.push(Series::new(&format!("{} points", p.points), colour, steps));
    }
    let b = &r.scenario.design_box;
    plans.push(line(
        "plans",
        "Audze-Eglais plans of 2, 3, 4, 5 and 10 points in the design box".into(),
        LineChart {
            title: "Audze-Eglais sampling plans".into(),
            x_label: "Ks [kN/m]".into(),
            y_label: "Cs [kNs/m]".into(),
            x_range: Some((b.ks_min / 1e3, b.ks_max / 1e3)),
            y_range: Some((b.cs_min / 1e3, b.cs_max / 1e3)),
            series: scatter,
            ..LineChart::default()
        },
    )?);
    plans.push(line(
        "gaps",
        "Gap distributions: how many point pairs lie at each distance (lattice units)".into(),
        LineChart {
            title: "Gap distributions of the plans".into(),
            x_label: "gap L [lattice units]".into(),
            y_label: "pairs [-]".into(),
            series: gaps,
            ..LineChart::default()
        },
    )?);
    // 4: the chosen surrogate's error maps on the validation grid.
    let chosen = &r.fidelity.chosen;
    let e = &chosen.error_map;
    let n = chosen.validation_levels;
    let mut errors = Vec::new();
    for (k, name) in ["bacc", "dtl", "sws"].into_iter().enumerate() {
        let values = e.relative_error.to_array()[k].clone();
        errors.push(map(
            format!("error-{name}"),
            format!(
                "Relative error of {} against the HiFi on the {n} x {n} validation grid, %",
                chosen.surrogate
            ),
            MapChart {
                title: format!(
                    "{}: {} error vs HiFi",
                    name.to_uppercase(),
                    chosen.surrogate
                ),
                unit: format!("{} error [%]", name.to_uppercase()),
                nx: n,
                ny: n,
                values,
                sampling: Sampling::Nodes,
                design_box: chosen.design_box,
                colour_map: ColourMap::Diverging,
                contours: Contours::None,
                ..MapChart::default()
            },
        )?);
    }
    // 5: the fronts.
    let mut fronts = Vec::new();
    let o = &r.optimisation;
    for (key, rep) in [
        ("front-stm", &o.stm),
        ("front-nsga2", &o.nsga2),
        ("front-hifi", &o.hifi),
    ] {
        if let Some(rep) = rep {
            fronts.push(line(
                key,
                format!(
                    "Pareto front on {} with its min-max pick, the pick re-checked on the HiFi and the datum",
                    rep.study.evaluator
                ),
                front_chart(&rep.study, &rep.datum, Some(&rep.hifi_recheck)),
            )?);
        }
    }
    Ok(vec![
        (1, frf),
        (2, maps),
        (3, plans),
        (4, errors),
        (5, fronts),
    ])
}
