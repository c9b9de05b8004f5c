//! Drawing a checked [`MapChart`]: cells, contours, hatching, axes, markers, legend and
//! colour bar, in that order (later on top).

use super::{
    Contours, MapChart, MapLayout, BAR_LABELS, HATCH, KILO, MARGIN_BOTTOM, MARGIN_LEFT,
    MARGIN_RIGHT, WASH, X_LABEL_AREA, Y_LABEL_AREA,
};
use crate::chart::axis::Scale;
use crate::chart::colour::Rgb;
use crate::chart::draw::{self, clip_polyline, drawing_error, font, round_all, Area, LABEL_PX};
use crate::chart::legend::legend_box;
use crate::chart::marker::draw_marker;
use crate::chart::Frame;
use crate::error::Result;
use crate::maps::{contour, nice_levels};
use crate::math;
use plotters::backend::DrawingBackend;
use plotters::chart::ChartBuilder;
use plotters::coord::Shift;
use plotters::drawing::DrawingArea;
use plotters::element::{PathElement, Rectangle};
use plotters::style::text_anchor::{HPos, Pos, VPos};
use plotters::style::{Color, RGBAColor, RGBColor, ShapeStyle, WHITE};

/// Decimals that tell neighbouring contour levels apart: those of the smallest gap.
fn level_decimals(levels: &[f64]) -> usize {
    let gap = levels
        .windows(2)
        .map(|w| (w[1] - w[0]).abs())
        .filter(|g| *g > 0.0)
        .fold(f64::INFINITY, f64::min);
    if !gap.is_finite() {
        return 2;
    }
    (-(math::log10(gap).floor()) as i64).clamp(0, 6) as usize
}

