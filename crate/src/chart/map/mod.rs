//! Design maps: a field over the Ks x Cs design box as coloured cells, contour lines,
//! the infeasible area greyed and hatched, markers, axes in kN/m and kNs/m, and a colour
//! bar with ticks and the field's unit.
//!
//! Values are laid out like the page's maps and [`crate::maps`]: row-major, Cs rows
//! (row `j = 0` at the lowest Cs) and Ks columns (`i` fast): value `(i, j)` is at
//! `j nx + i`. They sit either at the centres of `nx` x `ny` equal cells filling the box
//! (the page's maps, [`Sampling::Cells`]) or on `nx` x `ny` grid nodes from the box's
//! corner to corner (the CLI's [`crate::maps::Grid`], [`Sampling::Nodes`]; the cells
//! drawn are centred on the nodes, half cells along the edges).
//!
//! Layout, px: the plot spans from `left = 62` to `right = width - 95`, and from
//! `top = 34` (12 without a title) to `bottom = height - 53`; the colour bar from column
//! `width - 80` to `width - 65`, 8 px inside the plot's top and bottom.

use super::axis::{linear_ticks, Scale};
use super::colour::{ColourMap, Rgb};
use super::draw;
use super::marker::{Legend, MarkerShape};
use super::{check_size, Frame};
use crate::design::DesignBox;
use crate::error::{Result, RideError};
use crate::maps::{Axis, Grid};
use serde::{Deserialize, Serialize};

/// Most cells drawn across and up. One `<rect>` per cell of a 240 x 180 page map would
/// be 43 200 elements, about 4 MB of SVG and slow in any viewer; blocks of whole cells
/// (their mean) at most 80 x 60 keep a map well under 1 MB and still 6 px or more per
/// block on a 500 px plot, finer than the colour steps show. Runs of equal colour along a
/// row are merged into one `<rect>`. Contours are traced on the full grid.
pub const MAX_CELLS: (usize, usize) = (80, 60);

/// Grey wash over infeasible cells: `(1 - a) colour + a grey` (the page's wash).
const WASH: (Rgb, f64) = (Rgb(150, 150, 150), 0.62);
/// Hatch lines over infeasible cells: colour and spacing, px.
const HATCH: (Rgb, f64) = (Rgb(58, 58, 58), 7.0);

/// Where the values sit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Sampling {
    /// Centres of `nx` x `ny` equal cells filling the box (the page's maps).
    #[default]
    Cells,
    /// `nx` x `ny` nodes from corner to corner (a [`crate::maps::Grid`]).
    Nodes,
}

/// Contour lines to draw, in the values' unit.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub enum Contours {
    /// None.
    #[default]
    None,
    /// At most this many round levels inside the colour range ([`nice_levels`]).
    Auto(usize),
    /// These levels.
    Levels(Vec<f64>),
}

/// A marker on a map: a design point.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase", deny_unknown_fields)]
pub struct MapMarker {
    /// Legend label (none when empty).
    #[serde(default)]
    pub label: String,
    /// Front spring rate, N/m.
    pub ks: f64,
    /// Front damper rate, N s/m.
    pub cs: f64,
    /// Shape (default circle).
    #[serde(default)]
    pub shape: MarkerShape,
    /// Fill, `#rrggbb` (default white); the outline is black.
    #[serde(default, alias = "color")]
    pub colour: Option<String>,
    /// Size, px (default 6).
    #[serde(default)]
    pub size: Option<f64>,
}

