//! On-screen charts: `drawLineChart(canvas, spec, scale, layer)` draws a [`LineChart`]
//! (the same spec as `lineChartSvg`) and `drawMapFrame(canvas, spec, scale)` the axes and
//! colour bar of a [`MapChart`] (the same spec as `mapChartSvg`) on a `<canvas>` with
//! plotters, through `plotters-canvas`, and return where the data land, so the page can
//! put its dense data and live markers on the same axes.
//!
//! [`ScreenBackend`] wraps `plotters_canvas::CanvasBackend` for three things it does not
//! do:
//! - **HiDPI and large type.** The chart is laid out in logical pixels (`spec.width` x
//!   `spec.height`) and the context is scaled by `scale` (devicePixelRatio times the
//!   page's type zoom), so lines and text are sharp on any screen and grow with the type.
//!   `CanvasBackend` reports the backing store's size, which would lay the chart out in
//!   device pixels.
//! - **Text measured on the canvas.** plotters on wasm32 measures text by appending a
//!   `<span>` to the body and reading its size: a forced layout of the page per tick
//!   label. Here `measureText` on the context does it without touching the document (the
//!   chart module's legends measure through the backend too).
//! - **Font size.** The chart module asks for `px * 1.24` because the SVG backend writes
//!   sizes divided by 1.24; `CanvasBackend` writes them as given, so they are scaled back.
//!
//! Like the SVG charts (see `charts`), these refuse to run without a document, before
//! anything could reach plotters' own text measure.

use super::charts::{
    chart_error, check_items, check_keys, read_map_spec, read_spec, text_measurable,
};
use crate::chart::draw::drawing_error;
use crate::chart::line::{draw_line_chart, Layer, Layout};
use crate::chart::map::draw_map_frame;
use crate::chart::{Frame, LineChart, MapChart, MapMarker, Scale, Series};
use crate::error::RideError;
use js_sys::Reflect;
use plotters::coord::Shift;
use plotters::drawing::DrawingArea;
use plotters::drawing::IntoDrawingArea;
use plotters::style::WHITE;
use plotters_backend::{text_anchor, BackendColor, BackendCoord, BackendStyle, BackendTextStyle};
use plotters_backend::{DrawingBackend, DrawingErrorKind, FontFamily, FontStyle, FontTransform};
use plotters_canvas::CanvasBackend;
use serde::Serialize;
use wasm_bindgen::prelude::*;
use wasm_bindgen::JsCast;
use web_sys::{CanvasRenderingContext2d, HtmlCanvasElement};

/// The SVG backend's font size factor undone (see the module documentation).
const SVG_FONT_FACTOR: f64 = 1.24;

/// A canvas backend of a fixed logical size in a scaled context.
struct ScreenBackend {
    canvas: CanvasBackend,
    context: CanvasRenderingContext2d,
    size: (u32, u32),
}

/// A text style with its size scaled by a factor.
struct Resized<'a, S>(&'a S, f64);

impl<S: BackendTextStyle> BackendTextStyle for Resized<'_, S> {
    type FontError = S::FontError;

    fn color(&self) -> BackendColor {
        self.0.color()
    }

    fn size(&self) -> f64 {
        self.0.size() * self.1
    }

    fn transform(&self) -> FontTransform {
        self.0.transform()
    }

    fn style(&self) -> FontStyle {
        self.0.style()
    }

    fn anchor(&self) -> text_anchor::Pos {
        self.0.anchor()
    }

    fn family(&self) -> FontFamily<'_> {
        self.0.family()
    }

    fn layout_box(&self, text: &str) -> Result<((i32, i32), (i32, i32)), S::FontError> {
        self.0.layout_box(text)
    }

    fn draw<E, F: FnMut(i32, i32, BackendColor) -> Result<(), E>>(
        &self,
        text: &str,
        pos: BackendCoord,
        draw: F,
    ) -> Result<Result<(), E>, S::FontError> {
        self.0.draw(text, pos, draw)
    }
}

/// `plotters_canvas`'s error type (not exported by name).
type CanvasError = <CanvasBackend as DrawingBackend>::ErrorType;

type Drawn = Result<(), DrawingErrorKind<CanvasError>>;

impl DrawingBackend for ScreenBackend {
    type ErrorType = CanvasError;

    fn get_size(&self) -> (u32, u32) {
        self.size
    }

    fn ensure_prepared(&mut self) -> Drawn {
        self.canvas.ensure_prepared()
    }

    fn present(&mut self) -> Drawn {
        self.canvas.present()
    }

    fn draw_pixel(&mut self, point: BackendCoord, colour: BackendColor) -> Drawn {
        self.canvas.draw_pixel(point, colour)
    }

