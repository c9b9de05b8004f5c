//! `ridelab`: the command-line shell over the RideLab core (scripting, batch studies,
//! reports). Argument parsing (clap's derive API, with the core's types parsed by their
//! `FromStr`) and printing only; every number and every rule comes from the library.
//!
//! Every bad input gives exactly one line on stderr, `error: <option>: <reason>`, naming
//! the option at fault (the same messages as the page), and exit code 2.

use clap::error::{ContextKind, ContextValue, ErrorKind};
use clap::{Args, Parser, Subcommand};
use ridelab::analysis::{report, ModelKind, Report};
use ridelab::car::Car;
use ridelab::chart::{front_chart, line_chart_svg, map_chart_svg, map_report_charts};
use ridelab::comfort::Comfort;
use ridelab::design::DesignBox;
use ridelab::doe::doe_report;
use ridelab::dos::DesignObjectives;
use ridelab::error::{Result, RideError};
use ridelab::gpu::{Compute, ComputePath};
use ridelab::maps::{map_csv, map_report_on, Axis, Grid, MapSettings, Scale};
use ridelab::optimize::{
    optimize_report_on, EvaluatorSpec, Method, Nsga2Params, OptimizeReport, PickRule, StmParams,
    Warning,
};
use ridelab::report::{build, ReportInputs, SECTIONS};
use ridelab::road::{Road, RoadClass, Tracks};
use ridelab::robust::{
    case_map_report, robust_map_report, robust_optimize_report, CarFile, CaseSet, Combine,
    LoadCase, RobustOptimizeReport,
};
use ridelab::surrogate::adaptive::{
    self, adaptive_study, AdaptiveOptions, StudyOptions, DEFAULT_CANDIDATES, DEFAULT_MIN_DISTANCE,
};
use ridelab::surrogate::infill::Infill;
use ridelab::surrogate::uncertainty::UncertaintyMethod;
use ridelab::surrogate::{study, surrogate_report_in, PlanSpec, SurrogateSpec};
use ridelab::time_domain::{simulate, Damper, Knee, TimeOptions, TimeResponse};
use std::path::{Path, PathBuf};

/// Surrogate-based suspension design: ride criteria, design maps, sampling plans,
/// surrogates and Pareto fronts of a passenger car's front suspension.
#[derive(Parser)]
#[command(name = "ridelab", version, disable_help_subcommand = true)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// BAcc, DTL and SWS of one design by both routes, modes and ride properties.
    Eval(EvalArgs),
    /// An Audze-Eglais sampling plan in the default design box.
    Doe(DoeArgs),
    /// The Pareto front of BAcc and DTL, its min-max pick and the pick's HiFi re-check.
    Optimize(OptimizeArgs),
    /// The design criteria and objective maps over a Ks x Cs grid.
    Map(MapArgs),
    /// A surrogate fitted to HiFi samples and validated on a HiFi grid.
    Surrogate(SurrogateArgs),
    /// The fidelity study: every surrogate on every plan against the HiFi.
    Study(StudyArgs),
    /// A time response on a seeded road realisation.
    Simulate(SimulateArgs),
    /// The shipped cars with their literature sources.
    Presets(PresetsArgs),
    /// The study report: the method end to end as one HTML file, its Markdown twin,
    /// the figures as SVG and the data as JSON and CSV.
    Report(ReportArgs),
}

/// The car, the road and the front design.
#[derive(Args)]
struct CarRoad {
    /// A car file (JSON) or a preset name: sedan (the datum), compact, suv.
    #[arg(long, value_name = "FILE|PRESET")]
    car: Option<String>,
    /// ISO 8608 road class A..H [default: B].
    #[arg(long)]
    class: Option<RoadClass>,
    /// Speed, m/s [default: 20].
    #[arg(long, value_name = "M/S", value_parser = number, allow_negative_numbers = true)]
    speed: Option<f64>,
    /// Left and right tracks: correlated or independent [default: correlated].
    #[arg(long)]
    tracks: Option<Tracks>,
    /// Front spring rate, N/m [default: the car's].
    #[arg(long, value_name = "N/M", value_parser = number, allow_negative_numbers = true)]
    ks: Option<f64>,
    /// Front damper rate, N s/m [default: the car's].
    #[arg(long, value_name = "NS/M", value_parser = number, allow_negative_numbers = true)]
    cs: Option<f64>,
}

#[derive(Args)]
struct EvalArgs {
    /// quarter (LoFi) or full (HiFi).
    #[arg(long)]
    model: ModelKind,
    #[command(flatten)]
    car: CarRoad,
    /// Machine-readable output (JSON).
    #[arg(long)]
    json: bool,
}

#[derive(Args)]
struct DoeArgs {
    /// Number of points, 2..1000.
    #[arg(long, value_parser = count, allow_negative_numbers = true)]
    points: usize,
    /// Seed of the annealing (plans beyond the stored optima).
    #[arg(long, default_value_t = 1, value_parser = count_u64, allow_negative_numbers = true)]
    seed: u64,
    /// Machine-readable output (JSON).
    #[arg(long)]
    json: bool,
}

