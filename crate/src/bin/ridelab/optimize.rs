//! `ridelab optimize`: the front, its pick and the pick's HiFi re-check.

use crate::args::{
    count, count_u64, json, study_of, svg_target, warning_lines, write_svg, AdaptiveArgs, BoxArgs,
    CarRoad, CasesArgs, ObjectiveArgs,
};
use clap::Args;
use ridelab::chart::{front_chart, line_chart_svg};
use ridelab::comfort::Comfort;
use ridelab::error::Result;
use ridelab::gpu::{Compute, ComputePath};
use ridelab::optimize::{Method, Nsga2Params, PickRule, StmParams};
use ridelab::road_profile::RoadScenario;
use ridelab::study::adaptive;
use ridelab::study::RobustOptimizeReport;
use ridelab::study::{EvaluatorSpec, FrontAsk, FrontReport, OptimizeReport, StudySpec};
use ridelab::surrogate::PlanSpec;
use std::path::Path;

#[derive(Args)]
pub(crate) struct OptimizeArgs {
    /// quarter, full or a surrogate name (see `ridelab surrogate`).
    #[arg(long, default_value = "full")]
    pub(crate) evaluator: EvaluatorSpec,
    /// The surrogate's HiFi sampling plan: ae:N or grid:n.
    #[arg(long, default_value = "ae:10")]
    pub(crate) plan: PlanSpec,
    /// stm (space transformation) or nsga2.
    #[arg(long, default_value = "stm", value_parser = ["stm", "nsga2"])]
    pub(crate) method: String,
    #[command(flatten)]
    pub(crate) design_box: BoxArgs,
    #[command(flatten)]
    pub(crate) objectives: ObjectiveArgs,
    /// The pick: minmax (the thesis's), knee, or asf:W (weighted, comfort weight W in 0..1).
    #[arg(long, default_value = "minmax")]
    pub(crate) pick: PickRule,
    /// The comfort objective: bacc (RMS body acceleration) or wk (ISO 2631-1
    /// Wk-weighted), m/s^2; wk needs --evaluator quarter or full.
    #[arg(long, default_value = "bacc")]
    pub(crate) comfort: Comfort,
    /// STM grid points per variable, 2..2001; the work is bounded too: grid^2 +
    /// 12 (grid - 1) 2^levels model runs (times the cases) at most 4 000 000, so at
    /// --levels 3 the largest grid is 1952.
    #[arg(long, default_value_t = StmParams::default().grid, value_parser = count, allow_negative_numbers = true)]
    pub(crate) grid: usize,
    /// Where STM's grid on the full car is evaluated: gpu, cpu, or auto (a hardware GPU
    /// when there is one, else the CPU) [default: auto]; given, the JSON's `compute` says
    /// which ran.
    #[arg(long)]
    pub(crate) compute: Option<Compute>,
    /// STM refinement levels, 0..10 (the page's objective plane: --grid 61 --levels 2).
    #[arg(long, default_value_t = StmParams::default().levels, value_parser = count, allow_negative_numbers = true)]
    pub(crate) levels: usize,
    /// NSGA-II population, an even number 4..10000.
    #[arg(long, default_value_t = Nsga2Params::default().population, value_parser = count, allow_negative_numbers = true)]
    pub(crate) population: usize,
    /// NSGA-II generations, 1..10000.
    #[arg(long, default_value_t = Nsga2Params::default().generations, value_parser = count, allow_negative_numbers = true)]
    pub(crate) generations: usize,
    /// NSGA-II seed.
    #[arg(long, default_value_t = Nsga2Params::default().seed, value_parser = count_u64, allow_negative_numbers = true)]
    pub(crate) seed: u64,
    #[command(flatten)]
    pub(crate) adaptive: AdaptiveArgs,
    #[command(flatten)]
    pub(crate) car: CarRoad,
    #[command(flatten)]
    pub(crate) cases: CasesArgs,
    /// The front, pick and re-check as JSON (SI units, with a `units` object) instead of
    /// the text summary.
    #[arg(long)]
    pub(crate) json: bool,
    /// Also write the front in the BAcc-DTL plane as an SVG file.
    #[arg(long, value_name = "FILE")]
    pub(crate) svg: Option<String>,
}

pub(crate) fn optimize(a: OptimizeArgs) -> Result<String> {
    let svg = svg_target(a.svg.as_deref())?;
    let base = study_of(&a.car, Some(&a.cases))?;
    let method = if a.method == "stm" {
        Method::Stm(StmParams {
            grid: a.grid,
            levels: a.levels,
        })
    } else {
        Method::Nsga2(Nsga2Params {
            population: a.population,
            generations: a.generations,
            seed: a.seed,
            ..Nsga2Params::default()
        })
    };
    let objectives = a.objectives.objectives()?;
    let study = StudySpec {
        design_box: a.design_box.design_box()?,
        objectives,
        comfort: a.comfort,
        compute: a.compute,
        ..base
    };
    let out = study.front(&FrontAsk {
        evaluator: a.evaluator,
        plan: a.plan,
        method,
        pick: a.pick,
        adaptive: a.adaptive.options(),
    })?;
    if let Some(path) = &svg {
        write_front_svg(path, &out.front)?;
    }
    if a.json {
        return json(&out);
    }
    let text = match &out.front {
        FrontReport::One(r) => optimize_text(r),
        FrontReport::Adaptive(r) => optimize_text(&r.optimize) + &adaptive_text(&r.adaptive),
        FrontReport::Robust(r) => robust_optimize_text(r),
    };
    Ok(match &out.road {
        None => text,
        Some(about) => format!(
            "on {}\n{text}",
            crate::text::scenario_words(&RoadScenario::Measured(about.clone()))
        ),
    })
}