    fn draw_line<S: BackendStyle>(&mut self, from: BackendCoord, to: BackendCoord, s: &S) -> Drawn {
        self.canvas.draw_line(from, to, s)
    }

    fn draw_rect<S: BackendStyle>(
        &mut self,
        upper_left: BackendCoord,
        bottom_right: BackendCoord,
        s: &S,
        fill: bool,
    ) -> Drawn {
        self.canvas.draw_rect(upper_left, bottom_right, s, fill)
    }

    fn draw_path<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        path: I,
        s: &S,
    ) -> Drawn {
        self.canvas.draw_path(path, s)
    }

    fn draw_circle<S: BackendStyle>(
        &mut self,
        centre: BackendCoord,
        radius: u32,
        s: &S,
        fill: bool,
    ) -> Drawn {
        self.canvas.draw_circle(centre, radius, s, fill)
    }

    fn fill_polygon<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        vert: I,
        s: &S,
    ) -> Drawn {
        self.canvas.fill_polygon(vert, s)
    }

    fn draw_text<S: BackendTextStyle>(&mut self, text: &str, s: &S, pos: BackendCoord) -> Drawn {
        self.canvas
            .draw_text(text, &Resized(s, 1.0 / SVG_FONT_FACTOR), pos)
    }

    /// Width from the context's `measureText`, height the font size (px).
    fn estimate_text_size<S: BackendTextStyle>(
        &self,
        text: &str,
        s: &S,
    ) -> Result<(u32, u32), DrawingErrorKind<CanvasError>> {
        let px = s.size() / SVG_FONT_FACTOR;
        self.context.set_font(&format!(
            "{} {}px {}",
            s.style().as_str(),
            px,
            s.family().as_str()
        ));
        let width = self
            .context
            .measure_text(text)
            .map(|m| m.width())
            .unwrap_or(px * 0.6 * text.chars().count() as f64);
        let height = match s.transform() {
            FontTransform::Rotate90 | FontTransform::Rotate270 => {
                return Ok((px.ceil() as u32, width.ceil() as u32))
            }
            _ => px,
        };
        Ok((width.ceil() as u32, height.ceil() as u32))
    }
}

/// Where a drawn chart's data land, in the chart's logical pixels.
#[derive(Serialize)]
struct Placed {
    frame: Frame,
    x: AxisOut,
    y: AxisOut,
}

#[derive(Serialize)]
struct AxisOut {
    lo: f64,
    hi: f64,
    log: bool,
}

impl From<Layout> for Placed {
    fn from(l: Layout) -> Placed {
        let axis = |s: Scale| AxisOut {
            lo: s.lo,
            hi: s.hi,
            log: s.log,
        };
        Placed {
            frame: l.frame,
            x: axis(l.x),
            y: axis(l.y),
        }
    }
}

/// Scales the 2D context of `canvas` by `scale` and runs `draw` on a drawing area of
/// `size` logical px (filled white first unless `over`).
fn on_canvas<T>(
    canvas: HtmlCanvasElement,
    scale: f64,
    size: (u32, u32),
    over: bool,
    draw: impl FnOnce(&DrawingArea<ScreenBackend, Shift>) -> crate::Result<T>,
) -> Result<T, JsValue> {
    if !(scale.is_finite() && (0.25..=16.0).contains(&scale)) {
        return Err(chart_error(RideError::field(
            "scale",
            format!("{scale} is outside 0.25..=16"),
        )));
    }
    text_measurable()?;
    let no_context = || {
        chart_error(RideError::field(
            "canvas",
            "has no 2D context (is it already used for WebGL or WebGPU?)",
        ))
    };
    let context: CanvasRenderingContext2d = canvas
        .get_context("2d")
        .ok()
        .flatten()
        .and_then(|c| c.dyn_into().ok())
        .ok_or_else(no_context)?;
    context
        .set_transform(scale, 0.0, 0.0, scale, 0.0, 0.0)
        .map_err(|_| no_context())?;
    let backend = ScreenBackend {
        canvas: CanvasBackend::with_canvas_object(canvas).ok_or_else(no_context)?,
        context,
        size,
    };
    let root = backend.into_drawing_area();
    let fail = |e| chart_error(drawing_error(e));
    if !over {
        root.fill(&WHITE).map_err(fail)?;
    }
    let out = draw(&root).map_err(chart_error)?;
    root.present().map_err(fail)?;
    Ok(out)
}

/// A value as a JS value (plain objects, not Maps).
fn to_js<T: Serialize>(value: &T) -> Result<JsValue, JsValue> {
    value
        .serialize(&serde_wasm_bindgen::Serializer::json_compatible())
        .map_err(|e| chart_error(RideError::Numerical(e.to_string())))
}

