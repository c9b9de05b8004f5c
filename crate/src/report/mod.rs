//! The study report: the method end to end for one car, road and design box, as the
//! data behind `ridelab report` and the page's "Download report" (one function builds
//! it for both), rendered as one self-contained HTML file ([`html`]) and its Markdown
//! twin ([`markdown`]), with the figures as SVG ([`figures`], the core's plotters charts).
//!
//! Sections (the thesis's chapters 3 to 5):
//! 1. the car, road and design box; model verification: the closed form against the
//!    Lyapunov route against frequency integration against a long time-domain record,
//!    for the LoFi and the HiFi; their FRFs and modes;
//! 2. design-criteria maps of both models and the design objective space;
//! 3. the Audze-Eglais plans with their energies and gap distributions;
//! 4. the fidelity study and the chosen surrogate's error maps;
//! 5. STM and NSGA-II fronts on the surrogate, a brute-force HiFi front, hypervolumes,
//!    the min-max pick against the datum re-checked on the HiFi, beside the seed thesis's
//!    own result; the min-max, knee and weighted (W = 0.5) picks with their pseudo-weights,
//!    each re-checked on the HiFi. An infeasible scenario says why instead;
//! 6. adaptive sampling: the same surrogate on half the plan's HiFi runs as an
//!    Audze-Eglais plan and the other half chosen one by one where the expected
//!    hypervolume improvement of the feasible front is largest, against the plan itself.
//!
//! This module holds the report's data ([`MethodReport`]) and builds its sections once for
//! either road ([`SectionRoad`]): [`build`] on an ISO 8608 class ([`road`]), [`build_on`]
//! on a measured road ([`measured`]); [`MethodReport::documents`] renders it ([`render`]).
//!
//! Deterministic for given inputs (seeded); nothing in it depends on the clock.

pub mod document;
pub mod figures;
pub mod html;
pub mod markdown;
mod measured;
mod render;
mod road;
mod study;

pub(crate) use measured::build_on;
pub use render::Documents;
pub use road::build;

use crate::analysis::ModelKind;
use crate::car::{Car, QuarterCar};
use crate::criteria::{
    bacc_wk_exact, bacc_wk_spectral, comfort_label, criteria_exact, criteria_modal,
    criteria_spectral, quarter_car_rms, Spectrum,
};
use crate::design::DesignBox;
use crate::doe::{audze_eglais, gap_histogram};
use crate::dos::DesignObjectives;
use crate::error::{Result, RideError};
use crate::evaluate::{Criteria, Evaluator};
use crate::maps::Grid;
use crate::math;
use crate::model::{LinearModel, Mode};
use crate::optimize::{front_distance, FrontDistance, Method, Nsga2Params, PickRule, StmParams};
use crate::road::Road;
use crate::road_profile::RoadScenario;
use crate::study::adaptive::{AdaptiveOptimizeReport, AdaptiveOptions};
use crate::study::{EvaluatorSpec, OptimizeReport, OptimizeRequest};
use crate::study::{MapReport, MapSettings};
use crate::study::{StudyReport, SurrogateReport};
use crate::surrogate::{PlanSpec, SurrogateSpec};
use crate::time_domain::{simulate, TimeOptions};
use serde::Serialize;

/// What a report is made of.
#[derive(Debug, Clone, PartialEq)]
pub struct ReportInputs {
    /// The datum car (its own front spring and damper are the datum design).
    pub car: Car,
    /// The road.
    pub road: Road,
    /// The design box of the maps, plans, surrogates and fronts.
    pub design_box: DesignBox,
    /// The design objectives.
    pub objectives: DesignObjectives,
    /// The surrogate of sections 4 and 5 and its plan; `None`: the fidelity study's best
    /// at 10 HiFi samples.
    pub surrogate: Option<(SurrogateSpec, PlanSpec)>,
    /// Seed of the time-domain record and of NSGA-II.
    pub seed: u64,
}

impl ReportInputs {
    /// The default car, road, box and objectives; the study picks the surrogate; seed 1.
    pub fn new(car: Car, road: Road) -> ReportInputs {
        ReportInputs {
            car,
            road,
            design_box: DesignBox::default(),
            objectives: DesignObjectives::default(),
            surrogate: None,
            seed: 1,
        }
    }
}