/// A field over the design box. Missing JS keys take [`MapChart::default`]'s values.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase", deny_unknown_fields, default)]
pub struct MapChart {
    /// Title above the plot (none when empty).
    pub title: String,
    /// Colour-bar label with the unit, e.g. `BAcc [m/s^2]`.
    pub unit: String,
    /// Values across (Ks), 2..=1001.
    pub nx: usize,
    /// Values up (Cs), 2..=1001.
    pub ny: usize,
    /// `nx ny` finite values, row-major with Cs rows (see the module documentation).
    pub values: Vec<f64>,
    /// Cell centres or grid nodes (default cells).
    pub sampling: Sampling,
    /// The design box (N/m, N s/m); the axes show it in kN/m and kNs/m.
    pub design_box: DesignBox,
    /// Viridis or diverging (default viridis).
    pub colour_map: ColourMap,
    /// Colour range `[lo, hi]`; default: the range of the feasible values (all values
    /// without a mask or with nothing feasible), made symmetric about zero for the
    /// diverging map. Values beyond take the end colours.
    pub range: Option<(f64, f64)>,
    /// Per value, 1 where the design meets every objective and 0 where it breaks one
    /// (the page's `feasible`); infeasible cells are greyed and hatched and the boundary
    /// is drawn. Default: all feasible, nothing drawn.
    pub feasible: Option<Vec<u8>>,
    /// Contour lines (default none).
    pub contours: Contours,
    /// Markers, drawn in order; those outside the box are left out.
    pub markers: Vec<MapMarker>,
    /// Width, px (360..=4000, default 640).
    pub width: u32,
    /// Height, px (240..=4000, default 480).
    pub height: u32,
    /// Legend corner for the markers' labels (default upper right).
    pub legend: Legend,
}

impl Default for MapChart {
    fn default() -> Self {
        MapChart {
            title: String::new(),
            unit: String::new(),
            nx: 0,
            ny: 0,
            values: Vec::new(),
            sampling: Sampling::Cells,
            design_box: DesignBox::default(),
            colour_map: ColourMap::Viridis,
            range: None,
            feasible: None,
            contours: Contours::None,
            markers: Vec::new(),
            width: 640,
            height: 480,
            legend: Legend::UpperRight,
        }
    }
}

/// Where a map chart's parts go.
#[derive(Debug, Clone, PartialEq)]
pub struct MapLayout {
    /// The plot rectangle, px.
    pub frame: Frame,
    /// Ks axis, kN/m.
    pub ks: Scale,
    /// Cs axis, kNs/m.
    pub cs: Scale,
    /// The colour bar's rectangle, px.
    pub bar: Frame,
    /// The colour range (the bar's axis), in the values' unit.
    pub colours: Scale,
    /// Blocks drawn across and up (at most [`MAX_CELLS`]).
    pub blocks: (usize, usize),
    /// Values per block across and up (the last block of a row or column may have fewer).
    pub block_size: (usize, usize),
}

const MARGIN_LEFT: u32 = 6;
const Y_LABEL_AREA: u32 = 56;
const X_LABEL_AREA: u32 = 46;
const MARGIN_BOTTOM: u32 = 6;
const MARGIN_RIGHT: u32 = 4;
const BAR_LABELS: u32 = 60;
const BAR_WIDTH: u32 = 16;
const BAR_GAP: u32 = 14;
const BAR_INSET: i32 = 8;

/// kN/m per N/m (and kNs/m per N s/m).
const KILO: f64 = 1e-3;

impl MapLayout {
    /// The most ticks the colour bar takes: one per 36 px of bar, 2..=8.
    pub(crate) fn bar_tick_count(&self) -> usize {
        ((self.bar.bottom - self.bar.top) / 36).clamp(2, 8) as usize
    }

    /// The colour bar's ticks, in the values' unit (the page draws its contour lines at
    /// these levels).
    pub(crate) fn bar_ticks(&self) -> Vec<f64> {
        linear_ticks(self.colours.lo, self.colours.hi, self.bar_tick_count()).0
    }
}

impl MapMarker {
    /// The JS keys of a marker (`color` is accepted for `colour`).
    pub const FIELDS: [&'static str; 7] = ["label", "ks", "cs", "shape", "colour", "color", "size"];
}

impl MapChart {
    /// The JS keys of a map chart spec (see [`super::LineChart::FIELDS`]).
    pub const FIELDS: [&'static str; 15] = [
        "title",
        "unit",
        "nx",
        "ny",
        "values",
        "sampling",
        "designBox",
        "colourMap",
        "range",
        "feasible",
        "contours",
        "markers",
        "width",
        "height",
        "legend",
    ];