/// Draws a [`LineChart`] spec (see `lineChartSvg`) on `canvas`, laid out in
/// `spec.width` x `spec.height` logical px and scaled by `scale` (devicePixelRatio times
/// the type zoom, 0.25..=16). `layer`: `"all"`, `"axes"` (white background, title, grid,
/// ticks, labels) or `"series"` (series, frame, legend; drawn over what is there).
/// Returns `{frame: {left, right, top, bottom}, x: {lo, hi, log}, y: {lo, hi, log}}` in
/// logical px; throws an `Error` whose `field` names the spec field at fault (`layer`,
/// `scale`, `canvas` for the arguments).
#[wasm_bindgen(js_name = drawLineChart)]
pub fn draw_line_chart_js(
    canvas: HtmlCanvasElement,
    spec: JsValue,
    scale: f64,
    layer: &str,
) -> Result<JsValue, JsValue> {
    let layer = match layer {
        "all" => Layer::All,
        "axes" => Layer::Axes,
        "series" => Layer::Series,
        other => {
            return Err(chart_error(RideError::field(
                "layer",
                format!("`{other}` is not a layer; expected all, axes or series"),
            )))
        }
    };
    check_keys(&spec, "", &LineChart::FIELDS)?;
    check_items(&spec, "series", &Series::FIELDS)?;
    let chart: LineChart = read_spec(spec)?;
    chart.layout().map_err(chart_error)?;
    let size = (chart.width, chart.height);
    let layout = on_canvas(canvas, scale, size, layer == Layer::Series, |root| {
        draw_line_chart(root, &chart, layer)
    })?;
    to_js(&Placed::from(layout))
}

/// Where a drawn map frame's parts are, in logical px: the plot, the colour bar, the
/// axes (kN/m, kNs/m) and the colour range.
#[derive(Serialize)]
#[serde(rename_all = "camelCase")]
struct MapPlaced {
    frame: Frame,
    bar: Frame,
    ks: AxisOut,
    cs: AxisOut,
    colours: AxisOut,
    /// The colour bar's ticks.
    bar_ticks: Vec<f64>,
    /// The ticks strictly inside the colour range: the levels of the contour lines.
    levels: Vec<f64>,
}

/// Draws the frame of a [`MapChart`] spec (see `mapChartSvg`) on `canvas`: a white
/// background, the Ks and Cs axes with ticks and labels and the colour bar with its
/// ticks and unit (no cells, contours or markers: the page puts its RGBA map inside the
/// frame). Laid out in `spec.width` x `spec.height` logical px, scaled by `scale`.
/// Returns `{frame, bar: {left, right, top, bottom}, ks, cs, colours: {lo, hi, log},
/// barTicks: [...], levels: [...], contours: [Float64Array, ...]}`: `levels` are the
/// colour bar's ticks strictly inside the colour range (by 1e-9 of its span), `contours`
/// the lines of `spec.values` at each, as `contourSegments` gives them. The map's data
/// go one way: the page sends its values once, with the spec, and gets the frame's
/// placement and the contour lines to draw in it back (before, the values went back to
/// the core a second time for the lines at the ticks this call had chosen).
/// Errors as `drawLineChart`'s.
#[wasm_bindgen(js_name = drawMapFrame)]
pub fn draw_map_frame_js(
    canvas: HtmlCanvasElement,
    spec: JsValue,
    scale: f64,
) -> Result<JsValue, JsValue> {
    check_keys(&spec, "", &MapChart::FIELDS)?;
    check_items(&spec, "markers", &MapMarker::FIELDS)?;
    let design_box = Reflect::get(&spec, &"designBox".into()).unwrap_or(JsValue::UNDEFINED);
    check_keys(&design_box, "designBox", &MapChart::BOX_FIELDS)?;
    let chart = read_map_spec(spec)?;
    let l = chart.layout().map_err(chart_error)?;
    on_canvas(canvas, scale, (chart.width, chart.height), false, |root| {
        draw_map_frame(root, &chart).map(drop)
    })?;
    let axis = |s: Scale| AxisOut {
        lo: s.lo,
        hi: s.hi,
        log: s.log,
    };
    let (lo, hi) = chart.range.unwrap_or((l.colours.lo, l.colours.hi));
    let span = hi - lo;
    let ticks = l.bar_ticks();
    let levels: Vec<f64> = ticks
        .iter()
        .copied()
        .filter(|&t| t > lo + 1e-9 * span && t < hi - 1e-9 * span)
        .collect();
    let contours = super::contour_segments_js(&chart.values, chart.nx, chart.ny, &levels)?;
    let placed = to_js(&MapPlaced {
        frame: l.frame,
        bar: l.bar,
        ks: axis(l.ks),
        cs: axis(l.cs),
        colours: axis(l.colours),
        bar_ticks: ticks,
        levels,
    })?;
    Reflect::set(&placed, &"contours".into(), &contours)?;
    Ok(placed)
}