#[derive(Args)]
struct OptimizeArgs {
    /// quarter, full or a surrogate name (see `ridelab surrogate`).
    #[arg(long, default_value = "full")]
    evaluator: EvaluatorSpec,
    /// The surrogate's HiFi sampling plan: ae:N or grid:n.
    #[arg(long, default_value = "ae:10")]
    plan: PlanSpec,
    /// stm (space transformation) or nsga2.
    #[arg(long, default_value = "stm", value_parser = ["stm", "nsga2"])]
    method: String,
    #[command(flatten)]
    design_box: BoxArgs,
    #[command(flatten)]
    objectives: ObjectiveArgs,
    /// The pick: minmax (the thesis's), knee, or asf:W (weighted, comfort weight W in 0..1).
    #[arg(long, default_value = "minmax")]
    pick: PickRule,
    /// The comfort objective: bacc (RMS body acceleration) or wk (ISO 2631-1
    /// Wk-weighted), m/s^2; wk needs --evaluator quarter or full.
    #[arg(long, default_value = "bacc")]
    comfort: Comfort,
    /// STM grid points per variable, 2..2001.
    #[arg(long, default_value_t = StmParams::default().grid, value_parser = count, allow_negative_numbers = true)]
    grid: usize,
    /// Where STM's grid on the full car is evaluated: gpu, cpu, or auto (a hardware GPU
    /// when there is one, else the CPU) [default: auto]; given, the JSON's `compute` says
    /// which ran.
    #[arg(long)]
    compute: Option<Compute>,
    /// STM refinement levels, 0..10 (the page's objective plane: --grid 61 --levels 2).
    #[arg(long, default_value_t = StmParams::default().levels, value_parser = count, allow_negative_numbers = true)]
    levels: usize,
    /// NSGA-II population, an even number 4..10000.
    #[arg(long, default_value_t = Nsga2Params::default().population, value_parser = count, allow_negative_numbers = true)]
    population: usize,
    /// NSGA-II generations, 1..10000.
    #[arg(long, default_value_t = Nsga2Params::default().generations, value_parser = count, allow_negative_numbers = true)]
    generations: usize,
    /// NSGA-II seed.
    #[arg(long, default_value_t = Nsga2Params::default().seed, value_parser = count_u64, allow_negative_numbers = true)]
    seed: u64,
    #[command(flatten)]
    adaptive: AdaptiveArgs,
    #[command(flatten)]
    car: CarRoad,
    #[command(flatten)]
    cases: CasesArgs,
    /// Machine-readable output (JSON).
    #[arg(long)]
    json: bool,
    /// Also write the front in the BAcc-DTL plane as an SVG file.
    #[arg(long, value_name = "FILE")]
    svg: Option<String>,
}

#[derive(Args)]
struct MapArgs {
    /// quarter (LoFi) or full (HiFi).
    #[arg(long)]
    model: ModelKind,
    /// Ks axis, min:max:points (N/m).
    #[arg(long, default_value = "10000:40000:41", allow_hyphen_values = true, value_parser = |s: &str| Axis::parse("ks-range", s))]
    ks_range: Axis,
    /// Cs axis, min:max:points (N s/m).
    #[arg(long, default_value = "500:4000:41", allow_hyphen_values = true, value_parser = |s: &str| Axis::parse("cs-range", s))]
    cs_range: Axis,
    /// Criteria relative to the datum car's.
    #[arg(long)]
    relative: bool,
    /// The comfort field: bacc (RMS body acceleration) or wk (ISO 2631-1 Wk-weighted),
    /// m/s^2; the JSON's `comfort` says "wk" when it is weighted.
    #[arg(long, default_value = "bacc")]
    comfort: Comfort,
    /// Where the HiFi map is computed: gpu, cpu, or auto (a hardware GPU when there is
    /// one, else the CPU); the JSON's `compute` says which ran.
    #[arg(long, default_value = "auto")]
    compute: Compute,
    #[command(flatten)]
    car: CarRoad,
    #[command(flatten)]
    cases: CasesArgs,
    /// The map of case K alone (its loaded car on its road, its own datum) instead of
    /// the robust map; cases are numbered load-case-major from 0.
    #[arg(long, value_name = "K", value_parser = count, allow_negative_numbers = true)]
    case: Option<usize>,
    /// Machine-readable output (JSON).
    #[arg(long, conflicts_with = "csv")]
    json: bool,
    /// One row per grid point (CSV) instead of the text summary.
    #[arg(long)]
    csv: bool,
    /// Also write PREFIX-bacc.svg, PREFIX-dtl.svg and PREFIX-sws.svg.
    #[arg(long, value_name = "PREFIX")]
    svg: Option<String>,
    #[command(flatten)]
    objectives: ObjectiveArgs,
}

/// The cases of a robust design (issue #16), map and optimize.
#[derive(Args)]
struct CasesArgs {
    /// A cases file (JSON): load cases, operating points (class, speed, weight) and
    /// combine (worst or mean); the design is then robust over every case. A car file
    /// that lists load_cases makes it robust over them too.
    #[arg(long, value_name = "FILE")]
    cases: Option<String>,
}

impl CasesArgs {
    /// The case set when there is more than the car as given: `--cases`, or the car
    /// file's load cases at `--class`/`--speed`.
    fn set(&self, car: &Car, loads: &[LoadCase], road: &Road) -> Result<Option<CaseSet>> {
        match self.cases.as_deref() {
            Some(path) => {
                let text = std::fs::read_to_string(path)
                    .map_err(|e| RideError::field("cases", format!("cannot read '{path}': {e}")))?;
                CaseSet::from_json(&text, car, loads, road).map(Some)
            }
            None if loads.is_empty() => Ok(None),
            None => CaseSet::new(car, road, loads, &[], Combine::Worst).map(Some),
        }
    }
}

/// The design box (optimize, surrogate, report).
#[derive(Args)]
struct BoxArgs {
    /// Ks range of the design box, min:max (N/m).
    #[arg(long, value_name = "MIN:MAX", default_value = "10000:40000", allow_hyphen_values = true, value_parser = |s: &str| DesignBox::parse_range("ks-range", s))]
    ks_range: (f64, f64),
    /// Cs range of the design box, min:max (N s/m).
    #[arg(long, value_name = "MIN:MAX", default_value = "500:4000", allow_hyphen_values = true, value_parser = |s: &str| DesignBox::parse_range("cs-range", s))]
    cs_range: (f64, f64),
}