/// `"25.00"` as `"25"`, `"0.50"` as `"0.5"`.
fn trim_zeros(s: String) -> String {
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

/// Length of a polyline, px.
fn path_length(p: &[(f64, f64)]) -> f64 {
    p.windows(2)
        .map(|w| math::hypot(w[1].0 - w[0].0, w[1].1 - w[0].1))
        .sum()
}

/// The point half-way along a polyline (by length), px.
fn point_at_half(p: &[(f64, f64)]) -> (f64, f64) {
    let mut left = path_length(p) / 2.0;
    for w in p.windows(2) {
        let d = math::hypot(w[1].0 - w[0].0, w[1].1 - w[0].1);
        if d >= left && d > 0.0 {
            let t = left / d;
            return (
                w[0].0 + t * (w[1].0 - w[0].0),
                w[0].1 + t * (w[1].1 - w[0].1),
            );
        }
        left -= d;
    }
    p[p.len() - 1]
}

/// The map as an SVG document.
pub fn map_chart_svg(chart: &MapChart) -> Result<String> {
    let layout = chart.layout()?;
    draw::render(chart.width, chart.height, |root| {
        draw_map(root, chart, &layout)
    })
}

fn style(c: Rgb, alpha: f64, width: u32) -> ShapeStyle {
    ShapeStyle {
        color: RGBAColor(c.0, c.1, c.2, alpha),
        filled: false,
        stroke_width: width,
    }
}

fn draw_map<DB: DrawingBackend>(root: &Area<DB>, chart: &MapChart, l: &MapLayout) -> Result<()> {
    let f = l.frame;
    draw::title(root, &chart.title, chart.width)?;

    // Cells: block colours, runs of equal colour along a row merged.
    let (means, infeasible) = chart.blocks(l);
    let (xs, ys) = chart.block_pixels(l);
    let (mx, my) = l.blocks;
    let colour_of = |k: usize| {
        let c = chart.colour_map.colour(l.colours.fraction(means[k]));
        if infeasible[k] {
            c.mix(WASH.0, WASH.1)
        } else {
            c
        }
    };
    for bj in 0..my {
        let mut i0 = 0;
        while i0 < mx {
            let c = colour_of(bj * mx + i0);
            let mut i1 = i0 + 1;
            while i1 < mx && colour_of(bj * mx + i1) == c {
                i1 += 1;
            }
            root.draw(&Rectangle::new(
                [
                    (xs[i0].round() as i32, ys[bj + 1].round() as i32),
                    (xs[i1].round() as i32, ys[bj].round() as i32),
                ],
                c.plotters().filled(),
            ))
            .map_err(drawing_error)?;
            i0 = i1;
        }
    }

    // Contours on the full grid: a dark halo under a light line.
    let grid = chart.grid()?;
    let levels = match &chart.contours {
        Contours::None => Vec::new(),
        Contours::Auto(n) => nice_levels(l.colours.lo, l.colours.hi, *n),
        Contours::Levels(v) => v.clone(),
    };
    let to_px = |p: &[f64; 2]| f.pixel(&l.ks, &l.cs, (p[0] * KILO, p[1] * KILO));
    let stroke_lines = |field: &[f64], level: f64, styles: &[ShapeStyle]| -> Result<()> {
        let c = contour(&grid, field, level)?;
        for line in &c.polylines {
            let px: Vec<(f64, f64)> = line.points.iter().map(to_px).collect();
            for piece in clip_polyline(&f, &px) {
                let mut pts = round_all(&piece);
                pts.dedup();
                for s in styles {
                    root.draw(&PathElement::new(pts.clone(), *s))
                        .map_err(drawing_error)?;
                }
            }
        }
        Ok(())
    };
    for &level in &levels {
        stroke_lines(
            &chart.values,
            level,
            &[
                style(Rgb(0, 0, 0), 0.35, 3),
                style(Rgb(255, 255, 255), 0.85, 1),
            ],
        )?;
    }
    // Each level's value (in the colour bar's unit) on a white tab at the middle of its
    // longest visible piece, so a printed map reads without the colour bar; a tab that
    // would overlap one already placed is left out (crowded levels keep their lines).
    let decimals = level_decimals(&levels);
    let mut placed: Vec<[i32; 4]> = Vec::new();
    let tab = font(LABEL_PX - 1.0, false).pos(Pos::new(HPos::Center, VPos::Center));
    for &level in &levels {
        let c = contour(&grid, &chart.values, level)?;
        let longest = c
            .polylines
            .iter()
            .flat_map(|line| {
                let px: Vec<(f64, f64)> = line.points.iter().map(to_px).collect();
                clip_polyline(&f, &px)
            })
            .max_by(|a, b| path_length(a).total_cmp(&path_length(b)));
        let Some(piece) = longest.filter(|p| path_length(p) > 60.0) else {
            continue;
        };
        let (x, y) = point_at_half(&piece);
        let text = trim_zeros(format!("{:.*}", decimals, level));
        let half_w = (3.6 * text.len() as f64 + 3.0).round() as i32;
        let (x, y) = (x.round() as i32, y.round() as i32);
        let rect = [x - half_w - 2, y - 10, x + half_w + 2, y + 10];
        if placed
            .iter()
            .any(|r| rect[0] < r[2] && r[0] < rect[2] && rect[1] < r[3] && r[1] < rect[3])
        {
            continue;
        }
        placed.push(rect);
        root.draw(&Rectangle::new(
            [(x - half_w, y - 8), (x + half_w, y + 8)],
            WHITE.mix(0.85).filled(),
        ))
        .map_err(drawing_error)?;
        root.draw_text(&text, &tab, (x, y)).map_err(drawing_error)?;
    }

    // The infeasible area: hatched over the wash; its boundary on the full grid.
    hatch(root, &f, &xs, &ys, mx, &infeasible)?;
    if let Some(mask) = &chart.feasible {
        if mask.contains(&0) && mask.contains(&1) {
            let field: Vec<f64> = mask.iter().map(|&m| f64::from(m)).collect();
            stroke_lines(
                &field,
                0.5,
                &[
                    style(Rgb(255, 255, 255), 1.0, 4),
                    style(Rgb(0, 0, 0), 1.0, 2),
                ],
            )?;
        }
    }

    map_axes(root, chart, l)?;

    // Markers inside the box, and the legend of the labelled ones (see chart::legend).
    let mut labelled = Vec::new();
    for (k, m) in chart.markers.iter().enumerate() {
        let p = f.pixel(&l.ks, &l.cs, (m.ks * KILO, m.cs * KILO));
        if !f.contains(p) {
            continue;
        }
        let fill = match &m.colour {
            Some(c) => Rgb::parse(&format!("markers[{k}].colour"), c)?,
            None => Rgb(255, 255, 255),
        };
        let size = m.size.unwrap_or(6.0);
        draw_marker(root, p, m.shape, size, fill, Some(Rgb(0, 0, 0)))?;
        if !m.label.is_empty() {
            labelled.push((m, fill, size));
        }
    }
    root.draw(&Rectangle::new(
        [(f.left, f.top), (f.right, f.bottom)],
        style(Rgb(51, 51, 51), 1.0, 1),
    ))
    .map_err(drawing_error)?;
    let names: Vec<&str> = labelled.iter().map(|(m, _, _)| m.label.as_str()).collect();
    let rows = legend_box(root, chart.legend, &f, &names)?;
    for (r, (m, fill, size)) in rows.iter().zip(&labelled) {
        let at = (f64::from(r.centre), f64::from(r.y));
        draw_marker(root, at, m.shape, size.min(7.0), *fill, Some(Rgb(0, 0, 0)))?;
    }
    colour_bar(root, chart, l)
}

/// The Ks and Cs axes of the map: ticks, tick labels and axis descriptions (in kN/m and
/// kNs/m), no grid.
fn map_axes<DB: DrawingBackend>(root: &Area<DB>, chart: &MapChart, l: &MapLayout) -> Result<()> {
    let f = l.frame;
    let mut cc = ChartBuilder::on(root)
        .margin_top(f.top as u32)
        .margin_left(MARGIN_LEFT)
        .margin_right(chart.width - f.right as u32 - 1)
        .margin_bottom(MARGIN_BOTTOM)
        .x_label_area_size(X_LABEL_AREA)
        .y_label_area_size(Y_LABEL_AREA)
        .build_cartesian_2d(l.ks, l.cs)
        .map_err(drawing_error)?;
    debug_assert_eq!(
        cc.plotting_area().get_pixel_range(),
        (f.left..f.right + 1, f.top..f.bottom + 1)
    );
    let nx = ((f.right - f.left) / 55).clamp(2, 10) as usize;
    let ny = ((f.bottom - f.top) / 40).clamp(2, 10) as usize;
    let (xt, yt) = (l.ks.ticks(nx), l.cs.ticks(ny));
    let fx = |v: &f64| l.ks.label(*v, &xt);
    let fy = |v: &f64| l.cs.label(*v, &yt);
    cc.configure_mesh()
        .disable_mesh()
        .x_labels(nx)
        .y_labels(ny)
        .x_label_formatter(&fx)
        .y_label_formatter(&fy)
        .label_style(font(draw::LABEL_PX, false))
        .axis_desc_style(font(draw::DESC_PX, false))
        .x_desc("Ks front spring [kN/m]")
        .y_desc("Cs front damper [kNs/m]")
        .axis_style(RGBColor(51, 51, 51))
        .draw()
        .map_err(drawing_error)?;
    Ok(())
}

/// Draws the map's frame on `root` (an area of `chart.width` x `chart.height` px, its
/// background filled by the caller): the title, the axes with their ticks and labels and
/// the colour bar with its ticks and unit; not the cells, contours, hatching or markers.
/// The page draws those itself from its RGBA buffer, inside the returned layout's frame.
pub fn draw_map_frame<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    chart: &MapChart,
) -> Result<MapLayout> {
    let l = chart.layout()?;
    draw::title(root, &chart.title, chart.width)?;
    map_axes(root, chart, &l)?;
    colour_bar(root, chart, &l)?;
    Ok(l)
}

