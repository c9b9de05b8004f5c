//! Fronts, spectra and time responses for the page's objective plane, FRF/PSD plots and
//! time panel: thin layers over `optimize`, `criteria::Spectrum` and `time_domain`.

use super::state::Scenario;
use super::surrogate::FittedSurrogate;
use crate::analysis::ModelKind;
use crate::comfort::Comfort;
use crate::dos::DosContext;
use crate::error::{Result, RideError};
use crate::evaluate::{Criteria, Evaluator};
use crate::math;
use crate::optimize::{
    minmax::{normalised_distances, pick, pseudo_weights, recheck, PickRule, Recheck},
    nsga2::Nsga2Params,
    stm::StmParams,
    study::{run_study, Method, Study},
    suspension::SuspensionProblem,
    trust::{pick_warnings, Warning},
};
use crate::robust::{CaseSet, Combine};
use crate::study::robust::optimize::CasePick;
use crate::study::{EvaluatorSpec, OptimizeRequest};
use crate::surrogate::Surrogate;
use crate::time_domain::{simulate, Damper, TimeOptions, TimeResponse};
use serde::Serialize;

/// STM grid of the page's LoFi front (a few ms).
pub(crate) const STM_GRID: usize = 61;
/// STM refinement levels of the page's LoFi front.
pub(crate) const STM_LEVELS: usize = 2;

/// The page's front method: "stm" (space transformation) or "nsga2" (seeded NSGA-II).
pub fn method(name: &str) -> Result<Method> {
    match name {
        "stm" => Ok(Method::Stm(StmParams {
            grid: STM_GRID,
            levels: STM_LEVELS,
        })),
        "nsga2" => Ok(Method::Nsga2(Nsga2Params {
            population: 60,
            generations: 60,
            seed: 1,
            ..Nsga2Params::default()
        })),
        _ => Err(RideError::field(
            "method",
            format!("'{name}' is not 'stm' or 'nsga2'"),
        )),
    }
}

/// A front with its pick re-checked on the HiFi model.
#[derive(Debug, Clone, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct FrontResult {
    /// The study on the front's model; its pick is the scenario's rule's
    /// ([`crate::optimize::PickRule`]: min-max, knee or weighted).
    pub study: Study,
    /// The datum car's criteria by the front's model (the normalisation of the ratios).
    pub datum: Criteria,
    /// The datum car's HiFi criteria.
    pub datum_hifi: Criteria,
    /// The pick re-evaluated on the HiFi model.
    pub recheck: Recheck,
    /// The comfort measure of the front's, the datum's and the re-check's BAcc.
    pub comfort: Comfort,
    /// Each front point's pseudo-weights `[w_bacc, w_dtl]`,
    /// `w_i = (1 - d_i) / sum_j (1 - d_j)` of its normalised distances `d`, -.
    pub pseudo_weights: Vec<[f64; 2]>,
    /// How far the pick can be trusted: a design-box bound it sits on, a criterion its
    /// HiFi re-check misses by more than [`crate::optimize::trust::RECHECK_TOLERANCE_PERCENT`].
    pub warnings: Vec<Warning>,
    /// With robust cases: the rule, the normalisation and the pick in each case (its
    /// LoFi prediction and HiFi re-check against that case's datum, the objectives the
    /// re-check breaks), as `ridelab optimize --cases --json`'s `cases`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub robust: Option<RobustFront>,
}

/// What a robust front adds (see [`FrontResult::robust`]).
#[derive(Debug, Clone, Serialize)]
pub struct RobustFront {
    /// Worst case or weighted mean.
    pub combine: Combine,
    /// The normalisation sentence.
    pub normalisation: &'static str,
    /// The pick in each case.
    pub cases: Vec<CasePick>,
}

/// The robust front of the scenario's cases on `kind` (the quarter car for the plane, the
/// full car for the HiFi's own) by `method_name`, with the scenario's box, objectives,
/// comfort measure and pick rule: exactly [`OptimizeRequest::run_robust`]'s front, pick and
/// per-case re-checks (`ridelab optimize --cases --evaluator quarter|full`), the datum
/// its robust (HiFi, case 0's) datum.
pub(crate) fn robust_front(
    s: &Scenario,
    set: &CaseSet,
    method_name: &str,
    kind: ModelKind,
) -> Result<FrontResult> {
    let m = method(method_name)?;
    let r = OptimizeRequest {
        evaluator: EvaluatorSpec::Model(kind),
        plan: s.plan,
        comfort: s.comfort,
        pick: s.pick,
        ..OptimizeRequest::new(&s.datum, &s.road, s.dbox, m, s.objectives.clone())
    }
    .run_robust(set)?;
    let weights = normalised_distances(&r.study.front, &r.datum)
        .into_iter()
        .map(pseudo_weights)
        .collect();
    Ok(FrontResult {
        warnings: r.warnings,
        datum: r.datum,
        datum_hifi: r.datum,
        recheck: r.hifi_recheck,
        comfort: r.comfort,
        pseudo_weights: weights,
        robust: Some(RobustFront {
            combine: r.combine,
            normalisation: r.normalisation,
            cases: r.cases,
        }),
        study: r.study,
    })
}