impl BoxArgs {
    /// The box, checked against the domain (errors name `ks-range` or `cs-range`).
    fn design_box(&self) -> Result<DesignBox> {
        let b = DesignBox {
            ks_min: self.ks_range.0,
            ks_max: self.ks_range.1,
            cs_min: self.cs_range.0,
            cs_max: self.cs_range.1,
        };
        b.validate()?;
        Ok(b)
    }
}

/// Design objectives beyond the defaults (optimize, report, map).
#[derive(Args)]
struct ObjectiveArgs {
    /// RMS SWS limit, m [default: 0.007].
    #[arg(long, value_name = "M", value_parser = number, allow_negative_numbers = true)]
    sws_limit: Option<f64>,
    /// Tyre-load margin K: RMS DTL at most the static wheel load / K (e.g. 3) [default: off].
    #[arg(long, value_name = "K", value_parser = number, allow_negative_numbers = true)]
    dtl_margin: Option<f64>,
    /// Travel budget M:N: N x RMS SWS within M metres of bump travel (e.g. 0.025:3) [default: off].
    #[arg(long, value_name = "M:N", value_parser = |s: &str| DesignBox::parse_range("travel", s), allow_hyphen_values = true)]
    travel: Option<(f64, f64)>,
}

impl ObjectiveArgs {
    /// The objectives: the defaults with these options applied, validated.
    fn objectives(&self) -> Result<DesignObjectives> {
        let o = DesignObjectives {
            sws_limit: self.sws_limit.or(DesignObjectives::default().sws_limit),
            dtl_margin: self.dtl_margin,
            travel: self.travel,
            ..DesignObjectives::default()
        };
        o.validate()?;
        Ok(o)
    }
}

#[derive(Args)]
struct SurrogateArgs {
    /// The surrogate, e.g. rba-mul-rbf-mq, vba-qts, pba-smts.
    #[arg(long)]
    approach: SurrogateSpec,
    /// Its HiFi sampling plan: ae:N or grid:n.
    #[arg(long, default_value = "ae:10")]
    plan: PlanSpec,
    /// Validate on a grid:N HiFi grid instead of 20 x 20 and print the predictions.
    #[arg(long, value_name = "grid:N", value_parser = predict_grid)]
    predict: Option<usize>,
    #[command(flatten)]
    design_box: BoxArgs,
    #[command(flatten)]
    adaptive: AdaptiveArgs,
    #[command(flatten)]
    car: CarRoad,
    /// Machine-readable output (JSON).
    #[arg(long)]
    json: bool,
}

/// The adaptive loop after the plan (issue #15): `--plan ae:5 --adaptive 5` is 10 HiFi
/// runs, the last 5 placed one at a time by the infill criterion.
#[derive(Args)]
struct AdaptiveArgs {
    /// HiFi runs added one at a time after the plan (plan + runs <= 100).
    #[arg(long, value_name = "K", value_parser = count, allow_negative_numbers = true)]
    adaptive: Option<usize>,
    /// Infill criterion: ehvi-front (expected hypervolume improvement of the surrogate's
    /// predicted front x probability of meeting the SWS limit) or ehvi (of the feasible
    /// HiFi samples' front) [default: ehvi-front].
    #[arg(long, requires = "adaptive")]
    infill: Option<Infill>,
    /// Uncertainty estimate: model (gp-mul's own variance) or loo (leave-one-out, any
    /// surrogate) [default: model for gp-mul, else loo].
    #[arg(long, requires = "adaptive")]
    uncertainty: Option<UncertaintyMethod>,
    /// Candidate grid of the infill, points per axis, 2..201 [default: 41].
    #[arg(long, value_parser = count, requires = "adaptive", allow_negative_numbers = true)]
    candidates: Option<usize>,
    /// Smallest normalised distance of a new run to every sample, (0, 0.5] [default: 0.02].
    #[arg(long, value_name = "D", value_parser = number, allow_negative_numbers = true, requires = "adaptive")]
    min_distance: Option<f64>,
}

impl AdaptiveArgs {
    /// The loop's options, `None` without `--adaptive`.
    fn options(&self) -> Option<AdaptiveOptions> {
        let d = AdaptiveOptions::default();
        self.adaptive.map(|runs| AdaptiveOptions {
            runs,
            criterion: self.infill.unwrap_or(d.criterion),
            uncertainty: self.uncertainty,
            candidates: self.candidates.unwrap_or(DEFAULT_CANDIDATES),
            min_distance: self.min_distance.unwrap_or(DEFAULT_MIN_DISTANCE),
            ..d
        })
    }
}

#[derive(Args)]
struct StudyArgs {
    /// The adaptive study of this surrogate instead of the fidelity study: for every
    /// total of HiFi runs, Audze-Eglais + adaptive runs against an Audze-Eglais plan of
    /// that size, judged on the HiFi.
    #[arg(long, value_name = "SURROGATE")]
    adaptive: Option<SurrogateSpec>,
    /// Audze-Eglais points of the adaptive study's initial plan, 2.. [default: 5].
    #[arg(long, value_parser = count, requires = "adaptive", allow_negative_numbers = true)]
    initial: Option<usize>,
    /// Smallest total of HiFi runs of the adaptive study [default: 6].
    #[arg(long, value_parser = count, requires = "adaptive", allow_negative_numbers = true)]
    min_runs: Option<usize>,
    /// Largest total of HiFi runs of the adaptive study, ..100 [default: 20].
    #[arg(long, value_parser = count, requires = "adaptive", allow_negative_numbers = true)]
    max_runs: Option<usize>,
    /// STM grid points per variable of every front of the adaptive study (the HiFi's own
    /// included), 2..2001 [default: 201].
    #[arg(long, value_parser = count, requires = "adaptive", allow_negative_numbers = true)]
    grid: Option<usize>,
    #[command(flatten)]
    car: CarRoad,
    /// Machine-readable output (JSON).
    #[arg(long, conflicts_with = "markdown")]
    json: bool,
    /// The study as a Markdown table.
    #[arg(long)]
    markdown: bool,
}

