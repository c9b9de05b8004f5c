//! Welch's method: one-sided auto and cross spectral densities of uniformly sampled
//! tracks, with log-spaced band means.
//!
//! The estimate is taken of the tracks' first differences, the slopes
//! `s_i = (z_{i+1} - z_i) / dx`, and divided by the difference's gain
//! `|D(n)|^2 = (2 sin(pi n dx) / dx)^2` (pre-whitening): a road's elevation PSD falls
//! steeply (`n^-w`, `w` about 2), its slope PSD is nearly flat, and the Hann window's
//! leakage between neighbouring bins, which would bias the elevation estimate upward by
//! about 20 % at the third bin for `w = 2.5`, is then about 1 %. Each segment of `L` slopes
//! (50 % overlap, the set centred on the record) has its least-squares line removed and is
//! weighted by the periodic Hann window `w_k = (1 - cos(2 pi k / L)) / 2`; with `S_j` its
//! DFT, `U = sum w_k^2` and `K` segments,
//!
//! ```text
//! P_xy(n_j) = 2 dx / (U K) sum_segments conj(S_x,j) S_y,j / |D(n_j)|^2,  n_j = j / (L dx),  0 < j <= L/2
//! ```
//!
//! (the factor 2 folds the negative frequencies: one-sided; `j = L/2` without it), so that
//! `sum_j P_xx(n_j) dn` is the variance of the (detrended) record.

use super::{BAND_HZ, LOWEST_BIN, SEGMENT_DIVISOR};
use crate::fft::Dft;
use crate::math;
use num_complex::Complex64 as C64;

/// Whether `m` is `2^a 3^b 5^c` (a fast FFT length).
fn smooth(mut m: usize) -> bool {
    if m == 0 {
        return false;
    }
    for p in [2, 3, 5] {
        while m.is_multiple_of(p) {
            m /= p;
        }
    }
    m == 1
}

/// Welch segment length of [`super::describe`] for `n` samples (`n - 1` slopes): the
/// largest fast FFT length at most `(n - 1) / SEGMENT_DIVISOR`, and at least 16.
pub(crate) fn segment_length(n: usize) -> usize {
    let target = (n.saturating_sub(1) / SEGMENT_DIVISOR).max(16);
    (16..=target).rev().find(|&m| smooth(m)).unwrap_or(16)
}

/// Welch segment length, samples, for the band [`BAND_HZ`] at `speed` (m/s) and spacing
/// `dx` (m): the smallest fast FFT length whose [`LOWEST_BIN`]th bin is at most
/// `BAND_HZ[0] / speed` (as long as the band needs, so as many segments as possible
/// average).
pub(crate) fn segment_for_speed(speed: f64, dx: f64) -> usize {
    let need = (LOWEST_BIN * speed / (BAND_HZ[0] * dx)).ceil().max(16.0);
    let start = if need.is_finite() && need < 1e9 {
        need as usize
    } else {
        usize::MAX / 2
    };
    (start..start.saturating_mul(2).max(start + 1))
        .find(|&m| smooth(m))
        .unwrap_or(start)
}

/// Number of Welch segments of `seg` slopes in a record of `n` samples (50 % overlap).
pub(crate) fn segments(n: usize, seg: usize) -> usize {
    let slopes = n.saturating_sub(1);
    if slopes < seg {
        0
    } else {
        (slopes - seg) / (seg / 2).max(1) + 1
    }
}

/// Spectral densities of one or two tracks over the bins `n_j`, `j = 1..=L/2`.
pub(crate) struct Spectra {
    /// Spatial frequencies, cycle/m.
    pub n: Vec<f64>,
    /// One-sided auto PSD of the first track, m^3.
    pub pxx: Vec<f64>,
    /// Of the second track, if any.
    pub pyy: Option<Vec<f64>>,
    /// One-sided cross PSD `E[conj(X) Y]`, if two tracks.
    pub pxy: Option<Vec<C64>>,
    /// Segment length, slopes (samples).
    pub segment: usize,
    /// Number of segments averaged.
    pub segments: usize,
}