/// Runs the front method `method_name` on `model` for scenario `s` (`model` gives the
/// scenario's comfort measure in its BAcc slot), picks on it by the scenario's rule and
/// re-checks the pick on the HiFi model with the same comfort measure.
pub fn front<E: Evaluator + ?Sized>(
    s: &Scenario,
    method_name: &str,
    model: &E,
) -> Result<FrontResult> {
    let m = method(method_name)?;
    let ctx = DosContext::of_model(&s.datum, model)?;
    let datum = ctx.datum;
    let problem = SuspensionProblem::new(model, s.dbox, s.objectives.clone(), ctx)?;
    let mut study = run_study(&problem, &m, None)?;
    if s.pick != PickRule::MinMax {
        study.pick = pick(&study.front, &datum, s.pick)?;
    }
    let weights = normalised_distances(&study.front, &datum)
        .into_iter()
        .map(pseudo_weights)
        .collect();
    let hifi = s.evaluator(ModelKind::Full)?;
    let datum_hifi = hifi.evaluate(s.datum.front.spring, s.datum.front.damper)?;
    let recheck = recheck(&study.pick, &*hifi, &datum_hifi)?;
    Ok(FrontResult {
        warnings: pick_warnings(&study.pick, &recheck, &s.dbox),
        study,
        datum,
        datum_hifi,
        recheck,
        comfort: s.comfort,
        pseudo_weights: weights,
        robust: None,
    })
}

/// FRF magnitudes and output PSDs of one model on a log frequency grid.
#[derive(Debug, Clone, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct ModelSpectra {
    /// |H| from road displacement (right track / correlated source) of
    /// `[BAcc 1/s^2, DTL N/m, SWS m/m]`, one vector per output.
    pub frf: [Vec<f64>; 3],
    /// One-sided output PSDs `[(m/s^2)^2/Hz, N^2/Hz, m^2/Hz]`, one vector per output.
    pub psd: [Vec<f64>; 3],
}

/// Spectra of the design by the LoFi, HiFi and surrogate at `nfreq` log-spaced frequencies.
#[derive(Debug, Clone, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct Spectra {
    /// Frequencies, Hz (0.1..100, log spaced).
    pub f: Vec<f64>,
    /// Quarter car.
    pub lofi: ModelSpectra,
    /// Full car.
    pub hifi: ModelSpectra,
    /// The tuned LoFi of the scenario's surrogate (see [`surrogate_spectra`]).
    pub surrogate: ModelSpectra,
    /// How the surrogate's spectra were made: "tuned quarter car" or "LoFi scaled by S / LoFi".
    pub surrogate_route: String,
}

/// FRF magnitudes and PSDs of `model`'s outputs `outputs[o]` on the scenario's road: the
/// FRF from the first source of the ISO road with the scenario's speed and tracks (the
/// transfer does not depend on the class), the PSD on the measured road's PSD when the
/// scenario has one, else on the ISO road's.
fn spectra_of(
    model: &crate::model::LinearModel,
    s: &Scenario,
    f: &[f64],
    out: &mut ModelSpectra,
    outputs: std::ops::Range<usize>,
) -> Result<()> {
    let sp = crate::criteria::Spectrum::new(model, &s.road)?;
    let measured = match &s.measured {
        Some(m) => Some(m.0.output_psds(model, f)?),
        None => None,
    };
    for (k, &fi) in f.iter().enumerate() {
        let omega = 2.0 * std::f64::consts::PI * fi;
        let h = sp.displacement_transfer(0, omega);
        let p = measured.as_ref().map_or_else(|| sp.psd(fi), |m| m[k]);
        for o in outputs.clone() {
            out.frf[o].push(math::cabs(h[o]));
            out.psd[o].push(p[o]);
        }
    }
    Ok(())
}

fn model_spectra(kind: ModelKind, s: &Scenario, f: &[f64]) -> Result<ModelSpectra> {
    let mut out = ModelSpectra {
        frf: Default::default(),
        psd: Default::default(),
    };
    spectra_of(&kind.build(&s.design), s, f, &mut out, 0..3)?;
    Ok(out)
}

