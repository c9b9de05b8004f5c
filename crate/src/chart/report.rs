//! Chart specs of the CLI's reports: the three maps of a [`MapReport`] and the Pareto
//! front of a [`Study`] (what `ridelab map --svg` and `ridelab optimize --svg` write).

use super::line::{LineChart, Series, SeriesStyle};
use super::map::{Contours, MapChart, MapMarker, Sampling};
use super::marker::MarkerShape;
use super::ColourMap;
use crate::evaluate::Criteria;
use crate::maps::Scale;
use crate::optimize::{Method, Recheck, Study};
use crate::study::MapReport;

/// The criteria of a map: key, title, what it is, SI unit, display unit, display factor.
const CRITERIA: [(&str, &str, &str, &str, f64); 3] = [
    ("bacc", "BAcc", "RMS body acceleration", "m/s^2", 1.0),
    ("dtl", "DTL", "RMS dynamic tyre load", "N", 1.0),
    ("sws", "SWS", "RMS suspension working space", "mm", 1e3),
];

/// One [`MapChart`] per criterion of `r`, keyed `bacc`, `dtl`, `sws`: values on the
/// report's grid nodes (BAcc in m/s^2, DTL in N, SWS in mm; relative maps as the change
/// against the datum in %, on the diverging colour map), the report's contour levels,
/// the feasibility mask and the datum design.
pub fn map_report_charts(r: &MapReport) -> Vec<(&'static str, MapChart)> {
    let fields = [&r.bacc, &r.dtl, &r.sws];
    let levels = [&r.contours.bacc, &r.contours.dtl, &r.contours.sws];
    CRITERIA
        .iter()
        .enumerate()
        .map(|(k, &(key, name, long, unit, factor))| {
            let (name, long) = match (k, r.comfort) {
                (0, c @ crate::comfort::Comfort::Wk) => (c.label(), c.long_name()),
                _ => (name, long),
            };
            let (shown, unit, cmap): (Box<dyn Fn(f64) -> f64>, String, ColourMap) = match r.scale {
                Scale::Absolute => (
                    Box::new(move |v| v * factor),
                    format!("{name} [{unit}]"),
                    ColourMap::Viridis,
                ),
                Scale::Relative => (
                    Box::new(|v| (v - 1.0) * 100.0),
                    format!("{name} change vs datum [%]"),
                    ColourMap::Diverging,
                ),
            };
            let chart = MapChart {
                title: format!(
                    "{name}: {long} ({}, {}, {})",
                    r.evaluator,
                    r.car,
                    r.road.words()
                ),
                unit,
                nx: r.grid.ks.n,
                ny: r.grid.cs.n,
                values: fields[k].iter().map(|&v| shown(v)).collect(),
                sampling: Sampling::Nodes,
                design_box: r.grid.design_box(),
                colour_map: cmap,
                feasible: Some(
                    r.feasibility
                        .mask
                        .iter()
                        .map(|&m| u8::from(m == 0))
                        .collect(),
                ),
                contours: Contours::Levels(levels[k].iter().map(|c| shown(c.level)).collect()),
                markers: vec![MapMarker {
                    label: "datum".into(),
                    ks: r.datum.ks,
                    cs: r.datum.cs,
                    shape: MarkerShape::Diamond,
                    colour: None,
                    size: None,
                }],
                ..MapChart::default()
            };
            (key, chart)
        })
        .collect()
}

