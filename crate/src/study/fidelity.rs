//! The fidelity study (METHOD.md sections 4 and 5): every approach x scheme x plan, each
//! surrogate fitted to HiFi samples at the plan's points and validated on one `20 x 20` HiFi
//! grid over the design box (evaluated once and reused), and the one-surrogate report the CLI
//! prints.

use super::adaptive::AdaptiveReport;
use crate::analysis::HiFi;
use crate::car::{Car, QuarterCar};
use crate::design::DesignBox;
use crate::error::{Result, RideError};
use crate::evaluate::{Criteria, Evaluator, CRITERIA_NAMES};
use crate::optimize::Counted;
use crate::road::Road;
use crate::road_profile::RoadScenario;
use crate::surrogate::fit::{FitDiagnostics, LmOptions};
use crate::surrogate::metrics::{ByCriterion, ErrorMap, Metrics};
use crate::surrogate::spec::{Approach, PlanSpec, SurrogateSpec};
use crate::surrogate::uncertainty::{estimates, UncertaintyOutcome};
use crate::surrogate::{sample_plan, Parameter, Sample, Scheme, Setting, Surrogate};
use crate::surrogate::{ValidationSet, VALIDATION_LEVELS};
use serde::Serialize;
use std::fmt::Write;

/// Surrogate and HiFi values on the validation grid, with its points (the error map's).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GridPredictions {
    /// Front spring rate of each point, N/m.
    pub ks: Vec<f64>,
    /// Front damper rate of each point, N s/m.
    pub cs: Vec<f64>,
    /// Surrogate predictions.
    pub surrogate: Vec<Criteria>,
    /// HiFi values.
    pub hifi: Vec<Criteria>,
}

/// What `ridelab surrogate` reports about one fitted surrogate.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SurrogateReport {
    /// Canonical surrogate name.
    pub surrogate: String,
    /// Approach and scheme.
    pub spec: SurrogateSpec,
    /// Plan name (`ae:10`, `grid:5`).
    pub plan: String,
    /// How the plan was made.
    pub plan_method: String,
    /// Car name.
    pub car: String,
    /// Road scenario: an ISO class (JSON as [`Road`]) or a measured road.
    pub road: RoadScenario,
    /// Design box of the plan, the normalisation and the validation grid.
    pub design_box: DesignBox,
    /// The HiFi samples the surrogate was fitted to (in the order added).
    pub samples: Vec<Sample>,
    /// HiFi evaluations made: samples plus validation grid (plus the datum for an
    /// adaptive plan, whose decision judges the SWS limit against it).
    pub hifi_evaluations: usize,
    /// Tuning parameters.
    pub tuning: Vec<Parameter>,
    /// One entry per fit.
    pub diagnostics: Vec<FitDiagnostics>,
    /// VBA and PBA: the tuned quarter car behind each criterion `[bacc, dtl, sws]` at the
    /// car's own front design (its FRFs and modes can be drawn beside the HiFi's).
    pub tuned_quarters: Option<[QuarterCar; 3]>,
    /// Levels per axis of the validation grid.
    pub validation_levels: usize,
    /// Quality on the validation grid.
    pub metrics: ByCriterion<Metrics>,
    /// Signed relative error at each validation point, %.
    pub error_map: ErrorMap,
    /// Where the surrogate may be wrong: each uncertainty estimate (leave-one-out for
    /// every surrogate, the model's own for gp-mul), how it is computed, its correlation
    /// with the true error and its map at the validation points (beside the error map).
    pub uncertainty: Vec<UncertaintyOutcome>,
    /// The adaptive loop that chose the samples, `None` for a plain plan.
    pub adaptive: Option<AdaptiveReport>,
    /// Surrogate and HiFi values at the validation points, when asked for.
    pub predictions: Option<GridPredictions>,
}

/// Fits the surrogate `spec` to samples of `hifi` (the full car in `setting`: an ISO class
/// or a measured road, [`Setting::measured`]) at `plan_spec` over the setting's box and
/// validates it on the default `20 x 20` HiFi grid, or with `predict_grid = Some(n)` on an
/// `n x n` grid with the predictions there ([`crate::study::SurrogateRequest`]'s plain
/// fit). The report's `road` is the setting's ISO road, which the caller replaces for a
/// measured one.
pub(super) fn surrogate_report_on<E: Evaluator>(
    spec: SurrogateSpec,
    plan_spec: PlanSpec,
    setting: &Setting,
    hifi: E,
    predict_grid: Option<usize>,
) -> Result<SurrogateReport> {
    let design_box = &setting.design_box;
    let hifi = Counted::new(hifi);
    let plan = plan_spec.plan()?;
    let samples = sample_plan(&hifi, &plan, design_box)?;
    let options = LmOptions::default();
    let model = spec.fit(setting, &samples, &options)?;
    let fitted = Fitted {
        spec,
        plan: plan_spec.name(),
        plan_method: plan.method,
        samples,
        model: &model,
        options,
        adaptive: None,
    };
    fitted.report(setting, &hifi, predict_grid)
}

