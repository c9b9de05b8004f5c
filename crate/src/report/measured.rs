//! The report on a measured road (`ridelab report --road FILE`, issue #31): every section
//! on the profile's road at the scenario's speed. The models are the quarter and the full
//! car by the exact routes with the road's shaping filters ([`MeasuredModel`]); the
//! surrogates are fitted to the full car's samples there with the quarter car there as
//! their LoFi; section 1 checks the exact routes against each other, against the
//! frequency route on the raw Welch PSD and against the profile itself played back under
//! the wheels.

use super::{build_with, comfort_rows, frfs, rows, validate, Verification};
use super::{MethodReport, ReportInputs, SectionRoad};
use crate::analysis::ModelKind;
use crate::car::Car;
use crate::design::DesignBox;
use crate::error::{Result, RideError};
use crate::evaluate::{Criteria, Evaluator};
use crate::optimize::PickRule;
use crate::road::Road;
use crate::road_profile::{
    bacc_wk_shaped_fast, criteria_shaped, criteria_shaped_modal, criteria_shaped_spectral,
    playback, MeasuredModel, MeasuredRoad, RoadScenario, ShapedRoad, ShapedSpectrum,
};
use crate::study::adaptive::{AdaptiveOptimizeReport, AdaptiveOptions};
use crate::study::measured::optimize_measured;
use crate::study::{study_on, SurrogateRequest};
use crate::study::{MapReport, MapRequest, MapSettings, OptimizeReport, OptimizeRequest};
use crate::study::{MeasuredSource, StudyReport, SurrogateReport};
use crate::surrogate::{PlanSpec, Setting, SurrogateSpec};
use crate::time_domain::{simulate_playback, TimeOptions, MAX_STEPS};

/// [`build`](super::build) on the measured road `measured`, shaped at `inputs.road`'s
/// speed (its class is not used): `ridelab report --road FILE` (this module).
pub(crate) fn build_on(
    inputs: &ReportInputs,
    measured: &MeasuredSource,
    progress: impl FnMut(usize),
) -> Result<MethodReport> {
    validate(inputs)?;
    let on = OnRoad::new(&inputs.car, measured, &inputs.design_box)?;
    build_with(inputs, &on, progress)
}

/// The measured road shaped at the scenario's speed, with its models.
pub(super) struct OnRoad<'a> {
    source: &'a MeasuredSource,
    about: MeasuredRoad,
    shaped: &'a ShapedRoad,
    lofi: MeasuredModel,
    hifi: MeasuredModel,
    setting: Setting,
}

impl<'a> OnRoad<'a> {
    /// The models of `car` on the road `source` (shaped at its speed once, by
    /// [`MeasuredSource::new`]) and the surrogates' setting over `design_box`.
    pub(super) fn new(
        car: &Car,
        source: &'a MeasuredSource,
        design_box: &DesignBox,
    ) -> Result<OnRoad<'a>> {
        let shaped = &source.shaped;
        Ok(OnRoad {
            about: source.about(),
            lofi: MeasuredModel::new(ModelKind::Quarter, car, shaped.clone()),
            hifi: MeasuredModel::new(ModelKind::Full, car, shaped.clone()),
            setting: Setting::measured(car, shaped.clone(), design_box)?,
            source,
            shaped,
        })
    }

    /// Section 1 at the datum design: each model by its exact routes with the road's
    /// filters (the quarter car's closed form or the full car's residue route first, then
    /// the modal route and the Lyapunov equations), by the frequency route on the raw PSD
    /// and by the profile played back under the wheels from rest (`seed` does not apply);
    /// the Wk-weighted comfort by the exact and the frequency routes; the modes and FRFs
    /// (which do not depend on the road).
    fn verify_at(&self, car: &Car, speed: f64) -> Result<Verification> {
        let quarter = ModelKind::Quarter.build(car);
        let full = ModelKind::Full.build(car);
        let (k0, c0) = (car.front.spring, car.front.damper);
        let raw = |model| -> Result<Criteria> {
            Ok(criteria_shaped_spectral(model, self.shaped, 1e-8)?.criteria)
        };
        let mut notes = self.shaped.notes.clone();
        notes.push(format!(
            "the exact routes take the road's shaping filters, whose PSD is within {:.1} % of the measured one over {:.2}..{:.1} Hz; the frequency route takes the measured (Welch) PSD itself",
            100.0 * self.about.fit_error,
            self.about.band_hz[0],
            self.about.band_hz[1]
        ));
        let (record, lofi_played) = self.played(ModelKind::Quarter, car, speed)?;
        let lofi = vec![
            (
                "closed form with the road's filters".to_string(),
                self.lofi.evaluate(k0, c0)?,
            ),
            (
                "Lyapunov with the road's filters".into(),
                criteria_shaped(&quarter, self.shaped)?,
            ),
            (
                "frequency integration on the measured PSD".into(),
                raw(&quarter)?,
            ),
            (
                format!(
                    "time domain, the profile played back ({:.0} s)",
                    record.duration
                ),
                lofi_played,
            ),
        ];
        let mut hifi = vec![(
            "residue route with the road's filters".to_string(),
            self.hifi.evaluate(k0, c0)?,
        )];
        match criteria_shaped_modal(&full, self.shaped) {
            Ok(c) => hifi.push(("modal expansion with the road's filters".into(), c)),
            Err(e) => notes.push(format!("modal route does not apply: {e}")),
        }
        hifi.push((
            "Lyapunov with the road's filters and the delay".into(),
            criteria_shaped(&full, self.shaped)?,
        ));
        hifi.push((
            "frequency integration on the measured PSD, exact delay".into(),
            raw(&full)?,
        ));
        let (_, hifi_played) = self.played(ModelKind::Full, car, speed)?;
        hifi.push((
            format!(
                "time domain, the profile played back ({:.0} s)",
                record.duration
            ),
            hifi_played,
        ));
        let comfort = comfort_rows(&quarter, &full, &lofi[0].1, &hifi[0].1, |model| {
            Ok((
                bacc_wk_shaped_fast(model, self.shaped)?,
                ShapedSpectrum::new(model, self.shaped)?.bacc_wk(1e-10)?,
            ))
        })?;
        // The FRFs do not depend on the road's spectrum: ISO 8608's road at this speed
        // gives the delays.
        let iso = Road {
            speed,
            ..Road::default()
        };
        Ok(Verification {
            lofi: rows(lofi),
            hifi: rows(hifi),
            notes,
            record,
            lofi_modes: quarter.modes()?,
            hifi_modes: full.modes()?,
            frf: frfs(&quarter, &full, &iso)?,
            comfort,
        })
    }

    /// `kind`'s RMS criteria with the profile played back under its wheels at `speed`
    /// from rest (at most a 1 ms step that divides the spacing), and the run's options.
    fn played(&self, kind: ModelKind, car: &Car, speed: f64) -> Result<(TimeOptions, Criteria)> {
        let profile = &*self.source.profile;
        let dt = profile.playback_step(speed, 1e-3);
        let wheels = playback(profile, &kind.build(car).wheels, speed, dt)?;
        if wheels.len() as f64 > MAX_STEPS {
            return Err(RideError::field(
                "road",
                format!(
                    "playing the profile back takes {} steps of {dt:.3e} s; at most {MAX_STEPS:e}: a faster --speed",
                    wheels.len()
                ),
            ));
        }
        let opt = TimeOptions {
            dt,
            duration: (wheels.len() - 1) as f64 * dt,
            decimate: 1000,
            ..TimeOptions::default()
        };
        let r = simulate_playback(kind, car, dt, &wheels.wheels, &opt)?;
        Ok((opt, Criteria::from_array(r.rms)))
    }
}

