//! Describing a profile: its displacement PSD by Welch's method, the ISO 8608 fit and
//! class, and the coherence of two tracks.
//!
//! ISO 8608 fit: least squares of `log10 Gd` on `log10 (n / n0)` over the 1/12-octave band
//! means (each band weighs the same, as on ISO's log-log chart) in the fit band: ISO's
//! `[0.011, 2.83]` cycle/m clipped to what the profile resolves
//! ([`Profile::resolved_band`]). The line `log10 Gd = log10 Gd(n0) - w log10 (n / n0)` gives
//! `Gd(n0)` (m^3) and the waviness `w`; the class is the one whose centre
//! `16e-6 4^k` m^3 is nearest in `log Gd(n0)`, i.e. the class boundaries are the geometric
//! means between the class centres (`32e-6, 128e-6, ...` m^3). With two tracks the fit is
//! of their mean PSD.

use super::profile::Profile;
use super::welch::{band_means, welch};
use crate::error::{Result, RideError};
use crate::math;
use crate::road::{RoadClass, N0, N_MIN};
use serde::Serialize;
use std::collections::BTreeMap;

/// ISO 8608's highest spatial frequency of classification, cycle/m.
pub(crate) const N_MAX_ISO: f64 = 2.83;
/// Band means per octave of the fit and of [`RoadDescription::psd_bands`].
const BANDS_PER_OCTAVE: f64 = 12.0;

/// The ISO 8608 fit of a profile.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct IsoFit {
    /// Class A..H by `gd_n0` (boundaries at the geometric means of the class centres).
    pub class: RoadClass,
    /// `Gd(n0)` at `n0 = 0.1` cycle/m, m^3.
    pub gd_n0: f64,
    /// Waviness `w` of `Gd(n) = Gd(n0) (n / n0)^-w`, -.
    pub waviness: f64,
    /// Fit band `[n_lo, n_hi]`, cycle/m.
    pub band: [f64; 2],
    /// RMS of `log10(Gd / fit)` over the band means, -.
    pub residual: f64,
}

/// A PSD over spatial frequency.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PsdSeries {
    /// Spatial frequency, cycle/m.
    pub n: Vec<f64>,
    /// One-sided displacement PSD of the track `elevation_m` (or the only track), m^3.
    pub gd: Vec<f64>,
    /// Of the right track (`elevation_right_m`), m^3, with two tracks.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub gd_right: Option<Vec<f64>>,
}

/// Magnitude-squared coherence of the two tracks over spatial frequency.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CoherenceSeries {
    /// Spatial frequency, cycle/m.
    pub n: Vec<f64>,
    /// `|P_lr|^2 / (P_ll P_rr)` (Welch), 0..1.
    pub gamma2: Vec<f64>,
}

/// The settings of the Welch estimate.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WelchInfo {
    /// Segment length, samples.
    pub segment_samples: usize,
    /// Segment length, m.
    pub segment_m: f64,
    /// Segments averaged.
    pub segments: usize,
    /// Overlap of consecutive segments, -.
    pub overlap: f64,
    /// Bin spacing `1 / (segment dx)`, cycle/m.
    pub resolution: f64,
}

/// What [`describe`] tells about a profile.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RoadDescription {
    /// Number of samples.
    pub samples: usize,
    /// Spacing, m.
    pub spacing_m: f64,
    /// Length, m.
    pub length_m: f64,
    /// Number of tracks (1 or 2).
    pub tracks: usize,
    /// The ISO 8608 fit (of the mean of the tracks' PSDs with two).
    pub iso8608: IsoFit,
    /// The spatial frequencies the profile resolves, cycle/m: from the lowest trusted Welch
    /// bin to half the Nyquist frequency (the PSD outside it is not to be read).
    pub resolved_band: [f64; 2],
    /// The Welch PSD at every bin (DC left out).
    pub psd: PsdSeries,
    /// The same in 1/12-octave band means (the fit's data; the mean of the tracks).
    pub psd_bands: PsdSeries,
    /// The tracks' coherence, with two tracks.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub coherence: Option<CoherenceSeries>,
    /// The Welch settings.
    pub welch: WelchInfo,
    /// How it was computed, in words.
    pub method: String,
    /// The unit of every numeric field, by its JSON path.
    pub units: BTreeMap<&'static str, &'static str>,
    /// Notes from reading the file (resampling).
    pub notes: Vec<String>,
}