#[derive(Args)]
struct SimulateArgs {
    /// quarter (LoFi) or full (HiFi).
    #[arg(long)]
    model: ModelKind,
    /// Length of the road record, s.
    #[arg(long, value_name = "S", default_value_t = TimeOptions::default().duration, value_parser = number, allow_negative_numbers = true)]
    duration: f64,
    /// Time step, s (the road's highest frequency follows it: at most 0.4 / dt).
    #[arg(long, value_name = "S", value_parser = number, allow_negative_numbers = true)]
    dt: Option<f64>,
    /// Seed of the road's random phases.
    #[arg(long, default_value_t = 1, value_parser = count_u64, allow_negative_numbers = true)]
    seed: u64,
    /// Front damper bump (compression) rate, N s/m; the design's Cs is then the mean
    /// of bump and rebound, so --cs is left out.
    #[arg(long, value_name = "NS/M", value_parser = number, allow_negative_numbers = true, requires = "rebound")]
    bump: Option<f64>,
    /// Front damper rebound (extension) rate, N s/m.
    #[arg(long, value_name = "NS/M", value_parser = number, allow_negative_numbers = true, requires = "bump")]
    rebound: Option<f64>,
    /// Knee velocity of a digressive damper, m/s.
    #[arg(long, value_name = "M/S", value_parser = number, allow_negative_numbers = true, requires_all = ["bump", "bump_high", "rebound_high"])]
    knee: Option<f64>,
    /// Bump slope above the knee, N s/m.
    #[arg(long, value_name = "NS/M", value_parser = number, allow_negative_numbers = true, requires = "knee")]
    bump_high: Option<f64>,
    /// Rebound slope above the knee, N s/m.
    #[arg(long, value_name = "NS/M", value_parser = number, allow_negative_numbers = true, requires = "knee")]
    rebound_high: Option<f64>,
    /// Keep every n-th sample in the output.
    #[arg(long, default_value_t = 10, value_parser = count, allow_negative_numbers = true)]
    decimate: usize,
    #[command(flatten)]
    car: CarRoad,
    /// Machine-readable output (JSON).
    #[arg(long, conflicts_with = "csv")]
    json: bool,
    /// One row per kept sample (CSV) instead of the text summary.
    #[arg(long)]
    csv: bool,
}

#[derive(Args)]
struct ReportArgs {
    #[command(flatten)]
    car: CarRoad,
    #[command(flatten)]
    design_box: BoxArgs,
    #[command(flatten)]
    objectives: ObjectiveArgs,
    /// The surrogate of sections 4 and 5 [default: the study's best at 10 HiFi samples].
    #[arg(long, requires = "plan")]
    approach: Option<SurrogateSpec>,
    /// Its HiFi sampling plan: ae:N or grid:n.
    #[arg(long, requires = "approach")]
    plan: Option<PlanSpec>,
    /// Seed of the time-domain record and of NSGA-II.
    #[arg(long, default_value_t = 1, value_parser = count_u64, allow_negative_numbers = true)]
    seed: u64,
    /// Directory for report.html, report.md, figures/, report.json and the CSV tables
    /// (created if missing).
    #[arg(long, value_name = "DIR", default_value = "report")]
    out: PathBuf,
}

#[derive(Args)]
struct PresetsArgs {
    /// Machine-readable output (JSON).
    #[arg(long)]
    json: bool,
}

/// A finite number.
fn number(s: &str) -> Result<f64> {
    let v: f64 = s
        .trim()
        .parse()
        .map_err(|_| RideError::field("", format!("'{s}' is not a number")))?;
    if v.is_finite() {
        Ok(v)
    } else {
        Err(RideError::field("", "must be a finite number"))
    }
}

/// A whole number.
fn count(s: &str) -> Result<usize> {
    s.trim()
        .parse()
        .map_err(|_| RideError::field("", format!("'{s}' is not a whole number")))
}

fn count_u64(s: &str) -> Result<u64> {
    count(s).map(|n| n as u64)
}

/// `grid:N` of `--predict`: a grid plan's side.
fn predict_grid(s: &str) -> Result<usize> {
    match PlanSpec::parse(s) {
        Ok(PlanSpec::Grid(n)) => Ok(n),
        _ => Err(RideError::field("", format!("'{s}' is not grid:N"))),
    }
}

fn main() {
    // Mesa's device-select Vulkan layer (installed with lavapipe) connects to Wayland to
    // find the "default" GPU and prints "error: XDG_RUNTIME_DIR is invalid" on every
    // headless run; wgpu ranks the adapters itself, so the layer is off unless the user
    // set it. Still single-threaded here, so setting the variable is sound.
    #[cfg(feature = "gpu")]
    if std::env::var_os("NODEVICE_SELECT").is_none() {
        std::env::set_var("NODEVICE_SELECT", "1");
    }
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => exit_on_parse_error(e),
    };
    match run(cli.command) {
        Ok(text) => {
            // Not `print!`: it panics when the reader has gone (`ridelab map ... | head`).
            // A closed pipe is the reader's choice, so it ends the run quietly.
            use std::io::Write;
            let mut out = std::io::stdout().lock();
            if let Err(e) = out.write_all(text.as_bytes()).and_then(|()| out.flush()) {
                if e.kind() != std::io::ErrorKind::BrokenPipe {
                    eprintln!("error: writing the output: {e}");
                    std::process::exit(1);
                }
            }
        }
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(2);
        }
    }
}