/// Welch spectra of `x` (and `y`, same length) sampled every `dx` m, segments of
/// `seg` slopes (`seg < x.len()`; see the module doc).
pub(crate) fn welch(x: &[f64], y: Option<&[f64]>, dx: f64, seg: usize) -> Spectra {
    let slope = |z: &[f64]| -> Vec<f64> { z.windows(2).map(|w| (w[1] - w[0]) / dx).collect() };
    let xs = slope(x);
    let ys = y.map(slope);
    let x = &xs[..];
    let y = ys.as_deref();
    let n = x.len();
    let seg = seg.min(n).max(2);
    let hop = seg / 2;
    let k = (n - seg) / hop + 1;
    let offset = (n - seg - (k - 1) * hop) / 2;
    let window: Vec<f64> = (0..seg)
        .map(|i| 0.5 * (1.0 - math::cos(2.0 * std::f64::consts::PI * i as f64 / seg as f64)))
        .collect();
    let u: f64 = window.iter().map(|w| w * w).sum();
    let mut fft = Dft::new(seg);
    let half = seg / 2;
    let mut pxx = vec![0.0; half];
    let mut pyy = y.map(|_| vec![0.0; half]);
    let mut pxy = y.map(|_| vec![C64::new(0.0, 0.0); half]);
    // Two real segments go through one complex transform (`x + i y`, then split by
    // symmetry): the two tracks' segments together, one track's segments in pairs.
    let mut bz = vec![C64::new(0.0, 0.0); seg];
    let mut add = |bz: &[C64], both: bool, track2: bool| {
        for j in 1..=half {
            let (a, b) = (bz[j], bz[seg - j].conj());
            let first = (a + b) * 0.5;
            let second = (a - b) * C64::new(0.0, -0.5);
            pxx[j - 1] += first.norm_sqr();
            if !both {
                continue;
            }
            match (track2, pyy.as_mut(), pxy.as_mut()) {
                (true, Some(pyy), Some(pxy)) => {
                    pyy[j - 1] += second.norm_sqr();
                    pxy[j - 1] += first.conj() * second;
                }
                _ => pxx[j - 1] += second.norm_sqr(),
            }
        }
    };
    let at = |s: usize| offset + s * hop;
    match y {
        Some(y) => {
            for s in 0..k {
                prepare(&x[at(s)..at(s) + seg], &window, &mut bz, false);
                prepare(&y[at(s)..at(s) + seg], &window, &mut bz, true);
                fft.forward(&mut bz);
                add(&bz, true, true);
            }
        }
        None => {
            for s in (0..k).step_by(2) {
                prepare(&x[at(s)..at(s) + seg], &window, &mut bz, false);
                let both = s + 1 < k;
                if both {
                    prepare(&x[at(s + 1)..at(s + 1) + seg], &window, &mut bz, true);
                }
                fft.forward(&mut bz);
                add(&bz, both, false);
            }
        }
    }
    let scale = |j: usize| {
        let fold = if 2 * j == seg { 1.0 } else { 2.0 };
        let d = 2.0 * math::sin(std::f64::consts::PI * j as f64 / seg as f64) / dx;
        fold * dx / (u * k as f64 * d * d)
    };
    let nj: Vec<f64> = (1..=half).map(|j| j as f64 / (seg as f64 * dx)).collect();
    for (i, p) in pxx.iter_mut().enumerate() {
        *p *= scale(i + 1);
    }
    if let Some(p) = pyy.as_mut() {
        for (i, v) in p.iter_mut().enumerate() {
            *v *= scale(i + 1);
        }
    }
    if let Some(p) = pxy.as_mut() {
        for (i, v) in p.iter_mut().enumerate() {
            *v *= scale(i + 1);
        }
    }
    Spectra {
        n: nj,
        pxx,
        pyy,
        pxy,
        segment: seg,
        segments: k,
    }
}

/// Copies `x` into `buf`'s real parts (`imag`: its imaginary parts; a real copy zeroes
/// them) with its least-squares line removed and the window applied.
fn prepare(x: &[f64], window: &[f64], buf: &mut [C64], imag: bool) {
    let m = x.len() as f64;
    let tm = 0.5 * (m - 1.0);
    let xm = x.iter().sum::<f64>() / m;
    let (mut sxy, mut sxx) = (0.0, 0.0);
    for (i, v) in x.iter().enumerate() {
        let t = i as f64 - tm;
        sxy += t * (v - xm);
        sxx += t * t;
    }
    let slope = if sxx > 0.0 { sxy / sxx } else { 0.0 };
    for (i, (v, b)) in x.iter().zip(buf.iter_mut()).enumerate() {
        let d = v - xm - slope * (i as f64 - tm);
        if imag {
            b.im = d * window[i];
        } else {
            *b = C64::new(d * window[i], 0.0);
        }
    }
}

/// Log-spaced bands of `1 / per_octave` octave over the samples of the sorted `x` in
/// `[lo, hi]`, each widened until it holds at least `min_bins` samples (a short remainder
/// joins the last band): index ranges `start..end` into `x`.
pub(crate) fn band_ranges(
    x: &[f64],
    lo: f64,
    hi: f64,
    per_octave: f64,
    min_bins: usize,
) -> Vec<(usize, usize)> {
    let ratio = math::powf(2f64, 1.0 / per_octave);
    let first = x.partition_point(|&v| v < lo);
    let last = x.partition_point(|&v| v <= hi);
    let mut out = Vec::new();
    let mut i = first;
    let mut edge = lo * ratio;
    while i < last {
        let mut j = i;
        while j < last && (x[j] < edge || j - i < min_bins) {
            j += 1;
        }
        if last - j < min_bins {
            j = last;
        }
        out.push((i, j));
        if j < last {
            while edge <= x[j] {
                edge *= ratio;
            }
        }
        i = j;
    }
    out
}

