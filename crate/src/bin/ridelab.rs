//! `ridelab`: the command-line shell over the RideLab core (scripting, batch studies,
//! reports). Argument parsing and printing only; every number comes from the library.
//!
//! The parser is hand-written rather than clap so that every bad input gives exactly
//! one line naming the option at fault (the same messages as the page) and exit code 2.

use ridelab::analysis::{report, ModelKind, Report};
use ridelab::car::Car;
use ridelab::chart::{front_chart, line_chart_svg, map_chart_svg, map_report_charts};
use ridelab::design::DesignBox;
use ridelab::doe::doe_report;
use ridelab::dos::{DesignObjectives, DosContext};
use ridelab::error::{Result, RideError};
use ridelab::maps::{map_csv, map_report, Grid, MapSettings, Scale};
use ridelab::optimize::{recheck, run_study, Method, Nsga2Params, StmParams, SuspensionProblem};
use ridelab::road::{Road, RoadClass, Tracks};
use ridelab::surrogate::{
    sample_plan, study, surrogate_report, LmOptions, PlanSpec, Setting, SurrogateSpec,
};
use ridelab::time_domain::{simulate, Damper, Knee, TimeOptions};
use ridelab::{Evaluator, HiFi, LoFi};
use std::collections::HashMap;
use std::path::{Path, PathBuf};