/// Help and version go to stdout (exit 0); every other parse error is one line naming
/// the option (exit 2).
fn exit_on_parse_error(e: clap::Error) -> ! {
    if matches!(
        e.kind(),
        ErrorKind::DisplayHelp
            | ErrorKind::DisplayVersion
            | ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand
    ) {
        e.exit()
    }
    eprintln!("error: {}", parse_error_line(&e));
    std::process::exit(2)
}

/// `option: reason` for a clap error, the option without its dashes and value name.
fn parse_error_line(e: &clap::Error) -> String {
    let context = |kind: ContextKind| match e.get(kind) {
        Some(ContextValue::String(s)) => s.clone(),
        Some(ContextValue::Strings(v)) => v.join(", "),
        _ => String::new(),
    };
    let arg = context(ContextKind::InvalidArg);
    let option = arg
        .split_whitespace()
        .next()
        .unwrap_or_default()
        .trim_start_matches('-')
        .replace('_', "-");
    match e.kind() {
        ErrorKind::InvalidSubcommand | ErrorKind::MissingSubcommand => format!(
            "command: {} (eval, doe, optimize, map, surrogate, study, simulate, presets, report; --help lists them)",
            match context(ContextKind::InvalidSubcommand) {
                s if s.is_empty() => "missing".to_string(),
                s => format!("unknown command '{s}'"),
            }
        ),
        ErrorKind::UnknownArgument if arg.starts_with('-') => format!("{arg}: unknown option"),
        ErrorKind::UnknownArgument => {
            format!("{arg}: unexpected argument (options start with --)")
        }
        ErrorKind::MissingRequiredArgument => format!("{option}: missing"),
        ErrorKind::ArgumentConflict => {
            let prior = context(ContextKind::PriorArg);
            let prior = prior.split_whitespace().next().unwrap_or_default();
            if prior.is_empty() || prior.trim_start_matches('-') == option {
                format!("{option}: given twice")
            } else {
                format!("{option}: cannot be given with {prior}: they ask for two different outputs or settings; give one")
            }
        }
        ErrorKind::InvalidValue if context(ContextKind::InvalidValue).is_empty() => {
            format!("{option}: needs a value")
        }
        ErrorKind::InvalidValue => format!(
            "{option}: '{}' is not one of {}",
            context(ContextKind::InvalidValue),
            context(ContextKind::ValidValue)
        ),
        ErrorKind::ValueValidation => {
            let reason = match std::error::Error::source(e)
                .and_then(|s| s.downcast_ref::<RideError>())
            {
                Some(RideError::Field { reason, .. }) => reason.clone(),
                Some(other) => other.to_string(),
                None => context(ContextKind::InvalidValue),
            };
            format!("{option}: {reason}")
        }
        _ => {
            // Anything else: clap's own first line, without its "error: " prefix.
            let text = e.to_string();
            let line = text.lines().next().unwrap_or_default();
            format!(
                "{}: {}",
                if option.is_empty() { "arguments" } else { &option },
                line.trim_start_matches("error: ")
            )
        }
    }
}

fn run(command: Command) -> Result<String> {
    match command {
        Command::Eval(a) => eval(a),
        Command::Doe(a) => doe(a),
        Command::Optimize(a) => optimize(a),
        Command::Map(a) => map_cmd(a),
        Command::Surrogate(a) => surrogate_cmd(a),
        Command::Study(a) => study_cmd(a),
        Command::Simulate(a) => simulate_cmd(a),
        Command::Presets(a) => presets(a),
        Command::Report(a) => report_cmd(a),
    }
}

/// Car (with `--ks/--cs` applied to the front) and road from the options; a car file's
/// load cases are read and checked but only map and optimize use them.
fn car_and_road(o: &CarRoad) -> Result<(Car, Road)> {
    car_loads_road(o).map(|(car, _, road)| (car, road))
}

/// Car (with `--ks/--cs` applied to the front), the car file's load cases and road.
fn car_loads_road(o: &CarRoad) -> Result<(Car, Vec<LoadCase>, Road)> {
    let (car, loads) = match o.car.as_deref() {
        None => (Car::datum(), Vec::new()),
        Some(name) if ridelab::car::PRESETS.iter().any(|(n, _)| *n == name) => {
            (Car::preset(name)?, Vec::new())
        }
        Some(path) => {
            let text = std::fs::read_to_string(path)
                .map_err(|e| RideError::field("car", format!("cannot read '{path}': {e}")))?;
            let file = CarFile::from_json(&text)?;
            (file.car, file.load_cases)
        }
    };
    let ks = o.ks.unwrap_or(car.front.spring);
    let cs = o.cs.unwrap_or(car.front.damper);
    car.design_domain().check(ks, cs)?;
    let car = car.with_front(ks, cs)?;
    let mut road = Road::default();
    if let Some(c) = o.class {
        road.class = c;
    }
    if let Some(v) = o.speed {
        road.speed = v;
    }
    if let Some(t) = o.tracks {
        road.tracks = t;
    }
    road.validate()?;
    if !loads.is_empty() {
        // The load cases apply to the car with --ks/--cs; checked before any work.
        CaseSet::new(&car, &road, &loads, &[], Combine::Worst)?;
    }
    Ok((car, loads, road))
}

