//! Marker shapes (as small polygons around their centre) and legend placement.

use super::colour::Rgb;
use super::draw::Area;
use crate::error::Result;
use crate::math;
use plotters::backend::DrawingBackend;
use plotters::element::{PathElement, Polygon};
use plotters::style::{Color, ShapeStyle};
use serde::{Deserialize, Serialize};

/// The shape of a marker.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum MarkerShape {
    /// A disc (a 16-gon).
    #[default]
    Circle,
    /// An axis-aligned square of half side `size`.
    Square,
    /// A square on its corner, half diagonal `1.3 size` (the page's diamond).
    Diamond,
    /// An upward triangle.
    Triangle,
    /// A diagonal cross.
    Cross,
}

impl MarkerShape {
    /// The outline of the shape of size `r` px around `(0, 0)` (SVG rows grow down),
    /// as pixel offsets.
    pub fn outline(self, r: f64) -> Vec<(f64, f64)> {
        match self {
            MarkerShape::Circle => (0..16)
                .map(|k| {
                    let a = std::f64::consts::PI * k as f64 / 8.0;
                    (r * math::cos(a), r * math::sin(a))
                })
                .collect(),
            MarkerShape::Square => vec![(-r, -r), (r, -r), (r, r), (-r, r)],
            MarkerShape::Diamond => {
                let d = 1.3 * r;
                vec![(0.0, -d), (d, 0.0), (0.0, d), (-d, 0.0)]
            }
            MarkerShape::Triangle => {
                let h = 1.2 * r;
                vec![(0.0, -h), (h, 0.8 * h), (-h, 0.8 * h)]
            }
            MarkerShape::Cross => {
                // An X of arms half a marker wide.
                let (a, w) = (r, 0.35 * r);
                vec![
                    (-a, -a + w),
                    (-a + w, -a),
                    (0.0, -w),
                    (a - w, -a),
                    (a, -a + w),
                    (w, 0.0),
                    (a, a - w),
                    (a - w, a),
                    (0.0, w),
                    (-a + w, a),
                    (-a, a - w),
                    (-w, 0.0),
                ]
            }
        }
    }
}

/// Where a chart's legend goes (inside the plot), or none.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub enum Legend {
    /// Top right corner of the plot.
    #[default]
    UpperRight,
    /// Top left corner.
    UpperLeft,
    /// Bottom right corner.
    LowerRight,
    /// Bottom left corner.
    LowerLeft,
    /// No legend.
    None,
}

/// The marker polygon at pixel `(x, y)`, rounded once: filled with `fill`, outlined with
/// `stroke` (1.5 px wide, drawn 2 px: the backend's widths are whole pixels).
pub(crate) fn draw_marker<DB: DrawingBackend>(
    area: &Area<DB>,
    (x, y): (f64, f64),
    shape: MarkerShape,
    r: f64,
    fill: Rgb,
    stroke: Option<Rgb>,
) -> Result<()> {
    let pts: Vec<(i32, i32)> = shape
        .outline(r)
        .into_iter()
        .map(|(dx, dy)| ((x + dx).round() as i32, (y + dy).round() as i32))
        .collect();
    area.draw(&Polygon::new(pts.clone(), fill.plotters().filled()))
        .map_err(super::draw::drawing_error)?;
    if let Some(s) = stroke {
        let mut closed = pts;
        closed.push(closed[0]);
        area.draw(&PathElement::new(
            closed,
            ShapeStyle::from(s.plotters()).stroke_width(2),
        ))
        .map_err(super::draw::drawing_error)?;
    }
    Ok(())
}
