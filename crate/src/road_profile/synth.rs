//! Synthetic profiles: a seeded realisation of a stated displacement PSD, for the tests
//! and the shipped examples.
//!
//! The profile is a periodic sum of sinusoids on the grid `n_k = k / (N dx)`, `dn = 1 / (N dx)`,
//! with amplitudes `A_k = sqrt(2 Gd(n_k) dn)` and seeded random phases, built by one inverse
//! FFT (as `time_domain` builds its roads), for `n_min <= n_k < 1 / (2 dx)` and
//! `Gd(n) = Gd(n0) (n / n0)^-w` (ISO 8608 with any waviness `w`). Its variance is exactly
//! `sum_k A_k^2 / 2`, the PSD's integral on the grid.
//!
//! **Two tracks** with coherence `gamma(n) = exp(-n / n_c)`: a sum track `s` with PSD
//! `Gd (1 + gamma) / 2` and an independent difference track `d` with `Gd (1 - gamma) / 2`
//! give `right = s + d`, `left = s - d`, each with PSD `Gd` and cross PSD `gamma Gd`
//! (magnitude-squared coherence `gamma^2`).
//!
//! **Slab concrete road** ([`Slabs`]): added to the random profile (on both tracks: the
//! joints span the lane), each slab of length `Ls` sits at a random level `o_i ~ N(0, s_f^2)`
//! (faults at the joints: steps `o_{i+1} - o_i`) and is curled,
//! `c ((2u - 1)^2 - 1/3)` with `u` the position along the slab from 0 to 1 (zero mean);
//! the curl is periodic and puts spectral lines at `n = k / Ls`.

use super::profile::{Profile, MAX_SAMPLES, MAX_SPACING, MIN_SAMPLES, MIN_SPACING};
use crate::error::{Result, RideError};
use crate::math;
use crate::road::{RoadClass, N0, N_MIN};
use num_complex::Complex64 as C64;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// The joints of a slab concrete road.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Slabs {
    /// Slab length (joint spacing), m.
    pub length: f64,
    /// RMS of each slab's level about the road's, m (the faults, differences of
    /// neighbouring levels, have `sqrt 2` times that).
    pub fault_rms: f64,
    /// Curl: height of a slab's ends over its mean, less the mean's, m (`c` above).
    pub curl: f64,
}

impl Default for Slabs {
    /// 5 m slabs, 1.5 mm level RMS, 1.5 mm curl.
    fn default() -> Self {
        Slabs {
            length: 5.0,
            fault_rms: 0.0015,
            curl: 0.0015,
        }
    }
}

/// What to synthesise.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Synthesis {
    /// `Gd(n0)`, m^3.
    pub gd_n0: f64,
    /// Waviness `w`, -.
    pub waviness: f64,
    /// Lowest spatial frequency realised, cycle/m.
    pub n_min: f64,
    /// Length, m.
    pub length: f64,
    /// Spacing, m.
    pub spacing: f64,
    /// Seed of the phases (and of the slab levels).
    pub seed: u64,
    /// Slab joints added, if any.
    pub slabs: Option<Slabs>,
    /// Two tracks with coherence `exp(-n / coherence_n)` (`coherence_n` in cycle/m), if any.
    pub coherence_n: Option<f64>,
}

impl Default for Synthesis {
    /// Class C, waviness 2, from 0.011 cycle/m, 1 km at 5 cm, seed 1, one track.
    fn default() -> Self {
        Synthesis {
            gd_n0: RoadClass::C.gd_n0(),
            waviness: 2.0,
            n_min: N_MIN,
            length: 1000.0,
            spacing: 0.05,
            seed: 1,
            slabs: None,
            coherence_n: None,
        }
    }
}

impl Synthesis {
    /// Checks every field; messages name the field.
    pub(crate) fn validate(&self) -> Result<()> {
        let pos = |v: f64| v.is_finite() && v > 0.0;
        if !(pos(self.gd_n0) && self.gd_n0 <= 1.0) {
            return Err(RideError::field("gd_n0", "must be in (0, 1] m^3"));
        }
        if !(self.waviness.is_finite() && (0.5..=5.0).contains(&self.waviness)) {
            return Err(RideError::field("waviness", "must be in [0.5, 5]"));
        }
        if !(self.spacing.is_finite() && (MIN_SPACING..=MAX_SPACING).contains(&self.spacing)) {
            return Err(RideError::field(
                "spacing",
                format!("must be in [{MIN_SPACING}, {MAX_SPACING}] m"),
            ));
        }
        let n = self.length / self.spacing;
        if !(n.is_finite() && n >= MIN_SAMPLES as f64 && n < MAX_SAMPLES as f64) {
            return Err(RideError::field(
                "length",
                format!("must hold {MIN_SAMPLES}..{MAX_SAMPLES} samples at the spacing"),
            ));
        }
        if !(pos(self.n_min) && self.n_min < 0.5 / self.spacing) {
            return Err(RideError::field(
                "n_min",
                "must be > 0 and below the Nyquist frequency (cycle/m)",
            ));
        }
        if let Some(c) = self.coherence_n {
            if !pos(c) {
                return Err(RideError::field("coherence_n", "must be > 0 (cycle/m)"));
            }
        }
        if let Some(s) = &self.slabs {
            if !(pos(s.length) && s.length <= self.length / 2.0) {
                return Err(RideError::field(
                    "slabs.length",
                    "must be > 0 and at most half the profile (m)",
                ));
            }
            if !(s.fault_rms.is_finite() && s.fault_rms >= 0.0 && s.fault_rms <= 0.05) {
                return Err(RideError::field(
                    "slabs.fault_rms",
                    "must be in [0, 0.05] m",
                ));
            }
            if !(s.curl.is_finite() && s.curl.abs() <= 0.05) {
                return Err(RideError::field("slabs.curl", "must be in [-0.05, 0.05] m"));
            }
        }
        Ok(())
    }