/// The objective plane of a study: its Pareto front in BAcc (m/s^2) and DTL (N) (a line
/// for STM, dots for NSGA-II), the min-max pick, the pick re-checked (when given) and the
/// `datum` design's criteria. The range covers them all, widened to the upper right
/// (where the legend goes: a front runs from the upper left to the lower right).
pub fn front_chart(study: &Study, datum: &Criteria, recheck: Option<&Recheck>) -> LineChart {
    let mut front: Vec<(f64, f64)> = study.front.iter().map(|p| (p.bacc, p.dtl)).collect();
    crate::order::sort_by_f64_key(&mut front, |p| p.0);
    let (method, style) = match study.method {
        Method::Stm(_) => ("STM", SeriesStyle::Line),
        Method::Nsga2(_) => ("NSGA-II", SeriesStyle::Dots),
    };
    let pick = (study.pick.criteria.bacc, study.pick.criteria.dtl);
    let mut series = vec![
        Series::new(
            &format!("Pareto front, {method} ({} points)", front.len()),
            "#c2410c",
            front.clone(),
        )
        .with_style(style)
        .with_size(if style == SeriesStyle::Line { 2.5 } else { 2.6 }),
        Series::new("min-max pick", "#facc15", vec![pick])
            .with_style(SeriesStyle::Markers(MarkerShape::Diamond))
            .with_stroke("#000000"),
    ];
    let mut all = front;
    all.push(pick);
    all.push((datum.bacc, datum.dtl));
    if let Some(rc) = recheck {
        let p = (rc.rechecked.bacc, rc.rechecked.dtl);
        all.push(p);
        series.push(
            Series::new(
                &format!("pick re-checked ({})", rc.evaluator),
                "#ffffff",
                vec![p],
            )
            .with_style(SeriesStyle::Markers(MarkerShape::Diamond))
            .with_size(5.0)
            .with_stroke("#b91c1c"),
        );
    }
    series.push(
        Series::new("datum", "#ffffff", vec![(datum.bacc, datum.dtl)])
            .with_style(SeriesStyle::Markers(MarkerShape::Square))
            .with_size(5.0)
            .with_stroke("#000000"),
    );
    let range = |v: Vec<f64>| {
        let lo = v.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let d = if hi > lo {
            hi - lo
        } else {
            lo.abs().max(1e-9) * 0.1
        };
        (lo - 0.05 * d, hi + 0.6 * d)
    };
    LineChart {
        title: format!("Pareto front of BAcc and DTL ({})", study.evaluator),
        x_label: "BAcc [m/s^2]".into(),
        y_label: "DTL [N]".into(),
        x_range: Some(range(all.iter().map(|p| p.0).collect())),
        y_range: Some(range(all.iter().map(|p| p.1).collect())),
        series,
        ..LineChart::default()
    }
}

#[cfg(test)]
mod tests {
    use super::super::svgcheck::{all, parse, texts};
    use super::super::{line_chart_svg, map_chart_svg};
    use super::*;
    use crate::maps::Grid;
    use crate::study::{MapRequest, MapSettings};
    use crate::{Car, ModelKind, Road};

    #[test]
    fn map_report_charts_show_the_report() {
        let settings = MapSettings {
            grid: Grid::parse("10000:40000:16", "500:4000:12").unwrap(),
            ..MapSettings::default()
        };
        let r = MapRequest::new(
            ModelKind::Quarter,
            &Car::datum(),
            &Road::default(),
            settings,
        )
        .run()
        .unwrap();
        let charts = map_report_charts(&r);
        assert_eq!(
            charts.iter().map(|c| c.0).collect::<Vec<_>>(),
            ["bacc", "dtl", "sws"]
        );
        let (_, sws) = &charts[2];
        // SWS in mm, node layout, the report's mask (bits, 0 = feasible) turned into flags.
        assert!((sws.values[17] - 1e3 * r.sws[17]).abs() < 1e-12);
        assert_eq!(sws.unit, "SWS [mm]");
        let flags = sws.feasible.as_ref().unwrap();
        assert_eq!(
            flags.iter().filter(|&&f| f == 1).count(),
            r.feasibility.summary.feasible
        );
        for (key, chart) in &charts {
            let svg = map_chart_svg(chart).unwrap();
            let els = parse(&svg);
            let t = texts(&els);
            assert!(t.iter().any(|s| s == "datum"), "{key}");
            assert!(t.iter().any(|s| s == &chart.unit), "{key}");
            // Every contour level of the report is drawn (one white line per piece).
            let lines = all(&els, "polyline")
                .into_iter()
                .filter(|e| e.attr("stroke") == "#FFFFFF" && e.attr("stroke-width") == "1")
                .count();
            let pieces: usize = match *key {
                "bacc" => &r.contours.bacc,
                "dtl" => &r.contours.dtl,
                _ => &r.contours.sws,
            }
            .iter()
            .map(|c| c.polylines.len())
            .sum();
            assert_eq!(lines, pieces, "{key}");
        }
    }

