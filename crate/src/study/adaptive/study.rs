//! The adaptive study: for each total of HiFi samples, the loop against an Audze-Eglais
//! plan of the same size, both judged on the HiFi ([`super::front_check`]).

use super::{
    front_check, AdaptiveLoop, AdaptiveOptions, Decision, FrontCheck, HifiFront, MAX_HIFI_RUNS,
};
use crate::analysis::HiFi;
use crate::car::Car;
use crate::design::DesignBox;
use crate::dos::DesignObjectives;
use crate::error::{Result, RideError};
use crate::evaluate::Evaluator;
use crate::optimize::StmParams;
use crate::road::Road;
use crate::road_profile::RoadScenario;
use crate::surrogate::uncertainty::UncertaintyMethod;
use crate::surrogate::{sample_plan, PlanSpec, Sample, Setting, SurrogateSpec};
use serde::{Deserialize, Serialize};
use std::fmt::Write;

/// Settings of the adaptive study.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct StudyOptions {
    /// Audze-Eglais points of the loop's initial plan.
    pub initial: usize,
    /// Smallest total of HiFi samples compared (> `initial`).
    pub min_runs: usize,
    /// Largest total of HiFi samples compared (<= [`MAX_HIFI_RUNS`]).
    pub max_runs: usize,
    /// STM settings of every front (the HiFi's own included).
    pub stm: StmParams,
    /// The loop's settings (`runs` is set by the study).
    pub adaptive: AdaptiveOptions,
    /// The design box every plan, loop and front spans.
    pub design_box: DesignBox,
    /// What every front (the HiFi's own included) and the loop judge designs by.
    pub objectives: DesignObjectives,
}

impl Default for StudyOptions {
    /// 5 Audze-Eglais points, then 6 to 20 HiFi samples in all; default STM (201 x 201,
    /// 3 levels); the default box and objectives.
    fn default() -> Self {
        StudyOptions {
            initial: 5,
            min_runs: 6,
            max_runs: 20,
            stm: StmParams::default(),
            adaptive: AdaptiveOptions::default(),
            design_box: DesignBox::default(),
            objectives: DesignObjectives::default(),
        }
    }
}

/// One sample budget of the study.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StudyRow {
    /// HiFi samples in all.
    pub hifi_runs: usize,
    /// The loop: the initial plan plus `hifi_runs - initial` adaptive samples.
    pub adaptive: FrontCheck,
    /// An Audze-Eglais plan of `hifi_runs` points.
    pub audze_eglais: FrontCheck,
}

/// The adaptive study's results.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AdaptiveStudy {
    /// Car name.
    pub car: String,
    /// Road scenario: an ISO class (JSON as before) or a measured profile.
    pub road: RoadScenario,
    /// Canonical surrogate name.
    pub surrogate: String,
    /// The uncertainty estimate the loop used.
    pub uncertainty: UncertaintyMethod,
    /// The settings.
    pub options: StudyOptions,
    /// The reference HiFi front (STM on the HiFi).
    pub hifi_front: HifiFront,
    /// One row per sample budget, increasing.
    pub rows: Vec<StudyRow>,
    /// The loop's samples in the order added (the last budget's).
    pub samples: Vec<Sample>,
    /// Why each adaptive sample was chosen.
    pub reasons: Vec<String>,
    /// Wall time of the whole study, s (`None` in the browser, which has no clock here).
    pub seconds: Option<f64>,
}

/// The adaptive study of `spec` for `car` on `road` over `options`' box (module doc):
/// for every total `N` of HiFi samples from `min_runs` to `max_runs`, the loop (an
/// Audze-Eglais plan of `initial` points plus `N - initial` adaptive runs; one loop serves
/// every `N`, as it adds one sample at a time) against an Audze-Eglais plan of `N` points,
/// both judged on the HiFi by [`front_check`] against the HiFi's own STM front.
/// Errors name `initial`, `min_runs`, `max_runs` or the loop's fields.
pub fn adaptive_study(
    car: &Car,
    road: &Road,
    spec: SurrogateSpec,
    options: &StudyOptions,
) -> Result<AdaptiveStudy> {
    let setting = Setting::new(car, road, &options.design_box)?;
    let hifi = HiFi::new(car, road)?;
    adaptive_study_on(
        car,
        &setting,
        &hifi,
        RoadScenario::Iso(*road),
        spec,
        options,
    )
}

