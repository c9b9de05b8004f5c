//! The design box: ranges of the front spring rate Ks (N/m) and damper rate Cs (N s/m).

use crate::error::{Result, RideError};
use serde::{Deserialize, Serialize};

/// Rectangular design space over Ks (N/m) x Cs (N s/m).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct DesignBox {
    /// Lowest front spring rate, N/m.
    pub ks_min: f64,
    /// Highest front spring rate, N/m.
    pub ks_max: f64,
    /// Lowest front damper rate, N s/m.
    pub cs_min: f64,
    /// Highest front damper rate, N s/m.
    pub cs_max: f64,
}

impl Default for DesignBox {
    /// The default box of METHOD.md section 7: Ks 10..40 kN/m, Cs 0.5..4 kNs/m.
    fn default() -> Self {
        DesignBox {
            ks_min: 10_000.0,
            ks_max: 40_000.0,
            cs_min: 500.0,
            cs_max: 4_000.0,
        }
    }
}

impl DesignBox {
    /// Checks that both ranges are finite, positive and increasing.
    pub fn validate(&self) -> Result<()> {
        for (name, lo, hi) in [
            ("ks", self.ks_min, self.ks_max),
            ("cs", self.cs_min, self.cs_max),
        ] {
            if !lo.is_finite() || !hi.is_finite() {
                return Err(RideError::field(
                    format!("{name}-range"),
                    "must be finite numbers",
                ));
            }
            if lo <= 0.0 {
                return Err(RideError::field(
                    format!("{name}-range"),
                    "minimum must be > 0",
                ));
            }
            if lo >= hi {
                return Err(RideError::field(
                    format!("{name}-range"),
                    format!("minimum {lo} must be below maximum {hi}"),
                ));
            }
        }
        Ok(())
    }

    /// Parses `min:max` (N/m or N s/m) of one range; errors name `field`.
    pub fn parse_range(field: &str, text: &str) -> Result<(f64, f64)> {
        let bad = || RideError::field(field, format!("'{text}' is not min:max (e.g. 10000:40000)"));
        let (lo, hi) = text.split_once(':').ok_or_else(bad)?;
        let lo: f64 = lo.trim().parse().map_err(|_| bad())?;
        let hi: f64 = hi.trim().parse().map_err(|_| bad())?;
        Ok((lo, hi))
    }

    /// Maps unit coordinates `(u, v)` in [0, 1]^2 to `(ks, cs)`.
    pub fn scale(&self, u: f64, v: f64) -> (f64, f64) {
        (
            self.ks_min + u * (self.ks_max - self.ks_min),
            self.cs_min + v * (self.cs_max - self.cs_min),
        )
    }

    /// Maps `(ks, cs)` to unit coordinates in [0, 1]^2.
    pub fn normalize(&self, ks: f64, cs: f64) -> (f64, f64) {
        (
            (ks - self.ks_min) / (self.ks_max - self.ks_min),
            (cs - self.cs_min) / (self.cs_max - self.cs_min),
        )
    }
}