/// Sampling plans of section 3 (the seed's study: 2, 3, 4, 5 and 10 points).
const PLAN_SIZES: [usize; 5] = [2, 3, 4, 5, 10];
/// Grid points per axis of the design-criteria maps.
const MAP_POINTS: usize = 41;
/// Length of the time-domain record of the verification, s (the RMS of a record this
/// long agrees with the exact one to about 3 %).
const RECORD_S: f64 = 100.0;

/// The whole report's data (also written as `report.json`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MethodReport {
    /// The crate version that made it.
    pub version: String,
    /// Section 1: the scenario.
    pub scenario: Scenario,
    /// Section 1: model verification.
    pub verification: Verification,
    /// Section 2: the maps of both models.
    pub maps: Maps,
    /// Section 3: the sampling plans.
    pub sampling: Vec<PlanSummary>,
    /// Section 4: the fidelity study and the chosen surrogate.
    pub fidelity: Fidelity,
    /// Section 5: the fronts and the pick, or why there are none.
    pub optimisation: Optimisation,
    /// Section 6: adaptive sampling against the plan, or why it was not run.
    pub adaptive: AdaptiveSection,
    /// The seed thesis's own result, quoted.
    pub thesis: ThesisResult,
}

/// The car, road, box and objectives.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Scenario {
    /// The datum car.
    pub car: Car,
    /// Its front quarter car (the LoFi).
    pub quarter: QuarterCar,
    /// The road: an ISO class (class, speed, tracks) or a measured road (file, speed,
    /// tracks, the shaping filters' band and error).
    pub road: RoadScenario,
    /// Road velocity PSD of the ISO class, one-sided, m^2/s^2/Hz (none on a measured road:
    /// its PSD is the file's).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub velocity_psd: Option<f64>,
    /// Front-rear delay `L / v`, s.
    pub delay: f64,
    /// Static front wheel load, N.
    pub static_wheel_load: f64,
    /// The design box.
    pub design_box: DesignBox,
    /// The design objectives.
    pub objectives: DesignObjectives,
}

/// One route's criteria at the datum design and its largest relative difference from
/// the section's reference (the first row).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RouteRow {
    /// The route.
    pub route: String,
    /// Its criteria (m/s^2, N, m).
    pub criteria: Criteria,
    /// `max_k |c_k / ref_k - 1|` against the first row.
    pub difference: f64,
}

/// The FRF magnitudes |H| from road displacement (right track) of both models.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Frf {
    /// Frequencies, Hz (0.1..100, log spaced).
    pub f: Vec<f64>,
    /// LoFi `[BAcc 1/s^2, DTL N/m, SWS m/m]`.
    pub lofi: [Vec<f64>; 3],
    /// HiFi, same.
    pub hifi: [Vec<f64>; 3],
}

/// Model verification at the datum design.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Verification {
    /// The LoFi by the closed forms, Lyapunov, frequency integration and the record.
    pub lofi: Vec<RouteRow>,
    /// The HiFi by the Kronecker Lyapunov route with the delay (where it exists), the
    /// modal route, frequency integration and the record.
    pub hifi: Vec<RouteRow>,
    /// A note on a route that does not apply (a road warp needs ISO's low cutoff).
    pub notes: Vec<String>,
    /// The record: its length, step and seed.
    pub record: TimeOptions,
    /// LoFi modes.
    pub lofi_modes: Vec<Mode>,
    /// HiFi modes.
    pub hifi_modes: Vec<Mode>,
    /// FRFs of both models.
    pub frf: Frf,
    /// ISO 2631-1 Wk-weighted comfort of both models, LoFi first.
    pub comfort: Vec<ComfortRow>,
}

/// ISO 2631-1 Wk-weighted RMS body acceleration of one model by both routes.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ComfortRow {
    /// "LoFi" or "HiFi".
    pub model: String,
    /// Unweighted RMS BAcc, m/s^2.
    pub bacc: f64,
    /// Wk-weighted, exact route (the frequency route where a road warp rules it out), m/s^2.
    pub exact: f64,
    /// Wk-weighted, frequency route, m/s^2.
    pub spectral: f64,
    /// ISO 2631-1 Annex C's label of `exact`.
    pub label: String,
}

/// The maps of both models over the design box.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Maps {
    /// The LoFi's (the `ridelab map --model quarter` report).
    pub lofi: MapReport,
    /// The HiFi's.
    pub hifi: MapReport,
}

