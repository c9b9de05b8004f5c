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
//! (libm on both): a mixed-radix FFT for lengths whose prime factors are 2, 3 and 5 (the
//! Welch segments' and the time records' lengths) and Bluestein's chirp-z algorithm over
//! a power of two for any other length.
//!
//! Forward transform: `X_k = sum_j x_j exp(-2 pi i j k / n)`, `k = 0..n`.
//! Bluestein: with `jk = (j^2 + k^2 - (k - j)^2) / 2`, `X_k = c_k^* sum_j (x_j c_j^*)
//! c_{k-j}` where `c_m = exp(i pi m^2 / n)`: a convolution, done by FFTs of a power of
//! two `m >= 2 n - 1`.

use crate::math;
use num_complex::Complex64 as C64;
use std::f64::consts::PI;

/// A planned forward DFT of one length (twiddles and chirp computed once).
pub(crate) struct Dft {
    n: usize,
    plan: Plan,
}

enum Plan {
    /// `n` a product of 2, 3 and 5: mixed radix directly.
    Direct(MixedRadix),
    /// Bluestein over a power-of-two transform of length `m`: the chirp `c_j^*` (`j < n`)
    /// and the transform of the convolution kernel `c_{m'}` (`m' = -(n-1)..n-1`, wrapped).
    Bluestein {
        inner: MixedRadix,
        chirp: Vec<C64>,
        kernel: Vec<C64>,
        work: Vec<C64>,
    },
}

impl Dft {
    /// The transform of length `n >= 1`.
    pub(crate) fn new(n: usize) -> Dft {
        let n = n.max(1);
        if let Some(direct) = MixedRadix::new(n) {
            return Dft {
                n,
                plan: Plan::Direct(direct),
            };
        }
        let m = (2 * n - 1).next_power_of_two();
        // A power of two always factors.
        let Some(inner) = MixedRadix::new(m) else {
            unreachable!("{m} is a power of two")
        };
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
        let mut work = vec![C64::new(0.0, 0.0); m];
        inner.forward(&mut kernel, &mut work);
        Dft {
            n,
            plan: Plan::Bluestein {
                inner,
                chirp,
                kernel,
                work,
            },
        }
    }

    /// The unnormalised inverse of `x` in place: `x_j = sum_k X_k exp(2 pi i j k / n)`
    /// (the forward transform of the conjugate, conjugated).
    pub(crate) fn inverse(&mut self, x: &mut [C64]) {
        x.iter_mut().for_each(|v| *v = v.conj());
        self.forward(x);
        x.iter_mut().for_each(|v| *v = v.conj());
    }

    /// Transforms `x` (length `n`) in place.
    pub(crate) fn forward(&mut self, x: &mut [C64]) {
        debug_assert_eq!(x.len(), self.n);
        match &mut self.plan {
            Plan::Direct(r) => {
                let mut input = x.to_vec();
                r.run(&mut input, x);
            }
            Plan::Bluestein {
                inner,
                chirp,
                kernel,
                work,
            } => {
                let m = work.len();
                let mut a = vec![C64::new(0.0, 0.0); m];
                for (w, (xj, cj)) in a.iter_mut().zip(x.iter().zip(chirp.iter())) {
                    *w = xj * cj;
                }
                inner.run(&mut a, work);
                for (w, k) in work.iter_mut().zip(kernel.iter()) {
                    // The inverse through the forward transform of the conjugate.
                    *w = (*w * k).conj();
                }
                a.copy_from_slice(work);
                inner.run(&mut a, work);
                let scale = 1.0 / m as f64;
                for (xk, (w, ck)) in x.iter_mut().zip(work.iter().zip(chirp.iter())) {
                    *xk = w.conj() * scale * ck;
                }
            }
        }
    }
}

/// A recursive decimation-in-time FFT of a length whose factors are 2, 3 and 5: a length
/// `n = p m` is `p` transforms of length `m` (every `p`th sample from offset `r`), then
/// `m` butterflies of size `p`: `X_{k + q m} = sum_r W_p^{r q} (W_n^{r k} Y_r[k])`.
struct MixedRadix {
    /// The radices, outermost first.
    factors: Vec<usize>,
    /// `W_n^j = exp(-2 pi i j / n)`, `j < n`.
    twiddles: Vec<C64>,
}

impl MixedRadix {
    /// The plan for `n`, or `None` when `n` has a prime factor above 5.
    fn new(n: usize) -> Option<MixedRadix> {
        let mut factors = Vec::new();
        let mut rest = n;
        for p in [2, 3, 5] {
            while rest.is_multiple_of(p) {
                factors.push(p);
                rest /= p;
            }
        }
        (rest == 1).then(|| MixedRadix {
            factors,
            twiddles: (0..n)
                .map(|j| {
                    let (s, c) = math::sin_cos(-2.0 * PI * j as f64 / n as f64);
                    C64::new(c, s)
                })
                .collect(),
        })
    }

    /// `out` = the transform of `input` (both of the plan's length; `input` is left as it was).
    fn run(&self, input: &mut [C64], out: &mut [C64]) {
        self.step(input, 1, out, &self.factors);
    }

    /// As [`MixedRadix::run`], `x` transformed in place through `scratch` (same length).
    fn forward(&self, x: &mut [C64], scratch: &mut [C64]) {
        scratch.copy_from_slice(x);
        self.step(scratch, 1, x, &self.factors);
    }

    /// `out` (length `n`) = the transform of `input[0], input[stride], ...`.
    fn step(&self, input: &[C64], stride: usize, out: &mut [C64], factors: &[usize]) {
        let n = out.len();
        let Some((&p, inner)) = factors.split_first() else {
            out[0] = input[0];
            return;
        };
        let m = n / p;
        for r in 0..p {
            self.step(
                &input[r * stride..],
                stride * p,
                &mut out[r * m..(r + 1) * m],
                inner,
            );
        }
        // W_n^j is the plan's W_N^(j N / n); W_p^j its W_N^(j N / p).
        let top = self.twiddles.len();
        let (wn, wp) = (top / n, top / p);
        let mut y = [C64::new(0.0, 0.0); 5];
        for k in 0..m {
            for (r, yr) in y.iter_mut().enumerate().take(p) {
                *yr = out[r * m + k] * self.twiddles[(r * k % n) * wn];
            }
            for q in 0..p {
                let mut sum = y[0];
                for (r, yr) in y.iter().enumerate().take(p).skip(1) {
                    sum += yr * self.twiddles[(r * q % p) * wp];
                }
                out[q * m + k] = sum;
            }
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
        for n in [1, 2, 8, 64, 3, 5, 7, 12, 100, 257, 750, 1000] {
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