/// Band means of `p(x)` over [`band_ranges`]: `(centre, mean)` pairs, the centre the
/// geometric mean of the band's `x`, the mean the arithmetic mean of its `p` (power is
/// additive).
pub(crate) fn band_means(
    x: &[f64],
    p: &[f64],
    lo: f64,
    hi: f64,
    per_octave: f64,
    min_bins: usize,
) -> Vec<(f64, f64)> {
    band_ranges(x, lo, hi, per_octave, min_bins)
        .into_iter()
        .map(|(i, j)| {
            let count = (j - i) as f64;
            let lx = x[i..j].iter().map(|v| math::ln(*v)).sum::<f64>() / count;
            let mp = p[i..j].iter().sum::<f64>() / count;
            (math::exp(lx), mp)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn segment_lengths_are_fast_fft_lengths() {
        assert_eq!(segment_length(80_001), 10_000);
        assert_eq!(segment_length(257), 32);
        assert_eq!(segment_length(100), 16);
        let s = segment_length(123_457);
        assert!(
            s <= 123_456 / 8 && s as f64 > 0.95 * (123_456 / 8) as f64,
            "{s}"
        );
        // 20 m/s at 5 cm: 3 bins below 0.3 Hz need 200 m = 4000 samples.
        assert_eq!(segment_for_speed(20.0, 0.05), 4000);
        let s = segment_for_speed(13.0, 0.07);
        assert!(
            smooth(s) && 3.0 / (s as f64 * 0.07) * 13.0 <= 0.3 + 1e-12,
            "{s}"
        );
        assert_eq!(segments(80_001, 10_000), 15);
    }

    /// A sinusoid of amplitude A has variance A^2 / 2: the PSD around its frequency
    /// integrates to it, and the trusted bins (from the third) elsewhere hold almost nothing
    /// (the first two carry the detrend's share, amplified by the pre-whitening); a second
    /// track that is the first delayed has coherence 1.
    #[test]
    fn welch_keeps_the_variance_and_the_coherence() {
        let dx = 0.05;
        let n = 40_000;
        let (a, f0) = (0.003, 0.7);
        let x: Vec<f64> = (0..n)
            .map(|i| a * (2.0 * PI * f0 * i as f64 * dx + 0.3).sin())
            .collect();
        let y: Vec<f64> = (0..n)
            .map(|i| a * (2.0 * PI * f0 * (i as f64 * dx - 0.4) + 0.3).sin())
            .collect();
        let s = welch(&x, Some(&y), dx, segment_length(n));
        let dn = s.n[0];
        let peak = (0..s.n.len())
            .max_by(|&i, &j| s.pxx[i].total_cmp(&s.pxx[j]))
            .unwrap();
        let var: f64 = s.pxx[peak - 3..peak + 4].iter().sum::<f64>() * dn;
        assert!((var / (a * a / 2.0) - 1.0).abs() < 1e-3, "{var}");
        let rest: f64 = s.pxx[2..peak - 3]
            .iter()
            .chain(&s.pxx[peak + 4..])
            .sum::<f64>()
            * dn;
        assert!(rest < 0.01 * var, "{rest}");
        assert!((s.n[peak] - f0).abs() <= dn);
        let pyy = s.pyy.as_ref().unwrap();
        let pxy = s.pxy.as_ref().unwrap();
        let coh = pxy[peak].norm_sqr() / (s.pxx[peak] * pyy[peak]);
        assert!((coh - 1.0).abs() < 1e-9);
        // The cross phase is the delay's, 2 pi n 0.4.
        let ph = pxy[peak].arg();
        let expect = -2.0 * PI * s.n[peak] * 0.4;
        let d = (ph - expect).rem_euclid(2.0 * PI);
        assert!(d.min(2.0 * PI - d) < 0.2, "{ph} vs {expect}");
    }

    #[test]
    fn band_means_are_log_spaced_and_cover_the_range() {
        let x: Vec<f64> = (1..=1000).map(|i| i as f64 * 0.01).collect();
        let p: Vec<f64> = x.iter().map(|v| v * v).collect();
        let b = band_means(&x, &p, 0.05, 8.0, 3.0, 2);
        assert!(b.len() > 15 && b.len() < 30, "{}", b.len());
        assert!(b.windows(2).all(|w| w[1].0 > w[0].0));
        assert!(b[0].0 >= 0.05 && b.last().unwrap().0 <= 8.0);
    }
}