    /// The JS keys of `designBox` (the core's [`DesignBox`] names).
    pub const BOX_FIELDS: [&'static str; 4] = ["ks_min", "ks_max", "cs_min", "cs_max"];

    /// Checks the spec and places it.
    pub(crate) fn layout(&self) -> Result<MapLayout> {
        check_size(self.width, self.height, (360, 240))?;
        for (field, n) in [("nx", self.nx), ("ny", self.ny)] {
            if !(2..=Axis::MAX_POINTS).contains(&n) {
                return Err(RideError::field(
                    field,
                    format!("{n} is outside 2..={}", Axis::MAX_POINTS),
                ));
            }
        }
        if self.values.len() != self.nx * self.ny {
            return Err(RideError::field(
                "values",
                format!(
                    "has {} values, {} x {} needs {}",
                    self.values.len(),
                    self.nx,
                    self.ny,
                    self.nx * self.ny
                ),
            ));
        }
        if let Some(k) = self.values.iter().position(|v| !v.is_finite()) {
            return Err(RideError::field(
                format!("values[{k}]"),
                format!(
                    "is {} (Ks column {}, Cs row {}); every value must be a finite number",
                    self.values[k],
                    k % self.nx,
                    k / self.nx
                ),
            ));
        }
        let b = &self.design_box;
        for (lo, hi, what) in [(b.ks_min, b.ks_max, "ks"), (b.cs_min, b.cs_max, "cs")] {
            if !(lo.is_finite() && hi.is_finite() && 0.0 < lo && lo < hi) {
                return Err(RideError::field(
                    "designBox",
                    format!(
                        "{what}_min {lo} and {what}_max {hi} must be finite with 0 < min < max"
                    ),
                ));
            }
        }
        if let Some(mask) = &self.feasible {
            if mask.len() != self.values.len() {
                return Err(RideError::field(
                    "feasible",
                    format!("has {} flags for {} values", mask.len(), self.values.len()),
                ));
            }
            if let Some(k) = mask.iter().position(|&m| m > 1) {
                return Err(RideError::field(
                    format!("feasible[{k}]"),
                    format!("is {}; flags are 1 (feasible) or 0", mask[k]),
                ));
            }
        }
        for (k, m) in self.markers.iter().enumerate() {
            if !(m.ks.is_finite() && m.cs.is_finite()) {
                return Err(RideError::field(
                    format!("markers[{k}]"),
                    "ks and cs must be finite numbers",
                ));
            }
            if let Some(c) = &m.colour {
                Rgb::parse(&format!("markers[{k}].colour"), c)?;
            }
            if let Some(s) = m.size {
                if !(s.is_finite() && s > 0.0 && s <= 50.0) {
                    return Err(RideError::field(
                        format!("markers[{k}].size"),
                        format!("{s} px is outside (0, 50]"),
                    ));
                }
            }
        }
        match &self.contours {
            Contours::Auto(n) if *n > 50 => {
                return Err(RideError::field(
                    "contours",
                    format!("auto {n}: at most 50 levels"),
                ))
            }
            Contours::Levels(l) => {
                if let Some(k) = l.iter().position(|v| !v.is_finite()) {
                    return Err(RideError::field(
                        format!("contours.levels[{k}]"),
                        "must be a finite number",
                    ));
                }
            }
            _ => {}
        }
        let colours = self.colour_range()?;
        let top = draw::top_space(&self.title) as i32;
        let frame = Frame {
            left: (MARGIN_LEFT + Y_LABEL_AREA) as i32,
            right: (self.width - MARGIN_RIGHT - BAR_LABELS - BAR_WIDTH - BAR_GAP) as i32 - 1,
            top,
            bottom: (self.height - MARGIN_BOTTOM - X_LABEL_AREA) as i32 - 1,
        };
        let bar_left = (self.width - MARGIN_RIGHT - BAR_LABELS - BAR_WIDTH) as i32;
        let bar = Frame {
            left: bar_left,
            right: bar_left + BAR_WIDTH as i32 - 1,
            top: frame.top + BAR_INSET,
            bottom: frame.bottom - BAR_INSET,
        };
        let fx = self.nx.div_ceil(MAX_CELLS.0);
        let fy = self.ny.div_ceil(MAX_CELLS.1);
        Ok(MapLayout {
            frame,
            ks: Scale::new("designBox", b.ks_min * KILO, b.ks_max * KILO, false)?,
            cs: Scale::new("designBox", b.cs_min * KILO, b.cs_max * KILO, false)?,
            bar,
            colours,
            blocks: (self.nx.div_ceil(fx), self.ny.div_ceil(fy)),
            block_size: (fx, fy),
        })
    }

    fn feasible_at(&self, k: usize) -> bool {
        self.feasible.as_ref().is_none_or(|m| m[k] == 1)
    }

    /// The colour range (see [`MapChart::range`]).
    fn colour_range(&self) -> Result<Scale> {
        if let Some((lo, hi)) = self.range {
            return Scale::new("range", lo, hi, false);
        }
        let any_feasible = (0..self.values.len()).any(|k| self.feasible_at(k));
        let (mut lo, mut hi) = self
            .values
            .iter()
            .enumerate()
            .filter(|&(k, _)| !any_feasible || self.feasible_at(k))
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), (_, &v)| {
                (lo.min(v), hi.max(v))
            });
        if self.colour_map == ColourMap::Diverging {
            let m = lo.abs().max(hi.abs()).max(1e-9);
            (lo, hi) = (-m, m);
        } else if hi <= lo {
            let pad = (lo.abs() * 1e-3).max(1e-9);
            (lo, hi) = (lo - pad, hi + pad);
        }
        Scale::new("range", lo, hi, false)
    }