/// A fitted surrogate with what a [`SurrogateReport`] says about its samples.
pub(crate) struct Fitted<'a> {
    pub spec: SurrogateSpec,
    pub plan: String,
    pub plan_method: String,
    pub samples: Vec<Sample>,
    pub model: &'a dyn Surrogate,
    pub options: LmOptions,
    pub adaptive: Option<AdaptiveReport>,
}

impl Fitted<'_> {
    /// Validates the fit on a `predict_grid` (default 20 x 20) HiFi grid of `hifi`.
    /// Errors name `predict-grid` for a bad grid.
    pub fn report<E: Evaluator>(
        self,
        setting: &Setting,
        hifi: &Counted<E>,
        predict_grid: Option<usize>,
    ) -> Result<SurrogateReport> {
        let (car, design_box) = (&setting.lofi.car, &setting.design_box);
        let levels = predict_grid.unwrap_or(VALIDATION_LEVELS);
        let validation = ValidationSet::new(hifi, design_box, levels).map_err(|e| match e {
            RideError::Field { reason, .. } => RideError::field("predict-grid", reason),
            e => e,
        })?;
        let predicted = validation.predict(self.model)?;
        Ok(SurrogateReport {
            surrogate: self.spec.name(),
            spec: self.spec,
            plan: self.plan,
            plan_method: self.plan_method,
            car: car.name.clone(),
            road: RoadScenario::Iso(setting.lofi.road),
            design_box: *design_box,
            uncertainty: estimates(
                &self.spec,
                setting,
                &self.samples,
                &self.options,
                &validation,
            )?,
            samples: self.samples,
            hifi_evaluations: hifi.count(),
            tuning: self.model.tuning(),
            diagnostics: self.model.diagnostics(),
            tuned_quarters: self
                .model
                .tuned_quarters(car.front.spring, car.front.damper)?,
            validation_levels: levels,
            metrics: validation.metrics(&predicted)?,
            error_map: ErrorMap::new(&validation.points, &validation.hifi, &predicted),
            adaptive: self.adaptive,
            predictions: predict_grid.map(|_| GridPredictions {
                ks: validation.points.iter().map(|p| p.0).collect(),
                cs: validation.points.iter().map(|p| p.1).collect(),
                surrogate: predicted,
                hifi: validation.hifi.clone(),
            }),
        })
    }
}

/// The validation of one fitted surrogate of the study.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FittedRow {
    /// Quality on the validation grid.
    pub metrics: ByCriterion<Metrics>,
    /// Largest max RTE over the criteria, %: the ranking measure (JSON
    /// `worst_rte_max_percent`).
    #[serde(rename = "worst_rte_max_percent")]
    pub worst_rte_max: f64,
    /// Least R^2 over the criteria.
    pub min_r2: f64,
    /// Total fit cost over the fits (half the sum of squared relative errors at the samples).
    pub cost: f64,
    /// Whether every fit converged.
    pub converged: bool,
}

/// Outcome of one study combination.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "status", rename_all = "lowercase")]
pub enum Outcome {
    /// Fitted and validated.
    Fitted(FittedRow),
    /// Not fitted (too few samples for the parameter count, or a failed fit), and why.
    Skipped {
        /// The reason.
        reason: String,
    },
}

/// One approach x scheme x plan of the study.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StudyRow {
    /// Canonical surrogate name.
    pub surrogate: String,
    /// Scheme.
    pub scheme: Scheme,
    /// Plan name.
    pub plan: String,
    /// Number of HiFi samples of the plan.
    pub samples: usize,
    /// Result.
    pub outcome: Outcome,
}

/// The best surrogate for one sample budget.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BudgetBest {
    /// Number of HiFi samples.
    pub samples: usize,
    /// Surrogate name.
    pub surrogate: String,
    /// Plan name.
    pub plan: String,
    /// Its validation.
    pub fitted: FittedRow,
}