/// The surrogate's spectra at the design. A VBA or PBA surrogate is a tuned quarter car
/// per criterion: criterion `k`'s spectra are that car's. An RBA surrogate corrects the
/// LoFi's RMS values, `S_k = f_k (x) tau_k(x)` (or `+ d_k`), with no model behind it: its
/// spectra are the LoFi's scaled by `r_k = S_k / f_k` (FRF by `r_k`, PSD by `r_k^2`), so
/// that the PSD's area is `S_k^2` as the LoFi's is `f_k^2`.
fn surrogate_spectra(
    s: &Scenario,
    fit: &FittedSurrogate,
    f: &[f64],
    lofi: &ModelSpectra,
) -> Result<(ModelSpectra, String)> {
    let (ks, cs) = (s.design.front.spring, s.design.front.damper);
    let mut out = ModelSpectra {
        frf: Default::default(),
        psd: Default::default(),
    };
    if let Some(quarters) = fit.model.tuned_quarters(ks, cs)? {
        for (k, q) in quarters.iter().enumerate() {
            spectra_of(&crate::model::quarter_car(q), s, f, &mut out, k..k + 1)?;
        }
        return Ok((out, "tuned quarter car".into()));
    }
    let sur = fit.model.evaluate(ks, cs)?.to_array();
    let low = s
        .evaluator_with(ModelKind::Quarter, Comfort::Bacc)?
        .evaluate(ks, cs)?
        .to_array();
    for k in 0..3 {
        let r = sur[k] / low[k];
        out.frf[k] = lofi.frf[k].iter().map(|h| h * r).collect();
        out.psd[k] = lofi.psd[k].iter().map(|p| p * r * r).collect();
    }
    Ok((out, "LoFi scaled by S / LoFi".into()))
}

/// Largest frequency count of [`spectra`].
const MAX_NFREQ: usize = 4000;

/// FRFs and PSDs of the design by the LoFi, the HiFi and the fitted surrogate `fit`
/// (0.1..100 Hz, `nfreq` log-spaced points).
pub fn spectra(s: &Scenario, fit: &FittedSurrogate, nfreq: usize) -> Result<Spectra> {
    if !(2..=MAX_NFREQ).contains(&nfreq) {
        return Err(RideError::field(
            "nfreq",
            format!("must be 2..{MAX_NFREQ} (got {nfreq})"),
        ));
    }
    let f: Vec<f64> = (0..nfreq)
        .map(|i| 0.1 * math::powf(1000f64, i as f64 / (nfreq - 1) as f64))
        .collect();
    let lofi = model_spectra(ModelKind::Quarter, s, &f)?;
    let (surrogate, surrogate_route) = surrogate_spectra(s, fit, &f, &lofi)?;
    Ok(Spectra {
        hifi: model_spectra(ModelKind::Full, s, &f)?,
        lofi,
        surrogate,
        surrogate_route,
        f,
    })
}

/// Time responses of the design by both models on the same seeded road.
#[derive(Debug, Clone, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct TimeResult {
    /// The front damper's law of the run (`None`: the design's linear damper).
    pub damper: Option<Damper>,
    /// The design's front Cs of the run, N s/m: the state's Cs for a linear damper,
    /// the law's equivalent linear rate `(Csb + Csr) / 2` otherwise (the rule of [`Damper`]).
    pub damper_rate: f64,
    /// Quarter car (positions: zs, zu).
    pub lofi: TimeResponse,
    /// Full car (positions: z, theta, phi, zu1..zu4).
    pub hifi: TimeResponse,
    /// Front axle to CG, m.
    pub a: f64,
    /// Rear axle to CG, m.
    pub b: f64,
}

/// Simulates the design with both models, as `ridelab simulate` does.
///
/// On a measured road the profile itself is played back under the wheels from rest at its
/// start, for `opt.duration` seconds (the first seconds of `ridelab simulate --road FILE`).
pub fn time_response(s: &Scenario, opt: &TimeOptions) -> Result<TimeResult> {
    let run = |kind| match &s.measured {
        Some(m) => m.0.time_response(kind, &s.design, opt),
        None => simulate(kind, &s.design, &s.road, opt),
    };
    let lofi = run(ModelKind::Quarter)?;
    let hifi = run(ModelKind::Full)?;
    Ok(TimeResult {
        damper: opt.damper,
        damper_rate: hifi.damper_rate,
        lofi,
        hifi,
        a: s.design.a,
        b: s.design.b,
    })
}