/// The front in the BAcc-DTL plane as an SVG file ("Robust ..." over cases).
fn write_front_svg(path: &Path, front: &FrontReport) -> Result<()> {
    ridelab::finite::check(front)?;
    let (study, datum, recheck, comfort) = match front {
        FrontReport::One(r) => (&r.study, &r.datum, &r.hifi_recheck, r.comfort),
        FrontReport::Adaptive(r) => {
            let r = &r.optimize;
            (&r.study, &r.datum, &r.hifi_recheck, r.comfort)
        }
        FrontReport::Robust(r) => (&r.study, &r.datum, &r.hifi_recheck, r.comfort),
    };
    let mut chart = front_chart(study, datum, Some(recheck));
    if let FrontReport::Robust(_) = front {
        chart.title = format!("Robust {}", chart.title);
    }
    if comfort == Comfort::Wk {
        chart.title = chart.title.replacen("BAcc", comfort.label(), 1);
        chart.x_label = format!("{} [m/s^2]", comfort.label());
    }
    write_svg(path, &line_chart_svg(&chart)?)
}

/// The loop's added runs, one line each.
pub(crate) fn adaptive_text(r: &adaptive::AdaptiveReport) -> String {
    let mut s = format!(
        "adaptive: {} + {} HiFi runs ({}, {} uncertainty)\n",
        r.plan,
        r.added.len(),
        r.options.criterion.name(),
        r.uncertainty.name()
    );
    for a in &r.added {
        s += &format!(
            "  run {:>3}: Ks {:.1} N/m, Cs {:.1} N s/m: {}\n",
            a.run, a.sample.ks, a.sample.cs, a.reason
        );
    }
    if let Some(why) = &r.stopped {
        s += &format!("  {why}\n");
    }
    s
}

pub(crate) fn optimize_text(out: &OptimizeReport) -> String {
    let (study, check) = (&out.study, &out.hifi_recheck);
    let p = &study.pick;
    let bacc = out.comfort.label();
    let mut text = format!(
        "front: {} point{} on {} ({} evaluations), hypervolume {:.4} (m/s^2) N against [{:.4}, {:.2}]\n\
         {} pick: Ks {:.1} N/m, Cs {:.1} N s/m (pseudo-weights comfort {:.2}, road holding {:.2})\n{}  \
         {bacc} {:+.2} %, DTL {:+.2} %, SWS {:+.2} % against the datum's HiFi criteria{}\n\
         HiFi re-check: {bacc} {:+.2} %, DTL {:+.2} %, SWS {:+.2} % (prediction error {:.3} / {:.3} / {:.3} %)\n",
        study.front.len(),
        if study.front.len() == 1 { "" } else { "s" },
        study.evaluator,
        study.evaluations,
        study.hypervolume,
        study.reference_point[0],
        study.reference_point[1],
        p.rule,
        p.ks,
        p.cs,
        p.pseudo_weights[0],
        p.pseudo_weights[1],
        match &out.same_model {
            Some(m) => format!(
                "  {bacc} {:+.2} %, DTL {:+.2} %, SWS {:+.2} % against the datum on the same model ({}: like with like)\n",
                m.change_percent[0], m.change_percent[1], m.change_percent[2], study.evaluator
            ),
            None => String::new(),
        },
        p.change_percent[0],
        p.change_percent[1],
        p.change_percent[2],
        if out.same_model.is_some() { format!(" (includes the {} model's bias)", study.evaluator) } else { String::new() },
        check.rechecked_change_percent[0],
        check.rechecked_change_percent[1],
        check.rechecked_change_percent[2],
        check.error_percent[0],
        check.error_percent[1],
        check.error_percent[2],
    );
    text += &warning_lines(&out.warnings);
    match (out.compute, &out.adapter) {
        (Some(ComputePath::Gpu), Some(a)) => text += &format!("compute: gpu ({a})\n"),
        (Some(ComputePath::Gpu), None) => text += "compute: gpu\n",
        (Some(ComputePath::Cpu), _) => text += "compute: cpu\n",
        (None, _) => {}
    }
    text
}

/// The robust optimisation: the front and pick as [`optimize_text`], then each case.
pub(crate) fn robust_optimize_text(out: &RobustOptimizeReport) -> String {
    let single = OptimizeReport {
        study: out.study.clone(),
        datum: out.datum,
        hifi_recheck: out.hifi_recheck.clone(),
        comfort: out.comfort,
        compute: None,
        adapter: None,
        warnings: out.warnings.clone(),
        same_model: None,
    };
    let bacc = out.comfort.label();
    let mut s = format!(
        "robust over {} cases ({:?}; each case against its own datum, scaled to case 0's)\n",
        out.cases.len(),
        out.combine
    );
    s += &optimize_text(&single);
    for c in &out.cases {
        let (p, h) = (
            &c.hifi_recheck.predicted_change_percent,
            &c.hifi_recheck.rechecked_change_percent,
        );
        s += &format!(
            "  case {} {}: {bacc} {:+.2} %, DTL {:+.2} %, SWS {:+.2} %; HiFi {bacc} {:+.2} %, DTL {:+.2} %, SWS {:+.2} %{}\n",
            c.case.index,
            c.case.name,
            p[0],
            p[1],
            p[2],
            h[0],
            h[1],
            h[2],
            if c.broken.is_empty() {
                String::new()
            } else {
                let b: Vec<&str> = c.broken.iter().map(|o| o.label()).collect();
                format!(" (HiFi breaks {})", b.join(", "))
            }
        );
    }
    s
}