/// An Audze-Eglais plan.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PlanSummary {
    /// Points.
    pub points: usize,
    /// Potential energy, lattice units^-2.
    pub energy: f64,
    /// Proven optimal.
    pub optimal: bool,
    /// How it was made.
    pub method: String,
    /// Smallest gap, lattice units.
    pub min_gap: f64,
    /// Gap histogram `(lo, hi, count)`, lattice units.
    pub gaps: Vec<(f64, f64, usize)>,
    /// The points in the box `(ks N/m, cs N s/m)`.
    pub design: Vec<(f64, f64)>,
}

/// The fidelity study and the surrogate the report goes on with.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Fidelity {
    /// Every surrogate on every plan, validated on the 20 x 20 HiFi grid.
    pub study: StudyReport,
    /// Why this surrogate: chosen by the inputs, or the study's best at 10 samples.
    pub chosen_because: String,
    /// The chosen surrogate's report (samples, tuning, metrics, error map).
    pub chosen: SurrogateReport,
}

/// Section 5.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Optimisation {
    /// `None` when a front exists; otherwise why not (the binding objective).
    pub infeasible: Option<String>,
    /// STM on the surrogate.
    pub stm: Option<OptimizeReport>,
    /// NSGA-II on the surrogate.
    pub nsga2: Option<OptimizeReport>,
    /// STM on the HiFi itself: the brute-force reference front.
    pub hifi: Option<OptimizeReport>,
    /// Distance of the surrogate's STM front from the HiFi front (normalised plane).
    pub stm_to_hifi: Option<FrontDistance>,
    /// The before/after table (the datum, each pick predicted and re-checked).
    pub table: Vec<PickRow>,
    /// The picks of [`PICK_RULES`] on the surrogate's STM front, each re-checked on the HiFi.
    pub picks: Vec<RulePick>,
}

/// The pick rules of section 5's table of picks: the thesis's min-max, the knee, and the
/// weighted pick with equal weights.
const PICK_RULES: [PickRule; 3] = [PickRule::MinMax, PickRule::Knee, PickRule::Asf(0.5)];

/// One rule's pick on the surrogate's STM front and its HiFi re-check.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RulePick {
    /// The rule (`minmax`, `knee`, `asf:W`).
    pub rule: String,
    /// The pick's front spring, N/m.
    pub ks: f64,
    /// Its front damper, N s/m.
    pub cs: f64,
    /// Its pseudo-weights `[comfort, road holding]`, -.
    pub pseudo_weights: [f64; 2],
    /// BAcc and DTL change against the datum, predicted by the surrogate, %.
    pub predicted_change_percent: [f64; 2],
    /// BAcc and DTL change against the datum, re-checked on the HiFi, %.
    pub rechecked_change_percent: [f64; 2],
    /// The prediction error at the pick against the HiFi `[bacc, dtl, sws]`, %.
    pub error_percent: [f64; 3],
}

/// Section 6: the adaptive loop on the section's surrogate (STM front, min-max pick), with
/// as many HiFi runs in all as section 5's plan.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AdaptiveSection {
    /// `None` when the loop ran; otherwise why not.
    pub skipped: Option<String>,
    /// The loop (samples in order with their reasons, front and pick per HiFi run) and
    /// the optimisation on its final surrogate.
    pub run: Option<AdaptiveOptimizeReport>,
    /// The plan's pick and the adaptive pick, each re-checked on the HiFi.
    pub comparison: Vec<AdaptiveRow>,
}

/// One row of section 6's comparison.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AdaptiveRow {
    /// How the surrogate's samples were chosen.
    pub samples: String,
    /// HiFi runs the surrogate was fitted to.
    pub hifi_runs: usize,
    /// The min-max pick's front spring, N/m.
    pub ks: f64,
    /// Its front damper, N s/m.
    pub cs: f64,
    /// The prediction error at the pick against the HiFi `[bacc, dtl, sws]`, %.
    pub error_percent: [f64; 3],
    /// BAcc and DTL change against the datum, re-checked on the HiFi, %.
    pub rechecked_change_percent: [f64; 2],
}

/// One row of the before/after table: a design and its change against the datum.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PickRow {
    /// What the row is.
    pub design: String,
    /// Front spring rate, N/m.
    pub ks: f64,
    /// Front damper rate, N s/m.
    pub cs: f64,
    /// BAcc change against the datum, %.
    pub bacc_percent: f64,
    /// DTL change against the datum, %.
    pub dtl_percent: f64,
    /// RMS SWS, m.
    pub sws: f64,
}

