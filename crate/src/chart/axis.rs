//! Chart axes: a data range drawn linearly or on log10, its ticks and tick labels, and
//! the map from data to pixels the SVG backend draws with.
//!
//! A value `v` lies at the fraction `t = (v - lo) / (hi - lo)` of a linear axis and
//! `t = (log10 v - log10 lo) / (log10 hi - log10 lo)` of a log axis. Its pixel is
//! `p0 + t (p1 - p0)` **rounded to the nearest integer** (plotters' own `f64` axes floor
//! instead, up to 1 px off), where `p0`, `p1` are the pixels of `lo` and `hi`; see
//! [`super::Frame`].

use crate::error::{Result, RideError};
use crate::math;
use plotters::coord::ranged1d::{KeyPointHint, NoDefaultFormatting, Ranged, ValueFormatter};
use std::ops::Range;

/// Largest |pixel| handed to the backend: keeps far-away points (clipped anyway) from
/// overflowing the backend's `i32` coordinates.
const PIXEL_LIMIT: f64 = 1e6;

/// One axis: the data range `lo..hi` (in the axis' unit), linear or log10.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scale {
    /// Value at the low end (left or bottom).
    pub lo: f64,
    /// Value at the high end (right or top).
    pub hi: f64,
    /// True for a log10 axis (then `0 < lo`).
    pub log: bool,
}

impl Scale {
    /// A checked scale: finite, `lo < hi`, and `lo > 0` on a log axis; errors name `field`.
    pub fn new(field: &str, lo: f64, hi: f64, log: bool) -> Result<Scale> {
        if !(lo.is_finite() && hi.is_finite()) {
            return Err(RideError::field(field, "both ends must be finite numbers"));
        }
        if lo >= hi {
            return Err(RideError::field(
                field,
                format!("low end {lo} must be below high end {hi}"),
            ));
        }
        if log && lo <= 0.0 {
            return Err(RideError::field(
                field,
                format!("low end {lo} must be > 0 on a log axis"),
            ));
        }
        Ok(Scale { lo, hi, log })
    }

    /// The range drawn for data from `min` to `max` (finite; `> 0` on a log axis):
    /// linear, widened by 4 % of the span each side (by 5 % of |min|, or 1, when the data
    /// are one value); log, out to whole decades.
    pub fn auto(field: &str, min: f64, max: f64, log: bool) -> Result<Scale> {
        let (lo, hi) = if log {
            if min.is_nan() || min <= 0.0 {
                return Err(RideError::field(
                    field,
                    format!("smallest value {min} must be > 0 on a log axis"),
                ));
            }
            let lo = math::powf(10f64, math::log10(min).floor());
            let mut hi = math::powf(10f64, math::log10(max).ceil());
            if hi <= lo {
                hi = lo * 10.0;
            }
            (lo, hi)
        } else if max > min {
            let d = 0.04 * (max - min);
            (min - d, max + d)
        } else {
            let d = if min != 0.0 { 0.05 * min.abs() } else { 1.0 };
            (min - d, max + d)
        };
        Scale::new(field, lo, hi, log)
    }

    /// Fraction of the axis at `v`: 0 at `lo`, 1 at `hi` (not finite for `v <= 0` on a
    /// log axis).
    pub fn fraction(&self, v: f64) -> f64 {
        if self.log {
            (math::log10(v) - math::log10(self.lo)) / (math::log10(self.hi) - math::log10(self.lo))
        } else {
            (v - self.lo) / (self.hi - self.lo)
        }
    }

    /// The value at fraction `t` (inverse of [`Scale::fraction`]).
    pub fn value(&self, t: f64) -> f64 {
        if self.log {
            math::powf(
                10f64,
                math::log10(self.lo) + t * (math::log10(self.hi) - math::log10(self.lo)),
            )
        } else {
            self.lo + t * (self.hi - self.lo)
        }
    }

