//! The front damper's force-velocity law for the time domain: linear, asymmetric
//! (bump and rebound rates) or digressive (a knee velocity with a second pair of slopes).
//!
//! Sign convention: `v = d . q' = z_s' - z_u'`, the suspension's extension rate, m/s;
//! `v > 0` is rebound (extension), `v < 0` bump (compression). The damper's force
//! `f(v)` (N) resists the motion: it pulls the body down and the wheel up in rebound,
//!
//! ```text
//! f(v) = Csr v                                  0 <= v <= vk
//!        Csr vk + Csr2 (v - vk)                 v > vk
//!        Csb v                                  -vk <= v < 0
//!        -Csb vk + Csb2 (v + vk)                v < -vk
//! ```
//! (without a knee, `vk` is infinite). The force on the body is `-f(v)`.
//!
//! **What the design's Cs means.** The frequency-domain analysis (criteria, maps,
//! surrogates, optimisers) is linear: for it a damper given by slopes is the linear
//! damper of its low-speed slopes' mean, `Cs = (Csb + Csr) / 2`
//! ([`Damper::linear_rate`], METHOD.md's `Csm`). The time domain follows the same rule:
//! a run with a nonlinear damper is the design with `Cs = (Csb + Csr) / 2`, whatever Cs
//! the car carried (see [`super::simulate_car`]), and the page and the CLI both go through it.

use crate::error::{Result, RideError};
use serde::{Deserialize, Serialize};

/// Largest damper rate accepted, N s/m (a front damper of a passenger car is 0.5 to 10 kN s/m).
const MAX_RATE: f64 = 1.0e6;
/// Largest knee velocity accepted, m/s (damper velocities on a road stay under about 2 m/s).
pub const MAX_KNEE_VELOCITY: f64 = 10.0;

/// A digressive damper's knee: above `velocity` (either way) the slopes change.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Knee {
    /// Knee velocity `vk`, m/s (the same in bump and rebound).
    pub velocity: f64,
    /// Bump slope above the knee `Csb2`, N s/m.
    pub bump: f64,
    /// Rebound slope above the knee `Csr2`, N s/m.
    pub rebound: f64,
}

/// The front damper's force-velocity law (both front corners).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Damper {
    /// Bump (compression) rate `Csb` below the knee, N s/m.
    pub bump: f64,
    /// Rebound (extension) rate `Csr` below the knee, N s/m.
    pub rebound: f64,
    /// The knee of a digressive (or progressive) damper; `None`: two slopes only.
    #[serde(default)]
    pub knee: Option<Knee>,
}

impl Damper {
    /// A two-slope damper.
    pub fn asymmetric(bump: f64, rebound: f64) -> Damper {
        Damper {
            bump,
            rebound,
            knee: None,
        }
    }

    /// The equivalent linear rate the frequency-domain analysis uses, N s/m:
    /// the mean of the low-speed slopes, `(Csb + Csr) / 2`.
    pub(crate) fn linear_rate(&self) -> f64 {
        0.5 * (self.bump + self.rebound)
    }

    /// The damper force `f(v)`, N, at extension rate `v`, m/s (see the module docs).
    pub fn force(&self, v: f64) -> f64 {
        let (low, high) = if v >= 0.0 {
            (self.rebound, self.knee.map(|k| k.rebound))
        } else {
            (self.bump, self.knee.map(|k| k.bump))
        };
        match (self.knee, high) {
            (Some(k), Some(high)) if v.abs() > k.velocity => {
                let vk = k.velocity.copysign(v);
                low * vk + high * (v - vk)
            }
            _ => low * v,
        }
    }

    /// The law as a polyline `(v m/s, f N)` from `-v_max` to `v_max`: its corners
    /// (0 and the knees) and the ends, for charts.
    pub fn curve(&self, v_max: f64) -> Vec<(f64, f64)> {
        let mut v = vec![-v_max, 0.0, v_max];
        if let Some(k) = self.knee {
            if k.velocity < v_max {
                v.extend([-k.velocity, k.velocity]);
            }
        }
        crate::order::sort_by_f64_key(&mut v, |x| *x);
        v.into_iter().map(|v| (v, self.force(v))).collect()
    }

