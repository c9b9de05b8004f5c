//! `ridelab`: the command-line shell over the RideLab core (scripting, batch studies,
//! reports). Argument parsing (clap's derive API, with the core's types parsed by their
//! `FromStr`) and printing only; every number and every rule comes from the library.
//!
//! Every bad input gives exactly one line on stderr, `error: <option>: <reason>`, naming
//! the option at fault (the same messages as the page), and exit code 2.

use clap::error::{ContextKind, ContextValue, ErrorKind};
use clap::{Parser, Subcommand};
use doe::DoeArgs;
use eval::EvalArgs;
use map::MapArgs;
use optimize::OptimizeArgs;
use presets::PresetsArgs;
use report::ReportArgs;
use ridelab::error::{Result, RideError};
use simulate::SimulateArgs;
use study::StudyArgs;
use surrogate::SurrogateArgs;

mod args;
mod doe;
mod eval;
mod map;
mod optimize;
mod presets;
mod report;
mod road;
mod simulate;
mod study;
mod surrogate;
mod text;
mod units;

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
    /// A measured road profile described: its PSD (Welch), ISO 8608 class and waviness,
    /// the tracks' coherence.
    Road(road::RoadArgs),
    /// A shell completion script on stdout, e.g. `ridelab completions bash >
    /// ~/.local/share/bash-completion/completions/ridelab`.
    Completions(CompletionsArgs),
}

#[derive(clap::Args)]
struct CompletionsArgs {
    /// The shell.
    shell: clap_complete::Shell,
}

/// The completion script of `shell` for every command and option of [`Cli`].
fn completions(a: CompletionsArgs) -> Result<String> {
    use clap::CommandFactory;
    let mut out = Vec::new();
    clap_complete::generate(a.shell, &mut Cli::command(), "ridelab", &mut out);
    String::from_utf8(out).map_err(|e| RideError::Numerical(format!("completion script: {e}")))
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
        .trim_matches(['<', '>'])
        .to_lowercase()
        .replace('_', "-");
    match e.kind() {
        ErrorKind::InvalidSubcommand | ErrorKind::MissingSubcommand => format!(
            "command: {} (eval, doe, optimize, map, surrogate, study, simulate, presets, report, road, completions; --help lists them)",
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
        Command::Eval(a) => eval::eval(a),
        Command::Doe(a) => doe::doe(a),
        Command::Optimize(a) => optimize::optimize(a),
        Command::Map(a) => map::map_cmd(a),
        Command::Surrogate(a) => surrogate::surrogate_cmd(a),
        Command::Study(a) => study::study_cmd(a),
        Command::Simulate(a) => simulate::simulate_cmd(a),
        Command::Presets(a) => presets::presets(a),
        Command::Report(a) => report::report_cmd(a),
        Command::Completions(a) => completions(a),
        Command::Road(a) => road::road_cmd(a),
    }
}
