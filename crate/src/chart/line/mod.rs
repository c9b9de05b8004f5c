//! Line and scatter charts: series of `(x, y)` points drawn as lines, dots or markers on
//! linear or log10 axes with ticks, axis labels (with units) and a legend.
//!
//! Layout, px: the plot spans from `left = 80` to `right = width - 21` and from
//! `top = 34` (12 without a title) to `bottom = height - 53`; see [`LineChart::layout`].

use super::axis::Scale;
use super::colour::Rgb;
use super::draw::{
    self, clip_polyline, drawing_error, font, round_all, simplify, Area, SIMPLIFY_PX,
};
use super::legend::legend_box;
use super::marker::{draw_marker, Legend, MarkerShape};
use super::{check_size, Frame};
use crate::error::{Result, RideError};
use plotters::backend::DrawingBackend;
use plotters::chart::ChartBuilder;
use plotters::coord::Shift;
use plotters::drawing::DrawingArea;
use plotters::element::{Circle, PathElement, Rectangle};
use plotters::style::{Color, RGBAColor, RGBColor, ShapeStyle};
use serde::{Deserialize, Serialize};
use std::collections::HashSet;

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub enum SeriesStyle {
    /// A polyline through the points in order (`size`: width, px, default 2).
    #[default]
    Line,
    /// A small disc at each point (`size`: radius, px, default 2); points that land on
    /// the same pixel are drawn once.
    Dots,
    /// A marker of this shape at each point (`size`: px, default 6), outlined with
    /// `stroke` when given. JS: `{markers: "diamond"}`.
    Markers(MarkerShape),
}

/// One series of a [`LineChart`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase", deny_unknown_fields)]
pub struct Series {
    /// Legend label; an empty name keeps the series out of the legend.
    #[serde(default)]
    pub name: String,
    /// `#rrggbb`.
    #[serde(alias = "color")]
    pub colour: String,
    /// The data, `(x, y)` in the axes' units; finite, and `> 0` on a log axis. A series
    /// without points is drawn in the legend only (for data the caller draws itself).
    pub points: Vec<(f64, f64)>,
    /// Line, dots or markers (default line).
    #[serde(default)]
    pub style: SeriesStyle,
    /// Line width, dot radius or marker size, px (defaults: 2, 2, 6).
    #[serde(default)]
    pub size: Option<f64>,
    /// Marker outline colour, `#rrggbb` (markers only; default none).
    #[serde(default)]
    pub stroke: Option<String>,
    /// Opacity of lines and dots, 0..=1 (default 1).
    #[serde(default)]
    pub opacity: Option<f64>,
}

impl Series {
    /// The JS keys of a series (`color` is accepted for `colour`).
    pub const FIELDS: [&'static str; 8] = [
        "name", "colour", "color", "points", "style", "size", "stroke", "opacity",
    ];

    /// A line series with the default width.
    pub fn new(name: &str, colour: &str, points: Vec<(f64, f64)>) -> Series {
        Series {
            name: name.into(),
            colour: colour.into(),
            points,
            style: SeriesStyle::Line,
            size: None,
            stroke: None,
            opacity: None,
        }
    }

    /// The same series drawn in `style`.
    pub(crate) fn with_style(mut self, style: SeriesStyle) -> Series {
        self.style = style;
        self
    }

    /// The same series with `size` (px).
    pub(crate) fn with_size(mut self, size: f64) -> Series {
        self.size = Some(size);
        self
    }

    /// The same series with a marker outline.
    pub(crate) fn with_stroke(mut self, colour: &str) -> Series {
        self.stroke = Some(colour.into());
        self
    }
}