    /// Unrounded pixel of `v` when `lo` is at pixel `p0` and `hi` at `p1`.
    pub fn pixel(&self, v: f64, (p0, p1): (i32, i32)) -> f64 {
        f64::from(p0) + self.fraction(v) * f64::from(p1 - p0)
    }

    /// At most `max` ticks inside the range: round numbers (multiples of 1, 2, 2.5 or 5
    /// times a power of ten) on a linear axis; decades on a log axis (with 2 and 5 times
    /// the decades when fewer than two decades fit; linear ticks when still fewer).
    pub(crate) fn ticks(&self, max: usize) -> Vec<f64> {
        if max == 0 {
            return Vec::new();
        }
        if self.log {
            let (e0, e1) = (
                math::log10(self.lo).floor() as i32,
                math::log10(self.hi).ceil() as i32,
            );
            let inside = |v: &f64| *v >= self.lo * (1.0 - 1e-9) && *v <= self.hi * (1.0 + 1e-9);
            let decades: Vec<f64> = (e0..=e1).map(decade).filter(inside).collect();
            if decades.len() >= 2 {
                let step = decades.len().div_ceil(max);
                return decades.into_iter().step_by(step.max(1)).collect();
            }
            let mut more: Vec<f64> = (e0..=e1)
                .flat_map(|e| [1.0, 2.0, 5.0].map(|m| m * decade(e)))
                .filter(inside)
                .collect();
            if more.len() >= 2 && more.len() <= max {
                more.dedup();
                return more;
            }
            return linear_ticks(self.lo, self.hi, max).0;
        }
        linear_ticks(self.lo, self.hi, max).0
    }

    /// The label of tick `v` among `ticks` (as [`Scale::ticks`] gave them).
    pub fn label(&self, v: f64, ticks: &[f64]) -> String {
        let step = ticks
            .windows(2)
            .map(|w| (w[1] - w[0]).abs())
            .fold(f64::INFINITY, f64::min);
        if self.log && is_decade(v) {
            let e = math::log10(v).round() as i32;
            return if (-3..=4).contains(&e) {
                fixed(v, (-e).max(0) as usize)
            } else {
                format!("1e{e}")
            };
        }
        if self.log {
            // 2 or 5 times a decade: as many decimals as the value needs.
            let e = math::log10(v).floor() as i32;
            return if (-3..=4).contains(&e) {
                fixed(v, (-e).max(0) as usize)
            } else {
                format!("{}e{e}", (v / decade(e)).round())
            };
        }
        fixed(v, decimals(if step.is_finite() { step } else { v.abs() }))
    }
}

/// `10^e`, exact for the decades a chart meets (a negative power is a division).
fn decade(e: i32) -> f64 {
    if e >= 0 {
        10f64.powi(e)
    } else {
        1.0 / 10f64.powi(-e)
    }
}

fn is_decade(v: f64) -> bool {
    let e = math::log10(v).round() as i32;
    (v / decade(e) - 1.0).abs() < 1e-9
}

/// Decimals that write multiples of `step` exactly (at most 9).
fn decimals(step: f64) -> usize {
    if !(step.is_finite() && step > 0.0) {
        return 0;
    }
    (0..9)
        .find(|&d| {
            let s = step * 10f64.powi(d as i32);
            (s - s.round()).abs() < 1e-6 * s.max(1.0)
        })
        .unwrap_or(9)
}

/// `v` with `d` decimals, never "-0".
fn fixed(v: f64, d: usize) -> String {
    let s = format!("{:.*}", d, v);
    if s.starts_with('-') && s[1..].chars().all(|c| c == '0' || c == '.') {
        s[1..].to_string()
    } else {
        s
    }
}

