//! Drawing helpers shared by the charts: the SVG root, fonts, titles, error conversion
//! and clipping of polylines to the plot frame (in pixels).

use super::Frame;
use crate::error::{Result, RideError};
use crate::math;
use plotters::backend::{DrawingBackend, SVGBackend};
use plotters::coord::Shift;
use plotters::drawing::{DrawingArea, DrawingAreaErrorKind, IntoDrawingArea};
use plotters::style::text_anchor::{HPos, Pos, VPos};
use plotters::style::{FontDesc, FontFamily, FontStyle, TextStyle, WHITE};
use plotters_backend::{BackendColor, BackendCoord, BackendStyle, BackendTextStyle};

/// A drawing area in plain pixel coordinates on any plotters backend (the SVG backend
/// for documents, the page's canvas for the screen).
pub(crate) type Area<DB> = DrawingArea<DB, Shift>;

/// Pixels above the plot when the chart has a title (the title's row and a gap).
pub(crate) const TITLE_SPACE: u32 = 34;
/// Pixels above the plot without a title.
pub(crate) const TOP_MARGIN: u32 = 12;

/// A backend error as a core error (the string backend does not fail in practice).
pub(crate) fn drawing_error<E: std::error::Error + Send + Sync>(
    e: DrawingAreaErrorKind<E>,
) -> RideError {
    RideError::Numerical(format!("drawing the chart failed: {e}"))
}

/// Sans-serif text of `px` pixels. plotters writes `font-size` as the requested size
/// over 1.24, so the request is scaled up by that factor.
pub(crate) fn font(px: f64, bold: bool) -> TextStyle<'static> {
    let style = if bold {
        FontStyle::Bold
    } else {
        FontStyle::Normal
    };
    TextStyle::from(FontDesc::new(FontFamily::SansSerif, px * 1.24, style))
}

/// Tick label size, px.
pub(crate) const LABEL_PX: f64 = 12.0;
/// Axis description size, px.
pub(crate) const DESC_PX: f64 = 14.0;
/// Title size, px.
pub(crate) const TITLE_PX: f64 = 16.0;

/// plotters' SVG backend with one text metric everywhere. The SVG backend cannot know
/// how wide a viewer will draw a text; plotters estimates it natively with a fixed
/// advance per byte, but on wasm32 it measures through the page's DOM (and fails without
/// one, in a Web Worker). This wrapper always uses the native estimate, so an SVG is the
/// same document natively, on the page's main thread and in a worker.
pub(crate) struct SvgDocument<'a>(SVGBackend<'a>);

/// plotters' native text box of `text` at font size `size` (plotters-0.3.7
/// `style/font/naive.rs`): `em = size / 1.24^2`, width `round(0.7 em bytes)`, height
/// `round(em) + round(0.24 em)`.
fn naive_text_size(text: &str, size: f64) -> (u32, u32) {
    let em = size / 1.24 / 1.24;
    (
        (em * 0.7 * text.len() as f64).round() as u32,
        (em.round() + (em * 0.24).round()) as u32,
    )
}

type SvgError = <SVGBackend<'static> as DrawingBackend>::ErrorType;
type SvgDrawn = std::result::Result<(), plotters_backend::DrawingErrorKind<SvgError>>;

impl DrawingBackend for SvgDocument<'_> {
    type ErrorType = SvgError;

    fn get_size(&self) -> (u32, u32) {
        self.0.get_size()
    }
    fn ensure_prepared(&mut self) -> SvgDrawn {
        self.0.ensure_prepared()
    }
    fn present(&mut self) -> SvgDrawn {
        self.0.present()
    }
    fn draw_pixel(&mut self, p: BackendCoord, c: BackendColor) -> SvgDrawn {
        self.0.draw_pixel(p, c)
    }
    fn draw_line<S: BackendStyle>(&mut self, a: BackendCoord, b: BackendCoord, s: &S) -> SvgDrawn {
        self.0.draw_line(a, b, s)
    }
    fn draw_rect<S: BackendStyle>(
        &mut self,
        a: BackendCoord,
        b: BackendCoord,
        s: &S,
        fill: bool,
    ) -> SvgDrawn {
        self.0.draw_rect(a, b, s, fill)
    }
    fn draw_path<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        path: I,
        s: &S,
    ) -> SvgDrawn {
        self.0.draw_path(path, s)
    }
    fn draw_circle<S: BackendStyle>(
        &mut self,
        centre: BackendCoord,
        radius: u32,
        s: &S,
        fill: bool,
    ) -> SvgDrawn {
        self.0.draw_circle(centre, radius, s, fill)
    }
    fn fill_polygon<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        vertices: I,
        s: &S,
    ) -> SvgDrawn {
        self.0.fill_polygon(vertices, s)
    }
    fn draw_text<T: BackendTextStyle>(&mut self, text: &str, s: &T, pos: BackendCoord) -> SvgDrawn {
        self.0.draw_text(text, s, pos)
    }
    fn estimate_text_size<T: BackendTextStyle>(
        &self,
        text: &str,
        s: &T,
    ) -> std::result::Result<(u32, u32), plotters_backend::DrawingErrorKind<SvgError>> {
        Ok(naive_text_size(text, s.size()))
    }
    fn blit_bitmap(&mut self, pos: BackendCoord, size: (u32, u32), src: &[u8]) -> SvgDrawn {
        self.0.blit_bitmap(pos, size, src)
    }
}

