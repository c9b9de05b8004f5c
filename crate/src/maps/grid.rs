//! Map axes and the Ks x Cs grid.
//!
//! Layout of every field on a [`Grid`]: **row-major, Cs rows and Ks columns**. The value at
//! Ks index `i` (column, `0..ks.n`) and Cs index `j` (row, `0..cs.n`) is at `j * ks.n + i`,
//! so the first `ks.n` values are the lowest damper rate from the softest to the stiffest
//! spring.

use crate::design::DesignBox;
use crate::error::{Result, RideError};
use serde::{Deserialize, Serialize};

/// A uniform axis of `n` points from `min` to `max` (both included).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Axis {
    /// First value (N/m for Ks, N s/m for Cs).
    pub min: f64,
    /// Last value.
    pub max: f64,
    /// Number of points, `2..=`[`Axis::MAX_POINTS`].
    pub n: usize,
}

impl Axis {
    /// Most points one axis may have (a 1001 x 1001 map is a million evaluations).
    pub(crate) const MAX_POINTS: usize = 1001;

    /// A checked axis; errors name `field` (`ks-range` or `cs-range`).
    pub(crate) fn new(field: &str, min: f64, max: f64, n: usize) -> Result<Axis> {
        let a = Axis { min, max, n };
        a.validate(field)?;
        Ok(a)
    }

    /// Parses `min:max:points`, e.g. `10000:40000:41`; errors name `field`.
    pub fn parse(field: &str, text: &str) -> Result<Axis> {
        let parts: Vec<&str> = text.split(':').map(str::trim).collect();
        if parts.len() != 3 {
            return Err(RideError::field(
                field,
                format!("'{text}' is not min:max:points (e.g. 10000:40000:41)"),
            ));
        }
        let number = |what: &str, s: &str| {
            s.parse::<f64>()
                .map_err(|_| RideError::field(field, format!("{what} '{s}' is not a number")))
        };
        let min = number("minimum", parts[0])?;
        let max = number("maximum", parts[1])?;
        let n = parts[2].parse::<usize>().map_err(|_| {
            RideError::field(
                field,
                format!(
                    "points '{}' is not a whole number (2..={})",
                    parts[2],
                    Self::MAX_POINTS
                ),
            )
        })?;
        Axis::new(field, min, max, n)
    }

    /// Checks: finite, `0 < min < max`, `2 <= n <= MAX_POINTS`; errors name `field`.
    pub(crate) fn validate(&self, field: &str) -> Result<()> {
        if !(self.min.is_finite() && self.max.is_finite()) {
            return Err(RideError::field(
                field,
                "minimum and maximum must be finite",
            ));
        }
        if self.min <= 0.0 {
            return Err(RideError::field(
                field,
                format!("minimum {} must be > 0", self.min),
            ));
        }
        if self.min >= self.max {
            return Err(RideError::field(
                field,
                format!("minimum {} must be below maximum {}", self.min, self.max),
            ));
        }
        if self.n < 2 {
            return Err(RideError::field(
                field,
                format!("needs at least 2 points, got {}", self.n),
            ));
        }
        if self.n > Self::MAX_POINTS {
            return Err(RideError::field(
                field,
                format!("at most {} points, got {}", Self::MAX_POINTS, self.n),
            ));
        }
        Ok(())
    }

    /// The `k`-th value `(1 - t) min + t max`, `t = k / (n - 1)`: exactly `min` at 0 and
    /// exactly `max` at `n - 1`.
    pub(crate) fn value(&self, k: usize) -> f64 {
        let t = k as f64 / (self.n - 1) as f64;
        (1.0 - t) * self.min + t * self.max
    }

    /// All `n` values.
    pub(crate) fn values(&self) -> Vec<f64> {
        (0..self.n).map(|k| self.value(k)).collect()
    }

    /// Spacing `(max - min) / (n - 1)`.
    pub(crate) fn step(&self) -> f64 {
        (self.max - self.min) / (self.n - 1) as f64
    }
}

/// The Ks x Cs grid of a map (layout: see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Grid {
    /// Front spring rate axis (columns), N/m.
    pub ks: Axis,
    /// Front damper rate axis (rows), N s/m.
    pub cs: Axis,
}

impl Default for Grid {
    /// 41 x 41 points over the default design box (Ks 10..40 kN/m, Cs 0.5..4 kNs/m).
    fn default() -> Self {
        let b = DesignBox::default();
        Grid {
            ks: Axis {
                min: b.ks_min,
                max: b.ks_max,
                n: 41,
            },
            cs: Axis {
                min: b.cs_min,
                max: b.cs_max,
                n: 41,
            },
        }
    }
}

impl Grid {
    /// A checked grid.
    pub fn new(ks: Axis, cs: Axis) -> Result<Grid> {
        let g = Grid { ks, cs };
        g.validate()?;
        Ok(g)
    }

    /// Parses the CLI's `--ks-range` and `--cs-range` values (`min:max:points`).
    pub fn parse(ks_range: &str, cs_range: &str) -> Result<Grid> {
        Ok(Grid {
            ks: Axis::parse("ks-range", ks_range)?,
            cs: Axis::parse("cs-range", cs_range)?,
        })
    }

    /// `n_ks` x `n_cs` points over a design box.
    pub fn over_box(design: &DesignBox, n_ks: usize, n_cs: usize) -> Result<Grid> {
        Grid::new(
            Axis::new("ks-range", design.ks_min, design.ks_max, n_ks)?,
            Axis::new("cs-range", design.cs_min, design.cs_max, n_cs)?,
        )
    }