/// A chart of series over two axes. Missing JS keys take [`LineChart::default`]'s values.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase", deny_unknown_fields, default)]
pub struct LineChart {
    /// Title above the plot (none when empty).
    pub title: String,
    /// x axis label with its unit, e.g. `frequency [Hz]`.
    pub x_label: String,
    /// y axis label with its unit, e.g. `DTL [N]`.
    pub y_label: String,
    /// log10 x axis.
    pub x_log: bool,
    /// log10 y axis.
    pub y_log: bool,
    /// x axis range `[lo, hi]`; default: the data's (see [`Scale::auto`]). Data outside
    /// are clipped.
    pub x_range: Option<(f64, f64)>,
    /// y axis range `[lo, hi]`; default: the data's.
    pub y_range: Option<(f64, f64)>,
    /// Width, px (240..=4000, default 640).
    pub width: u32,
    /// Height, px (200..=4000, default 400).
    pub height: u32,
    /// Legend corner (default upper right).
    pub legend: Legend,
    /// The series, drawn in order (the first underneath).
    pub series: Vec<Series>,
}

impl Default for LineChart {
    fn default() -> Self {
        LineChart {
            title: String::new(),
            x_label: String::new(),
            y_label: String::new(),
            x_log: false,
            y_log: false,
            x_range: None,
            y_range: None,
            width: 640,
            height: 400,
            legend: Legend::UpperRight,
            series: Vec::new(),
        }
    }
}

/// Where a line chart's data go: its frame and axes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Layout {
    /// The plot rectangle, px.
    pub frame: Frame,
    /// The x axis.
    pub x: Scale,
    /// The y axis.
    pub y: Scale,
}

const MARGIN_LEFT: u32 = 10;
const MARGIN_RIGHT: u32 = 20;
const MARGIN_BOTTOM: u32 = 6;
const Y_LABEL_AREA: u32 = 70;
const X_LABEL_AREA: u32 = 46;

/// Series styles resolved from a checked spec.
struct Drawn {
    colour: Rgb,
    stroke: Option<Rgb>,
    size: f64,
    opacity: f64,
}

impl LineChart {
    /// The JS keys of a line chart spec (serde-wasm-bindgen reads only the keys it knows,
    /// so the wasm shell refuses others with this list).
    pub const FIELDS: [&'static str; 11] = [
        "title", "xLabel", "yLabel", "xLog", "yLog", "xRange", "yRange", "width", "height",
        "legend", "series",
    ];

    /// Checks the spec and places it: the frame follows from the size and the title,
    /// the axes from the ranges or the data.
    pub(crate) fn layout(&self) -> Result<Layout> {
        check_size(self.width, self.height, (240, 200))?;
        if self.series.is_empty() && (self.x_range.is_none() || self.y_range.is_none()) {
            return Err(RideError::field(
                "series",
                "no series to draw; give a series, or both xRange and yRange for empty axes",
            ));
        }
        let (mut xmin, mut xmax) = (f64::INFINITY, f64::NEG_INFINITY);
        let (mut ymin, mut ymax) = (f64::INFINITY, f64::NEG_INFINITY);
        for (k, s) in self.series.iter().enumerate() {
            for (i, &(x, y)) in s.points.iter().enumerate() {
                for (axis, v, log) in [("x", x, self.x_log), ("y", y, self.y_log)] {
                    if !v.is_finite() {
                        return Err(RideError::field(
                            format!("series[{k}].points[{i}]"),
                            format!("{axis} is {v}; every value must be a finite number"),
                        ));
                    }
                    if log && v <= 0.0 {
                        return Err(RideError::field(
                            format!("series[{k}].points[{i}]"),
                            format!("{axis} = {v} cannot be drawn on a log axis (must be > 0)"),
                        ));
                    }
                }
                xmin = xmin.min(x);
                xmax = xmax.max(x);
                ymin = ymin.min(y);
                ymax = ymax.max(y);
            }
            self.drawn(k)?;
        }
        let scale = |field: &str, range: Option<(f64, f64)>, min: f64, max: f64, log| match range {
            Some((lo, hi)) => Scale::new(field, lo, hi, log),
            None if min > max => Err(RideError::field(
                field,
                "no series has a point to take the range from; give the range or a point",
            )),
            None => Scale::auto(field, min, max, log),
        };
        let x = scale("xRange", self.x_range, xmin, xmax, self.x_log)?;
        let y = scale("yRange", self.y_range, ymin, ymax, self.y_log)?;
        let top = draw::top_space(&self.title) as i32;
        let frame = Frame {
            left: (MARGIN_LEFT + Y_LABEL_AREA) as i32,
            right: (self.width - MARGIN_RIGHT) as i32 - 1,
            top,
            bottom: (self.height - MARGIN_BOTTOM - X_LABEL_AREA) as i32 - 1,
        };
        Ok(Layout { frame, x, y })
    }

