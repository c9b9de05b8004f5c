use super::super::svgcheck::{all, keys, parse, texts, Element};
use super::*;

/// `nx` x `ny` cell values `f(i, j)` over the default box.
fn chart(nx: usize, ny: usize, f: impl Fn(usize, usize) -> f64) -> MapChart {
    MapChart {
        title: "BAcc: RMS body acceleration".into(),
        unit: "BAcc [m/s^2]".into(),
        nx,
        ny,
        values: (0..nx * ny).map(|k| f(k % nx, k / nx)).collect(),
        ..MapChart::default()
    }
}

/// The filled cell rects (not the background, not the colour bar).
fn cells<'a>(els: &'a [Element], l: &MapLayout) -> Vec<&'a Element> {
    all(els, "rect")
        .into_iter()
        .filter(|r| {
            r.attr("stroke") == "none"
                && r.num("x") >= f64::from(l.frame.left)
                && r.num("x") < f64::from(l.frame.right)
                && r.num("width") < f64::from(l.frame.right - l.frame.left + 2)
        })
        .collect()
}

/// The fill of the last cell rect that covers pixel `p`.
fn fill_at(cells: &[&Element], p: (f64, f64)) -> String {
    cells
        .iter()
        .rev()
        .find(|r| {
            let (x, y) = (r.num("x"), r.num("y"));
            p.0 >= x && p.0 <= x + r.num("width") && p.1 >= y && p.1 <= y + r.num("height")
        })
        .map(|r| r.attr("fill").to_string())
        .unwrap_or_else(|| panic!("no cell at {p:?}"))
}

#[test]
fn cells_take_the_colour_maps_colour() {
    // 6 x 4 cells, all values distinct and far apart in colour: no merging, no blocks.
    let c = chart(6, 4, |i, j| (i + 6 * j) as f64 * 0.1);
    let l = c.layout().unwrap();
    assert_eq!(l.blocks, (6, 4));
    assert_eq!(l.colours.lo, 0.0);
    assert!((l.colours.hi - 2.3).abs() < 1e-12);
    let svg = map_chart_svg(&c).unwrap();
    let els = parse(&svg);
    let cells = cells(&els, &l);
    assert_eq!(cells.len(), 24);
    let b = c.design_box;
    for (i, j) in [(0, 0), (5, 0), (2, 1), (0, 3), (5, 3), (3, 2)] {
        // The cell centre, placed independently: cells split the box evenly.
        let ks = (b.ks_min + (i as f64 + 0.5) * (b.ks_max - b.ks_min) / 6.0) / 1000.0;
        let cs = (b.cs_min + (j as f64 + 0.5) * (b.cs_max - b.cs_min) / 4.0) / 1000.0;
        let f = l.frame;
        let px = f64::from(f.left) + (ks - 10.0) / 30.0 * f64::from(f.right - f.left);
        let py = f64::from(f.bottom) - (cs - 0.5) / 3.5 * f64::from(f.bottom - f.top);
        let v = c.values[j * 6 + i];
        let want = ColourMap::Viridis.colour(v / l.colours.hi).hex();
        assert_eq!(fill_at(&cells, (px, py)), want, "cell ({i}, {j}) value {v}");
    }
    // The lowest value is viridis' first colour, the highest its last.
    assert!(svg.contains("fill=\"#440154\""));
    assert!(svg.contains("fill=\"#FDE725\""));
    // Cells tile the frame: from the left to the right edge, bottom to top.
    let xmin = cells
        .iter()
        .map(|r| r.num("x"))
        .fold(f64::INFINITY, f64::min);
    let xmax = cells
        .iter()
        .map(|r| r.num("x") + r.num("width"))
        .fold(0.0, f64::max);
    let ymin = cells
        .iter()
        .map(|r| r.num("y"))
        .fold(f64::INFINITY, f64::min);
    let ymax = cells
        .iter()
        .map(|r| r.num("y") + r.num("height"))
        .fold(0.0, f64::max);
    assert_eq!(
        (xmin, xmax, ymin, ymax),
        (
            f64::from(l.frame.left),
            f64::from(l.frame.right),
            f64::from(l.frame.top),
            f64::from(l.frame.bottom)
        )
    );
}