/// The seed thesis's result on its own (unpublished here) datum car (METHOD.md section 6).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ThesisResult {
    /// Front spring rate of its pick, N/m.
    pub ks: f64,
    /// Front damper rate of its pick, N s/m.
    pub cs: f64,
    /// BAcc change, %.
    pub bacc_percent: f64,
    /// DTL change, %.
    pub dtl_percent: f64,
    /// Why the numbers here differ.
    pub note: String,
}

impl ThesisResult {
    fn quoted() -> ThesisResult {
        ThesisResult {
            ks: 12_535.6,
            cs: 1_416.7,
            bacc_percent: -12.6,
            dtl_percent: 6.4,
            note: "The seed thesis optimised its own datum car, whose data are not published; \
                   RideLab's datum is the Ikenaga et al. (2000) car, so the numbers differ. \
                   What should agree is the shape of the trade-off: a softer spring with \
                   about the datum's damping buys comfort for some road holding, inside the \
                   7 mm SWS limit."
                .into(),
        }
    }
}

/// The report's sections in order, for progress messages.
pub const SECTIONS: [&str; 6] = [
    "1 scenario and model verification",
    "2 design maps",
    "3 sampling plans",
    "4 fidelity study",
    "5 fronts and the pick",
    "6 adaptive sampling",
];

fn validate(inputs: &ReportInputs) -> Result<()> {
    inputs.car.validate()?;
    inputs.road.validate()?;
    inputs.design_box.validate()?;
    inputs.objectives.validate()
}

/// What the report's sections need of the road they run on: an ISO 8608 class
/// ([`road::IsoRoad`]) or a measured road ([`measured::OnRoad`]). Each section asks it for
/// its models' results, so the sections are written once ([`build`] and [`build_on`] are
/// the same code on either road, [`build_with`]), and the page's wasm, which builds ISO
/// reports only, carries the ISO road's code alone.
trait SectionRoad {
    /// The road as the reports record it.
    fn scenario(&self) -> RoadScenario;
    /// The ISO road's velocity PSD, m^2/s^2/Hz (none on a measured road).
    fn velocity_psd(&self) -> Option<f64>;
    /// Section 1 at the datum design of `car`.
    fn verify(&self, car: &Car, seed: u64) -> Result<Verification>;
    /// Section 2: `kind`'s map of `car`.
    fn map(&self, kind: ModelKind, car: &Car, settings: &MapSettings) -> Result<MapReport>;
    /// Section 4: the fidelity study over `design_box`.
    fn study(&self, car: &Car, design_box: &DesignBox) -> Result<StudyReport>;
    /// Section 4: the chosen surrogate's report.
    fn surrogate(
        &self,
        spec: SurrogateSpec,
        plan: PlanSpec,
        car: &Car,
        design_box: &DesignBox,
    ) -> Result<SurrogateReport>;
    /// Section 5: one optimisation (the request's road is this one).
    fn optimize(&self, request: &OptimizeRequest) -> Result<OptimizeReport>;
    /// Section 5: the full car of `car` on this road.
    fn hifi(&self, car: &Car) -> Result<Box<dyn Evaluator + '_>>;
    /// Section 5: `r` picked again by `rule`, re-checked on the HiFi.
    fn repick(
        &self,
        r: &mut OptimizeReport,
        rule: PickRule,
        car: &Car,
        design_box: &DesignBox,
    ) -> Result<()>;
    /// Section 6: the adaptive loop's optimisation.
    fn adaptive(
        &self,
        request: &OptimizeRequest,
        options: AdaptiveOptions,
    ) -> Result<AdaptiveOptimizeReport>;
}