const USAGE: &str = "usage: ridelab <command> [options]
commands:
  eval      --model quarter|full [--car FILE|PRESET] [--class B] [--speed 20] [--tracks correlated|independent]
            [--ks N/m] [--cs Ns/m] [--json]
  doe       --points N [--seed S] [--json]
  optimize  --evaluator quarter|full|SURROGATE [--plan ae:10] --method stm|nsga2 [car/road options]
            [--ks N/m --cs Ns/m for the datum] [--sws-limit m] [--grid 201] [--population 100]
            [--generations 100] [--seed 1] [--json] [--svg FILE]
  map       --model quarter|full [car/road options] [--ks-range 10000:40000:41] [--cs-range 500:4000:41]
            [--relative] --json|--csv [--svg PREFIX]
  surrogate --approach rba-mul-poly2|vba-qts|pba-smts|... --plan ae:10|grid:5 [car/road options]
            [--predict grid:20] [--json]
  study     [car/road options] --json|--markdown
  simulate  --model quarter|full [car/road options] [--ks] [--cs] [--duration 20] [--dt 0.001] [--seed 1]
            [--bump Ns/m --rebound Ns/m [--knee m/s --bump-high Ns/m --rebound-high Ns/m]]
            [--decimate 10] [--json|--csv]
            (with --bump and --rebound the design's Cs is their mean; leave --cs out)
  presets   [--json]
car: a JSON file or a preset name (sedan, compact, suv); default sedan (the datum car)
--svg: optimize writes the front chart to FILE; map writes PREFIX-bacc.svg, PREFIX-dtl.svg and
       PREFIX-sws.svg (a trailing .svg on PREFIX is dropped); stdout is unchanged";

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match run(&args) {
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

/// Parsed `--name value` options and `--flag` switches.
struct Opts {
    values: HashMap<String, String>,
    flags: Vec<String>,
}

impl Opts {
    fn parse(args: &[String], flags: &[&str], values: &[&str]) -> Result<Opts> {
        let mut o = Opts {
            values: HashMap::new(),
            flags: Vec::new(),
        };
        let mut i = 0;
        while i < args.len() {
            let a = &args[i];
            let name = a.strip_prefix("--").ok_or_else(|| {
                RideError::field(a.clone(), "unexpected argument (options start with --)")
            })?;
            if flags.contains(&name) {
                o.flags.push(name.to_string());
                i += 1;
            } else if values.contains(&name) {
                let v = args
                    .get(i + 1)
                    .ok_or_else(|| RideError::field(name, "needs a value"))?;
                if o.values.insert(name.to_string(), v.clone()).is_some() {
                    return Err(RideError::field(name, "given twice"));
                }
                i += 2;
            } else {
                return Err(RideError::field(a.clone(), "unknown option"));
            }
        }
        Ok(o)
    }

    fn flag(&self, name: &str) -> bool {
        self.flags.iter().any(|f| f == name)
    }

    fn str(&self, name: &str) -> Option<&str> {
        self.values.get(name).map(String::as_str)
    }

    fn num(&self, name: &str) -> Result<Option<f64>> {
        match self.str(name) {
            None => Ok(None),
            Some(s) => {
                let v: f64 = s
                    .trim()
                    .parse()
                    .map_err(|_| RideError::field(name, format!("'{s}' is not a number")))?;
                if v.is_finite() {
                    Ok(Some(v))
                } else {
                    Err(RideError::field(name, "must be a finite number"))
                }
            }
        }
    }

    fn count(&self, name: &str, default: usize) -> Result<usize> {
        match self.str(name) {
            None => Ok(default),
            Some(s) => s
                .trim()
                .parse()
                .map_err(|_| RideError::field(name, format!("'{s}' is not a whole number"))),
        }
    }
}

const CAR_ROAD: [&str; 6] = ["car", "class", "speed", "tracks", "ks", "cs"];

/// Car (with `--ks/--cs` applied to the front) and road from the options.
fn car_and_road(o: &Opts) -> Result<(Car, Road)> {
    let car = match o.str("car") {
        None => Car::datum(),
        Some(name) if ridelab::car::PRESETS.iter().any(|(n, _)| *n == name) => Car::preset(name)?,
        Some(path) => {
            let text = std::fs::read_to_string(path)
                .map_err(|e| RideError::field("car", format!("cannot read '{path}': {e}")))?;
            Car::from_json(&text)?
        }
    };
    let ks = o.num("ks")?.unwrap_or(car.front.spring);
    let cs = o.num("cs")?.unwrap_or(car.front.damper);
    let car = car.with_front(ks, cs).map_err(|e| match e {
        RideError::Field { field, reason } if field == "front.spring" => {
            RideError::field("ks", reason)
        }
        RideError::Field { field, reason } if field == "front.damper" => {
            RideError::field("cs", reason)
        }
        other => other,
    })?;
    let mut road = Road::default();
    if let Some(c) = o.str("class") {
        road.class = RoadClass::parse(c)?;
    }
    if let Some(v) = o.num("speed")? {
        road.speed = v;
    }
    if let Some(t) = o.str("tracks") {
        road.tracks = Tracks::parse(t)?;
    }
    road.validate()?;
    Ok((car, road))
}

fn json<T: serde::Serialize>(v: &T) -> Result<String> {
    serde_json::to_string_pretty(v)
        .map(|s| s + "\n")
        .map_err(|e| RideError::Numerical(format!("cannot write JSON: {e}")))
}

/// The `--svg` target, checked before any work: a file name (not a directory) in a
/// directory that exists.
fn svg_target(o: &Opts) -> Result<Option<PathBuf>> {
    let Some(text) = o.str("svg") else {
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

fn run(args: &[String]) -> Result<String> {
    let Some((cmd, rest)) = args.split_first() else {
        return Err(RideError::field("command", format!("missing\n{USAGE}")));
    };
    match cmd.as_str() {
        "eval" => eval(rest),
        "doe" => doe(rest),
        "optimize" => optimize(rest),
        "simulate" => simulate_cmd(rest),
        "map" => map_cmd(rest),
        "surrogate" => surrogate_cmd(rest),
        "study" => study_cmd(rest),
        "presets" => presets(rest),
        "help" | "--help" | "-h" => Ok(format!("{USAGE}\n")),
        other => Err(RideError::field(
            "command",
            format!("unknown command '{other}' (eval, doe, optimize, map, surrogate, study, simulate, presets)"),
        )),
    }
}

fn model_kind(o: &Opts) -> Result<ModelKind> {
    ModelKind::parse(
        o.str("model")
            .ok_or_else(|| RideError::field("model", "missing (quarter or full)"))?,
    )
}

fn eval(args: &[String]) -> Result<String> {
    let mut values = vec!["model"];
    values.extend(CAR_ROAD);
    let o = Opts::parse(args, &["json"], &values)?;
    let kind = model_kind(&o)?;
    let (car, road) = car_and_road(&o)?;
    let r = report(kind, &car, &road)?;
    if o.flag("json") {
        json(&r)
    } else {
        Ok(text_report(&r))
    }
}

fn text_report(r: &Report) -> String {
    let mut s = format!(
        "{} model, {} on ISO class {:?} at {} m/s ({:?} tracks)\nKs {:.1} N/m, Cs {:.1} N s/m\n\
         BAcc {:.5} m/s^2\nDTL  {:.3} N ({:.2} % of static wheel load)\nSWS  {:.4} mm\n\
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

fn doe(args: &[String]) -> Result<String> {
    let o = Opts::parse(args, &["json"], &["points", "seed"])?;
    let n = match o.str("points") {
        None => return Err(RideError::field("points", "missing")),
        Some(_) => o.count("points", 0)?,
    };
    let seed = o.count("seed", 1)? as u64;
    let r = doe_report(n, seed, &DesignBox::default())?;
    if o.flag("json") {
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

fn optimize(args: &[String]) -> Result<String> {
    let mut values = vec![
        "evaluator",
        "plan",
        "method",
        "sws-limit",
        "grid",
        "population",
        "generations",
        "seed",
        "svg",
    ];
    values.extend(CAR_ROAD);
    let o = Opts::parse(args, &["json"], &values)?;
    let svg = svg_target(&o)?;
    let (car, road) = car_and_road(&o)?;
    let mut objectives = DesignObjectives::default();
    if let Some(l) = o.num("sws-limit")? {
        objectives.sws_limit = Some(l);
    }
    objectives.validate()?;
    let method = match o.str("method").unwrap_or("stm") {
        "stm" => Method::Stm(StmParams {
            grid: o.count("grid", 201)?,
            ..StmParams::default()
        }),
        "nsga2" => Method::Nsga2(Nsga2Params {
            population: o.count("population", 100)?,
            generations: o.count("generations", 100)?,
            seed: o.count("seed", 1)? as u64,
            ..Nsga2Params::default()
        }),
        other => {
            return Err(RideError::field(
                "method",
                format!("'{other}' is not stm or nsga2"),
            ))
        }
    };
    let hifi = HiFi::new(&car, &road)?;
    let datum = hifi.evaluate(car.front.spring, car.front.damper)?;
    let ctx = DosContext::new(&car, datum);
    let design_box = DesignBox::default();
    let evaluator: Box<dyn Evaluator> = match o.str("evaluator").unwrap_or("full") {
        "full" | "hifi" => Box::new(hifi.clone()),
        "quarter" | "lofi" => Box::new(LoFi {
            car: car.clone(),
            road,
        }),
        name => {
            let spec = SurrogateSpec::parse(name).map_err(|e| match e {
                RideError::Field { reason, .. } => RideError::field("evaluator", reason),
                other => other,
            })?;
            let plan = PlanSpec::parse(o.str("plan").unwrap_or("ae:10"))?.plan()?;
            let samples = sample_plan(&hifi, &plan, &design_box)?;
            let setting = Setting::new(&car, &road, &design_box)?;
            Box::new(spec.fit(&setting, &samples, &LmOptions::default())?)
        }
    };
    let problem = SuspensionProblem::new(evaluator, design_box, objectives, ctx)?;
    let study = run_study(&problem, &method, None)?;
    let check = recheck(&study.pick, &hifi, &datum)?;
    if let Some(path) = &svg {
        write_svg(
            path,
            &line_chart_svg(&front_chart(&study, &datum, Some(&check)))?,
        )?;
    }
    #[derive(serde::Serialize)]
    struct Out<'a> {
        #[serde(flatten)]
        study: &'a ridelab::optimize::Study,
        datum: ridelab::Criteria,
        hifi_recheck: ridelab::optimize::Recheck,
    }
    let out = Out {
        study: &study,
        datum,
        hifi_recheck: check,
    };
    if o.flag("json") {
        return json(&out);
    }
    let p = &study.pick;
    Ok(format!(
        "front: {} points on {} ({} evaluations), hypervolume {:.4} (m/s^2) N against [{:.4}, {:.2}]\n\
         min-max pick: Ks {:.1} N/m, Cs {:.1} N s/m\n  BAcc {:+.2} %, DTL {:+.2} %, SWS {:+.2} % against the datum\n\
         HiFi re-check: BAcc {:+.2} %, DTL {:+.2} %, SWS {:+.2} % (prediction error {:.3} / {:.3} / {:.3} %)\n",
        study.front.len(),
        study.evaluator,
        study.evaluations,
        study.hypervolume,
        study.reference_point[0],
        study.reference_point[1],
        p.ks,
        p.cs,
        p.change_percent[0],
        p.change_percent[1],
        p.change_percent[2],
        out.hifi_recheck.rechecked_change_percent[0],
        out.hifi_recheck.rechecked_change_percent[1],
        out.hifi_recheck.rechecked_change_percent[2],
        out.hifi_recheck.error_percent[0],
        out.hifi_recheck.error_percent[1],
        out.hifi_recheck.error_percent[2],
    ))
}

/// The front damper law of `--bump --rebound [--knee --bump-high --rebound-high]`.
fn damper_law(o: &Opts) -> Result<Option<Damper>> {
    let knee = match (o.num("knee")?, o.num("bump-high")?, o.num("rebound-high")?) {
        (None, None, None) => None,
        (Some(velocity), Some(bump), Some(rebound)) => Some(Knee {
            velocity,
            bump,
            rebound,
        }),
        _ => {
            return Err(RideError::field(
                "knee",
                "give --knee m/s with both --bump-high and --rebound-high",
            ))
        }
    };
    match (o.num("bump")?, o.num("rebound")?) {
        (None, None) if knee.is_some() => Err(RideError::field(
            "bump",
            "a knee needs the low-speed --bump and --rebound rates",
        )),
        (None, None) => Ok(None),
        (Some(bump), Some(rebound)) => {
            let law = Damper {
                bump,
                rebound,
                knee,
            };
            // Errors name the option: knee.bump is --bump-high, and so on.
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
            Ok(Some(law))
        }
        _ => Err(RideError::field("bump", "give both --bump and --rebound")),
    }
}

fn simulate_cmd(args: &[String]) -> Result<String> {
    let mut values = vec![
        "model",
        "duration",
        "dt",
        "seed",
        "bump",
        "rebound",
        "knee",
        "bump-high",
        "rebound-high",
        "decimate",
    ];
    values.extend(CAR_ROAD);
    let o = Opts::parse(args, &["json", "csv"], &values)?;
    let kind = model_kind(&o)?;
    let (car, road) = car_and_road(&o)?;
    let mut opt = TimeOptions::default();
    if let Some(v) = o.num("duration")? {
        opt.duration = v;
    }
    if let Some(v) = o.num("dt")? {
        opt = opt.with_step(v);
    }
    opt.seed = o.count("seed", 1)? as u64;
    opt.decimate = o.count("decimate", 10)?;
    opt.damper = damper_law(&o)?;
    if let (Some(law), Some(cs)) = (opt.damper, o.num("cs")?) {
        if cs != law.linear_rate() {
            return Err(RideError::field(
                "cs",
                format!(
                    "with --bump and --rebound the design's Cs is their mean {} Ns/m: leave --cs out",
                    law.linear_rate()
                ),
            ));
        }
    }
    let r = simulate(kind, &car, &road, &opt)?;
    if o.flag("json") {
        return json(&r);
    }
    if o.flag("csv") {
        let mut s = String::from("t_s,road_m,bacc_m_per_s2,dtl_n,sws_m\n");
        for i in 0..r.t.len() {
            s += &format!(
                "{},{},{},{},{}\n",
                r.t[i], r.road[i], r.outputs[0][i], r.outputs[1][i], r.outputs[2][i]
            );
        }
        return Ok(s);
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

fn presets(args: &[String]) -> Result<String> {
    let o = Opts::parse(args, &["json"], &[])?;
    let cars: Vec<Car> = ridelab::car::PRESETS
        .iter()
        .map(|(n, _)| Car::preset(n))
        .collect::<Result<_>>()?;
    if o.flag("json") {
        return json(&cars);
    }
    Ok(ridelab::car::PRESETS
        .iter()
        .zip(&cars)
        .map(|((n, _), c)| format!("{n:<8} {}\n         source: {}\n", c.name, c.source))
        .collect())
}

fn map_cmd(args: &[String]) -> Result<String> {
    let mut values = vec!["model", "ks-range", "cs-range", "svg"];
    values.extend(CAR_ROAD);
    let o = Opts::parse(args, &["json", "csv", "relative"], &values)?;
    let svg = svg_target(&o)?;
    let kind = model_kind(&o)?;
    let (car, road) = car_and_road(&o)?;
    let settings = MapSettings {
        grid: Grid::parse(
            o.str("ks-range").unwrap_or("10000:40000:41"),
            o.str("cs-range").unwrap_or("500:4000:41"),
        )?,
        scale: if o.flag("relative") {
            Scale::Relative
        } else {
            Scale::Absolute
        },
        ..MapSettings::default()
    };
    let r = map_report(kind, &car, &road, &settings)?;
    if let Some(prefix) = svg {
        let prefix = prefix.to_string_lossy();
        let prefix = prefix.strip_suffix(".svg").unwrap_or(&prefix);
        for (key, chart) in map_report_charts(&r) {
            write_svg(
                Path::new(&format!("{prefix}-{key}.svg")),
                &map_chart_svg(&chart)?,
            )?;
        }
    }
    if o.flag("csv") {
        Ok(map_csv(&r))
    } else {
        json(&r)
    }
}

fn surrogate_cmd(args: &[String]) -> Result<String> {
    let mut values = vec!["approach", "plan", "predict"];
    values.extend(CAR_ROAD);
    let o = Opts::parse(args, &["json"], &values)?;
    let (car, road) = car_and_road(&o)?;
    let approach = o
        .str("approach")
        .ok_or_else(|| RideError::field("approach", "missing"))?;
    let plan = o.str("plan").unwrap_or("ae:10");
    let predict = match o.str("predict") {
        None => None,
        Some(p) => Some(
            p.strip_prefix("grid:")
                .and_then(|n| n.parse::<usize>().ok())
                .ok_or_else(|| RideError::field("predict", format!("'{p}' is not grid:N")))?,
        ),
    };
    let r = surrogate_report(approach, plan, &car, &road, predict)?;
    json(&r)
}

fn study_cmd(args: &[String]) -> Result<String> {
    let o = Opts::parse(args, &["json", "markdown"], &CAR_ROAD)?;
    let (car, road) = car_and_road(&o)?;
    let r = study(&car, &road)?;
    if o.flag("markdown") {
        Ok(r.to_markdown())
    } else {
        json(&r)
    }
}
