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
    /// Checks that both ranges lie in the design domain ([`crate::domain::SPRING`],
    /// [`crate::domain::DAMPER`]) and increase; errors name `ks-range` or `cs-range`.
    pub fn validate(&self) -> Result<()> {
        for (name, lo, hi, limit) in [
            ("ks", self.ks_min, self.ks_max, &crate::domain::SPRING),
            ("cs", self.cs_min, self.cs_max, &crate::domain::DAMPER),
        ] {
            let field = format!("{name}-range");
            if !lo.is_finite() || !hi.is_finite() {
                return Err(RideError::field(field, "must be finite numbers"));
            }
            if lo <= 0.0 {
                return Err(RideError::field(field, "minimum must be > 0"));
            }
            if lo >= hi {
                return Err(RideError::field(
                    field,
                    format!("minimum {lo} must be below maximum {hi}"),
                ));
            }
            for (end, v) in [("minimum", lo), ("maximum", hi)] {
                limit.check(&field, v).map_err(|e| match e {
                    RideError::Field { field, reason } => {
                        RideError::field(field, format!("{end} {reason}"))
                    }
                    other => other,
                })?;
            }
        }
        Ok(())
    }

    /// Checks that the box's four corners lie in `domain` (a car's front-design domain:
    /// the body-bounce frequency and damping ratio in range, [`crate::car::DesignDomain`]);
    /// errors name `ks-range` (a bounce frequency) or `cs-range` (a damping ratio) and
    /// the corner.
    pub(crate) fn check_on(&self, domain: &crate::car::DesignDomain) -> Result<()> {
        for (ks, cs) in [
            (self.ks_min, self.cs_min),
            (self.ks_min, self.cs_max),
            (self.ks_max, self.cs_min),
            (self.ks_max, self.cs_max),
        ] {
            domain.check(ks, cs).map_err(|e| match e {
                RideError::Field { field, reason } => RideError::field(
                    if field == "ks" {
                        "ks-range"
                    } else {
                        "cs-range"
                    },
                    format!(
                        "the box's corner Ks {} N/m, Cs {} N s/m: {reason}",
                        crate::domain::num(ks),
                        crate::domain::num(cs)
                    ),
                ),
                other => other,
            })?;
        }
        Ok(())
    }

    /// Parses `min:max` (N/m or N s/m) of one range; errors name `field`.
    pub fn parse_range(field: &str, text: &str) -> Result<(f64, f64)> {
        let example = match field {
            "cs-range" => "500:4000",
            "travel" => "0.025:3",
            "bounce-band" => "0.8:1.5",
            "damping-band" => "0.2:0.5",
            _ => "10000:40000",
        };
        let shape = if field == "travel" {
            "M:N, bump travel in m and sigma factor"
        } else {
            "min:max"
        };
        let bad = || RideError::field(field, format!("'{text}' is not {shape} (e.g. {example})"));
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
