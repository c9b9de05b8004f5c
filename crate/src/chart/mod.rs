//! Charts drawn with the `plotters` crate: line and scatter charts ([`LineChart`]:
//! objective plane, FRF / PSD plots, time responses) and design maps ([`MapChart`]: a
//! criterion over Ks x Cs with contours, the infeasible area hatched, markers and a colour
//! bar). Plain Rust, generic over the plotters backend: as SVG documents through plotters'
//! SVG backend (the CLI writes them to files, the page exports them through `web::charts`),
//! and on the page's canvas ([`line::draw_line_chart`] by layers, [`map::draw_map_frame`]
//! for a map's axes and colour bar) through the wasm shell (`web::screen`).
//!
//! Specs deserialise from the page's plain JS objects (camelCase keys, unknown keys
//! refused); every error is a [`RideError::Field`] naming the spec field at fault by its
//! JS name (`series[1].points[7]`, `yRange`, `values`, ...). Nothing here panics on bad
//! input.
//!
//! Geometry is in pixels of the SVG (`width` x `height`, origin top left). Layout is fixed
//! (margins and label areas in px, not measured), so a chart's [`Frame`] (the pixels of
//! its axis ends) follows from its size alone and data points land at
//! `round(p0 + t (p1 - p0))` (see [`axis`]).
//!
//! ```
//! use ridelab::chart::{line_chart_svg, LineChart, Series, SeriesStyle};
//!
//! let chart = LineChart {
//!     title: "Body acceleration".into(),
//!     x_label: "frequency [Hz]".into(),
//!     y_label: "PSD BAcc [(m/s^2)^2/Hz]".into(),
//!     x_log: true,
//!     y_log: true,
//!     series: vec![Series::new("LoFi", "#1d4ed8", vec![(0.1, 1e-4), (1.0, 0.2), (10.0, 3e-3)])],
//!     ..LineChart::default()
//! };
//! let svg = line_chart_svg(&chart)?;
//! assert!(svg.starts_with("<svg") && svg.contains("frequency [Hz]"));
//! # Ok::<(), ridelab::RideError>(())
//! ```

pub mod axis;
pub mod colour;
pub(crate) mod draw;
mod legend;
pub mod line;
pub mod map;
pub mod marker;
pub mod report;
#[cfg(test)]
mod svgcheck;

pub use axis::Scale;
pub use colour::{ColourMap, Rgb};
pub use line::{line_chart_svg, LineChart, Series, SeriesStyle};
pub use map::{map_chart_svg, Contours, MapChart, MapMarker, Sampling, MAX_CELLS};
pub use marker::{Legend, MarkerShape};
pub use report::{front_chart, map_report_charts};

use crate::error::{Result, RideError};
use serde::Serialize;

/// The plot rectangle of a chart: the pixels (SVG user units) where the axis ends are
/// drawn. A value at fraction `t` of the x axis lands at `left + t (right - left)`, one at
/// fraction `t` of the y axis at `bottom + t (top - bottom)`, both rounded.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct Frame {
    /// Pixel column of the x axis' low end.
    pub left: i32,
    /// Pixel column of the x axis' high end.
    pub right: i32,
    /// Pixel row of the y axis' high end.
    pub top: i32,
    /// Pixel row of the y axis' low end.
    pub bottom: i32,
}

impl Frame {
    /// Unrounded pixel `(column, row)` of the data point `(x, y)` on scales `sx`, `sy`.
    pub fn pixel(&self, sx: &Scale, sy: &Scale, (x, y): (f64, f64)) -> (f64, f64) {
        (
            sx.pixel(x, (self.left, self.right)),
            sy.pixel(y, (self.bottom, self.top)),
        )
    }

    /// True when the unrounded pixel `p` lies inside (or on) the frame.
    pub fn contains(&self, p: (f64, f64)) -> bool {
        let eps = 1e-6;
        p.0 >= f64::from(self.left) - eps
            && p.0 <= f64::from(self.right) + eps
            && p.1 >= f64::from(self.top) - eps
            && p.1 <= f64::from(self.bottom) + eps
    }
}

/// Checks a chart size: whole pixels from `min` to 4000 each way; errors name
/// `width` or `height`.
pub(crate) fn check_size(width: u32, height: u32, min: (u32, u32)) -> Result<()> {
    for (field, v, lo) in [("width", width, min.0), ("height", height, min.1)] {
        if !(lo..=MAX_SIZE).contains(&v) {
            return Err(RideError::field(
                field,
                format!("{v} px is outside {lo}..={MAX_SIZE} px"),
            ));
        }
    }
    Ok(())
}

/// Largest chart width or height, px.
const MAX_SIZE: u32 = 4000;
