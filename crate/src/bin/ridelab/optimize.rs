//! `ridelab optimize`: the front, its pick and the pick's HiFi re-check.

use crate::args::{
    car_loads_road_of, count, count_u64, json, svg_target, warning_lines, write_svg, AdaptiveArgs,
    BoxArgs, CarRoad, CasesArgs, ObjectiveArgs,
};
use crate::road::{measured_model, one_scenario};
use clap::Args;
use ridelab::analysis::ModelKind;
use ridelab::car::Car;
use ridelab::chart::{front_chart, line_chart_svg};
use ridelab::comfort::Comfort;
use ridelab::design::DesignBox;
use ridelab::dos::DesignObjectives;
use ridelab::error::{Result, RideError};
use ridelab::gpu::{Compute, ComputePath};
use ridelab::optimize::{Method, Nsga2Params, PickRule, StmParams};
use ridelab::road::Road;
use ridelab::road_profile::RoadScenario;
use ridelab::robust::LoadCase;
use ridelab::study::adaptive;
use ridelab::study::measured::{check_measured_request, optimize_measured};
use ridelab::study::RobustOptimizeReport;
use ridelab::study::{EvaluatorSpec, OptimizeReport, OptimizeRequest};
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
    let (car, loads, road) = car_loads_road_of(&a.car)?;
    let objectives = a.objectives.objectives()?;
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
    let design_box = a.design_box.design_box()?;
    if let Some(path) = a.car.road.as_deref() {
        return measured_optimize(&a, &car, &loads, &design_box, &method, objectives, path);
    }
    let set = a.cases.set(&car, &loads, &road)?;
    if let Some(set) = set {
        if a.compute == Some(Compute::Gpu) {
            return Err(RideError::field(
                "compute",
                "gpu: the robust design's cases are evaluated on the CPU; use --compute cpu or auto",
            ));
        }
        if a.adaptive.adaptive.is_some() {
            return Err(RideError::field(
                "adaptive",
                "the adaptive loop runs on one case: leave out --cases (and the car file's load_cases)",
            ));
        }
        let out = OptimizeRequest {
            evaluator: a.evaluator,
            plan: a.plan,
            comfort: a.comfort,
            pick: a.pick,
            ..OptimizeRequest::new(&car, &road, design_box, method, objectives)
        }
        .run_robust(&set)?;
        if let Some(path) = &svg {
            ridelab::finite::check(&out)?;
            let mut chart = front_chart(&out.study, &out.datum, Some(&out.hifi_recheck));
            chart.title = format!("Robust {}", chart.title);
            if out.comfort == Comfort::Wk {
                chart.title = chart.title.replacen("BAcc", out.comfort.label(), 1);
                chart.x_label = format!("{} [m/s^2]", out.comfort.label());
            }
            write_svg(path, &line_chart_svg(&chart)?)?;
        }
        return if a.json {
            json(&out)
        } else {
            Ok(robust_optimize_text(&out))
        };
    }
    let request = OptimizeRequest {
        evaluator: a.evaluator,
        plan: a.plan,
        comfort: a.comfort,
        compute: a.compute,
        pick: a.pick,
        ..OptimizeRequest::new(&car, &road, design_box, method, objectives)
    };
    let (mut out, looped) = match a.adaptive.options() {
        None => (request.run()?, None),
        Some(_) if a.compute == Some(Compute::Gpu) => {
            return Err(RideError::field(
                "compute",
                "gpu: the adaptive loop's HiFi runs are single designs on the CPU; use --compute cpu or auto",
            ))
        }
        Some(_) if a.comfort == Comfort::Wk => {
            return Err(RideError::field(
                "comfort",
                "wk needs --evaluator quarter or full: the adaptive loop's surrogates are fitted to the unweighted BAcc",
            ))
        }
        Some(options) => {
            let r = request.run_adaptive(options)?;
            let mut out = r.optimize;
            out.compute = a.compute.map(|_| ComputePath::Cpu);
            (out, Some(r.adaptive))
        }
    };
    if looped.is_some() && a.pick != PickRule::MinMax {
        out.repick(a.pick, &car, &road, &design_box)?;
    }
    if let Some(path) = &svg {
        write_front_svg(path, &out)?;
    }
    if let Some(looped) = looped {
        let report = adaptive::AdaptiveOptimizeReport {
            optimize: out,
            adaptive: looped,
        };
        if a.json {
            return json(&report);
        }
        return Ok(optimize_text(&report.optimize) + &adaptive_text(&report.adaptive));
    }
    if a.json {
        return json(&out);
    }
    Ok(optimize_text(&out))
}