/// `v` as pretty JSON, once every number in it is known to be finite (serde_json would
/// write a NaN as `null` silently).
fn json<T: serde::Serialize>(v: &T) -> Result<String> {
    ridelab::finite::check(v)?;
    serde_json::to_string_pretty(v)
        .map(|s| s + "\n")
        .map_err(|e| RideError::Numerical(format!("cannot write JSON: {e}")))
}

/// The `--svg` target, checked before any work: a file name (not a directory) in a
/// directory that exists.
fn svg_target(text: Option<&str>) -> Result<Option<PathBuf>> {
    let Some(text) = text else {
        return Ok(None);
    };
    if text.trim().is_empty() {
        return Err(RideError::field("svg", "needs a file name"));
    }
    let path = PathBuf::from(text);
    if path.is_dir() {
        return Err(RideError::field(
            "svg",
            format!(
                "'{text}' is a directory; give a file name (for map, a prefix such as {}/map)",
                text.trim_end_matches('/')
            ),
        ));
    }
    match path.parent() {
        Some(dir) if !dir.as_os_str().is_empty() && !dir.is_dir() => Err(RideError::field(
            "svg",
            format!("directory '{}' does not exist", dir.display()),
        )),
        _ => Ok(Some(path)),
    }
}

fn write_svg(path: &Path, svg: &str) -> Result<()> {
    std::fs::write(path, svg)
        .map_err(|e| RideError::field("svg", format!("cannot write '{}': {e}", path.display())))
}

fn eval(a: EvalArgs) -> Result<String> {
    let (car, road) = car_and_road(&a.car)?;
    let r = report(a.model, &car, &road)?;
    if a.json {
        json(&r)
    } else {
        Ok(text_report(&r))
    }
}

fn text_report(r: &Report) -> String {
    let mut s = format!(
        "{} model, {} on ISO class {:?} at {} m/s ({:?} tracks)\nKs {:.1} N/m, Cs {:.1} N s/m\n\
         BAcc {:.5} m/s^2 (ISO 2631-1 Wk-weighted {:.5} m/s^2: {})\n\
         DTL  {:.3} N ({:.2} % of static wheel load)\nSWS  {:.4} mm\n\
         route {} (frequency route differs by {:.1e})\n",
        match r.model {
            ModelKind::Quarter => "Quarter-car (LoFi)",
            ModelKind::Full => "Full-car (HiFi)",
        },
        r.car,
        r.road.class,
        r.road.speed,
        r.road.tracks,
        r.ks,
        r.cs,
        r.bacc,
        r.bacc_wk,
        r.comfort,
        r.dtl,
        100.0 * r.dtl_relative,
        1e3 * r.sws,
        r.route,
        r.route_difference
    );
    if let Some(f) = r.low_cutoff_hz {
        s += &format!("note: road warp; band starts at ISO 8608's 0.011 cycle/m = {f:.3} Hz\n");
    }
    s += &format!(
        "body bounce {:.3} Hz, damping ratio {:.3}, critical damping {:.0} N s/m, wheel rate {:.0} N/m\nmodes:\n",
        r.body_bounce_hz, r.damping_ratio, r.critical_damping, r.wheel_rate
    );
    for m in &r.modes {
        s += &format!(
            "  {:>7.3} Hz  zeta {:.3}  {}\n",
            m.frequency, m.damping_ratio, m.label
        );
    }
    s
}

fn doe(a: DoeArgs) -> Result<String> {
    let r = doe_report(a.points, a.seed, &DesignBox::default())?;
    if a.json {
        return json(&r);
    }
    let mut s = format!(
        "Audze-Eglais plan, {} points ({}, {}), energy {:.6}\n  level   Ks N/m      Cs N s/m\n",
        r.points,
        r.method,
        if r.optimal { "optimal" } else { "heuristic" },
        r.energy
    );
    for p in &r.samples {
        s += &format!(
            "  {:>2},{:<2}  {:>9.1}  {:>9.1}\n",
            p.level[0], p.level[1], p.ks, p.cs
        );
    }
    Ok(s)
}