/// Diagonal hatching (rows grow down: lines `x + y = c`, `c` a multiple of the spacing)
/// over the infeasible blocks: each line is walked through the block grid and drawn
/// where it crosses infeasible blocks, one segment per unbroken stretch.
fn hatch<DB: DrawingBackend>(
    root: &Area<DB>,
    f: &Frame,
    xs: &[f64],
    ys: &[f64],
    mx: usize,
    infeasible: &[bool],
) -> Result<()> {
    if !infeasible.contains(&true) {
        return Ok(());
    }
    let (gap, line) = (HATCH.1, style(HATCH.0, 1.0, 1));
    let (left, right) = (f64::from(f.left), f64::from(f.right));
    let (top, bottom) = (f64::from(f.top), f64::from(f.bottom));
    let my = ys.len() - 1;
    let bad = |x: f64, y: f64| {
        let i = xs.partition_point(|&e| e <= x).clamp(1, mx) - 1;
        let j = ys.partition_point(|&e| e > y).clamp(1, my) - 1;
        infeasible[j * mx + i]
    };
    let k0 = ((left + top) / gap).ceil() as i64;
    let k1 = ((right + bottom) / gap).floor() as i64;
    for k in k0..=k1 {
        let c = k as f64 * gap;
        let (a, b) = (left.max(c - bottom), right.min(c - top));
        if b - a < 1e-9 {
            continue;
        }
        let mut cuts: Vec<f64> = xs
            .iter()
            .copied()
            .chain(ys.iter().map(|&y| c - y))
            .filter(|&x| x > a && x < b)
            .collect();
        cuts.push(a);
        cuts.push(b);
        crate::order::sort_by_f64_key(&mut cuts, |x| *x);
        let mut start: Option<f64> = None;
        for w in cuts.windows(2) {
            if w[1] - w[0] < 1e-9 {
                continue;
            }
            let m = 0.5 * (w[0] + w[1]);
            match (bad(m, c - m), start) {
                (true, None) => start = Some(w[0]),
                (false, Some(s)) => {
                    draw_segment(root, (s, c - s), (w[0], c - w[0]), line)?;
                    start = None;
                }
                _ => {}
            }
        }
        if let Some(s) = start {
            draw_segment(root, (s, c - s), (b, c - b), line)?;
        }
    }
    Ok(())
}