#[test]
fn axes_and_colour_bar_carry_units() {
    let c = chart(6, 4, |i, j| (i + j) as f64);
    let l = c.layout().unwrap();
    let f = l.frame;
    assert_eq!((f.left, f.right, f.top, f.bottom), (62, 545, 34, 427));
    assert_eq!(
        (l.bar.left, l.bar.right, l.bar.top, l.bar.bottom),
        (560, 575, 42, 419)
    );
    let els = parse(&map_chart_svg(&c).unwrap());
    let t = texts(&els);
    for want in [
        "Ks front spring [kN/m]",
        "Cs front damper [kNs/m]",
        "BAcc [m/s^2]",
        "BAcc: RMS body acceleration",
        // Box ticks in kN/m and kNs/m, colour ticks over 0..8.
        "10",
        "40",
        "0.5",
        "4.0",
        "8",
    ] {
        assert!(t.iter().any(|s| s == want), "{want} missing from {t:?}");
    }
    // The colour bar runs from the low end (bottom) to the high end (top).
    let bar: Vec<_> = all(&els, "rect")
        .into_iter()
        .filter(|r| r.num("x") == f64::from(l.bar.left) && r.attr("stroke") == "none")
        .collect();
    assert_eq!(bar.len(), 64);
    let lowest = bar
        .iter()
        .max_by(|a, b| a.num("y").total_cmp(&b.num("y")))
        .unwrap();
    assert_eq!(
        lowest.attr("fill"),
        ColourMap::Viridis.colour(0.5 / 64.0).hex()
    );
}

#[test]
fn a_page_sized_map_is_resampled_and_stays_small() {
    // The page's 240 x 180 map with cell-to-cell noise (nothing merges).
    let c = MapChart {
        contours: Contours::Auto(8),
        feasible: Some((0..240 * 180).map(|k| u8::from(k / 240 >= 40)).collect()),
        ..chart(240, 180, |i, j| {
            let (x, y) = (i as f64 / 240.0, j as f64 / 180.0);
            x * x + y + 0.01 * (((i * 7919 + j * 104_729) % 97) as f64 / 97.0)
        })
    };
    let l = c.layout().unwrap();
    assert_eq!(l.blocks, (80, 60));
    assert_eq!(l.block_size, (3, 3));
    let svg = map_chart_svg(&c).unwrap();
    let els = parse(&svg);
    let n = cells(&els, &l).len();
    assert!(n <= 80 * 60, "{n} cell rects");
    assert!(n > 1000, "{n}: noise should keep most blocks apart");
    let rects = all(&els, "rect").len();
    assert!(rects <= 80 * 60 + 64 + 8, "{rects} rects in all");
    assert!(svg.len() < 1_000_000, "{} bytes", svg.len());
    println!(
        "240 x 180 map: {} bytes, {n} cell rects, {} polylines",
        svg.len(),
        all(&els, "polyline").len()
    );
    // A block is the mean of its 3 x 3 cells: block (10, 20) from cells 30..33 x 60..63.
    let mean: f64 = (60..63)
        .flat_map(|j| (30..33).map(move |i| (i, j)))
        .map(|(i, j)| c.values[j * 240 + i])
        .sum::<f64>()
        / 9.0;
    let ks = 10.0 + 31.5 / 240.0 * 30.0;
    let cs = 0.5 + 61.5 / 180.0 * 3.5;
    let f = l.frame;
    let p = (
        f64::from(f.left) + (ks - 10.0) / 30.0 * f64::from(f.right - f.left),
        f64::from(f.bottom) - (cs - 0.5) / 3.5 * f64::from(f.bottom - f.top),
    );
    let want = ColourMap::Viridis.colour(l.colours.fraction(mean)).hex();
    assert_eq!(fill_at(&cells(&els, &l), p), want);
}