/// The sections on `on`, either road ([`SectionRoad`]).
fn build_with<R: SectionRoad>(
    inputs: &ReportInputs,
    on: &R,
    mut progress: impl FnMut(usize),
) -> Result<MethodReport> {
    let ReportInputs {
        car,
        road,
        design_box,
        objectives,
        ..
    } = inputs;
    validate(inputs)?;
    progress(0);
    let scenario = Scenario {
        car: car.clone(),
        quarter: car.quarter(),
        road: on.scenario(),
        velocity_psd: on.velocity_psd(),
        delay: road.delay(car.wheelbase()),
        static_wheel_load: car.front_wheel_load(),
        design_box: *design_box,
        objectives: objectives.clone(),
    };
    let verification = on.verify(car, inputs.seed)?;
    progress(1);
    let settings = MapSettings {
        grid: Grid::over_box(design_box, MAP_POINTS, MAP_POINTS)?,
        objectives: objectives.clone(),
        ..MapSettings::default()
    };
    let maps = Maps {
        lofi: on.map(ModelKind::Quarter, car, &settings)?,
        hifi: on.map(ModelKind::Full, car, &settings)?,
    };
    progress(2);
    let sampling = PLAN_SIZES
        .iter()
        .map(|&n| {
            let plan = audze_eglais(n, 1)?;
            let gaps = plan.gaps();
            Ok(PlanSummary {
                points: n,
                energy: plan.energy,
                optimal: plan.optimal,
                method: plan.method.clone(),
                min_gap: gaps.iter().copied().fold(f64::INFINITY, f64::min),
                gaps: gap_histogram(&gaps, 6),
                design: plan.points(design_box),
            })
        })
        .collect::<Result<Vec<_>>>()?;
    progress(3);
    let study = on.study(car, design_box)?;
    let (spec, plan, chosen_because) = match inputs.surrogate {
        Some((spec, plan)) => (spec, plan, "chosen in the view".to_string()),
        None => {
            let best = study
                .best_per_budget
                .iter()
                .find(|b| b.samples == 10)
                .ok_or_else(|| {
                    RideError::Numerical("the study fitted nothing at 10 samples".into())
                })?;
            (
                SurrogateSpec::parse(&best.surrogate)?,
                PlanSpec::parse(&best.plan)?,
                format!(
                    "the study's best at 10 HiFi samples (worst max RTE {:.3} %)",
                    best.fitted.worst_rte_max
                ),
            )
        }
    };
    let chosen = on.surrogate(spec, plan, car, design_box)?;
    let fidelity = Fidelity {
        study,
        chosen_because,
        chosen,
    };
    progress(4);
    let optimisation = optimise(inputs, on, spec, plan)?;
    progress(5);
    let adaptive = adaptive_section(inputs, on, spec, plan, &optimisation)?;
    progress(SECTIONS.len());
    Ok(MethodReport {
        version: env!("CARGO_PKG_VERSION").into(),
        scenario,
        verification,
        maps,
        sampling,
        fidelity,
        optimisation,
        adaptive,
        thesis: ThesisResult::quoted(),
    })
}

impl MethodReport {
    /// The report's title.
    pub fn title(&self) -> String {
        let s = &self.scenario;
        match &s.road {
            RoadScenario::Iso(r) => format!(
                "RideLab study report: {}, class {:?} at {} m/s",
                s.car.name, r.class, r.speed
            ),
            RoadScenario::Measured(m) => format!(
                "RideLab study report: {}, the measured road {} at {} m/s",
                s.car.name, m.file, m.speed
            ),
        }
    }
}

impl MethodReport {
    /// The report's tables as CSV files `(file name, text)`: the verification routes,
    /// the fidelity study, the before/after table and every front point.
    pub fn csv_files(&self) -> Vec<(&'static str, String)> {
        let mut verification = String::from("model,route,bacc_m_per_s2,dtl_n,sws_m,difference\n");
        for (model, rows) in [
            ("lofi", &self.verification.lofi),
            ("hifi", &self.verification.hifi),
        ] {
            for r in rows {
                verification += &format!(
                    "{model},\"{}\",{},{},{},{}\n",
                    r.route, r.criteria.bacc, r.criteria.dtl, r.criteria.sws, r.difference
                );
            }
        }
        let mut study =
            String::from("surrogate,plan,samples,status,worst_rte_max_percent,min_r2\n");
        for row in &self.fidelity.study.rows {
            let (status, rte, r2) = match &row.outcome {
                crate::study::fidelity::Outcome::Fitted(f) => {
                    ("fitted", f.worst_rte_max.to_string(), f.min_r2.to_string())
                }
                crate::study::fidelity::Outcome::Skipped { .. } => {
                    ("skipped", String::new(), String::new())
                }
            };
            study += &format!(
                "{},{},{},{status},{rte},{r2}\n",
                row.surrogate, row.plan, row.samples
            );
        }
        let mut picks =
            String::from("design,ks_n_per_m,cs_ns_per_m,bacc_percent,dtl_percent,sws_m\n");
        for p in &self.optimisation.table {
            picks += &format!(
                "\"{}\",{},{},{},{},{}\n",
                p.design, p.ks, p.cs, p.bacc_percent, p.dtl_percent, p.sws
            );
        }
        let mut fronts = String::from("front,ks_n_per_m,cs_ns_per_m,bacc_m_per_s2,dtl_n,sws_m\n");
        let o = &self.optimisation;
        for (name, rep) in [("stm", &o.stm), ("nsga2", &o.nsga2), ("hifi-stm", &o.hifi)] {
            for p in rep.iter().flat_map(|r| &r.study.front) {
                fronts += &format!("{name},{},{},{},{},{}\n", p.ks, p.cs, p.bacc, p.dtl, p.sws);
            }
        }
        vec![
            ("verification.csv", verification),
            ("study.csv", study),
            ("picks.csv", picks),
            ("fronts.csv", fronts),
        ]
    }
}