/// Draws an SVG document of `width` x `height` px on a white background with `draw`.
pub(crate) fn render(
    width: u32,
    height: u32,
    draw: impl FnOnce(&Area<SvgDocument<'_>>) -> Result<()>,
) -> Result<String> {
    let mut buf = String::new();
    {
        let root =
            SvgDocument(SVGBackend::with_string(&mut buf, (width, height))).into_drawing_area();
        root.fill(&WHITE).map_err(drawing_error)?;
        draw(&root)?;
        root.present().map_err(drawing_error)?;
    }
    // Map cells are abutting rectangles; anti-aliased edges would show the background
    // through every seam as a fine white grid, so rectangles are drawn with crisp edges
    // (lines and text stay anti-aliased).
    if let Some(end) = buf.find('>') {
        buf.insert_str(end + 1, "\n<style>rect{shape-rendering:crispEdges}</style>");
    }
    Ok(buf)
}

/// The chart title, centred in the top row (nothing for an empty title).
pub(crate) fn title<DB: DrawingBackend>(root: &Area<DB>, text: &str, width: u32) -> Result<()> {
    if text.is_empty() {
        return Ok(());
    }
    let style = font(TITLE_PX, true).pos(Pos::new(HPos::Center, VPos::Top));
    root.draw_text(text, &style, ((width / 2) as i32, 9))
        .map_err(drawing_error)
}

/// Pixels above the plot for a chart with this title.
pub(crate) fn top_space(title: &str) -> u32 {
    if title.is_empty() {
        TOP_MARGIN
    } else {
        TITLE_SPACE
    }
}

/// The pieces of the polyline `points` (unrounded pixels) inside `frame`, cut where the
/// line leaves and enters it (Liang-Barsky on each segment). A polyline wholly inside
/// comes back whole, one piece with every point.
pub(crate) fn clip_polyline(frame: &Frame, points: &[(f64, f64)]) -> Vec<Vec<(f64, f64)>> {
    let (x0, x1) = (f64::from(frame.left), f64::from(frame.right));
    let (y0, y1) = (f64::from(frame.top), f64::from(frame.bottom));
    let mut out = Vec::new();
    let mut cur: Vec<(f64, f64)> = Vec::new();
    let flush = |cur: &mut Vec<(f64, f64)>, out: &mut Vec<Vec<(f64, f64)>>| {
        if cur.len() >= 2 {
            out.push(std::mem::take(cur));
        } else {
            cur.clear();
        }
    };
    for w in points.windows(2) {
        let (a, b) = (w[0], w[1]);
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let (mut t0, mut t1) = (0.0f64, 1.0f64);
        let mut visible = true;
        for (p, q) in [
            (-dx, a.0 - x0),
            (dx, x1 - a.0),
            (-dy, a.1 - y0),
            (dy, y1 - a.1),
        ] {
            if p == 0.0 {
                if q < -1e-9 {
                    visible = false;
                }
            } else {
                let r = q / p;
                if p < 0.0 {
                    t0 = t0.max(r);
                } else {
                    t1 = t1.min(r);
                }
            }
        }
        if !visible || t0 > t1 {
            flush(&mut cur, &mut out);
            continue;
        }
        let at = |t: f64| (a.0 + t * dx, a.1 + t * dy);
        if t0 > 0.0 || cur.is_empty() {
            flush(&mut cur, &mut out);
            cur.push(if t0 > 0.0 { at(t0) } else { a });
        }
        cur.push(if t1 < 1.0 { at(t1) } else { b });
        if t1 < 1.0 {
            flush(&mut cur, &mut out);
        }
    }
    flush(&mut cur, &mut out);
    out
}

/// How far a dropped vertex may lie from the simplified polyline, px.
pub(crate) const SIMPLIFY_PX: f64 = 0.5;

/// The polyline `points` (unrounded pixels) with the vertices dropped that lie within
/// `tol` px of the line through the ones kept (Ramer-Douglas-Peucker). Backends draw at
/// whole pixels; a smooth curve sampled more densely than that, with each vertex rounded,
/// draws as a staircase on a HiDPI canvas. With near-collinear vertices dropped, the
/// rounding error spreads over long segments. Peaks of noisy data stand out by more than
/// `tol` and stay. The ends are always kept.
pub(crate) fn simplify(points: &[(f64, f64)], tol: f64) -> Vec<(f64, f64)> {
    let n = points.len();
    if n < 3 {
        return points.to_vec();
    }
    let mut keep = vec![false; n];
    keep[0] = true;
    keep[n - 1] = true;
    let mut stack = vec![(0usize, n - 1)];
    while let Some((a, b)) = stack.pop() {
        let (p, q) = (points[a], points[b]);
        let (dx, dy) = (q.0 - p.0, q.1 - p.1);
        let len = math::hypot(dx, dy);
        let mut worst = (0.0f64, a);
        for (k, r) in points.iter().enumerate().take(b).skip(a + 1) {
            // Distance to the segment's line, or to `p` when the segment is a point.
            let d = if len > 0.0 {
                ((r.0 - p.0) * dy - (r.1 - p.1) * dx).abs() / len
            } else {
                math::hypot(r.0 - p.0, r.1 - p.1)
            };
            if d > worst.0 {
                worst = (d, k);
            }
        }
        if worst.0 > tol {
            keep[worst.1] = true;
            stack.push((a, worst.1));
            stack.push((worst.1, b));
        }
    }
    points
        .iter()
        .zip(keep)
        .filter_map(|(&p, k)| k.then_some(p))
        .collect()
}

/// Rounds pixels for the backend.
pub(crate) fn round_all(points: &[(f64, f64)]) -> Vec<(i32, i32)> {
    points
        .iter()
        .map(|&(x, y)| (x.round() as i32, y.round() as i32))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::super::svgcheck::farthest_from;
    use super::*;

    #[test]
    fn simplifying_keeps_every_point_within_the_tolerance() {
        // A straight line of 500 points: its ends only.
        let line: Vec<(f64, f64)> = (0..500)
            .map(|i| (i as f64 * 0.7, 3.0 + i as f64 * 0.2))
            .collect();
        assert_eq!(simplify(&line, 0.5), vec![line[0], line[499]]);
        // A smooth arc, 400 points over 300 px: far fewer vertices, none dropped
        // further than 0.5 px from what is drawn.
        let arc: Vec<(f64, f64)> = (0..400)
            .map(|i| {
                let t = i as f64 / 399.0 * 1.5;
                (150.0 + 150.0 * t.cos(), 200.0 - 150.0 * t.sin())
            })
            .collect();
        let s = simplify(&arc, 0.5);
        assert!(s.len() < 40, "{} vertices kept", s.len());
        assert_eq!((s[0], s[s.len() - 1]), (arc[0], arc[399]));
        let worst = farthest_from(&arc, &s);
        assert!(worst <= 0.5, "worst distance {worst} px");
        // A zigzag of 2 px amplitude (noisy data) keeps every peak.
        let zig: Vec<(f64, f64)> = (0..100)
            .map(|i| (i as f64, if i % 2 == 0 { 0.0 } else { 2.0 }))
            .collect();
        assert_eq!(simplify(&zig, 0.5), zig);
    }

    #[test]
    fn clipping_keeps_inside_lines_whole_and_cuts_at_the_frame() {
        let f = Frame {
            left: 0,
            right: 100,
            top: 0,
            bottom: 50,
        };
        let inside = [(0.0, 0.0), (10.0, 20.0), (100.0, 50.0)];
        assert_eq!(clip_polyline(&f, &inside), vec![inside.to_vec()]);
        // Out through the right edge and back in.
        let pieces = clip_polyline(
            &f,
            &[(50.0, 10.0), (150.0, 10.0), (50.0, 30.0), (60.0, 30.0)],
        );
        assert_eq!(pieces.len(), 2, "{pieces:?}");
        assert_eq!(pieces[0], vec![(50.0, 10.0), (100.0, 10.0)]);
        assert_eq!(pieces[1][0], (100.0, 20.0));
        assert_eq!(pieces[1][2], (60.0, 30.0));
        // Wholly outside.
        assert!(clip_polyline(&f, &[(-5.0, -5.0), (-1.0, 60.0)]).is_empty());
        // A diagonal across the whole frame from outside to outside.
        let p = clip_polyline(&f, &[(-50.0, -25.0), (150.0, 75.0)]);
        assert_eq!(p, vec![vec![(0.0, 0.0), (100.0, 50.0)]]);
    }
}