    /// The checked style of series `k`.
    fn drawn(&self, k: usize) -> Result<Drawn> {
        let s = &self.series[k];
        let colour = Rgb::parse(&format!("series[{k}].colour"), &s.colour)?;
        let stroke = match &s.stroke {
            Some(c) => Some(Rgb::parse(&format!("series[{k}].stroke"), c)?),
            None => None,
        };
        let default = match s.style {
            SeriesStyle::Line | SeriesStyle::Dots => 2.0,
            SeriesStyle::Markers(_) => 6.0,
        };
        let size = s.size.unwrap_or(default);
        if !(size.is_finite() && size > 0.0 && size <= 50.0) {
            return Err(RideError::field(
                format!("series[{k}].size"),
                format!("{size} px is outside (0, 50]"),
            ));
        }
        let opacity = s.opacity.unwrap_or(1.0);
        if !(0.0..=1.0).contains(&opacity) {
            return Err(RideError::field(
                format!("series[{k}].opacity"),
                format!("{opacity} is outside 0..=1"),
            ));
        }
        Ok(Drawn {
            colour,
            stroke,
            size,
            opacity,
        })
    }
}

fn rgba(c: Rgb, a: f64) -> RGBAColor {
    RGBAColor(c.0, c.1, c.2, a)
}

/// Whole-pixel stroke width of at least 1 for `px`.
fn stroke_px(px: f64) -> u32 {
    px.round().max(1.0) as u32
}

/// The chart as an SVG document.
pub fn line_chart_svg(chart: &LineChart) -> Result<String> {
    let layout = chart.layout()?;
    draw::render(chart.width, chart.height, |root| {
        draw_layers(root, chart, &layout, Layer::All)
    })
}

/// The parts of a line chart, drawn in this order: the page draws dense data of its own
/// (the objective plane's cloud of feasible designs) between the axes and the series.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Layer {
    /// Title, grid, ticks, tick labels and axis descriptions.
    Axes,
    /// The series, the frame around the plot and the legend.
    Series,
    /// Both.
    All,
}

/// Draws `layer` of the checked chart on `root`, an area of `chart.width` x
/// `chart.height` px whose background the caller has filled, and returns the layout
/// (where data land). Any plotters backend: the page passes its canvas.
pub fn draw_line_chart<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    chart: &LineChart,
    layer: Layer,
) -> Result<Layout> {
    let layout = chart.layout()?;
    draw_layers(root, chart, &layout, layer)?;
    Ok(layout)
}