/// The fidelity study's results.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StudyReport {
    /// Car name.
    pub car: String,
    /// Road scenario: an ISO class, or a measured road (`ridelab report --road FILE`).
    pub road: RoadScenario,
    /// Design box.
    pub design_box: DesignBox,
    /// Levels per axis of the validation grid.
    pub validation_levels: usize,
    /// HiFi evaluations made: every plan's samples plus the validation grid once.
    pub hifi_evaluations: usize,
    /// The untuned LoFi on the validation grid: the fidelity gap the surrogates close.
    pub lofi: ByCriterion<Metrics>,
    /// How the best surrogate of a budget is chosen.
    pub ranking: String,
    /// Every combination, by surrogate then plan.
    pub rows: Vec<StudyRow>,
    /// The best fitted surrogate for each number of samples, by increasing budget.
    pub best_per_budget: Vec<BudgetBest>,
}

/// The surrogates of the study: every RBA variant, VBA and the PBA options of METHOD.md
/// (SMTS, UMTS, both, both plus tyre rate), each in every scheme it offers, then the
/// quadratic and RBF data fits.
pub(crate) fn study_specs() -> Vec<SurrogateSpec> {
    SurrogateSpec::all()
        .into_iter()
        .filter(|s| match s.approach {
            Approach::Pba(p) => !p.tyre || (p.sprung && p.unsprung),
            Approach::Data(r) => r != crate::surrogate::ResponseKind::Poly(1),
            _ => true,
        })
        .collect()
}

/// Runs the study on `hifi` (wrap it in [`Counted`] to count its runs): the plans are sampled
/// once each, every spec is fitted to every plan and validated on `validation`. A
/// combination that cannot be fitted is a skipped row, not an error.
fn fidelity_study<E: Evaluator>(
    hifi: &E,
    setting: &Setting,
    specs: &[SurrogateSpec],
    plans: &[PlanSpec],
    validation: &ValidationSet,
    options: &LmOptions,
) -> Result<Vec<StudyRow>> {
    let sampled = plans
        .iter()
        .map(|p| Ok((p, sample_plan(hifi, &p.plan()?, &setting.design_box)?)))
        .collect::<Result<Vec<_>>>()?;
    let mut rows = Vec::with_capacity(specs.len() * plans.len());
    for spec in specs {
        for (plan, samples) in &sampled {
            let outcome = match validate(spec, setting, samples, validation, options) {
                Ok(f) => Outcome::Fitted(f),
                Err(e) => Outcome::Skipped {
                    reason: e.to_string(),
                },
            };
            rows.push(StudyRow {
                surrogate: spec.name(),
                scheme: spec.scheme,
                plan: plan.name(),
                samples: samples.len(),
                outcome,
            });
        }
    }
    Ok(rows)
}

/// Fits `spec` to `samples` and validates it.
fn validate(
    spec: &SurrogateSpec,
    setting: &Setting,
    samples: &[Sample],
    validation: &ValidationSet,
    options: &LmOptions,
) -> Result<FittedRow> {
    let model = spec.fit(setting, samples, options)?;
    let metrics = validation.metrics(&validation.predict(&model)?)?;
    let diagnostics = model.diagnostics();
    let all = metrics.to_array();
    Ok(FittedRow {
        worst_rte_max: all.iter().map(|m| m.rte_max).fold(0.0, f64::max),
        min_r2: all.iter().map(|m| m.r2).fold(f64::INFINITY, f64::min),
        cost: diagnostics.iter().map(|d| d.cost).sum(),
        converged: diagnostics.iter().all(|d| d.converged),
        metrics,
    })
}

/// For each sample budget, the fitted row with the least worst-case max RTE.
pub fn best_per_budget(rows: &[StudyRow]) -> Vec<BudgetBest> {
    let mut budgets: Vec<usize> = rows.iter().map(|r| r.samples).collect();
    budgets.sort_unstable();
    budgets.dedup();
    budgets
        .into_iter()
        .filter_map(|n| {
            rows.iter()
                .filter(|r| r.samples == n)
                .filter_map(|r| match &r.outcome {
                    Outcome::Fitted(f) => Some((r, f)),
                    Outcome::Skipped { .. } => None,
                })
                .min_by(|a, b| a.1.worst_rte_max.total_cmp(&b.1.worst_rte_max))
                .map(|(r, f)| BudgetBest {
                    samples: n,
                    surrogate: r.surrogate.clone(),
                    plan: r.plan.clone(),
                    fitted: f.clone(),
                })
        })
        .collect()
}