    /// Cell edges along one axis, in the axis' unit (kN/m or kNs/m): `n + 1` values.
    fn edges(&self, lo: f64, hi: f64, n: usize) -> Vec<f64> {
        let (lo, hi) = (lo * KILO, hi * KILO);
        match self.sampling {
            Sampling::Cells => (0..=n)
                .map(|k| lo + (hi - lo) * k as f64 / n as f64)
                .collect(),
            Sampling::Nodes => {
                let step = (hi - lo) / (n - 1) as f64;
                (0..=n)
                    .map(|k| match k {
                        0 => lo,
                        k if k == n => hi,
                        k => lo + (k as f64 - 0.5) * step,
                    })
                    .collect()
            }
        }
    }

    /// The grid whose nodes carry the values (for contours), N/m and N s/m.
    fn grid(&self) -> Result<Grid> {
        let b = &self.design_box;
        let axis = |field: &str, lo: f64, hi: f64, n: usize| match self.sampling {
            Sampling::Nodes => Axis::new(field, lo, hi, n),
            Sampling::Cells => {
                let half = 0.5 * (hi - lo) / n as f64;
                Axis::new(field, lo + half, hi - half, n)
            }
        };
        Grid::new(
            axis("nx", b.ks_min, b.ks_max, self.nx)?,
            axis("ny", b.cs_min, b.cs_max, self.ny)?,
        )
    }

    /// Block means and infeasible flags (a block is infeasible when more than half its
    /// values are), row-major with block rows up.
    fn blocks(&self, l: &MapLayout) -> (Vec<f64>, Vec<bool>) {
        let ((mx, my), (fx, fy)) = (l.blocks, l.block_size);
        let mut means = Vec::with_capacity(mx * my);
        let mut infeasible = Vec::with_capacity(mx * my);
        for bj in 0..my {
            for bi in 0..mx {
                let (mut sum, mut n, mut bad) = (0.0, 0usize, 0usize);
                for j in bj * fy..((bj + 1) * fy).min(self.ny) {
                    for i in bi * fx..((bi + 1) * fx).min(self.nx) {
                        let k = j * self.nx + i;
                        sum += self.values[k];
                        n += 1;
                        bad += usize::from(!self.feasible_at(k));
                    }
                }
                means.push(sum / n as f64);
                infeasible.push(2 * bad > n);
            }
        }
        (means, infeasible)
    }

    /// Block edges in pixels: columns (increasing) and rows (decreasing: block row 0 is
    /// at the bottom).
    fn block_pixels(&self, l: &MapLayout) -> (Vec<f64>, Vec<f64>) {
        let b = &self.design_box;
        let ((mx, my), (fx, fy)) = (l.blocks, l.block_size);
        let ex = self.edges(b.ks_min, b.ks_max, self.nx);
        let ey = self.edges(b.cs_min, b.cs_max, self.ny);
        let f = &l.frame;
        let xs = (0..=mx)
            .map(|k| l.ks.pixel(ex[(k * fx).min(self.nx)], (f.left, f.right)))
            .collect();
        let ys = (0..=my)
            .map(|k| l.cs.pixel(ey[(k * fy).min(self.ny)], (f.bottom, f.top)))
            .collect();
        (xs, ys)
    }
}

mod render;

pub use render::{draw_map_frame, map_chart_svg};

#[cfg(test)]
mod tests;