fn draw_segment<DB: DrawingBackend>(
    root: &Area<DB>,
    a: (f64, f64),
    b: (f64, f64),
    s: ShapeStyle,
) -> Result<()> {
    root.draw(&PathElement::new(round_all(&[a, b]), s))
        .map_err(drawing_error)
}

/// The colour bar: the colour map in 64 steps from the range's low end (bottom) to its
/// high end, ticks at round values, the unit along its right side.
fn colour_bar<DB: DrawingBackend>(root: &Area<DB>, chart: &MapChart, l: &MapLayout) -> Result<()> {
    const STEPS: usize = 64;
    let (bar, s) = (l.bar, l.colours);
    let row = |t: f64| (f64::from(bar.bottom) + t * f64::from(bar.top - bar.bottom)).round() as i32;
    for k in 0..STEPS {
        let (t0, t1) = (k as f64 / STEPS as f64, (k + 1) as f64 / STEPS as f64);
        let c = chart.colour_map.colour(0.5 * (t0 + t1));
        root.draw(&Rectangle::new(
            [(bar.left, row(t1)), (bar.right + 1, row(t0))],
            c.plotters().filled(),
        ))
        .map_err(drawing_error)?;
    }
    let mut cc = ChartBuilder::on(root)
        .margin_top(bar.top as u32)
        .margin_bottom(chart.height - bar.bottom as u32 - 1)
        .margin_left(bar.left as u32)
        .margin_right(MARGIN_RIGHT)
        .right_y_label_area_size(BAR_LABELS)
        .build_cartesian_2d(Scale::new("range", 0.0, 1.0, false)?, s)
        .map_err(drawing_error)?;
    let ticks = l.bar_ticks();
    let fy = |v: &f64| s.label(*v, &ticks);
    cc.configure_mesh()
        .disable_mesh()
        .disable_x_axis()
        .y_labels(l.bar_tick_count())
        .y_label_formatter(&fy)
        .label_style(font(draw::LABEL_PX, false))
        .axis_desc_style(font(draw::DESC_PX, false))
        .y_desc(chart.unit.as_str())
        .axis_style(RGBColor(51, 51, 51))
        .draw()
        .map_err(drawing_error)?;
    root.draw(&Rectangle::new(
        [(bar.left, bar.top), (bar.right + 1, bar.bottom)],
        style(Rgb(51, 51, 51), 1.0, 1),
    ))
    .map_err(drawing_error)
}