/// [`adaptive_study`] on any HiFi (the full car on a measured road, say) with the
/// surrogates' `setting` (its LoFi on the same road; its box, not `options`', is the
/// study's); `road` names the road in the report.
pub(crate) fn adaptive_study_on<E: Evaluator + Sync>(
    car: &Car,
    setting: &Setting,
    hifi: &E,
    road: RoadScenario,
    spec: SurrogateSpec,
    options: &StudyOptions,
) -> Result<AdaptiveStudy> {
    #[cfg(not(target_arch = "wasm32"))]
    let start = std::time::Instant::now();
    if options.initial < 2 {
        return Err(RideError::field("initial", "needs at least 2 points"));
    }
    if options.min_runs <= options.initial {
        return Err(RideError::field(
            "min_runs",
            format!("must exceed the {} initial points", options.initial),
        ));
    }
    if options.max_runs < options.min_runs || options.max_runs > MAX_HIFI_RUNS {
        return Err(RideError::field(
            "max_runs",
            format!(
                "needs min_runs ({}) <= max_runs <= {MAX_HIFI_RUNS}",
                options.min_runs
            ),
        ));
    }
    options.stm.validate()?;
    options.objectives.validate()?;
    // Two fronts per row and the HiFi's own, each STM; the loop's infill predictions.
    let rows = (options.max_runs - options.min_runs + 1) as u64;
    let fronts = 2 * rows + 1;
    let infill =
        (options.max_runs - options.initial) as u64 * (options.adaptive.candidates as u64).pow(2);
    crate::budget::check(
        fronts
            .saturating_mul(crate::budget::stm_runs(
                options.stm.grid,
                options.stm.levels,
            ))
            .saturating_add(infill),
        "grid",
        &format!(
            "the adaptive study ({fronts} STM fronts on a {0} x {0} grid, runs {1}..{2})",
            options.stm.grid, options.min_runs, options.max_runs
        ),
        "--grid or --max-runs",
    )?;
    let design_box = setting.design_box;
    let decision = Decision {
        objectives: options.objectives.clone(),
        stm: options.stm.clone(),
        ..Decision::of_car(car, hifi)?
    };
    let hifi_front = HifiFront::new(hifi, &decision, &design_box)?;
    let adaptive = AdaptiveOptions {
        runs: options.max_runs - options.initial,
        ..options.adaptive
    };
    let plan = PlanSpec::AudzeEglais(options.initial);
    let initial = sample_plan(hifi, &plan.plan()?, &design_box)?;
    let mut state = AdaptiveLoop::new(
        spec,
        setting.clone(),
        decision.clone(),
        plan.name(),
        initial,
        adaptive,
    )?;
    let lm = adaptive.lm();
    let mut rows = Vec::new();
    for n in options.initial + 1..=options.max_runs {
        state.step(hifi)?;
        if n < options.min_runs {
            continue;
        }
        let looped = front_check(state.model(), hifi, &decision, &design_box, &hifi_front, n)?;
        let ae = sample_plan(hifi, &PlanSpec::AudzeEglais(n).plan()?, &design_box)?;
        let model = spec.fit(setting, &ae, &lm)?;
        let fixed = front_check(&model, hifi, &decision, &design_box, &hifi_front, n)?;
        rows.push(StudyRow {
            hifi_runs: n,
            adaptive: looped,
            audze_eglais: fixed,
        });
    }
    let report = state.report();
    #[cfg(not(target_arch = "wasm32"))]
    let seconds = Some(start.elapsed().as_secs_f64());
    #[cfg(target_arch = "wasm32")]
    let seconds = None;
    Ok(AdaptiveStudy {
        car: car.name.clone(),
        road,
        surrogate: spec.name(),
        uncertainty: report.uncertainty,
        options: StudyOptions {
            adaptive,
            design_box,
            ..options.clone()
        },
        hifi_front,
        rows,
        samples: state.samples().to_vec(),
        reasons: report.added.into_iter().map(|a| a.reason).collect(),
        seconds,
    })
}

impl AdaptiveStudy {
    /// The study as a markdown table.
    pub fn to_markdown(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(
            s,
            "# Adaptive HiFi sampling: {} ({}), {} with {} uncertainty\n\n\
             Adaptive = Audze-Eglais {} + the rest by {}; AE = an Audze-Eglais plan of the same size. \
             HV ratio: the front's designs re-run on the HiFi, against STM on the HiFi itself \
             ({} HiFi runs, hypervolume {:.5} (m/s^2) N). Re-check: the min-max pick's largest \
             HiFi error. Front error: the largest error over the front's designs.{}\n",
            self.car,
            match &self.road {
                RoadScenario::Iso(r) => format!("{:?} road, {} m/s", r.class, r.speed),
                RoadScenario::Measured(m) => format!("{} at {} m/s", m.file, m.speed),
            },
            self.surrogate,
            self.uncertainty.name(),
            self.options.initial,
            self.options.adaptive.criterion.name(),
            self.hifi_front.hifi_runs,
            self.hifi_front.hypervolume,
            self.seconds
                .map_or(String::new(), |t| format!(" Study time {t:.1} s.")),
        );
        let _ = writeln!(
            s,
            "| HiFi runs | re-check % adaptive | re-check % AE | HV ratio adaptive | HV ratio AE | front error % adaptive | front error % AE |"
        );
        let _ = writeln!(s, "|{}", "---|".repeat(7));
        for r in &self.rows {
            let (a, e) = (&r.adaptive, &r.audze_eglais);
            let _ = writeln!(
                s,
                "| {} | {:.3} | {:.3} | {:.5} | {:.5} | {:.3} | {:.3} |",
                r.hifi_runs,
                a.recheck_error_percent,
                e.recheck_error_percent,
                a.hypervolume_ratio,
                e.hypervolume_ratio,
                a.front_max_error_percent,
                e.front_max_error_percent
            );
        }
        s
    }
}
