//! A measured road as the explorer's road (#31): the page's road menu offers a dropped
//! profile in place of the ISO class, and the session's maps, readout, surrogate and
//! fronts are then computed on it.
//!
//! The session holds the road as a [`RoadSource`] trait object, so that only a build
//! that makes one (the page's workers and on-demand module, the tests) links the shaped
//! routes: the page's first-screen wasm never makes one and stays small (#29).

use crate::analysis::{ModelKind, Readout, Report};
use crate::car::Car;
use crate::comfort::Comfort;
use crate::design::DesignBox;
use crate::error::Result;
use crate::evaluate::{Criteria, Evaluator};
use crate::model::LinearModel;
use crate::road::{MeasuredRoad, ProfileTracks, RoadScenario};
use crate::road_profile::{
    criteria_shaped_spectral, playback, MeasuredModel, Profile, ShapedRoad, ShapedSpectrum,
};
use crate::study::MeasuredSource;
use crate::surrogate::Setting;
use crate::time_domain::{simulate_playback, TimeOptions, TimeResponse};
use std::fmt::Debug;
use std::sync::Arc;

/// A road the explorer's session evaluates on in place of its ISO class: the models on
/// it, the report and readout of a design there, and the surrogate's setting there.
pub trait RoadSource: Debug + Send + Sync {
    /// What identifies the road: the profile's content, its speed and how its tracks
    /// drive the wheels (two sources with the same key are the same road).
    fn key(&self) -> &str;
    /// What a report says of the road (file, speed, tracks, band, filter error).
    fn summary(&self) -> &MeasuredRoad;
    /// The quarter (`Quarter`) or full (`Full`) car of `car` (its front design the datum)
    /// on the road, with `comfort` in the BAcc slot.
    fn evaluator(&self, kind: ModelKind, car: &Car, comfort: Comfort) -> Box<dyn Evaluator + Sync>;
    /// The report of `design` (the `datum` car with its front design) by `kind` on the
    /// road: the exact route's criteria (the model prepared on `datum`), with `check`
    /// checked against the frequency route on the raw PSD, as `ridelab eval --road FILE`
    /// (its adaptive quadrature is most of the report's time: 3.9 ms of 4 ms natively for
    /// the quarter car on the shipped slab road, so a slider step leaves it out).
    fn report(&self, kind: ModelKind, datum: &Car, design: &Car, check: bool) -> Result<Report>;
    /// The report without its frequency-route check (what a slider step shows).
    fn readout(&self, kind: ModelKind, datum: &Car, design: &Car) -> Result<Readout>;
    /// The surrogate's setting for `car` over `dbox` on the road (its LoFi the quarter
    /// car there), as `ridelab surrogate --road FILE`.
    fn setting(&self, car: &Car, dbox: &DesignBox) -> Result<Setting>;
    /// One-sided output PSDs `[BAcc (m/s^2)^2/Hz, DTL N^2/Hz, SWS m^2/Hz]` of `model` at
    /// each frequency of `f` (Hz) on the road's measured PSD (with its extensions).
    fn output_psds(&self, model: &LinearModel, f: &[f64]) -> Result<Vec<[f64; 3]>>;
    /// The time response of `design` by `kind` on the profile itself, played back under
    /// the wheels from rest at its start (as `ridelab simulate --road FILE`, whose run
    /// this is the first `opt.duration` seconds of), at the largest step at most
    /// `opt.dt` that divides the profile's spacing at the road's speed; `opt`'s seed does
    /// not apply.
    fn time_response(
        &self,
        kind: ModelKind,
        design: &Car,
        opt: &TimeOptions,
    ) -> Result<TimeResponse>;
    /// The road as a study takes it (the file, profile and tracks, and the road shaped at
    /// its speed): the session's report is [`crate::study::StudySpec::report`] on it, as
    /// `ridelab report --road FILE`'s.
    fn source(&self) -> &MeasuredSource;
}

/// A profile shaped at a speed, as the session's road.
#[derive(Debug, Clone)]
pub struct OnRoad {
    key: String,
    summary: MeasuredRoad,
    /// The profile, how its tracks drive the wheels and the road shaped from it.
    source: MeasuredSource,
}

impl OnRoad {
    /// The road `road`, shaped from `profile` (the file `file`) with `tracks`; `content`
    /// names the profile's bytes (a hash: two files of one name are two roads).
    pub fn new(
        file: &str,
        content: u64,
        profile: Arc<Profile>,
        road: ShapedRoad,
        tracks: ProfileTracks,
    ) -> OnRoad {
        OnRoad {
            key: OnRoad::key_of(file, content, road.speed, tracks),
            summary: MeasuredRoad::of(file, &road, tracks),
            source: MeasuredSource {
                file: file.to_string(),
                profile,
                tracks,
                shaped: road,
            },
        }
    }

    /// The shaped road (speed, band, sources and their filters).
    pub fn road(&self) -> &ShapedRoad {
        &self.source.shaped
    }

    /// How the profile's tracks drive the wheels.
    pub fn tracks(&self) -> ProfileTracks {
        self.source.tracks
    }

    /// The key of the profile `file` (content hash `content`) at `speed` m/s with
    /// `tracks`: `"<file>#<hash>@<speed>:<tracks>"`.
    pub fn key_of(file: &str, content: u64, speed: f64, tracks: ProfileTracks) -> String {
        format!("{file}#{content:016x}@{speed}:{}", <&str>::from(tracks))
    }

    /// The exact criteria and the Wk-weighted BAcc (m/s^2) of `design`'s front by
    /// `kind`, as `ridelab eval --road FILE` computes them (the model prepared on `datum`).
    fn exact(&self, kind: ModelKind, datum: &Car, design: &Car) -> Result<(Criteria, f64)> {
        let q = design.quarter();
        let model = MeasuredModel::new(kind, datum, self.source.shaped.clone());
        let exact = model.evaluate(q.ks, q.cs)?;
        let wk = model.with_comfort(Comfort::Wk).evaluate(q.ks, q.cs)?.bacc;
        Ok((exact, wk))
    }
}

