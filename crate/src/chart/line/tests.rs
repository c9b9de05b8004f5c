use super::super::svgcheck::{all, farthest_from, keys, parse, texts};
use super::*;

fn spectrum() -> LineChart {
    // |H| of a 1.2 Hz, 30 % damped resonance, 0.1..100 Hz, 200 points.
    let pts: Vec<(f64, f64)> = (0..200)
        .map(|k| {
            let f = 0.1 * 1000f64.powf(k as f64 / 199.0);
            let r = f / 1.2;
            let h =
                ((1.0 + (0.6 * r).powi(2)) / ((1.0 - r * r).powi(2) + (0.6 * r).powi(2))).sqrt();
            (f, h)
        })
        .collect();
    LineChart {
        title: "FRF BAcc".into(),
        x_label: "frequency [Hz]".into(),
        y_label: "|H| BAcc / road [1/s^2]".into(),
        x_log: true,
        y_log: true,
        series: vec![
            Series::new("HiFi (full car)", "#b91c1c", pts.clone()).with_size(4.0),
            Series::new("LoFi (quarter car)", "#1d4ed8", pts),
        ],
        ..LineChart::default()
    }
}

#[test]
fn a_log_log_chart_is_well_formed_and_labelled() {
    let chart = spectrum();
    let svg = line_chart_svg(&chart).unwrap();
    let els = parse(&svg);
    assert_eq!(els[0].num("width"), 640.0);
    assert_eq!(els[0].attr("viewBox"), "0 0 640 400");
    let t = texts(&els);
    for want in [
        "FRF BAcc",
        "frequency [Hz]",
        "|H| BAcc / road [1/s^2]",
        "LoFi (quarter car)",
        "HiFi (full car)",
    ] {
        assert!(t.iter().any(|s| s == want), "{want} missing from {t:?}");
    }
    // Decade tick labels of 0.1..100 Hz.
    for want in ["0.1", "1", "10", "100"] {
        assert!(
            t.iter().any(|s| s == want),
            "tick {want} missing from {t:?}"
        );
    }
    // Both series: one polyline each, the same vertices (simplified alike: fewer than
    // the 200 points, how close they stay is `data_points_land_within_half_a_pixel`).
    let lines: Vec<_> = all(&els, "polyline")
        .into_iter()
        .filter(|e| e.attr("stroke") == "#1D4ED8" || e.attr("stroke") == "#B91C1C")
        .collect();
    let data: Vec<_> = lines.iter().filter(|e| e.points().len() > 2).collect();
    assert_eq!(data.len(), 2);
    assert_eq!(data[0].points(), data[1].points());
    let n = data[0].points().len();
    assert!(n > 10 && n < 200, "{n} vertices");
    println!("log-log FRF chart: {} bytes", svg.len());
}

#[test]
fn data_points_land_within_half_a_pixel() {
    let chart = spectrum();
    let layout = chart.layout().unwrap();
    let f = layout.frame;
    assert_eq!((f.left, f.right, f.top, f.bottom), (80, 619, 34, 347));
    // Decades 0.1..100 Hz; y decades from the data.
    assert_eq!((layout.x.lo, layout.x.hi), (0.1, 100.0));
    let (ylo, yhi) = (layout.y.lo, layout.y.hi);
    let svg = line_chart_svg(&chart).unwrap();
    let els = parse(&svg);
    // The frame drawn is the layout's.
    let frame = all(&els, "rect")
        .into_iter()
        .find(|r| r.attr("fill") == "none" && r.attr("stroke") == "#555555")
        .expect("frame rect");
    assert_eq!(
        (
            frame.num("x"),
            frame.num("y"),
            frame.num("width"),
            frame.num("height")
        ),
        (80.0, 34.0, 539.0, 313.0)
    );
    let line = all(&els, "polyline")
        .into_iter()
        .find(|e| e.attr("stroke") == "#1D4ED8")
        .unwrap();
    let pts = line.points();
    // Independent of the chart code: log10 fractions of the frame.
    let exact: Vec<(f64, f64)> = chart.series[1]
        .points
        .iter()
        .map(|&(x, y)| {
            let ex = 80.0 + (x.log10() - (-1.0)) / 3.0 * (619.0 - 80.0);
            let ey =
                347.0 - (y.log10() - ylo.log10()) / (yhi.log10() - ylo.log10()) * (347.0 - 34.0);
            (ex, ey)
        })
        .collect();
    // Each vertex drawn is a data point rounded to the pixel, the ends included ...
    assert!(pts.len() >= 2 && pts.len() <= 200);
    assert_eq!(pts[0], (exact[0].0.round(), exact[0].1.round()));
    let last = exact[exact.len() - 1];
    assert_eq!(pts[pts.len() - 1], (last.0.round(), last.1.round()));
    for &(x, y) in &pts {
        let near = exact
            .iter()
            .any(|&(ex, ey)| (x - ex).abs() <= 0.5 && (y - ey).abs() <= 0.5);
        assert!(near, "vertex ({x}, {y}) is no data point");
    }
    // ... and every data point lies within a pixel of the line drawn (half a pixel of
    // simplification plus the rounding of the vertices).
    let worst = farthest_from(&exact, &pts);
    assert!(
        worst <= 1.0,
        "worst distance of a data point from the line {worst} px"
    );
}