/// Describes `profile`: Welch PSD, ISO 8608 fit and class, coherence (see the module doc).
pub fn describe(profile: &Profile) -> Result<RoadDescription> {
    let dx = profile.spacing;
    let seg = profile.segment_samples();
    let right = profile.elevation_right.as_deref();
    let s = welch(&profile.elevation, right, dx, seg);
    let mean: Vec<f64> = match &s.pyy {
        Some(pyy) => s.pxx.iter().zip(pyy).map(|(a, b)| 0.5 * (a + b)).collect(),
        None => s.pxx.clone(),
    };
    let [r_lo, r_hi] = profile.resolved_band();
    let band = [N_MIN.max(r_lo), N_MAX_ISO.min(r_hi)];
    if band[1] < 4.0 * band[0] {
        return Err(RideError::field(
            "distance_m",
            format!(
                "the profile ({:.0} m at {dx} m) resolves {r_lo:.4}..{r_hi:.3} cycle/m: too \
                 little of ISO 8608's band 0.011..2.83 cycle/m for a fit (two octaves needed)",
                profile.length()
            ),
        ));
    }
    let fit = iso_fit(&s.n, &mean, band)?;
    let bands = band_means(&s.n, &mean, s.n[0], f64::INFINITY, BANDS_PER_OCTAVE, 1);
    let coherence = match (&s.pyy, &s.pxy) {
        (Some(pyy), Some(pxy)) => Some(CoherenceSeries {
            n: s.n.clone(),
            gamma2: (0..s.n.len())
                .map(|j| {
                    let d = s.pxx[j] * pyy[j];
                    if d > 0.0 {
                        (pxy[j].norm_sqr() / d).min(1.0)
                    } else {
                        0.0
                    }
                })
                .collect(),
        }),
        _ => None,
    };
    let info = WelchInfo {
        segment_samples: s.segment,
        segment_m: s.segment as f64 * dx,
        segments: s.segments,
        overlap: 0.5,
        resolution: 1.0 / (s.segment as f64 * dx),
    };
    let method = format!(
        "displacement PSD by Welch's method: each track split into {} segments of {} samples \
         ({:.1} m, bin spacing {:.5} cycle/m) with 50 % overlap, each with its least-squares \
         line removed and a Hann window, one-sided (m^2 per cycle/m); ISO 8608 fit: least \
         squares of log10 Gd on log10 n over 1/12-octave band means in {:.4}..{:.3} cycle/m \
         (ISO's 0.011..2.83 clipped to the {:.4}..{:.3} cycle/m the profile resolves: from {} \
         bins to half the Nyquist frequency){}; class by Gd(n0) with boundaries at the \
         geometric means of the class centres 16e-6 4^k m^3",
        info.segments,
        info.segment_samples,
        info.segment_m,
        info.resolution,
        band[0],
        band[1],
        r_lo,
        r_hi,
        super::LOWEST_BIN,
        if right.is_some() {
            "; two tracks: the fit is of the mean of their PSDs, coherence |P_lr|^2 / (P_ll P_rr) by Welch"
        } else {
            ""
        }
    );
    Ok(RoadDescription {
        samples: profile.len(),
        spacing_m: dx,
        length_m: profile.length(),
        tracks: profile.tracks(),
        iso8608: fit,
        resolved_band: [r_lo, r_hi],
        psd: PsdSeries {
            n: s.n.clone(),
            gd: s.pxx.clone(),
            gd_right: s.pyy.clone(),
        },
        psd_bands: PsdSeries {
            n: bands.iter().map(|b| b.0).collect(),
            gd: bands.iter().map(|b| b.1).collect(),
            gd_right: None,
        },
        coherence,
        welch: info,
        method,
        units: units(),
        notes: profile.notes.clone(),
    })
}

/// The ISO 8608 fit over `band` (see the module doc).
pub(super) fn iso_fit(n: &[f64], gd: &[f64], band: [f64; 2]) -> Result<IsoFit> {
    let pts: Vec<(f64, f64)> = band_means(n, gd, band[0], band[1], BANDS_PER_OCTAVE, 1)
        .into_iter()
        .filter(|(_, g)| *g > 0.0)
        .map(|(x, g)| (math::log10(x / N0), math::log10(g)))
        .collect();
    if pts.len() < 3 {
        return Err(RideError::field(
            "distance_m",
            "too few PSD bins in the ISO 8608 band for a fit",
        ));
    }
    let m = pts.len() as f64;
    let xm = pts.iter().map(|p| p.0).sum::<f64>() / m;
    let ym = pts.iter().map(|p| p.1).sum::<f64>() / m;
    let sxx: f64 = pts.iter().map(|p| (p.0 - xm).powi(2)).sum();
    let sxy: f64 = pts.iter().map(|p| (p.0 - xm) * (p.1 - ym)).sum();
    let slope = sxy / sxx;
    let a = ym - slope * xm;
    let residual = (pts
        .iter()
        .map(|p| (p.1 - a - slope * p.0).powi(2))
        .sum::<f64>()
        / m)
        .sqrt();
    let gd_n0 = math::powf(10f64, a);
    Ok(IsoFit {
        class: class_of(gd_n0),
        gd_n0,
        waviness: -slope,
        band,
        residual,
    })
}

/// The ISO 8608 class whose centre `16e-6 4^k` is nearest to `gd_n0` in log.
fn class_of(gd_n0: f64) -> RoadClass {
    let k = (math::ln(gd_n0 / 16e-6) / math::ln(4f64))
        .round()
        .clamp(0.0, 7.0) as usize;
    RoadClass::ALL[k]
}