impl SectionRoad for OnRoad<'_> {
    fn scenario(&self) -> RoadScenario {
        RoadScenario::Measured(self.about.clone())
    }

    fn velocity_psd(&self) -> Option<f64> {
        None
    }

    /// The played-back profile has no seed: `seed` does not apply.
    fn verify(&self, car: &Car, _seed: u64) -> Result<Verification> {
        self.verify_at(car, self.about.speed)
    }

    fn map(&self, kind: ModelKind, car: &Car, settings: &MapSettings) -> Result<MapReport> {
        let model = match kind {
            ModelKind::Quarter => &self.lofi,
            ModelKind::Full => &self.hifi,
        };
        let mut r = MapRequest::new(kind, car, &Road::default(), settings.clone()).run_on(model)?;
        r.road = self.scenario();
        Ok(r)
    }

    fn study(&self, car: &Car, _design_box: &DesignBox) -> Result<StudyReport> {
        study_on(car, &self.setting, self.hifi.clone(), self.scenario())
    }

    fn surrogate(
        &self,
        spec: SurrogateSpec,
        plan: PlanSpec,
        car: &Car,
        _design_box: &DesignBox,
    ) -> Result<SurrogateReport> {
        let request = SurrogateRequest {
            design_box: self.setting.design_box,
            ..SurrogateRequest::new(spec, plan)
        };
        let mut r = request.report_on(car, &self.setting, self.hifi.clone())?;
        r.road = self.scenario();
        Ok(r)
    }

    fn optimize(&self, request: &OptimizeRequest) -> Result<OptimizeReport> {
        optimize_measured(request, &self.hifi, None).map(|(r, _)| r)
    }

    fn hifi(&self, _car: &Car) -> Result<Box<dyn Evaluator + '_>> {
        Ok(Box::new(self.hifi.clone()))
    }

    fn repick(
        &self,
        r: &mut OptimizeReport,
        rule: PickRule,
        _car: &Car,
        design_box: &DesignBox,
    ) -> Result<()> {
        r.repick_on(rule, &self.hifi, design_box)
    }

    fn adaptive(
        &self,
        request: &OptimizeRequest,
        options: AdaptiveOptions,
    ) -> Result<AdaptiveOptimizeReport> {
        let (optimize, adaptive) = optimize_measured(request, &self.hifi, Some(options))?;
        let adaptive = adaptive
            .ok_or_else(|| RideError::Numerical("the adaptive loop gave no report".into()))?;
        Ok(AdaptiveOptimizeReport { optimize, adaptive })
    }
}
