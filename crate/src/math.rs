//! The core's transcendental functions: the same bits natively and in the page.
//!
//! `f64::exp`, `ln`, `powf`, `sin`, `hypot`, ... and num-complex's methods over them call
//! the platform's C library natively (glibc on Linux) and Rust's port of musl's libm in
//! the wasm build. The two differ in the last bit for some arguments, and an
//! ill-conditioned step (a two-sample surrogate fit choosing its RBF shape by
//! leave-one-out) turns that into a different fourth digit: the page's report and
//! `ridelab report` differed for a heavy sedan (issue #28). Every transcendental in the
//! core goes through these functions instead, which call the [`libm`] crate (musl's
//! algorithms, the ones the wasm build's `f64` methods use) on every target; nalgebra's
//! own (`hypot` in its decompositions) do too, through simba's `libm_force` feature.
//! `clippy.toml` forbids the `f64` and num-complex methods in the crate.
//!
//! `sqrt`, `abs`, `powi` and the arithmetic are exact or the same algorithm everywhere
//! and stay as they are.

use num_complex::Complex64 as C64;

/// `e^x`.
#[inline]
pub(crate) fn exp(x: f64) -> f64 {
    libm::exp(x)
}

/// Natural logarithm `ln x`.
#[inline]
pub(crate) fn ln(x: f64) -> f64 {
    libm::log(x)
}

/// `ln(1 + x)`, accurate for small `x`.
#[inline]
pub(crate) fn ln_1p(x: f64) -> f64 {
    libm::log1p(x)
}

/// Base-10 logarithm.
#[inline]
pub(crate) fn log10(x: f64) -> f64 {
    libm::log10(x)
}

/// `x^y`.
#[inline]
pub(crate) fn powf(x: f64, y: f64) -> f64 {
    libm::pow(x, y)
}

/// `sin x`, `x` in radians.
#[inline]
pub(crate) fn sin(x: f64) -> f64 {
    libm::sin(x)
}

/// `cos x`, `x` in radians.
#[inline]
pub(crate) fn cos(x: f64) -> f64 {
    libm::cos(x)
}

/// `(sin x, cos x)`, `x` in radians.
#[inline]
pub(crate) fn sin_cos(x: f64) -> (f64, f64) {
    libm::sincos(x)
}

/// `tan x`, `x` in radians.
#[inline]
pub(crate) fn tan(x: f64) -> f64 {
    libm::tan(x)
}

/// `atan x`, radians.
#[inline]
pub(crate) fn atan(x: f64) -> f64 {
    libm::atan(x)
}

/// `sqrt(x^2 + y^2)` without overflow or underflow.
#[inline]
pub(crate) fn hypot(x: f64, y: f64) -> f64 {
    libm::hypot(x, y)
}

/// `e^z = e^re (cos im + i sin im)`.
#[inline]
pub(crate) fn cexp(z: C64) -> C64 {
    cpolar(exp(z.re), z.im)
}

/// `r (cos theta + i sin theta)`.
#[inline]
pub(crate) fn cpolar(r: f64, theta: f64) -> C64 {
    let (s, c) = sin_cos(theta);
    C64::new(r * c, r * s)
}

/// `|z|`.
#[inline]
pub(crate) fn cabs(z: C64) -> f64 {
    hypot(z.re, z.im)
}

/// The principal square root of `z` (real part >= 0; the branch cut along the negative
/// real axis, the sign of `im` kept there), by `t = sqrt((|re| + |z|) / 2)`.
pub(crate) fn csqrt(z: C64) -> C64 {
    if z.re == 0.0 && z.im == 0.0 {
        return C64::new(0.0, z.im);
    }
    let t = ((z.re.abs() + cabs(z)) / 2.0).sqrt();
    if z.re >= 0.0 {
        C64::new(t, z.im / (2.0 * t))
    } else {
        C64::new(z.im.abs() / (2.0 * t), t.copysign(z.im))
    }
}

#[cfg(test)]
#[allow(clippy::disallowed_methods)] // the platform's functions, to compare with
mod tests {
    use super::*;

    // Against the platform's own functions: libm's are within an ulp or two of them.
    #[test]
    fn agrees_with_the_platform_within_two_ulps() {
        let close =
            |a: f64, b: f64| (a - b).abs() <= 2.0 * f64::EPSILON * b.abs().max(f64::MIN_POSITIVE);
        for k in 0..2000 {
            let x = -20.0 + 0.0173 * k as f64;
            assert!(close(exp(x), x.exp()), "exp {x}");
            assert!(
                close(sin(x), x.sin()) || (sin(x) - x.sin()).abs() < 1e-15,
                "sin {x}"
            );
            assert!(
                close(cos(x), x.cos()) || (cos(x) - x.cos()).abs() < 1e-15,
                "cos {x}"
            );
            assert!(close(hypot(x, 0.7), x.hypot(0.7)), "hypot {x}");
            let p = x.abs() + 1e-3;
            assert!(
                close(ln(p), p.ln()) || (ln(p) - p.ln()).abs() < 1e-15,
                "ln {p}"
            );
            assert!(close(powf(p, 1.7), p.powf(1.7)), "powf {p}");
            assert!(
                close(log10(p), p.log10()) || (log10(p) - p.log10()).abs() < 1e-15,
                "log10 {p}"
            );
        }
    }

    // The complex square root squares back to its argument, with the principal branch.
    #[test]
    fn complex_square_root_squares_back() {
        for (re, im) in [
            (4.0, 0.0),
            (-4.0, 0.0),
            (-4.0, -0.0),
            (3.0, 4.0),
            (-3.0, 4.0),
            (-3.0, -4.0),
            (1e-300, 1e-300),
            (0.0, 2.0),
        ] {
            let z = C64::new(re, im);
            let s = csqrt(z);
            assert!(s.re >= 0.0, "{z}");
            assert!(
                (s * s - z).norm() <= 1e-15 * z.norm().max(1e-300),
                "{z}: {s}"
            );
        }
        assert_eq!(csqrt(C64::new(-4.0, -0.0)), C64::new(0.0, -2.0));
        let e = cexp(C64::new(0.3, 2.0));
        assert!((e - C64::new(0.3, 2.0).exp()).norm() < 1e-15);
    }
}