fn optimize(a: OptimizeArgs) -> Result<String> {
    let svg = svg_target(a.svg.as_deref())?;
    let (car, loads, road) = car_loads_road(&a.car)?;
    let set = a.cases.set(&car, &loads, &road)?;
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
        let out = robust_optimize_report(
            &set,
            &design_box,
            a.evaluator,
            a.plan,
            &method,
            objectives,
            a.comfort,
            a.pick,
        )?;
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
    let (mut out, looped) = match a.adaptive.options() {
        None => (
            optimize_report_on(
                &car,
                &road,
                &design_box,
                a.evaluator,
                a.plan,
                &method,
                objectives,
                a.comfort,
                a.compute,
            )?,
            None,
        ),
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
            let r = adaptive::optimize_report(
                &car,
                &road,
                &design_box,
                a.evaluator,
                a.plan,
                &method,
                objectives,
                options,
            )?;
            let mut out = r.optimize;
            out.compute = a.compute.map(|_| ComputePath::Cpu);
            (out, Some(r.adaptive))
        }
    };
    if a.pick != PickRule::MinMax {
        out.repick(a.pick, &car, &road, &design_box)?;
    }
    if let Some(path) = &svg {
        ridelab::finite::check(&out)?;
        let mut chart = front_chart(&out.study, &out.datum, Some(&out.hifi_recheck));
        if out.comfort == Comfort::Wk {
            chart.title = chart.title.replacen("BAcc", out.comfort.label(), 1);
            chart.x_label = format!("{} [m/s^2]", out.comfort.label());
        }
        write_svg(path, &line_chart_svg(&chart)?)?;
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

/// The loop's added runs, one line each.
fn adaptive_text(r: &adaptive::AdaptiveReport) -> String {
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
    s
}

fn optimize_text(out: &OptimizeReport) -> String {
    let (study, check) = (&out.study, &out.hifi_recheck);
    let p = &study.pick;
    let bacc = out.comfort.label();
    let mut text = format!(
        "front: {} points on {} ({} evaluations), hypervolume {:.4} (m/s^2) N against [{:.4}, {:.2}]\n\
         {} pick: Ks {:.1} N/m, Cs {:.1} N s/m (pseudo-weights comfort {:.2}, road holding {:.2})\n  {bacc} {:+.2} %, DTL {:+.2} %, SWS {:+.2} % against the datum\n\
         HiFi re-check: {bacc} {:+.2} %, DTL {:+.2} %, SWS {:+.2} % (prediction error {:.3} / {:.3} / {:.3} %)\n",
        study.front.len(),
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
        p.change_percent[0],
        p.change_percent[1],
        p.change_percent[2],
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

/// One `warning:` line per warning about a pick ([`ridelab::optimize::trust`]).
fn warning_lines(w: &[Warning]) -> String {
    w.iter().map(|w| format!("warning: {}\n", w.message)).collect()
}

/// The robust optimisation: the front and pick as [`optimize_text`], then each case.
fn robust_optimize_text(out: &RobustOptimizeReport) -> String {
    let single = OptimizeReport {
        study: out.study.clone(),
        datum: out.datum,
        hifi_recheck: out.hifi_recheck.clone(),
        comfort: out.comfort,
        compute: None,
        adapter: None,
        warnings: out.warnings.clone(),
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

/// The front damper law of `--bump --rebound [--knee --bump-high --rebound-high]`
/// (clap makes sure they come together); the core's field names become the options'.
fn damper_law(a: &SimulateArgs) -> Result<Option<Damper>> {
    let (Some(bump), Some(rebound)) = (a.bump, a.rebound) else {
        return Ok(None);
    };
    let knee = match (a.knee, a.bump_high, a.rebound_high) {
        (Some(velocity), Some(bump), Some(rebound)) => Some(Knee {
            velocity,
            bump,
            rebound,
        }),
        _ => None,
    };
    let law = Damper {
        bump,
        rebound,
        knee,
    };
    law.validate().map_err(|e| match e {
        RideError::Field { field, reason } => {
            let option = match field.as_str() {
                "knee.velocity" => "knee",
                "knee.bump" => "bump-high",
                "knee.rebound" => "rebound-high",
                other => other,
            };
            RideError::field(option, reason)
        }
        other => other,
    })?;
    if let Some(cs) = a.car.cs {
        law.check_design_cs(cs)?;
    }
    Ok(Some(law))
}

fn simulate_cmd(a: SimulateArgs) -> Result<String> {
    let (car, road) = car_and_road(&a.car)?;
    let mut opt = TimeOptions {
        duration: a.duration,
        seed: a.seed,
        decimate: a.decimate,
        damper: damper_law(&a)?,
        ..TimeOptions::default()
    };
    if let Some(dt) = a.dt {
        opt = opt.with_step(dt);
    }
    let r = simulate(a.model, &car, &road, &opt)?;
    if a.json {
        return json(&r);
    }
    if a.csv {
        ridelab::finite::check(&r)?;
        return Ok(simulate_csv(&r));
    }
    let damper = match opt.damper {
        None => format!("linear front damper Cs {} Ns/m", r.damper_rate),
        Some(law) => format!(
            "front damper bump {} / rebound {} Ns/m{}: Cs = their mean {} Ns/m, energy-equivalent rate over the run {:.1} Ns/m",
            law.bump,
            law.rebound,
            law.knee.map_or(String::new(), |k| format!(
                " (knee {} m/s, then {} / {} Ns/m)",
                k.velocity, k.bump, k.rebound
            )),
            r.damper_rate,
            r.equivalent_rate
        ),
    };
    Ok(format!(
        "{} s at {} s steps: RMS BAcc {:.5} m/s^2, DTL {:.3} N, SWS {:.4} mm\n{damper}\n",
        opt.duration,
        opt.dt,
        r.rms[0],
        r.rms[1],
        1e3 * r.rms[2]
    ))
}

fn simulate_csv(r: &TimeResponse) -> String {
    let mut s = String::from("t_s,road_m,bacc_m_per_s2,dtl_n,sws_m\n");
    for i in 0..r.t.len() {
        s += &format!(
            "{},{},{},{},{}\n",
            r.t[i], r.road[i], r.outputs[0][i], r.outputs[1][i], r.outputs[2][i]
        );
    }
    s
}

fn presets(a: PresetsArgs) -> Result<String> {
    let cars: Vec<Car> = ridelab::car::PRESETS
        .iter()
        .map(|(n, _)| Car::preset(n))
        .collect::<Result<_>>()?;
    if a.json {
        return json(&cars);
    }
    Ok(ridelab::car::PRESETS
        .iter()
        .zip(&cars)
        .map(|((n, _), c)| format!("{n:<8} {}\n         source: {}\n", c.name, c.source))
        .collect())
}

fn map_cmd(a: MapArgs) -> Result<String> {
    let svg = svg_target(a.svg.as_deref())?;
    let (car, loads, road) = car_loads_road(&a.car)?;
    let set = a.cases.set(&car, &loads, &road)?;
    let settings = MapSettings {
        grid: Grid::new(a.ks_range, a.cs_range)?,
        scale: if a.relative {
            Scale::Relative
        } else {
            Scale::Absolute
        },
        objectives: a.objectives.objectives()?,
        comfort: a.comfort,
        ..MapSettings::default()
    };
    if set.is_some() && a.compute == Compute::Gpu {
        return Err(RideError::field(
            "compute",
            "gpu: the robust maps' cases are evaluated on the CPU; use --compute cpu or auto",
        ));
    }
    let (r, json_text) = match (set, a.case) {
        (None, None) => {
            let r = map_report_on(a.model, &car, &road, &settings, a.compute)?;
            let text = if a.csv { String::new() } else { json(&r)? };
            (r, text)
        }
        (set, Some(k)) => {
            let set = match set {
                Some(s) => s,
                None => CaseSet::new(&car, &road, &[], &[], Combine::Worst)?,
            };
            let r = case_map_report(a.model, &set, k, &settings, a.compute)?;
            let text = if a.csv { String::new() } else { json(&r)? };
            (r.map, text)
        }
        (Some(set), None) => {
            let r = robust_map_report(a.model, &car, &road, &set, &settings, a.compute)?;
            let text = if a.csv { String::new() } else { json(&r)? };
            (r.map, text)
        }
    };
    if let Some(prefix) = svg {
        ridelab::finite::check(&r)?;
        let prefix = prefix.to_string_lossy();
        let prefix = prefix.strip_suffix(".svg").unwrap_or(&prefix);
        for (key, chart) in map_report_charts(&r) {
            write_svg(
                Path::new(&format!("{prefix}-{key}.svg")),
                &map_chart_svg(&chart)?,
            )?;
        }
    }
    if a.csv {
        ridelab::finite::check(&r)?;
        Ok(map_csv(&r))
    } else {
        Ok(json_text)
    }
}

fn surrogate_cmd(a: SurrogateArgs) -> Result<String> {
    let (car, road) = car_and_road(&a.car)?;
    let design_box = a.design_box.design_box()?;
    let r = match a.adaptive.options() {
        None => surrogate_report_in(a.approach, a.plan, &car, &road, &design_box, a.predict),
        Some(options) => adaptive::surrogate_report(
            a.approach,
            a.plan,
            &car,
            &road,
            &design_box,
            a.predict,
            options,
        ),
    }
    .map_err(|e| match e {
        RideError::Field { field, reason } if field == "predict-grid" => {
            RideError::field("predict", reason)
        }
        other => other,
    })?;
    json(&r)
}

fn study_cmd(a: StudyArgs) -> Result<String> {
    let (car, road) = car_and_road(&a.car)?;
    if let Some(spec) = a.adaptive {
        let d = StudyOptions::default();
        let options = StudyOptions {
            initial: a.initial.unwrap_or(d.initial),
            min_runs: a.min_runs.unwrap_or(d.min_runs),
            max_runs: a.max_runs.unwrap_or(d.max_runs),
            stm: StmParams {
                grid: a.grid.unwrap_or(d.stm.grid),
                ..d.stm.clone()
            },
            ..d
        };
        let r = adaptive_study(&car, &road, spec, &options).map_err(|e| match e {
            RideError::Field { field, reason } => RideError::field(field.replace('_', "-"), reason),
            other => other,
        })?;
        return if a.markdown {
            Ok(r.to_markdown())
        } else {
            json(&r)
        };
    }
    let r = study(&car, &road)?;
    if a.markdown {
        Ok(r.to_markdown())
    } else {
        json(&r)
    }
}

fn report_cmd(a: ReportArgs) -> Result<String> {
    let (car, road) = car_and_road(&a.car)?;
    let design_box = a.design_box.design_box()?;
    let inputs = ReportInputs {
        design_box,
        objectives: a.objectives.objectives()?,
        surrogate: a.approach.zip(a.plan),
        seed: a.seed,
        ..ReportInputs::new(car, road)
    };
    let figures_dir = a.out.join("figures");
    std::fs::create_dir_all(&figures_dir).map_err(|e| {
        RideError::field(
            "out",
            format!("cannot create '{}': {e}", figures_dir.display()),
        )
    })?;
    // Progress on stderr, one line per section with its time.
    let start = std::time::Instant::now();
    let mut last = (start, None::<usize>);
    let report = build(&inputs, |k| {
        let now = std::time::Instant::now();
        if let Some(prev) = last.1 {
            eprintln!(
                "report: {} took {:.2} s",
                SECTIONS[prev],
                (now - last.0).as_secs_f64()
            );
        }
        if k < SECTIONS.len() {
            eprintln!("report: {} ...", SECTIONS[k]);
        }
        last = (now, Some(k));
    })?;
    // Nothing is written unless every number in the report is finite.
    ridelab::finite::check(&report)?;
    let render = std::time::Instant::now();
    let docs = report.documents()?;
    let write = |name: &Path, text: &str| {
        std::fs::write(name, text)
            .map_err(|e| RideError::field("out", format!("cannot write '{}': {e}", name.display())))
    };
    write(&a.out.join("report.html"), &docs.html)?;
    write(&a.out.join("report.md"), &docs.markdown)?;
    write(&a.out.join("report.json"), &json(&report)?)?;
    for (name, text) in report.csv_files() {
        write(&a.out.join(name), &text)?;
    }
    for f in &docs.figures {
        write(&figures_dir.join(format!("{}.svg", f.key)), &f.svg)?;
    }
    eprintln!(
        "report: rendering {} figures took {:.2} s; {:.2} s in all",
        docs.figures.len(),
        render.elapsed().as_secs_f64(),
        start.elapsed().as_secs_f64()
    );
    Ok(format!(
        "{}: {} (and report.md, report.json, {} figures, CSV tables)\n",
        report.title(),
        a.out.join("report.html").display(),
        docs.figures.len()
    ))
}