/// At most `max` round ticks in `[lo, hi]` (both included when round) and their step:
/// the multiples of the smallest step `m 10^e`, `m` in {1, 2, 2.5, 5}, that gives no more
/// than `max` of them.
pub(crate) fn linear_ticks(lo: f64, hi: f64, max: usize) -> (Vec<f64>, f64) {
    if max == 0 || !(lo.is_finite() && hi.is_finite()) || hi <= lo {
        return (Vec::new(), 0.0);
    }
    let tol = 1e-9 * (hi - lo);
    let e0 = math::log10((hi - lo) / max as f64).floor() as i32 - 1;
    for e in e0..e0 + 4 {
        for m in [1.0, 2.0, 2.5, 5.0] {
            let step = m * decade(e);
            let k0 = ((lo - tol) / step).ceil();
            let k1 = ((hi + tol) / step).floor();
            let n = k1 - k0 + 1.0;
            if n <= max as f64 {
                let ticks = (0..n.max(0.0) as usize)
                    .map(|k| {
                        // Rounded once to the step's decimals: 0.1 * 3 is 0.30000000000000004.
                        let v = (k0 + k as f64) * step;
                        let d = decimals(step) as i32;
                        (v * 10f64.powi(d)).round() / 10f64.powi(d) + 0.0
                    })
                    .collect();
                return (ticks, step);
            }
        }
    }
    (vec![lo, hi], hi - lo)
}

impl Ranged for Scale {
    type FormatOption = NoDefaultFormatting;
    type ValueType = f64;

    fn map(&self, value: &f64, limit: (i32, i32)) -> i32 {
        let p = self.pixel(*value, limit);
        if p.is_nan() {
            return limit.0;
        }
        p.round().clamp(-PIXEL_LIMIT, PIXEL_LIMIT) as i32
    }

    fn key_points<Hint: KeyPointHint>(&self, hint: Hint) -> Vec<f64> {
        self.ticks(hint.max_num_points())
    }

    fn range(&self) -> Range<f64> {
        self.lo..self.hi
    }
}

impl ValueFormatter<f64> for Scale {
    fn format(value: &f64) -> String {
        format!("{value}")
    }