#[test]
fn infeasible_cells_are_greyed_and_hatched() {
    // Infeasible below Cs row 2 of 8 (the lowest quarter of the box).
    let mut c = chart(10, 8, |i, j| (i + 10 * j) as f64);
    c.feasible = Some((0..80).map(|k| u8::from(k / 10 >= 2)).collect());
    let l = c.layout().unwrap();
    // The colour range spans the feasible values only: 20..79.
    assert_eq!((l.colours.lo, l.colours.hi), (20.0, 79.0));
    let svg = map_chart_svg(&c).unwrap();
    let els = parse(&svg);
    let cells = cells(&els, &l);
    let f = l.frame;
    let px = |i: f64, j: f64| {
        (
            f64::from(f.left) + (i + 0.5) / 10.0 * f64::from(f.right - f.left),
            f64::from(f.bottom) - (j + 0.5) / 8.0 * f64::from(f.bottom - f.top),
        )
    };
    // Cell (3, 1): value 13 is below the range: the first colour, washed grey.
    let washed = ColourMap::Viridis.colour(0.0).mix(Rgb(150, 150, 150), 0.62);
    assert_eq!(fill_at(&cells, px(3.0, 1.0)), washed.hex());
    assert_eq!(
        fill_at(&cells, px(3.0, 4.0)),
        ColourMap::Viridis.colour(23.0 / 59.0).hex()
    );
    // Hatch segments: all inside the infeasible quarter, at 45 degrees.
    let hatch: Vec<_> = all(&els, "polyline")
        .into_iter()
        .filter(|e| e.attr("stroke") == "#3A3A3A")
        .collect();
    assert!(hatch.len() > 20, "{} hatch lines", hatch.len());
    let boundary = f64::from(f.bottom) - 0.25 * f64::from(f.bottom - f.top);
    for h in &hatch {
        let p = h.points();
        assert_eq!(p.len(), 2);
        assert!((p[1].0 - p[0].0 + (p[1].1 - p[0].1)).abs() <= 1.0, "{p:?}");
        for q in p {
            assert!(
                q.1 >= boundary - 1.0 && q.1 <= f64::from(f.bottom) + 0.5,
                "{q:?}"
            );
        }
    }
    // The boundary is drawn (black over white) along Cs row 1.5 -> 2.5 mid: between rows 1 and 2.
    let outline: Vec<_> = all(&els, "polyline")
        .into_iter()
        .filter(|e| {
            e.attr("stroke") == "#000000" && e.attr("stroke-width") == "2" && e.points().len() > 2
        })
        .collect();
    assert_eq!(outline.len(), 1);
    let y = px(0.0, 1.5).1;
    for q in outline[0].points() {
        assert!((q.1 - y).abs() <= 0.5, "{q:?} vs row {y}");
    }
}

#[test]
fn contours_and_markers_land_where_they_should() {
    // Values = Ks in kN/m at the cell centres: the 25 kN/m contour is the vertical line
    // Ks = 25 kN/m.
    let nx = 12;
    let mut c = chart(nx, 5, |i, _| 10.0 + (i as f64 + 0.5) * 30.0 / nx as f64);
    c.contours = Contours::Levels(vec![25.0]);
    c.markers = vec![
        MapMarker {
            label: "datum".into(),
            ks: 20_000.0,
            cs: 1_500.0,
            shape: MarkerShape::Diamond,
            colour: None,
            size: None,
        },
        MapMarker {
            label: "outside".into(),
            ks: 50_000.0,
            cs: 1_500.0,
            shape: MarkerShape::Square,
            colour: Some("#facc15".into()),
            size: None,
        },
    ];
    let l = c.layout().unwrap();
    let f = l.frame;
    let els = parse(&map_chart_svg(&c).unwrap());
    let x25 = f64::from(f.left) + 0.5 * f64::from(f.right - f.left);
    let lines: Vec<_> = all(&els, "polyline")
        .into_iter()
        .filter(|e| e.attr("stroke") == "#FFFFFF" && e.attr("stroke-width") == "1")
        .collect();
    assert_eq!(lines.len(), 1);
    for q in lines[0].points() {
        assert!((q.0 - x25).abs() <= 0.5, "{q:?} vs column {x25}");
    }
    // Its level is written on the line, half-way along it (the axis's and the colour
    // bar's "25" ticks lie outside the frame).
    let label = all(&els, "text")
        .into_iter()
        .find(|e| {
            e.text.trim() == "25"
                && e.num("y") < f64::from(f.bottom)
                && e.num("x") < f64::from(f.right)
        })
        .expect("the contour's level label");
    let ys: Vec<f64> = lines[0].points().iter().map(|q| q.1).collect();
    let y_mid = 0.5 * (ys[0] + ys[ys.len() - 1]);
    assert!(
        (label.num("x") - x25).abs() <= 1.0,
        "label x {} vs {x25}",
        label.num("x")
    );
    assert!(
        (label.num("y") - y_mid).abs() <= 10.0,
        "label y {} vs {y_mid}",
        label.num("y")
    );
    // Datum: a white diamond centred on (20 kN/m, 1.5 kNs/m); the outside marker is left
    // out.
    let white: Vec<_> = all(&els, "polygon")
        .into_iter()
        .filter(|e| e.attr("fill") == "#FFFFFF")
        .collect();
    let (cx, cy) = (
        f64::from(f.left) + (20.0 - 10.0) / 30.0 * f64::from(f.right - f.left),
        f64::from(f.bottom) - (1.5 - 0.5) / 3.5 * f64::from(f.bottom - f.top),
    );
    let centre = |e: &Element| {
        let p = e.points();
        let n = p.len() as f64;
        (
            p.iter().map(|q| q.0).sum::<f64>() / n,
            p.iter().map(|q| q.1).sum::<f64>() / n,
        )
    };
    assert!(white
        .iter()
        .any(|e| (centre(e).0 - cx).abs() <= 0.5 && (centre(e).1 - cy).abs() <= 0.5));
    let yellow = all(&els, "polygon")
        .into_iter()
        .filter(|e| e.attr("fill") == "#FACC15")
        .count();
    assert_eq!(yellow, 0, "not drawn, not in the legend");
    let t = texts(&els);
    assert!(t.iter().any(|s| s == "datum"));
    assert!(!t.iter().any(|s| s == "outside"));
}