    /// The centres of `nx` x `ny` equal cells tiling a design box (the page's maps):
    /// `ks_i = ks_min + (i + 1/2) (ks_max - ks_min) / nx`, likewise `cs_j`, as the vertex
    /// grid from the first centre to the last. Errors name `nx` or `ny` (2..=[`Axis::MAX_POINTS`]).
    pub fn cells(design: &DesignBox, nx: usize, ny: usize) -> Result<Grid> {
        let axis = |field: &str, lo: f64, hi: f64, n: usize| {
            if !(2..=Axis::MAX_POINTS).contains(&n) {
                return Err(RideError::field(
                    field,
                    format!("grid size must be 2..={} (got {n})", Axis::MAX_POINTS),
                ));
            }
            let half = 0.5 * (hi - lo) / n as f64;
            Axis::new(field, lo + half, hi - half, n)
        };
        Ok(Grid {
            ks: axis("nx", design.ks_min, design.ks_max, nx)?,
            cs: axis("ny", design.cs_min, design.cs_max, ny)?,
        })
    }

    /// Checks both axes (errors name `ks-range` or `cs-range`).
    pub(crate) fn validate(&self) -> Result<()> {
        self.ks.validate("ks-range")?;
        self.cs.validate("cs-range")
    }

    /// The design box the grid spans.
    pub(crate) fn design_box(&self) -> DesignBox {
        DesignBox {
            ks_min: self.ks.min,
            ks_max: self.ks.max,
            cs_min: self.cs.min,
            cs_max: self.cs.max,
        }
    }

    /// Number of points `ks.n * cs.n`.
    pub fn len(&self) -> usize {
        self.ks.n * self.cs.n
    }

    /// Always false for a valid grid (at least 2 x 2 points).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Index of Ks column `i`, Cs row `j`: `j * ks.n + i`.
    pub fn index(&self, i: usize, j: usize) -> usize {
        j * self.ks.n + i
    }

    /// `(i, j)` of a flat index.
    pub(crate) fn indices(&self, index: usize) -> (usize, usize) {
        (index % self.ks.n, index / self.ks.n)
    }

    /// `(ks, cs)` of Ks column `i`, Cs row `j`.
    pub fn point(&self, i: usize, j: usize) -> (f64, f64) {
        (self.ks.value(i), self.cs.value(j))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn message(r: Result<Axis>) -> String {
        r.unwrap_err().to_string()
    }

    #[test]
    fn parses_and_spans_exactly() {
        let a = Axis::parse("ks-range", "10000:40000:41").unwrap();
        assert_eq!(
            a,
            Axis {
                min: 1e4,
                max: 4e4,
                n: 41
            }
        );
        assert_eq!(a.value(0), 1e4);
        assert_eq!(a.value(40), 4e4);
        assert!((a.value(20) - 25_000.0).abs() < 1e-9);
        assert!((a.step() - 750.0).abs() < 1e-12);
        let b = Axis::parse("cs-range", " 500 : 4000 : 2 ").unwrap();
        assert_eq!(b.values(), vec![500.0, 4000.0]);
    }

    #[test]
    fn parse_errors_name_the_field() {
        for (field, text, why) in [
            ("ks-range", "40000:10000:41", "below maximum"),
            ("ks-range", "10000:10000:41", "below maximum"),
            ("cs-range", "500:4000:1", "at least 2"),
            ("cs-range", "500:4000:0", "at least 2"),
            ("ks-range", "inf:40000:41", "finite"),
            ("ks-range", "10000:NaN:41", "finite"),
            ("cs-range", "0:4000:41", "> 0"),
            ("cs-range", "-5:4000:41", "> 0"),
            ("ks-range", "10000:40000:1002", "at most 1001"),
            ("ks-range", "10000:40000", "min:max:points"),
            ("cs-range", "a:4000:41", "not a number"),
            ("cs-range", "500:4000:4.5", "whole number"),
        ] {
            let m = message(Axis::parse(field, text));
            assert!(m.starts_with(&format!("{field}: ")), "{text}: {m}");
            assert!(m.contains(why), "{text}: {m}");
        }
        assert!(Axis::parse("ks-range", "10000:40000:1001").is_ok());
        let g = Grid::parse("10000:40000:41", "500:400:41").unwrap_err();
        assert!(g.to_string().starts_with("cs-range: "), "{g}");
    }

    #[test]
    fn grid_layout_is_row_major_cs_rows() {
        let g = Grid::parse("1:3:3", "10:20:2").unwrap();
        assert_eq!(g.len(), 6);
        assert_eq!(g.index(2, 1), 5);
        assert_eq!(g.indices(4), (1, 1));
        assert_eq!(g.point(2, 1), (3.0, 20.0));
        assert_eq!(g.design_box().cs_max, 20.0);
    }

    #[test]
    fn cells_tile_the_box() {
        let b = DesignBox::default();
        let g = Grid::cells(&b, 4, 2).unwrap();
        // Cell width 7500 N/m: centres at 13750, 21250, 28750, 36250.
        assert!((g.ks.value(0) - 13_750.0).abs() < 1e-9);
        assert!((g.ks.value(3) - 36_250.0).abs() < 1e-9);
        assert!((g.cs.value(1) - 3_125.0).abs() < 1e-9);
        let m = Grid::cells(&b, 1, 5).unwrap_err().to_string();
        assert!(m.starts_with("nx: grid size must be 2..=1001"), "{m}");
        assert!(Grid::cells(&b, 5, 1002)
            .unwrap_err()
            .to_string()
            .starts_with("ny:"));
    }
}