fn units() -> BTreeMap<&'static str, &'static str> {
    [
        ("samples", "-"),
        ("spacing_m", "m"),
        ("length_m", "m"),
        ("tracks", "-"),
        (
            "iso8608.gd_n0",
            "m^3 (m^2 per cycle/m, at n0 = 0.1 cycle/m)",
        ),
        ("iso8608.waviness", "-"),
        ("iso8608.band", "cycle/m"),
        ("iso8608.residual", "- (RMS of log10 Gd / fit)"),
        ("resolved_band", "cycle/m"),
        ("psd.n", "cycle/m"),
        ("psd.gd", "m^3 (m^2 per cycle/m), one-sided"),
        ("psd.gd_right", "m^3 (m^2 per cycle/m), one-sided"),
        ("psd_bands.n", "cycle/m"),
        ("psd_bands.gd", "m^3 (m^2 per cycle/m), one-sided"),
        ("coherence.n", "cycle/m"),
        ("coherence.gamma2", "-"),
        ("welch.segment_samples", "-"),
        ("welch.segment_m", "m"),
        ("welch.segments", "-"),
        ("welch.overlap", "-"),
        ("welch.resolution", "cycle/m"),
    ]
    .into_iter()
    .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::road_profile::synth::{synthesize, Synthesis};

    #[test]
    fn class_boundaries_are_geometric_means() {
        assert_eq!(class_of(16e-6), RoadClass::A);
        assert_eq!(class_of(31.9e-6), RoadClass::A);
        assert_eq!(class_of(32.1e-6), RoadClass::B);
        assert_eq!(class_of(256e-6), RoadClass::C);
        assert_eq!(class_of(1e-9), RoadClass::A);
        assert_eq!(class_of(131_000e-6), RoadClass::G);
        assert_eq!(class_of(131_200e-6), RoadClass::H);
        assert_eq!(class_of(10.0), RoadClass::H);
    }

    /// Profiles synthesised from every ISO class (seeded; several waviness values) are
    /// recovered: class right, Gd(n0) within 25 %, waviness within 0.2.
    #[test]
    fn iso_classes_a_to_h_are_recovered() {
        let wav = [2.0, 2.5, 1.8, 3.0, 2.0, 2.2, 3.5, 2.0];
        for (k, class) in RoadClass::ALL.iter().enumerate() {
            let syn = Synthesis {
                gd_n0: class.gd_n0(),
                waviness: wav[k],
                length: 1500.0,
                spacing: 0.05,
                seed: 100 + k as u64,
                ..Synthesis::default()
            };
            let p = synthesize(&syn).unwrap();
            let d = describe(&p).unwrap();
            let f = &d.iso8608;
            assert_eq!(f.class, *class, "{f:?}");
            assert!(
                (f.gd_n0 / class.gd_n0() - 1.0).abs() < 0.25,
                "{class:?} {f:?}"
            );
            assert!((f.waviness - wav[k]).abs() < 0.2, "{class:?} {f:?}");
            assert!(f.residual < 0.1, "{f:?}");
        }
    }

    #[test]
    fn two_tracks_give_coherence_and_the_json_names_units() {
        let syn = Synthesis {
            length: 800.0,
            coherence_n: Some(0.2),
            ..Synthesis::default()
        };
        let p = synthesize(&syn).unwrap();
        let d = describe(&p).unwrap();
        let c = d.coherence.as_ref().unwrap();
        // gamma(n) = exp(-n / 0.2) by construction, so gamma^2 = exp(-2 n / 0.2).
        let mean_near = |n0: f64| {
            let v: Vec<f64> =
                c.n.iter()
                    .zip(&c.gamma2)
                    .filter(|(n, _)| (**n / n0 - 1.0).abs() < 0.2)
                    .map(|(_, g)| *g)
                    .collect();
            v.iter().sum::<f64>() / v.len() as f64
        };
        assert!((mean_near(0.05) - (-0.5f64).exp()).abs() < 0.1);
        assert!(mean_near(2.0) < 0.1);
        let json = serde_json::to_value(&d).unwrap();
        for key in ["class", "gd_n0", "waviness", "band", "residual"] {
            assert!(json["iso8608"].get(key).is_some(), "{key}");
        }
        assert!(json["psd"]["n"].is_array() && json["psd"]["gd_right"].is_array());
        for (k, v) in json.as_object().unwrap() {
            if v.is_number() {
                assert!(d.units.contains_key(k.as_str()), "{k} has no unit");
            }
        }
        assert!(d.method.contains("Welch") && d.method.contains("Hann"));
    }

    #[test]
    fn a_profile_too_short_for_a_fit_is_refused() {
        let z: Vec<f64> = (0..300).map(|i| 0.001 * (i as f64 * 0.3).sin()).collect();
        let p = Profile::uniform(0.5, 0.0, z, None).unwrap();
        let e = describe(&p).unwrap_err().to_string();
        assert!(
            e.starts_with("distance_m") && e.contains("two octaves"),
            "{e}"
        );
    }
}