#[test]
fn nodes_put_half_cells_on_the_edges_and_diverging_is_symmetric() {
    let mut c = chart(4, 3, |i, j| i as f64 - 1.0 + 0.1 * j as f64);
    c.sampling = Sampling::Nodes;
    c.colour_map = ColourMap::Diverging;
    let l = c.layout().unwrap();
    assert_eq!((l.colours.lo, l.colours.hi), (-2.2, 2.2));
    let els = parse(&map_chart_svg(&c).unwrap());
    let cells = cells(&els, &l);
    assert_eq!(cells.len(), 12);
    let f = l.frame;
    let w = f64::from(f.right - f.left);
    // Columns: half a step (of 3) at each end: edges at 0, 1/6, 1/2, 5/6, 1 of the width.
    let mut xs: Vec<f64> = cells.iter().map(|r| r.num("x")).collect();
    xs.sort_by(f64::total_cmp);
    xs.dedup();
    let want: Vec<f64> = [0.0, 1.0 / 6.0, 0.5, 5.0 / 6.0]
        .iter()
        .map(|t| (f64::from(f.left) + t * w).round())
        .collect();
    assert_eq!(xs, want);
    // Zero is white.
    let zero = cells
        .iter()
        .find(|r| {
            (r.num("x") - want[1]).abs() < 0.1
                && r.num("y") + r.num("height") == f64::from(f.bottom)
        })
        .unwrap();
    // Node (1, 0) has value 0.0: the middle of the diverging map (entry 128, a hair
    // past the white stop, as on the page).
    assert_eq!(zero.attr("fill"), ColourMap::Diverging.colour(0.5).hex());
    assert_eq!(zero.attr("fill"), "#F7F6F6");
}

fn err(c: &MapChart) -> String {
    map_chart_svg(c).unwrap_err().to_string()
}