fn draw_layers<DB: DrawingBackend>(
    root: &Area<DB>,
    chart: &LineChart,
    layout: &Layout,
    layer: Layer,
) -> Result<()> {
    let Layout {
        frame,
        x: sx,
        y: sy,
    } = *layout;
    let mut cc = ChartBuilder::on(root)
        .margin_top(frame.top as u32)
        .margin_left(MARGIN_LEFT)
        .margin_right(MARGIN_RIGHT)
        .margin_bottom(MARGIN_BOTTOM)
        .x_label_area_size(X_LABEL_AREA)
        .y_label_area_size(Y_LABEL_AREA)
        .build_cartesian_2d(sx, sy)
        .map_err(drawing_error)?;
    debug_assert_eq!(
        cc.plotting_area().get_pixel_range(),
        (frame.left..frame.right + 1, frame.top..frame.bottom + 1)
    );
    if layer != Layer::Series {
        draw::title(root, &chart.title, chart.width)?;
        let nx = ((frame.right - frame.left) / 80).clamp(2, 10) as usize;
        let ny = ((frame.bottom - frame.top) / 40).clamp(2, 10) as usize;
        let (xt, yt) = (sx.ticks(nx), sy.ticks(ny));
        let fx = |v: &f64| sx.label(*v, &xt);
        let fy = |v: &f64| sy.label(*v, &yt);
        cc.configure_mesh()
            .x_labels(nx)
            .y_labels(ny)
            .max_light_lines(0)
            .x_label_formatter(&fx)
            .y_label_formatter(&fy)
            .label_style(font(draw::LABEL_PX, false))
            .axis_desc_style(font(draw::DESC_PX, false))
            .x_desc(chart.x_label.as_str())
            .y_desc(chart.y_label.as_str())
            .bold_line_style(RGBColor(227, 230, 234))
            .axis_style(RGBColor(85, 85, 85))
            .draw()
            .map_err(drawing_error)?;
    }
    if layer == Layer::Axes {
        return Ok(());
    }

    for (k, s) in chart.series.iter().enumerate() {
        let d = chart.drawn(k)?;
        let pixels: Vec<(f64, f64)> = s.points.iter().map(|&p| frame.pixel(&sx, &sy, p)).collect();
        let colour = rgba(d.colour, d.opacity);
        match s.style {
            SeriesStyle::Line => {
                let style = ShapeStyle {
                    color: colour,
                    filled: false,
                    stroke_width: stroke_px(d.size),
                };
                for piece in clip_polyline(&frame, &pixels) {
                    let piece = simplify(&piece, SIMPLIFY_PX);
                    root.draw(&PathElement::new(round_all(&piece), style))
                        .map_err(drawing_error)?;
                }
            }
            SeriesStyle::Dots => {
                let r = stroke_px(d.size);
                let mut seen = HashSet::new();
                for p in pixels.into_iter().filter(|&p| frame.contains(p)) {
                    let at = (p.0.round() as i32, p.1.round() as i32);
                    if seen.insert(at) {
                        root.draw(&Circle::new(at, r, colour.filled()))
                            .map_err(drawing_error)?;
                    }
                }
            }
            SeriesStyle::Markers(shape) => {
                for p in pixels.into_iter().filter(|&p| frame.contains(p)) {
                    draw_marker(root, p, shape, d.size, d.colour, d.stroke)?;
                }
            }
        }
    }
    root.draw(&Rectangle::new(
        [(frame.left, frame.top), (frame.right, frame.bottom)],
        ShapeStyle::from(RGBColor(85, 85, 85)).stroke_width(1),
    ))
    .map_err(drawing_error)?;
    draw_legend(root, chart, &frame)
}

/// The legend of the named series in the chart's corner: a sample of each series' style
/// and its name (see [`super::legend`]).
fn draw_legend<DB: DrawingBackend>(
    root: &Area<DB>,
    chart: &LineChart,
    frame: &Frame,
) -> Result<()> {
    let named: Vec<usize> = (0..chart.series.len())
        .filter(|&k| !chart.series[k].name.is_empty())
        .collect();
    let names: Vec<&str> = named
        .iter()
        .map(|&k| chart.series[k].name.as_str())
        .collect();
    let rows = legend_box(root, chart.legend, frame, &names)?;
    for (r, &k) in rows.iter().zip(&named) {
        let s = &chart.series[k];
        let d = chart.drawn(k)?;
        let (xs, xc, y) = (r.left, r.centre, r.y);
        let colour = rgba(d.colour, d.opacity.max(0.6));
        match s.style {
            SeriesStyle::Line => {
                let line = ShapeStyle {
                    color: colour,
                    filled: false,
                    stroke_width: stroke_px(d.size).min(4),
                };
                root.draw(&PathElement::new(vec![(xs, y), (xs + r.width, y)], line))
                    .map_err(drawing_error)?;
            }
            SeriesStyle::Dots => {
                let r = stroke_px(d.size).clamp(2, 5);
                root.draw(&Circle::new((xc, y), r, colour.filled()))
                    .map_err(drawing_error)?;
            }
            SeriesStyle::Markers(shape) => {
                let at = (f64::from(xc), f64::from(y));
                draw_marker(root, at, shape, d.size.min(7.0), d.colour, d.stroke)?;
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests;