/// `max_k |a_k / b_k - 1|`.
fn max_rel(a: &Criteria, b: &Criteria) -> f64 {
    a.to_array()
        .iter()
        .zip(b.to_array())
        .map(|(x, y)| (x / y - 1.0).abs())
        .fold(0.0, f64::max)
}

fn rows(routes: Vec<(String, Criteria)>) -> Vec<RouteRow> {
    let reference = routes[0].1;
    routes
        .into_iter()
        .map(|(route, criteria)| RouteRow {
            difference: max_rel(&criteria, &reference),
            route,
            criteria,
        })
        .collect()
}

/// Section 1's checks at the datum design.
fn verify(car: &Car, road: &Road, seed: u64) -> Result<Verification> {
    let record = TimeOptions {
        duration: RECORD_S,
        dt: 1e-3,
        seed,
        f_min: 0.05,
        f_max: 250.0,
        decimate: 1000,
        damper: None,
    };
    let quarter = ModelKind::Quarter.build(car);
    let full = ModelKind::Full.build(car);
    let q = car.quarter();
    let mut lofi = Vec::new();
    if q.ct == 0.0 {
        lofi.push((
            "closed form (Gobbi and Mastinu 2001)".to_string(),
            quarter_car_rms(&q, road.intensity()),
        ));
    }
    lofi.push(("Lyapunov".into(), criteria_exact(&quarter, road)?));
    lofi.push((
        "frequency integration".into(),
        criteria_spectral(&quarter, road, 1e-8)?.criteria,
    ));
    lofi.push((
        format!("time domain, {RECORD_S} s record"),
        Criteria::from_array(simulate(ModelKind::Quarter, car, road, &record)?.rms),
    ));
    let mut hifi = Vec::new();
    let mut notes = Vec::new();
    match criteria_exact(&full, road) {
        Ok(c) => hifi.push(("Lyapunov with the delay (Kronecker)".to_string(), c)),
        Err(e) => notes.push(format!("Lyapunov with the delay does not apply: {e}")),
    }
    match criteria_modal(&full, road) {
        Ok(c) => hifi.push(("modal expansion".into(), c)),
        Err(e) => notes.push(format!("modal route does not apply: {e}")),
    }
    let spectral = criteria_spectral(&full, road, 1e-8)?;
    if let Some(fc) = spectral.low_cutoff_hz {
        notes.push(format!(
            "independent tracks of unequal widths make the road warp a random walk: the frequency route starts at ISO 8608's 0.011 cycle/m = {fc:.3} Hz"
        ));
    }
    hifi.push((
        "frequency integration, exact delay".into(),
        spectral.criteria,
    ));
    let hifi_record = TimeOptions {
        f_min: spectral.low_cutoff_hz.unwrap_or(record.f_min),
        ..record
    };
    hifi.push((
        format!("time domain, {RECORD_S} s record"),
        Criteria::from_array(simulate(ModelKind::Full, car, road, &hifi_record)?.rms),
    ));
    let comfort = comfort_rows(&quarter, &full, &lofi[0].1, &hifi[0].1, |model| {
        let spectral = bacc_wk_spectral(model, road, 1e-10)?;
        Ok((bacc_wk_exact(model, road).unwrap_or(spectral), spectral))
    })?;
    Ok(Verification {
        lofi: rows(lofi),
        hifi: rows(hifi),
        notes,
        record,
        lofi_modes: quarter.modes()?,
        hifi_modes: full.modes()?,
        frf: frfs(&quarter, &full, road)?,
        comfort,
    })
}