    /// Checks a design's Cs given together with this law: by the rule of the module,
    /// the design's Cs is the law's [`Damper::linear_rate`], so any other Cs is refused
    /// (errors name `cs`).
    pub fn check_design_cs(&self, cs: f64) -> Result<()> {
        if cs == self.linear_rate() {
            Ok(())
        } else {
            Err(RideError::field(
                "cs",
                format!(
                    "with bump and rebound rates the design's Cs is their mean {} Ns/m (got {cs}): leave Cs out",
                    self.linear_rate()
                ),
            ))
        }
    }

    /// Checks every rate and the knee; messages name the field.
    pub fn validate(&self) -> Result<()> {
        let rate = |field: &str, x: f64, zero_ok: bool| {
            let ok = x.is_finite() && x <= MAX_RATE && if zero_ok { x >= 0.0 } else { x > 0.0 };
            if ok {
                Ok(())
            } else {
                let lo = if zero_ok { ">= 0" } else { "> 0" };
                Err(RideError::field(
                    field,
                    format!("must be a finite rate {lo} and at most {MAX_RATE} N s/m (got {x})"),
                ))
            }
        };
        rate("bump", self.bump, false)?;
        rate("rebound", self.rebound, false)?;
        if let Some(k) = self.knee {
            if !(k.velocity.is_finite() && k.velocity > 0.0 && k.velocity <= MAX_KNEE_VELOCITY) {
                return Err(RideError::field(
                    "knee.velocity",
                    format!(
                        "must be in (0, {MAX_KNEE_VELOCITY}] m/s (got {})",
                        k.velocity
                    ),
                ));
            }
            crate::domain::KNEE_VELOCITY.check("knee.velocity", k.velocity)?;
            rate("knee.bump", k.bump, true)?;
            rate("knee.rebound", k.rebound, true)?;
            for (field, x) in [("knee.bump", k.bump), ("knee.rebound", k.rebound)] {
                if x > crate::domain::DAMPER.max {
                    crate::domain::DAMPER.check(field, x)?;
                }
            }
        }
        // The two low-speed rates are dampers of a road vehicle ([`crate::domain::DAMPER`]).
        crate::domain::DAMPER.check("bump", self.bump)?;
        crate::domain::DAMPER.check("rebound", self.rebound)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_slopes_and_a_knee() {
        let d = Damper::asymmetric(500.0, 2500.0);
        assert_eq!(d.force(0.1), 250.0);
        assert_eq!(d.force(-0.1), -50.0);
        assert_eq!(d.linear_rate(), 1500.0);
        let g = Damper {
            knee: Some(Knee {
                velocity: 0.1,
                bump: 200.0,
                rebound: 1000.0,
            }),
            ..d
        };
        // Continuous at the knees, with the second slopes beyond them.
        assert_eq!(g.force(0.1), 250.0);
        assert!((g.force(0.3) - (250.0 + 1000.0 * 0.2)).abs() < 1e-9);
        assert!((g.force(-0.3) - (-50.0 - 200.0 * 0.2)).abs() < 1e-9);
        assert_eq!(g.linear_rate(), 1500.0);
        let c = g.curve(0.5);
        assert_eq!(c.len(), 5);
        assert!(c.windows(2).all(|w| w[0].0 < w[1].0 && w[0].1 < w[1].1));
    }

    #[test]
    fn bad_laws_name_the_field() {
        let err = |d: Damper| d.validate().unwrap_err().to_string();
        assert!(err(Damper::asymmetric(0.0, 1.0)).starts_with("bump:"));
        assert!(err(Damper::asymmetric(1.0, f64::NAN)).starts_with("rebound:"));
        let k = |velocity, bump, rebound| Damper {
            knee: Some(Knee {
                velocity,
                bump,
                rebound,
            }),
            ..Damper::asymmetric(1000.0, 2000.0)
        };
        assert!(err(k(0.0, 1.0, 1.0)).starts_with("knee.velocity:"));
        assert!(err(k(0.1, -1.0, 1.0)).starts_with("knee.bump:"));
        assert!(err(k(0.1, 1.0, f64::INFINITY)).starts_with("knee.rebound:"));
        assert!(k(0.1, 0.0, 0.0).validate().is_ok());
    }
}