    fn format_ext(&self, value: &f64) -> String {
        // The charts pass their own formatter (with the ticks they asked for); this is
        // the fallback for a mesh drawn with the default count.
        self.label(*value, &self.ticks(10))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn linear_ticks_are_round_and_inclusive() {
        assert_eq!(
            linear_ticks(10.0, 40.0, 7).0,
            vec![10.0, 15.0, 20.0, 25.0, 30.0, 35.0, 40.0]
        );
        assert_eq!(
            linear_ticks(0.5, 4.0, 8).0,
            vec![0.5, 1.0, 1.5, 2.0, 2.5, 3.0, 3.5, 4.0]
        );
        assert_eq!(linear_ticks(0.13, 0.97, 5).0, vec![0.2, 0.4, 0.6, 0.8]);
        let (t, step) = linear_ticks(-0.31, 0.29, 6);
        assert_eq!(t, vec![-0.3, -0.2, -0.1, 0.0, 0.1, 0.2]);
        assert!((step - 0.1).abs() < 1e-15);
        assert!(linear_ticks(1.0, 1.0, 5).0.is_empty());
        assert!(linear_ticks(0.0, 1.0, 0).0.is_empty());
        for (lo, hi, n) in [
            (0.7, 2.9, 10),
            (1e-3, 9.9e-3, 7),
            (12.0, 5e4, 9),
            (-5e3, -4e3, 4),
        ] {
            let t = linear_ticks(lo, hi, n).0;
            assert!(t.len() >= 2 && t.len() <= n, "{lo} {hi}: {t:?}");
            assert!(t.windows(2).all(|w| w[0] < w[1]));
            assert!(t[0] >= lo && *t.last().unwrap() <= hi);
        }
    }

    #[test]
    fn log_ticks_are_decades_or_their_multiples() {
        let s = Scale::new("x", 0.1, 100.0, true).unwrap();
        assert_eq!(s.ticks(10), vec![0.1, 1.0, 10.0, 100.0]);
        let labels: Vec<String> = s.ticks(10).iter().map(|&v| s.label(v, &[])).collect();
        assert_eq!(labels, ["0.1", "1", "10", "100"]);
        let s = Scale::new("y", 1e-9, 1e3, true).unwrap();
        let t = s.ticks(5);
        assert_eq!(t.len(), 5);
        assert_eq!(s.label(t[0], &t), "1e-9");
        assert_eq!(s.label(1e-3, &t), "0.001");
        let s = Scale::new("y", 2.0, 30.0, true).unwrap();
        assert_eq!(s.ticks(10), vec![2.0, 5.0, 10.0, 20.0]);
        let s = Scale::new("y", 2.1, 2.9, true).unwrap();
        let t = s.ticks(6);
        assert!(
            t.len() >= 2 && t[0] >= 2.1 && *t.last().unwrap() <= 2.9,
            "{t:?}"
        );
    }

    #[test]
    fn labels_carry_the_step_decimals() {
        let s = Scale::new("x", 0.0, 1.0, false).unwrap();
        let (t, _) = linear_ticks(0.0, 1.0, 5);
        let l: Vec<String> = t.iter().map(|&v| s.label(v, &t)).collect();
        assert_eq!(l, ["0.00", "0.25", "0.50", "0.75", "1.00"]);
        let (t, _) = linear_ticks(-2000.0, 2000.0, 5);
        let l: Vec<String> = t.iter().map(|&v| s.label(v, &t)).collect();
        assert_eq!(l, ["-2000", "-1000", "0", "1000", "2000"]);
        assert_eq!(fixed(-0.0001, 2), "0.00");
    }

    #[test]
    fn auto_ranges_and_errors_name_the_field() {
        let s = Scale::auto("x", 2.0, 12.0, false).unwrap();
        assert!((s.lo - 1.6).abs() < 1e-12 && (s.hi - 12.4).abs() < 1e-12);
        let s = Scale::auto("x", 3.0, 3.0, false).unwrap();
        assert!((s.lo - 2.85).abs() < 1e-12 && (s.hi - 3.15).abs() < 1e-12);
        let s = Scale::auto("y", 0.003, 470.0, true).unwrap();
        assert_eq!((s.lo, s.hi), (0.001, 1000.0));
        let s = Scale::auto("y", 10.0, 10.0, true).unwrap();
        assert_eq!((s.lo, s.hi), (10.0, 100.0));
        for (lo, hi, log, why) in [
            (0.0, 1.0, true, "> 0"),
            (-1.0, 1.0, true, "> 0"),
            (2.0, 1.0, false, "below"),
            (f64::NAN, 1.0, false, "finite"),
        ] {
            let e = Scale::new("yRange", lo, hi, log).unwrap_err().to_string();
            assert!(e.starts_with("yRange: ") && e.contains(why), "{e}");
        }
        let e = Scale::auto("y", -1.0, 5.0, true).unwrap_err().to_string();
        assert!(e.starts_with("y: ") && e.contains("> 0"), "{e}");
    }

    #[test]
    fn pixels_round_to_nearest() {
        let s = Scale::new("x", 0.0, 10.0, false).unwrap();
        // 3.33 of 10 over pixels 100..=399: 199.9 -> 200 (plotters' floor gives 199).
        assert_eq!(s.map(&3.33, (100, 400)), 200);
        // Flipped (y): 0 at the bottom pixel 300, 10 at the top pixel 0.
        assert_eq!(s.map(&2.5, (300, 0)), 225);
        let l = Scale::new("x", 0.1, 100.0, true).unwrap();
        assert_eq!(l.map(&1.0, (0, 300)), 100);
        assert_eq!(l.map(&f64::NAN, (0, 300)), 0);
        assert_eq!(s.map(&1e300, (0, 300)), 1_000_000);
        assert_eq!(l.map(&1e300, (0, 300)), 30_100);
        assert!((l.value(l.fraction(3.7)) - 3.7).abs() < 1e-12);
    }
}