/// Section 1's comfort rows beside each model's first route (`lofi`, `hifi`): the
/// Wk-weighted BAcc `(exact, spectral)` that `wk` gives for the model, with Annex C's label.
fn comfort_rows(
    quarter: &LinearModel,
    full: &LinearModel,
    lofi: &Criteria,
    hifi: &Criteria,
    wk: impl Fn(&LinearModel) -> Result<(f64, f64)>,
) -> Result<Vec<ComfortRow>> {
    [("LoFi", quarter, lofi), ("HiFi", full, hifi)]
        .into_iter()
        .map(|(name, model, plain)| {
            let (exact, spectral) = wk(model)?;
            Ok(ComfortRow {
                model: name.into(),
                bacc: plain.bacc,
                exact,
                spectral,
                label: comfort_label(exact).into(),
            })
        })
        .collect()
}

/// The FRFs |H| of both models from the right track's road displacement, 0.1 to 100 Hz
/// (121 frequencies, log spaced), the rear wheels `L / v` later on `road`.
fn frfs(quarter: &LinearModel, full: &LinearModel, road: &Road) -> Result<Frf> {
    let f: Vec<f64> = (0..121)
        .map(|i| 0.1 * math::powf(1000f64, i as f64 / 120.0))
        .collect();
    let frf = |model: &LinearModel| -> Result<[Vec<f64>; 3]> {
        let sp = Spectrum::new(model, road)?;
        let mut out: [Vec<f64>; 3] = Default::default();
        for &fi in &f {
            let h = sp.displacement_transfer(0, 2.0 * std::f64::consts::PI * fi);
            for k in 0..3 {
                out[k].push(math::cabs(h[k]));
            }
        }
        Ok(out)
    };
    Ok(Frf {
        lofi: frf(quarter)?,
        hifi: frf(full)?,
        f,
    })
}

/// Section 6: the surrogate on an Audze-Eglais plan of `ceil(n / 2)` points plus
/// `floor(n / 2)` adaptive HiFi runs (EHVI over the feasible front, the loop's defaults),
/// `n` the points of section 5's plan, compared with section 5's STM pick. Skipped, with
/// the reason, when section 5 has no front or the loop cannot run on so few points.
fn adaptive_section(
    inputs: &ReportInputs,
    on: &impl SectionRoad,
    spec: SurrogateSpec,
    plan: PlanSpec,
    o: &Optimisation,
) -> Result<AdaptiveSection> {
    let skipped = |why: String| AdaptiveSection {
        skipped: Some(why),
        run: None,
        comparison: Vec::new(),
    };
    let (Some(stm), None) = (&o.stm, &o.infeasible) else {
        return Ok(skipped(
            "section 5 found no feasible design, so there is no front to improve".into(),
        ));
    };
    let n = plan.plan()?.levels.len();
    let initial = n.div_ceil(2);
    let options = AdaptiveOptions {
        runs: n - initial,
        seed: inputs.seed,
        ..AdaptiveOptions::default()
    };
    let request = OptimizeRequest {
        evaluator: EvaluatorSpec::Surrogate(spec),
        plan: PlanSpec::AudzeEglais(initial),
        ..OptimizeRequest::new(
            &inputs.car,
            &inputs.road,
            inputs.design_box,
            Method::Stm(StmParams::default()),
            inputs.objectives.clone(),
        )
    };
    let run = match on.adaptive(&request, options) {
        Ok(r) => r,
        Err(RideError::Field { field, reason }) => {
            return Ok(skipped(format!(
                "{} on ae:{initial} + {} adaptive runs: {field}: {reason}",
                spec.name(),
                options.runs
            )))
        }
        Err(e) => return Err(e),
    };
    let row = |samples: String, hifi_runs: usize, r: &OptimizeReport| {
        let c = &r.hifi_recheck;
        AdaptiveRow {
            samples,
            hifi_runs,
            ks: r.study.pick.ks,
            cs: r.study.pick.cs,
            error_percent: c.error_percent,
            rechecked_change_percent: [
                c.rechecked_change_percent[0],
                c.rechecked_change_percent[1],
            ],
        }
    };
    let comparison = vec![
        row(format!("{} (section 5)", plan.name()), n, stm),
        row(
            format!("ae:{initial} + {} adaptive", options.runs),
            n,
            &run.optimize,
        ),
    ];
    Ok(AdaptiveSection {
        skipped: None,
        run: Some(run),
        comparison,
    })
}

