//! `ridelab report`: the study report as HTML, Markdown, SVG, JSON and CSV.

use crate::args::{count_u64, json, study_of, BoxArgs, CarRoad, ObjectiveArgs};
use clap::Args;
use ridelab::error::{Result, RideError};
use ridelab::report::SECTIONS;
use ridelab::study::StudySpec;
use ridelab::surrogate::{PlanSpec, SurrogateSpec};
use std::path::PathBuf;

#[derive(Args)]
pub(crate) struct ReportArgs {
    #[command(flatten)]
    pub(crate) car: CarRoad,
    #[command(flatten)]
    pub(crate) design_box: BoxArgs,
    #[command(flatten)]
    pub(crate) objectives: ObjectiveArgs,
    /// The surrogate of sections 4 and 5 [default: the study's best at 10 HiFi samples].
    #[arg(long, requires = "plan")]
    pub(crate) approach: Option<SurrogateSpec>,
    /// Its HiFi sampling plan: ae:N or grid:n.
    #[arg(long, requires = "approach")]
    pub(crate) plan: Option<PlanSpec>,
    /// Seed of the time-domain record and of NSGA-II.
    #[arg(long, default_value_t = 1, value_parser = count_u64, allow_negative_numbers = true)]
    pub(crate) seed: u64,
    /// Directory for report.html, report.md, figures/, report.json and the CSV tables
    /// (created if missing).
    #[arg(long, value_name = "DIR", default_value = "report")]
    pub(crate) out: PathBuf,
    /// A JSON summary on stdout (title, every file written, each section's time) instead
    /// of the one-line text.
    #[arg(long)]
    pub(crate) json: bool,
}

/// `report --json`: what was written where, and what each section took.
#[derive(serde::Serialize)]
struct Summary {
    title: String,
    out: String,
    /// Every file written, relative to `out`.
    files: Vec<String>,
    sections: Vec<SectionTime>,
    /// Rendering the documents and figures, and the whole run, s.
    render_seconds: f64,
    total_seconds: f64,
}

#[derive(serde::Serialize)]
struct SectionTime {
    name: &'static str,
    seconds: f64,
}

pub(crate) fn report_cmd(a: ReportArgs) -> Result<String> {
    let base = study_of(&a.car, None)?;
    let study = StudySpec {
        design_box: a.design_box.design_box()?,
        objectives: a.objectives.objectives()?,
        ..base
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
    let mut sections = Vec::new();
    let progress = |k| {
        let now = std::time::Instant::now();
        if let Some(prev) = last.1 {
            let seconds = (now - last.0).as_secs_f64();
            eprintln!("report: {} took {seconds:.2} s", SECTIONS[prev]);
            sections.push(SectionTime {
                name: SECTIONS[prev],
                seconds,
            });
        }
        if k < SECTIONS.len() {
            eprintln!("report: {} ...", SECTIONS[k]);
        }
        last = (now, Some(k));
    };
    let report = study.report(a.approach.zip(a.plan), a.seed, progress)?;
    // Nothing is written unless every number in the report is finite.
    ridelab::finite::check(&report)?;
    let render = std::time::Instant::now();
    let docs = report.documents()?;
    let mut files = Vec::new();
    let mut write = |name: String, text: &str| {
        let path = a.out.join(&name);
        std::fs::write(&path, text).map_err(|e| {
            RideError::field("out", format!("cannot write '{}': {e}", path.display()))
        })?;
        files.push(name);
        Ok::<(), RideError>(())
    };
    write("report.html".into(), &docs.html)?;
    write("report.md".into(), &docs.markdown)?;
    write("report.json".into(), &json(&report)?)?;
    for (name, text) in report.csv_files() {
        write(name.to_string(), &text)?;
    }
    for f in &docs.figures {
        write(format!("figures/{}.svg", f.key), &f.svg)?;
    }
    eprintln!(
        "report: rendering {} figures took {:.2} s; {:.2} s in all",
        docs.figures.len(),
        render.elapsed().as_secs_f64(),
        start.elapsed().as_secs_f64()
    );
    if a.json {
        return json(&Summary {
            title: report.title(),
            out: a.out.display().to_string(),
            files,
            sections,
            render_seconds: render.elapsed().as_secs_f64(),
            total_seconds: start.elapsed().as_secs_f64(),
        });
    }
    Ok(format!(
        "{}: {} (and report.md, report.json, {} figures, CSV tables)\n",
        report.title(),
        a.out.join("report.html").display(),
        docs.figures.len()
    ))
}