    /// The PSD realised, `Gd(n) = Gd(n0) (n / n0)^-w`, m^3 (before slabs).
    pub(crate) fn gd(&self, n: f64) -> f64 {
        self.gd_n0 * math::powf(n / N0, -self.waviness)
    }
}

/// The example profiles shipped in `assets/roads/` (written by
/// `cargo run -p ridelab --example make_road_profiles`), by file name:
///
/// - `class-c-waviness-2.5.csv`: ISO class C (`Gd(n0) = 256e-6` m^3), waviness 2.5, 4 km at
///   10 cm, two tracks with coherence `exp(-n / 0.2 cycle/m)`;
/// - `concrete-slab-5m.csv`: ISO class B, waviness 2, with 5 m slabs (1.5 mm level RMS,
///   1.5 mm curl), 3 km at 5 cm, one track.
pub fn shipped_examples() -> [(&'static str, Synthesis); 2] {
    [
        (
            "class-c-waviness-2.5.csv",
            Synthesis {
                gd_n0: RoadClass::C.gd_n0(),
                waviness: 2.5,
                length: 4000.0,
                spacing: 0.1,
                seed: 31,
                coherence_n: Some(0.2),
                ..Synthesis::default()
            },
        ),
        (
            "concrete-slab-5m.csv",
            Synthesis {
                gd_n0: RoadClass::B.gd_n0(),
                waviness: 2.0,
                length: 3000.0,
                spacing: 0.05,
                seed: 5,
                slabs: Some(Slabs::default()),
                ..Synthesis::default()
            },
        ),
    ]
}

/// Decimals of the shipped examples' CSV: distance (m) and elevation (m, micrometres).
pub const EXAMPLE_DECIMALS: (usize, usize) = (2, 6);

/// A seeded profile realising `s` (see the module doc).
pub fn synthesize(s: &Synthesis) -> Result<Profile> {
    s.validate()?;
    let n = (s.length / s.spacing).round() as usize + 1;
    let dn = 1.0 / (n as f64 * s.spacing);
    let mut rng = ChaCha8Rng::seed_from_u64(s.seed);
    // The sum and difference tracks' shares of the PSD, by the coherence (1 without).
    let coh = |k: f64| s.coherence_n.map_or(1.0, |nc| math::exp(-k / nc));
    let sum = realise(n, dn, s, &|k| 0.5 * (1.0 + coh(k)), &mut rng);
    let diff = s
        .coherence_n
        .is_some()
        .then(|| realise(n, dn, s, &|k| 0.5 * (1.0 - coh(k)), &mut rng));
    let slab = s.slabs.map(|sl| slabs(n, s.spacing, &sl, &mut rng));
    let add = |mut z: Vec<f64>| {
        if let Some(sl) = &slab {
            for (v, a) in z.iter_mut().zip(sl) {
                *v += a;
            }
        }
        z
    };
    let (left, right) = match diff {
        None => (add(sum), None),
        Some(d) => (
            add(sum.iter().zip(&d).map(|(a, b)| a - b).collect()),
            Some(add(sum.iter().zip(&d).map(|(a, b)| a + b).collect())),
        ),
    };
    Profile::uniform(s.spacing, 0.0, left, right)
}

/// One track with PSD `share(n) Gd(n)`: random phases, exact amplitudes.
fn realise(
    n: usize,
    dn: f64,
    s: &Synthesis,
    share: &dyn Fn(f64) -> f64,
    rng: &mut ChaCha8Rng,
) -> Vec<f64> {
    let mut spec = vec![C64::new(0.0, 0.0); n];
    for k in 1..n.div_ceil(2) {
        let ph: f64 = rng.random_range(0.0..2.0 * PI);
        let nk = k as f64 * dn;
        if nk < s.n_min {
            continue;
        }
        let amp = (2.0 * s.gd(nk) * share(nk) * dn).sqrt();
        let z = math::cpolar(0.5 * amp, ph);
        spec[k] = z;
        spec[n - k] = z.conj();
    }
    crate::fft::Dft::new(n).inverse(&mut spec);
    spec.into_iter().map(|c| c.re).collect()
}

/// The slab levels and curl at every sample (see the module doc).
fn slabs(n: usize, dx: f64, sl: &Slabs, rng: &mut ChaCha8Rng) -> Vec<f64> {
    let count = ((n as f64 * dx) / sl.length).ceil() as usize + 1;
    let levels: Vec<f64> = (0..count)
        .map(|_| sl.fault_rms * standard_normal(rng))
        .collect();
    (0..n)
        .map(|i| {
            let x = i as f64 * dx / sl.length;
            let slab = x.floor() as usize;
            let u = x - x.floor();
            levels[slab] + sl.curl * ((2.0 * u - 1.0).powi(2) - 1.0 / 3.0)
        })
        .collect()
}

/// A standard normal draw by Box-Muller (written here: `rand_distr` is not a dependency
/// and two lines do not warrant one).
fn standard_normal(rng: &mut ChaCha8Rng) -> f64 {
    let u1: f64 = 1.0 - rng.random::<f64>(); // (0, 1]
    let u2: f64 = rng.random();
    (-2.0 * math::ln(u1)).sqrt() * math::cos(2.0 * PI * u2)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_variance_is_the_psd_integral_and_seeds_repeat() {
        let s = Synthesis {
            length: 500.0,
            ..Synthesis::default()
        };
        let p = synthesize(&s).unwrap();
        let n = p.len();
        let dn = 1.0 / (n as f64 * s.spacing);
        let expect: f64 = (1..n.div_ceil(2))
            .map(|k| k as f64 * dn)
            .filter(|&nk| nk >= s.n_min)
            .map(|nk| s.gd(nk) * dn)
            .sum();
        let mean = p.elevation.iter().sum::<f64>() / n as f64;
        let var = p.elevation.iter().map(|z| (z - mean).powi(2)).sum::<f64>() / n as f64;
        assert!((var / expect - 1.0).abs() < 1e-9, "{var} vs {expect}");
        assert_eq!(synthesize(&s).unwrap(), p);
        let other = synthesize(&Synthesis { seed: 2, ..s }).unwrap();
        assert_ne!(other.elevation, p.elevation);
    }

    /// The curl puts lines at `k / Ls`: its first harmonic has amplitude `4 c / pi^2`
    /// (variance `(4 c / pi^2)^2 / 2`), its second a quarter of that; Welch finds their power
    /// in the bins around `0.2` and `0.4` cycle/m over a negligible random background.
    #[test]
    fn slabs_put_lines_at_the_joint_spacing() {
        let c = 0.0015;
        let s = Synthesis {
            gd_n0: 1e-9,
            length: 600.0,
            slabs: Some(Slabs {
                length: 5.0,
                fault_rms: 0.0,
                curl: c,
            }),
            ..Synthesis::default()
        };
        let p = synthesize(&s).unwrap();
        let d = super::super::describe(&p).unwrap();
        let dn = d.welch.resolution;
        let power = |n0: f64| -> f64 {
            d.psd
                .n
                .iter()
                .zip(&d.psd.gd)
                .filter(|(n, _)| (**n - n0).abs() <= 4.0 * dn)
                .map(|(_, g)| g * dn)
                .sum()
        };
        let a1 = 4.0 * c / (PI * PI);
        for (k, n0) in [(1.0, 0.2), (2.0, 0.4)] {
            let expect = (a1 / (k * k)).powi(2) / 2.0;
            assert!(
                (power(n0) / expect - 1.0).abs() < 0.05,
                "{k}: {} vs {expect}",
                power(n0)
            );
        }
        // With faults the slab levels add a sinc^2 spectrum that vanishes at the lines.
        let f = synthesize(&Synthesis {
            slabs: Some(Slabs::default()),
            ..s
        })
        .unwrap();
        assert!(
            f.elevation.iter().map(|z| z * z).sum::<f64>()
                > p.elevation.iter().map(|z| z * z).sum::<f64>()
        );
    }

    #[test]
    fn bad_settings_name_the_field() {
        let bad = [
            (
                Synthesis {
                    gd_n0: -1.0,
                    ..Synthesis::default()
                },
                "gd_n0",
            ),
            (
                Synthesis {
                    waviness: f64::NAN,
                    ..Synthesis::default()
                },
                "waviness",
            ),
            (
                Synthesis {
                    spacing: 3.0,
                    ..Synthesis::default()
                },
                "spacing",
            ),
            (
                Synthesis {
                    length: 1.0,
                    ..Synthesis::default()
                },
                "length",
            ),
            (
                Synthesis {
                    coherence_n: Some(0.0),
                    ..Synthesis::default()
                },
                "coherence_n",
            ),
            (
                Synthesis {
                    slabs: Some(Slabs {
                        length: -5.0,
                        ..Slabs::default()
                    }),
                    ..Synthesis::default()
                },
                "slabs.length",
            ),
        ];
        for (s, field) in bad {
            let e = synthesize(&s).unwrap_err().to_string();
            assert!(e.starts_with(field), "{e}");
        }
    }
}