#[test]
fn explicit_ranges_clip_lines_and_drop_outside_points() {
    let chart = LineChart {
        x_label: "BAcc [m/s^2]".into(),
        y_label: "DTL [N]".into(),
        x_range: Some((0.0, 10.0)),
        y_range: Some((0.0, 10.0)),
        series: vec![
            Series::new(
                "",
                "#c2410c",
                vec![(1.0, 1.0), (5.0, 5.0), (20.0, 5.0), (5.0, 8.0)],
            ),
            Series::new(
                "cloud",
                "#78a0d2",
                vec![(1.0, 1.0), (11.0, 1.0), (2.0, 2.0), (2.0, 2.0)],
            )
            .with_style(SeriesStyle::Dots),
            Series::new("pick", "#facc15", vec![(3.0, 3.0), (3.0, -1.0)])
                .with_style(SeriesStyle::Markers(MarkerShape::Diamond))
                .with_stroke("#000000"),
        ],
        ..LineChart::default()
    };
    let layout = chart.layout().unwrap();
    let els = parse(&line_chart_svg(&chart).unwrap());
    let lines: Vec<_> = all(&els, "polyline")
        .into_iter()
        .filter(|e| e.attr("stroke") == "#C2410C")
        .collect();
    assert_eq!(lines.len(), 2, "cut where the line leaves the plot");
    // The cut is on the right edge of the frame.
    assert_eq!(
        lines[0].points().last().unwrap().0,
        f64::from(layout.frame.right)
    );
    assert_eq!(lines[1].points()[0].0, f64::from(layout.frame.right));
    // Dots: (11, 1) is outside and (2, 2) twice is one pixel: two circles, and the
    // legend's.
    let dots = all(&els, "circle")
        .into_iter()
        .filter(|e| e.attr("fill") == "#78A0D2")
        .count();
    assert_eq!(dots, 3);
    // One marker inside (a polygon plus its outline), and the legend's.
    let markers = all(&els, "polygon")
        .into_iter()
        .filter(|e| e.attr("fill") == "#FACC15")
        .count();
    assert_eq!(markers, 2);
}

fn err(chart: &LineChart) -> String {
    line_chart_svg(chart).unwrap_err().to_string()
}