    #[test]
    fn front_chart_draws_the_front_pick_recheck_and_datum() {
        use crate::optimize::{FrontPoint, Pick, StmParams};
        let c = |bacc: f64, dtl: f64| Criteria {
            bacc,
            dtl,
            sws: 0.005,
        };
        // A front given out of order: the chart sorts it by BAcc.
        let pts = [(0.45, 360.0), (0.40, 380.0), (0.50, 350.0), (0.42, 370.0)];
        let study = Study {
            method: Method::Stm(StmParams::default()),
            evaluator: "quarter".into(),
            front: pts
                .iter()
                .map(|&(bacc, dtl)| FrontPoint {
                    ks: 2e4,
                    cs: 1.5e3,
                    bacc,
                    dtl,
                    sws: 0.005,
                })
                .collect(),
            reference_point: [0.6, 400.0],
            reference_rule: "test".into(),
            hypervolume: 1.0,
            pick: Pick {
                rule: "minmax".into(),
                index: 3,
                ks: 2e4,
                cs: 1.5e3,
                criteria: c(0.42, 370.0),
                ratio: [0.9, 0.95],
                distance: [0.1, 0.1],
                score: 0.1,
                pseudo_weights: [0.5, 0.5],
                change_percent: [-10.0, -5.0, 0.0],
            },
            evaluations: 100,
        };
        let recheck = Recheck {
            evaluator: "full".into(),
            predicted: c(0.42, 370.0),
            rechecked: c(0.43, 371.0),
            error_percent: [0.0; 3],
            predicted_change_percent: [0.0; 3],
            rechecked_change_percent: [0.0; 3],
        };
        let chart = front_chart(&study, &c(0.48, 390.0), Some(&recheck));
        // x: 0.40..0.50 widened by 5 % below and 60 % above.
        let (lo, hi) = chart.x_range.unwrap();
        assert!(
            (lo - 0.395).abs() < 1e-12 && (hi - 0.56).abs() < 1e-12,
            "{lo} {hi}"
        );
        let layout = chart.layout().unwrap();
        let els = parse(&line_chart_svg(&chart).unwrap());
        let front = all(&els, "polyline")
            .into_iter()
            .find(|e| e.attr("stroke") == "#C2410C" && e.points().len() == 4)
            .expect("the front line");
        let xs: Vec<f64> = front.points().iter().map(|p| p.0).collect();
        assert!(xs.windows(2).all(|w| w[0] < w[1]), "sorted by BAcc: {xs:?}");
        // The pick lands on its pixel: a diamond centred there.
        let (px, py) = layout.frame.pixel(&layout.x, &layout.y, (0.42, 370.0));
        let pick = all(&els, "polygon")
            .into_iter()
            .find(|e| e.attr("fill") == "#FACC15")
            .unwrap();
        let p = pick.points();
        let cx = p.iter().map(|q| q.0).sum::<f64>() / p.len() as f64;
        let cy = p.iter().map(|q| q.1).sum::<f64>() / p.len() as f64;
        assert!(
            (cx - px).abs() <= 0.5 && (cy - py).abs() <= 0.5,
            "({cx}, {cy}) vs ({px}, {py})"
        );
        let t = texts(&els);
        for want in [
            "BAcc [m/s^2]",
            "DTL [N]",
            "Pareto front, STM (4 points)",
            "min-max pick",
            "pick re-checked (full)",
            "datum",
        ] {
            assert!(t.iter().any(|s| s == want), "{want} missing from {t:?}");
        }
    }
}