/// The whole study for `car` on the ISO `road` over `design_box` (plans, normalisation and
/// validation grid span it): [`study_specs`], the plans of [`PlanSpec::study`], the
/// `20 x 20` validation grid, default fit options.
pub fn study(car: &Car, road: &Road, design_box: &DesignBox) -> Result<StudyReport> {
    let setting = Setting::new(car, road, design_box)?;
    study_on(
        car,
        &setting,
        HiFi::new(car, road)?,
        RoadScenario::Iso(*road),
    )
}

/// [`study`] on `setting` (an ISO class or a measured road: its LoFi and box) with
/// `hifi` the full car of `car` there; `road` is recorded.
pub(crate) fn study_on<E: Evaluator>(
    car: &Car,
    setting: &Setting,
    hifi: E,
    road: RoadScenario,
) -> Result<StudyReport> {
    let design_box = setting.design_box;
    let hifi = Counted::new(hifi);
    let validation = ValidationSet::new(&hifi, &design_box, VALIDATION_LEVELS)?;
    let rows = fidelity_study(
        &hifi,
        setting,
        &study_specs(),
        &PlanSpec::study(),
        &validation,
        &LmOptions::default(),
    )?;
    let lofi = validation.metrics(&validation.predict(&setting.lofi)?)?;
    Ok(StudyReport {
        car: car.name.clone(),
        road,
        design_box,
        validation_levels: VALIDATION_LEVELS,
        hifi_evaluations: hifi.count(),
        lofi,
        ranking: "least worst-case max RTE over the three criteria".into(),
        best_per_budget: best_per_budget(&rows),
        rows,
    })
}

impl StudyReport {
    /// The study as markdown: the best surrogate per budget, then every row.
    pub fn to_markdown(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(
            s,
            "# Fidelity study: {} ({})\n\nValidation: {n} x {n} HiFi grid; {} HiFi evaluations in all. Best = {}.\n",
            self.car,
            match &self.road {
                RoadScenario::Iso(r) => format!("{:?} road, {} m/s", r.class, r.speed),
                RoadScenario::Measured(m) => format!("the measured road {}, {} m/s", m.file, m.speed),
            },
            self.hifi_evaluations,
            self.ranking,
            n = self.validation_levels,
        );
        let names = CRITERIA_NAMES.map(str::to_uppercase);
        let head = ["R2", "max RTE %", "mean RTE %"]
            .iter()
            .flat_map(|m| names.iter().map(move |n| format!("{m} {n} |")))
            .collect::<Vec<_>>()
            .join(" ");
        let metric_cells = |metrics: &ByCriterion<Metrics>| {
            let m = metrics.to_array();
            let r2: Vec<String> = m.iter().map(|m| format!("{:.4}", m.r2)).collect();
            let rte: Vec<String> = m.iter().map(|m| format!("{:.2}", m.rte_max)).collect();
            let mean: Vec<String> = m.iter().map(|m| format!("{:.2}", m.rte_mean)).collect();
            format!(
                "{} | {} | {} |",
                r2.join(" | "),
                rte.join(" | "),
                mean.join(" | ")
            )
        };
        let _ = writeln!(
            s,
            "## Best per sample budget\n\n| samples | surrogate | plan | {head}"
        );
        let _ = writeln!(s, "|{}", "---|".repeat(12));
        let _ = writeln!(s, "| 0 | untuned LoFi | - | {}", metric_cells(&self.lofi));
        for b in &self.best_per_budget {
            let _ = writeln!(
                s,
                "| {} | {} | {} | {}",
                b.samples,
                b.surrogate,
                b.plan,
                metric_cells(&b.fitted.metrics)
            );
        }
        let _ = writeln!(
            s,
            "\n## All combinations\n\n| surrogate | plan | samples | {head} note |"
        );
        let _ = writeln!(s, "|{}", "---|".repeat(13));
        for r in &self.rows {
            let cells = match &r.outcome {
                Outcome::Fitted(f) => format!(
                    "{} {} |",
                    metric_cells(&f.metrics),
                    if f.converged { "" } else { "not converged" }
                ),
                Outcome::Skipped { reason } => {
                    format!(
                        "{}skipped: {} |",
                        " - |".repeat(9),
                        reason.replace('|', "/")
                    )
                }
            };
            let _ = writeln!(
                s,
                "| {} | {} | {} | {cells}",
                r.surrogate, r.plan, r.samples
            );
        }
        s
    }
}