impl RoadSource for OnRoad {
    fn key(&self) -> &str {
        &self.key
    }

    fn summary(&self) -> &MeasuredRoad {
        &self.summary
    }

    fn evaluator(&self, kind: ModelKind, car: &Car, comfort: Comfort) -> Box<dyn Evaluator + Sync> {
        Box::new(MeasuredModel::new(kind, car, self.source.shaped.clone()).with_comfort(comfort))
    }

    fn report(&self, kind: ModelKind, datum: &Car, car: &Car, check: bool) -> Result<Report> {
        let r = self.readout(kind, datum, car)?;
        let spectral = match check {
            true => Some(criteria_shaped_spectral(
                &kind.build(car),
                &self.source.shaped,
                1e-8,
            )?),
            false => None,
        };
        let exact = Criteria {
            bacc: r.bacc,
            dtl: r.dtl,
            sws: r.sws,
        };
        let diff = spectral.as_ref().map(|s| {
            exact
                .to_array()
                .iter()
                .zip(s.criteria.to_array())
                .map(|(a, b)| (a / b - 1.0).abs())
                .fold(0.0, f64::max)
        });
        Ok(Report {
            model: kind,
            car: car.name.clone(),
            road: RoadScenario::Measured(self.summary.clone()),
            ks: r.ks,
            cs: r.cs,
            bacc: r.bacc,
            dtl: r.dtl,
            sws: r.sws,
            bacc_wk: r.bacc_wk,
            comfort: r.comfort,
            dtl_relative: r.dtl_relative,
            route: r.route,
            spectral: spectral.as_ref().map(|s| s.criteria),
            route_difference: diff,
            spectral_error_estimate: spectral.map(|s| s.relative_error),
            low_cutoff_hz: None,
            modes: r.modes,
            body_bounce_hz: r.body_bounce_hz,
            critical_damping: r.critical_damping,
            damping_ratio: r.damping_ratio,
            wheel_rate: r.wheel_rate,
            static_wheel_load: r.static_wheel_load,
        })
    }

    fn readout(&self, kind: ModelKind, datum: &Car, car: &Car) -> Result<Readout> {
        car.validate()?;
        let (values, wk) = self.exact(kind, datum, car)?;
        Readout::of(kind, car, values, wk, "exact", None)
    }

    fn setting(&self, car: &Car, dbox: &DesignBox) -> Result<Setting> {
        Setting::measured(car, self.source.shaped.clone(), dbox)
    }

    fn output_psds(&self, model: &LinearModel, f: &[f64]) -> Result<Vec<[f64; 3]>> {
        let sp = ShapedSpectrum::new(model, &self.source.shaped)?;
        Ok(f.iter().map(|&fi| sp.psd(fi)).collect())
    }

    fn time_response(
        &self,
        kind: ModelKind,
        design: &Car,
        opt: &TimeOptions,
    ) -> Result<TimeResponse> {
        opt.validate()?;
        let speed = self.source.shaped.speed;
        let dt = self.source.profile.playback_step(speed, opt.dt);
        let mut road = playback(&self.source.profile, &kind.build(design).wheels, speed, dt)?;
        let n = ((opt.duration / dt).round() as usize + 1).min(road.len());
        for w in &mut road.wheels {
            w.truncate(n);
        }
        let opt = TimeOptions {
            dt,
            duration: (n.max(1) - 1) as f64 * dt,
            ..*opt
        };
        simulate_playback(kind, design, dt, &road.wheels, &opt)
    }

    fn source(&self) -> &MeasuredSource {
        &self.source
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::road::Road;
    use crate::road_profile::ShapedRoad;
    use crate::road_profile::{synthesize, Synthesis};

    /// The readout on a road shaped from ISO class C (waviness 2) is the ISO readout
    /// within the filter's stated error, and the report's two routes agree.
    #[test]
    fn readout_on_an_iso_shaped_road_is_the_iso_readout() {
        let iso = Road::default();
        let road = ShapedRoad::iso(&iso, 2.0).unwrap();
        // The profile only feeds the study report, not tested here.
        let profile = synthesize(&Synthesis::default()).unwrap();
        let on = OnRoad::new(
            "iso-c.csv",
            7,
            Arc::new(profile),
            road,
            ProfileTracks::Correlated,
        );
        let car = Car::preset("sedan").unwrap();
        for kind in [ModelKind::Quarter, ModelKind::Full] {
            let want = crate::analysis::readout(kind, &car, &iso).unwrap();
            let got = on.readout(kind, &car, &car).unwrap();
            for (g, w) in [
                (got.bacc, want.bacc),
                (got.dtl, want.dtl),
                (got.sws, want.sws),
            ] {
                assert!((g / w - 1.0).abs() < 0.02, "{kind:?}: {g} against {w}");
            }
            assert!((got.bacc_wk / want.bacc_wk - 1.0).abs() < 0.02);
            assert_eq!(got.modes, want.modes);
            let rep = on.report(kind, &car, &car, true).unwrap();
            let step = on.report(kind, &car, &car, false).unwrap();
            assert_eq!(
                (step.bacc, step.spectral, step.route_difference),
                (rep.bacc, None, None)
            );
            assert!(
                rep.route_difference.unwrap() < 1e-6,
                "{kind:?}: {:?}",
                rep.route_difference
            );
            assert_eq!(rep.bacc, got.bacc);
        }
        assert!(on.key().starts_with("iso-c.csv#0000000000000007@20:"));
    }
}