#[test]
fn bad_input_names_the_field() {
    let base = spectrum();
    let mut c = base.clone();
    c.series[1].points[7].1 = f64::NAN;
    let e = err(&c);
    assert!(e.starts_with("series[1].points[7]: y is NaN"), "{e}");
    let mut c = base.clone();
    c.series[0].points[3].0 = f64::INFINITY;
    assert!(
        err(&c).starts_with("series[0].points[3]: x is inf"),
        "{}",
        err(&c)
    );
    let mut c = base.clone();
    c.series[1].points[2].1 = -0.5;
    let e = err(&c);
    assert!(
        e.starts_with("series[1].points[2]: y = -0.5") && e.contains("log axis"),
        "{e}"
    );
    let mut c = base.clone();
    c.series[1].points[0].0 = 0.0;
    assert!(
        err(&c).starts_with("series[1].points[0]: x = 0"),
        "{}",
        err(&c)
    );
    let mut c = base.clone();
    c.series.clear();
    assert!(err(&c).starts_with("series: "));
    // A series without points is a legend entry only; with no point anywhere the ranges
    // must be given.
    let mut c = base.clone();
    c.series[1].points.clear();
    let svg = line_chart_svg(&c).expect("a legend-only series is fine");
    assert!(svg.contains(&c.series[1].name), "its legend entry is drawn");
    for s in &mut c.series {
        s.points.clear();
    }
    assert!(
        err(&c).starts_with("xRange: no series has a point"),
        "{}",
        err(&c)
    );
    c.x_range = Some((1.0, 2.0));
    assert!(
        err(&c).starts_with("yRange: no series has a point"),
        "{}",
        err(&c)
    );
    c.y_range = Some((1.0, 2.0));
    assert!(
        line_chart_svg(&c).is_ok(),
        "explicit ranges and no data: an empty frame"
    );
    let mut c = base.clone();
    c.series[0].colour = "red".into();
    assert!(err(&c).starts_with("series[0].colour: "));
    let mut c = base.clone();
    c.y_range = Some((0.0, 10.0));
    let e = err(&c);
    assert!(e.starts_with("yRange: ") && e.contains("> 0"), "{e}");
    let mut c = base.clone();
    c.x_range = Some((5.0, 1.0));
    assert!(err(&c).starts_with("xRange: "));
    let mut c = base.clone();
    c.width = 10;
    assert!(err(&c).starts_with("width: "));
    let mut c = base.clone();
    c.series[1].size = Some(f64::NAN);
    assert!(err(&c).starts_with("series[1].size: "));
    let mut c = base;
    c.series[1].opacity = Some(1.5);
    assert!(err(&c).starts_with("series[1].opacity: "));
}

#[test]
fn specs_read_from_json_with_camel_case_keys() {
    let c: LineChart = serde_json::from_str(
        r##"{"title": "t", "xLabel": "time [s]", "yLabel": "SWS [mm]", "yRange": [-5, 5],
            "series": [{"name": "a", "color": "#000000", "points": [[0, 1], [1, 2]]},
                       {"colour": "#ffffff", "points": [[0, 1]], "style": {"markers": "cross"}, "size": 4}]}"##,
    )
    .unwrap();
    assert_eq!(c.width, 640);
    assert_eq!(c.y_range, Some((-5.0, 5.0)));
    assert_eq!(c.series[1].style, SeriesStyle::Markers(MarkerShape::Cross));
    assert!(line_chart_svg(&c).is_ok());
    let bad = serde_json::from_str::<LineChart>(r#"{"xlabel": "oops"}"#).unwrap_err();
    assert!(bad.to_string().contains("unknown field `xlabel`"), "{bad}");
}

#[test]
fn field_lists_are_the_serde_keys() {
    let mut want: Vec<String> = LineChart::FIELDS.iter().map(|s| s.to_string()).collect();
    want.sort();
    assert_eq!(keys(&LineChart::default()), want);
    let mut want: Vec<String> = Series::FIELDS
        .iter()
        .filter(|&&s| s != "color")
        .map(|s| s.to_string())
        .collect();
    want.sort();
    assert_eq!(keys(&Series::new("a", "#000000", vec![])), want);
}

#[test]
fn the_layers_drawn_in_turn_make_the_whole_chart() {
    let chart = spectrum();
    let whole = line_chart_svg(&chart).unwrap();
    let layered = draw::render(chart.width, chart.height, |root| {
        let a = draw_line_chart(root, &chart, Layer::Axes)?;
        let b = draw_line_chart(root, &chart, Layer::Series)?;
        assert_eq!(a, b, "both layers place the data alike");
        Ok(())
    })
    .unwrap();
    assert_eq!(layered, whole);
    let axes = draw::render(chart.width, chart.height, |root| {
        draw_line_chart(root, &chart, Layer::Axes).map(drop)
    })
    .unwrap();
    let body = |svg: &str| svg.trim_end().trim_end_matches("</svg>").to_string();
    assert!(whole.starts_with(&body(&axes)), "the axes come first");
    for colour in ["#B91C1C", "#1D4ED8"] {
        assert!(
            whole.contains(colour) && !axes.contains(colour),
            "no {colour} series in the axes"
        );
    }
}