/// Section 5: the fronts on the surrogate and on the HiFi, or why there are none.
fn optimise(
    inputs: &ReportInputs,
    on: &impl SectionRoad,
    spec: SurrogateSpec,
    plan: PlanSpec,
) -> Result<Optimisation> {
    let run = |evaluator: EvaluatorSpec, method: &Method| {
        on.optimize(&OptimizeRequest {
            evaluator,
            plan,
            ..OptimizeRequest::new(
                &inputs.car,
                &inputs.road,
                inputs.design_box,
                method.clone(),
                inputs.objectives.clone(),
            )
        })
    };
    let stm = Method::Stm(StmParams::default());
    let nsga2 = Method::Nsga2(Nsga2Params {
        seed: inputs.seed,
        ..Nsga2Params::default()
    });
    let surrogate = EvaluatorSpec::Surrogate(spec);
    let stm_front = match run(surrogate, &stm) {
        Ok(r) => r,
        Err(RideError::Infeasible { field, reason }) => {
            return Ok(Optimisation {
                infeasible: Some(format!("{field}: {reason}")),
                stm: None,
                nsga2: None,
                hifi: None,
                stm_to_hifi: None,
                table: Vec::new(),
                picks: Vec::new(),
            })
        }
        Err(e) => return Err(e),
    };
    let nsga2_front = run(surrogate, &nsga2)?;
    let hifi_front = run(EvaluatorSpec::Model(ModelKind::Full), &stm)?;
    let points = |r: &OptimizeReport| -> Vec<[f64; 2]> {
        r.study.front.iter().map(|p| [p.bacc, p.dtl]).collect()
    };
    let stm_to_hifi = front_distance(&points(&stm_front), &points(&hifi_front));
    let hifi = on.hifi(&inputs.car)?;
    let datum = hifi.evaluate(inputs.car.front.spring, inputs.car.front.damper)?;
    let mut table = vec![PickRow {
        design: "datum".into(),
        ks: inputs.car.front.spring,
        cs: inputs.car.front.damper,
        bacc_percent: 0.0,
        dtl_percent: 0.0,
        sws: datum.sws,
    }];
    for (name, r) in [
        ("STM", &stm_front),
        ("NSGA-II", &nsga2_front),
        ("HiFi STM", &hifi_front),
    ] {
        let p = &r.study.pick;
        table.push(PickRow {
            design: format!("{name} min-max pick ({})", r.study.evaluator),
            ks: p.ks,
            cs: p.cs,
            bacc_percent: p.change_percent[0],
            dtl_percent: p.change_percent[1],
            sws: p.criteria.sws,
        });
        if name != "HiFi STM" {
            let c = &r.hifi_recheck;
            table.push(PickRow {
                design: format!("{name} pick re-checked on the HiFi"),
                ks: p.ks,
                cs: p.cs,
                bacc_percent: c.rechecked_change_percent[0],
                dtl_percent: c.rechecked_change_percent[1],
                sws: c.rechecked.sws,
            });
        }
    }
    let picks = PICK_RULES
        .iter()
        .map(|&rule| {
            let mut r = stm_front.clone();
            on.repick(&mut r, rule, &inputs.car, &inputs.design_box)?;
            let (p, c) = (&r.study.pick, &r.hifi_recheck);
            Ok(RulePick {
                rule: p.rule.clone(),
                ks: p.ks,
                cs: p.cs,
                pseudo_weights: p.pseudo_weights,
                predicted_change_percent: [p.change_percent[0], p.change_percent[1]],
                rechecked_change_percent: [
                    c.rechecked_change_percent[0],
                    c.rechecked_change_percent[1],
                ],
                error_percent: c.error_percent,
            })
        })
        .collect::<Result<Vec<_>>>()?;
    Ok(Optimisation {
        infeasible: None,
        picks,
        stm: Some(stm_front),
        nsga2: Some(nsga2_front),
        hifi: Some(hifi_front),
        stm_to_hifi: Some(stm_to_hifi),
        table,
    })
}