#[test]
fn bad_input_names_the_field() {
    let base = chart(4, 3, |i, j| (i + j) as f64);
    let mut c = base.clone();
    c.values[5] = f64::NAN;
    let e = err(&c);
    assert!(
        e.starts_with("values[5]: is NaN (Ks column 1, Cs row 1)"),
        "{e}"
    );
    let mut c = base.clone();
    c.values.pop();
    assert!(
        err(&c).starts_with("values: has 11 values, 4 x 3 needs 12"),
        "{}",
        err(&c)
    );
    let mut c = base.clone();
    c.nx = 1;
    c.values.truncate(3);
    assert!(err(&c).starts_with("nx: "));
    let mut c = base.clone();
    c.design_box.cs_min = 0.0;
    assert!(err(&c).starts_with("designBox: cs_min 0"), "{}", err(&c));
    let mut c = base.clone();
    c.feasible = Some(vec![1; 11]);
    assert!(err(&c).starts_with("feasible: "));
    let mut c = base.clone();
    c.feasible = Some(vec![2; 12]);
    assert!(err(&c).starts_with("feasible[0]: "));
    let mut c = base.clone();
    c.range = Some((3.0, 3.0));
    assert!(err(&c).starts_with("range: "));
    let mut c = base.clone();
    c.contours = Contours::Levels(vec![1.0, f64::INFINITY]);
    assert!(err(&c).starts_with("contours.levels[1]: "));
    let mut c = base.clone();
    c.markers.push(MapMarker {
        label: String::new(),
        ks: f64::NAN,
        cs: 1.0,
        shape: MarkerShape::Circle,
        colour: None,
        size: None,
    });
    assert!(err(&c).starts_with("markers[0]: "));
    let mut c = base.clone();
    c.height = 100_000;
    assert!(err(&c).starts_with("height: "));
    // A constant map still draws (a padded range).
    let c = chart(3, 3, |_, _| 5.0);
    assert!(map_chart_svg(&c).is_ok());
}

#[test]
fn specs_read_from_json_like_the_page_sends_them() {
    let c: MapChart = serde_json::from_str(
        r##"{"unit": "DTL [N]", "nx": 2, "ny": 2, "values": [1, 2, 3, 4],
            "designBox": {"ks_min": 10000, "ks_max": 40000, "cs_min": 500, "cs_max": 4000},
            "colourMap": "diverging", "feasible": [1, 1, 0, 1], "contours": {"auto": 4},
            "markers": [{"label": "design", "ks": 25000, "cs": 2000, "shape": "circle", "color": "#000000"}]}"##,
    )
    .unwrap();
    assert_eq!(c.contours, Contours::Auto(4));
    assert!(map_chart_svg(&c).is_ok());
    let e = serde_json::from_str::<MapChart>(r#"{"colorMap": "viridis"}"#).unwrap_err();
    assert!(e.to_string().contains("unknown field `colorMap`"), "{e}");
}

fn sorted(list: &[&str]) -> Vec<String> {
    let mut v: Vec<String> = list
        .iter()
        .filter(|&&s| s != "color")
        .map(|s| s.to_string())
        .collect();
    v.sort();
    v
}

#[test]
fn field_lists_are_the_serde_keys() {
    assert_eq!(keys(&MapChart::default()), sorted(&MapChart::FIELDS));
    assert_eq!(keys(&DesignBox::default()), sorted(&MapChart::BOX_FIELDS));
    let m = MapMarker {
        label: String::new(),
        ks: 1.0,
        cs: 1.0,
        shape: MarkerShape::Circle,
        colour: None,
        size: None,
    };
    assert_eq!(keys(&m), sorted(&MapMarker::FIELDS));
}

#[test]
fn the_frame_alone_has_the_axes_and_colour_bar_but_no_cells() {
    let c = chart(40, 30, |i, j| 0.4 + 0.01 * i as f64 + 0.002 * j as f64);
    let l = c.layout().unwrap();
    let whole = parse(&map_chart_svg(&c).unwrap());
    let frame_svg = draw::render(c.width, c.height, |root| {
        let placed = draw_map_frame(root, &c)?;
        assert_eq!(placed, l, "the frame is placed as the whole chart");
        Ok(())
    })
    .unwrap();
    let frame = parse(&frame_svg);
    // Every label of the whole chart (title, axis descriptions, ticks of both axes and
    // of the colour bar) and nothing else.
    assert_eq!(texts(&frame), texts(&whole));
    assert!(texts(&frame).iter().any(|t| t == "Ks front spring [kN/m]"));
    assert!(texts(&frame).iter().any(|t| t == "BAcc [m/s^2]"));
    // No cells: the whole chart has 40 x 30 of them (merged into runs along rows).
    assert!(cells(&whole, &l).len() >= 30, "{}", cells(&whole, &l).len());
    assert!(
        cells(&frame, &l).is_empty(),
        "{} cells",
        cells(&frame, &l).len()
    );
}