/// The front in the BAcc-DTL plane as an SVG file.
fn write_front_svg(path: &Path, out: &OptimizeReport) -> Result<()> {
    ridelab::finite::check(out)?;
    let mut chart = front_chart(&out.study, &out.datum, Some(&out.hifi_recheck));
    if out.comfort == Comfort::Wk {
        chart.title = chart.title.replacen("BAcc", out.comfort.label(), 1);
        chart.x_label = format!("{} [m/s^2]", out.comfort.label());
    }
    write_svg(path, &line_chart_svg(&chart)?)
}

/// `optimize --road FILE`: the front of the LoFi, the HiFi or a surrogate on the measured
/// road (the models by the exact route at every design; a surrogate fitted to the HiFi's
/// samples there, its LoFi the quarter car there), the datum and the pick's re-check on
/// its HiFi; with `--adaptive K` the surrogate is the adaptive loop's on this road. One
/// scenario: `--cases` (and a car file's load_cases) and `--compute gpu` are refused
/// naming them, `--adaptive` with a model evaluator and `--comfort wk` with a surrogate
/// (as on an ISO class). A run costs more here (the residue route with the road's
/// filters: the default STM on the HiFi, 48 517 runs, took 0.17 s on the shipped slab
/// road), so the work is bounded by [`ridelab::budget::MAX_MEASURED_RUNS`] runs
/// (`grid^2 + 12 (grid - 1) 2^levels` for STM, `population (generations + 1)` for
/// NSGA-II, plus the loop's plan and added HiFi runs).
fn measured_optimize(
    a: &OptimizeArgs,
    car: &Car,
    loads: &[LoadCase],
    design_box: &DesignBox,
    method: &Method,
    objectives: DesignObjectives,
    path: &str,
) -> Result<String> {
    one_scenario(
        a.cases.cases.is_some() || !loads.is_empty(),
        a.compute == Some(Compute::Gpu),
    )?;
    let looped = a.adaptive.options();
    check_measured_request(a.evaluator, a.comfort, looped.is_some())?;
    // The optimisation's runs, and the loop's HiFi runs (its plan and added runs).
    let plan_runs = match looped {
        Some(o) => a.plan.plan()?.points(design_box).len() as u64 + o.runs as u64,
        None => 0,
    };
    let runs = match method {
        Method::Stm(p) => ridelab::budget::stm_runs(p.grid, p.levels),
        Method::Nsga2(p) => (p.population as u64).saturating_mul(p.generations as u64 + 1),
    }
    .saturating_add(plan_runs);
    let (field, options) = match method {
        Method::Stm(_) => ("grid", "--grid or --levels"),
        Method::Nsga2(_) => ("generations", "--generations or --population"),
    };
    ridelab::budget::check_measured(runs, field, "this optimisation", options)?;
    let (hifi, about) = measured_model(ModelKind::Full, car, &a.car, path, a.comfort)?;
    // The request's ISO road is not used: the models are on the measured one.
    let unused = Road::default();
    let request = OptimizeRequest {
        evaluator: a.evaluator,
        plan: a.plan,
        comfort: a.comfort,
        ..OptimizeRequest::new(car, &unused, *design_box, method.clone(), objectives)
    };
    let (mut out, report) = optimize_measured(&request, &hifi, looped)?;
    out.compute = a.compute.map(|_| ComputePath::Cpu);
    if a.pick != PickRule::MinMax {
        out.repick_on(a.pick, &hifi, design_box)?;
    }
    if let Some(p) = svg_target(a.svg.as_deref())? {
        write_front_svg(&p, &out)?;
    }
    let loop_text = report.as_ref().map(adaptive_text).unwrap_or_default();
    if a.json {
        let mut v = match report {
            None => to_value(&out)?,
            Some(adaptive) => to_value(&adaptive::AdaptiveOptimizeReport {
                optimize: out,
                adaptive,
            })?,
        };
        v["road"] = to_value(&about)?;
        return json(&v);
    }
    Ok(format!(
        "on {}\n{}{loop_text}",
        crate::text::scenario_words(&RoadScenario::Measured(about)),
        optimize_text(&out)
    ))
}

/// `v` as a JSON value (to add the measured road to a report).
fn to_value<T: serde::Serialize>(v: &T) -> Result<serde_json::Value> {
    serde_json::to_value(v).map_err(|e| RideError::Numerical(e.to_string()))
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
