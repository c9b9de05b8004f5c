//! The discrete Fourier transform (Welch's segments, the road realisations), the same to
//! the last bit natively and in the browser.
//!
//! Written here rather than taken from rustfft because rustfft picks its algorithms per
//! target (AVX or SSE natively, scalar in wasm) and takes its twiddles from the
//! platform's `sin`/`cos`: the Welch PSD then differed in the 15th digit between
//! `ridelab road` and the page, and the shaping filter fitted to it carried that to the
//! 8th digit of a criterion (2e-8 relative on the shipped class C profile), where the
//! page must equal the CLI to 1e-9. It also keeps rustfft's many kernels out of the wasm. This transform does the same
//! arithmetic in the same order on every target, its twiddles from [`crate::math`]
//! (libm on both): an iterative radix-2 FFT for powers of two and Bluestein's chirp-z
//! algorithm over it for any other length.
//!
//! Forward transform: `X_k = sum_j x_j exp(-2 pi i j k / n)`, `k = 0..n`.
//! Bluestein: with `jk = (j^2 + k^2 - (k - j)^2) / 2`, `X_k = c_k^* sum_j (x_j c_j^*)
//! c_{k-j}` where `c_m = exp(i pi m^2 / n)`: a convolution, done by radix-2 FFTs of a
//! length `m >= 2 n - 1`.

use crate::math;
use num_complex::Complex64 as C64;
use std::f64::consts::PI;

/// A planned forward DFT of one length (twiddles and chirp computed once).
pub struct Dft {
    n: usize,
    plan: Plan,
}

enum Plan {
    /// `n` a power of two: radix-2 directly.
    Radix2(Radix2),
    /// Bluestein over a radix-2 transform of length `m`: the chirp `c_j^*` (`j < n`) and
    /// the transform of the convolution kernel `c_{m'}` (`m' = -(n-1)..n-1`, wrapped).
    Bluestein {
        inner: Radix2,
        chirp: Vec<C64>,
        kernel: Vec<C64>,
        work: Vec<C64>,
    },
}

impl Dft {
    /// The transform of length `n >= 1`.
    pub fn new(n: usize) -> Dft {
        let n = n.max(1);
        if n.is_power_of_two() {
            return Dft {
                n,
                plan: Plan::Radix2(Radix2::new(n)),
            };
        }
        let m = (2 * n - 1).next_power_of_two();
        let inner = Radix2::new(m);
        // c_j = exp(i pi j^2 / n), with j^2 taken mod 2 n so the angle stays small.
        let c = |j: usize| {
            let j2 = (j as u128 * j as u128 % (2 * n) as u128) as f64;
            let (s, co) = math::sin_cos(PI * j2 / n as f64);
            C64::new(co, s)
        };
        let chirp: Vec<C64> = (0..n).map(|j| c(j).conj()).collect();
        let mut kernel = vec![C64::new(0.0, 0.0); m];
        kernel[0] = c(0);
        for j in 1..n {
            kernel[j] = c(j);
            kernel[m - j] = c(j);
        }
        inner.forward(&mut kernel);
        Dft {
            n,
            plan: Plan::Bluestein {
                inner,
                chirp,
                kernel,
                work: vec![C64::new(0.0, 0.0); m],
            },
        }
    }

    /// The unnormalised inverse of `x` in place: `x_j = sum_k X_k exp(2 pi i j k / n)`
    /// (the forward transform of the conjugate, conjugated).
    pub fn inverse(&mut self, x: &mut [C64]) {
        x.iter_mut().for_each(|v| *v = v.conj());
        self.forward(x);
        x.iter_mut().for_each(|v| *v = v.conj());
    }

    /// Transforms `x` (length `n`) in place.
    pub fn forward(&mut self, x: &mut [C64]) {
        debug_assert_eq!(x.len(), self.n);
        match &mut self.plan {
            Plan::Radix2(r) => r.forward(x),
            Plan::Bluestein {
                inner,
                chirp,
                kernel,
                work,
            } => {
                let m = work.len();
                for (w, (xj, cj)) in work.iter_mut().zip(x.iter().zip(chirp.iter())) {
                    *w = xj * cj;
                }
                work[x.len()..].fill(C64::new(0.0, 0.0));
                inner.forward(work);
                for (w, k) in work.iter_mut().zip(kernel.iter()) {
                    // The inverse through the forward transform of the conjugate.
                    *w = (*w * k).conj();
                }
                inner.forward(work);
                let scale = 1.0 / m as f64;
                for (xk, (w, ck)) in x.iter_mut().zip(work.iter().zip(chirp.iter())) {
                    *xk = w.conj() * scale * ck;
                }
            }
        }
    }
}

/// An iterative radix-2 decimation-in-time FFT of a power-of-two length.
struct Radix2 {
    /// `exp(-2 pi i k / n)`, `k < n / 2`.
    twiddles: Vec<C64>,
}

impl Radix2 {
    fn new(n: usize) -> Radix2 {
        Radix2 {
            twiddles: (0..n / 2)
                .map(|k| {
                    let (s, c) = math::sin_cos(-2.0 * PI * k as f64 / n as f64);
                    C64::new(c, s)
                })
                .collect(),
        }
    }

    fn forward(&self, x: &mut [C64]) {
        let n = x.len();
        if n < 2 {
            return;
        }
        let bits = n.trailing_zeros();
        for i in 0..n {
            let j = i.reverse_bits() >> (usize::BITS - bits);
            if j > i {
                x.swap(i, j);
            }
        }
        let mut len = 2;
        while len <= n {
            let stride = n / len;
            for start in (0..n).step_by(len) {
                for k in 0..len / 2 {
                    let t = x[start + k + len / 2] * self.twiddles[k * stride];
                    let u = x[start + k];
                    x[start + k] = u + t;
                    x[start + k + len / 2] = u - t;
                }
            }
            len *= 2;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The transform against the DFT's definition summed directly, for powers of two and
    /// other lengths (primes among them): within 1e-12 of the largest coefficient.
    #[test]
    fn equals_the_dft_by_its_definition() {
        for n in [1, 2, 8, 64, 3, 7, 12, 100, 257, 750] {
            let x: Vec<C64> = (0..n)
                .map(|j| {
                    C64::new(
                        math::sin(0.37 * j as f64 + 0.1),
                        math::cos(1.3 * j as f64) - 0.2,
                    )
                })
                .collect();
            let mut got = x.clone();
            Dft::new(n).forward(&mut got);
            let want: Vec<C64> = (0..n)
                .map(|k| {
                    x.iter()
                        .enumerate()
                        .map(|(j, xj)| {
                            let a = -2.0 * PI * ((j * k) % n) as f64 / n as f64;
                            xj * C64::new(math::cos(a), math::sin(a))
                        })
                        .sum()
                })
                .collect();
            let top = want.iter().map(|w| w.norm()).fold(0.0, f64::max);
            for (k, (g, w)) in got.iter().zip(&want).enumerate() {
                assert!(
                    (g - w).norm() <= 1e-12 * top.max(1.0),
                    "n = {n}, k = {k}: {g} against {w}"
                );
            }
        }
    }
}
