//! The report as a sequence of blocks (headings, paragraphs, tables, figures), written
//! once and rendered twice: as HTML ([`super::html`]) and as Markdown ([`super::markdown`]),
//! so the two say the same thing with the same numbers.

use super::figures::Figure;
use super::{MethodReport, RouteRow};
use crate::dos::DesignObjectives;
use crate::model::Mode;
use crate::road_profile::RoadScenario;
use crate::study::fidelity::Outcome;

/// One block of the report.
#[derive(Debug, Clone, PartialEq)]
pub enum Block {
    /// A heading of level 1..3.
    Heading(u8, String),
    /// A paragraph of plain text.
    Paragraph(String),
    /// A table: header cells and rows of cells (numbers already formatted).
    Table(Vec<String>, Vec<Vec<String>>),
    /// A figure.
    Figure(Figure),
}

fn num(v: f64, digits: usize) -> String {
    format!("{v:.digits$}")
}

fn signed(v: f64, digits: usize) -> String {
    format!("{v:+.digits$}")
}

fn routes_table(rows: &[RouteRow]) -> Block {
    Block::Table(
        [
            "route",
            "BAcc [m/s^2]",
            "DTL [N]",
            "SWS [mm]",
            "largest difference from the first row",
        ]
        .map(String::from)
        .to_vec(),
        rows.iter()
            .map(|r| {
                vec![
                    r.route.clone(),
                    num(r.criteria.bacc, 6),
                    num(r.criteria.dtl, 3),
                    num(1e3 * r.criteria.sws, 4),
                    format!("{:.1e}", r.difference),
                ]
            })
            .collect(),
    )
}

fn modes_table(modes: &[Mode]) -> Block {
    Block::Table(
        [
            "mode",
            "natural frequency [Hz]",
            "damped frequency [Hz]",
            "damping ratio [-]",
        ]
        .map(String::from)
        .to_vec(),
        modes
            .iter()
            .map(|m| {
                vec![
                    m.label.clone(),
                    num(m.frequency, 3),
                    num(m.damped_frequency, 3),
                    num(m.damping_ratio, 3),
                ]
            })
            .collect(),
    )
}

fn objectives_text(o: &DesignObjectives) -> String {
    let mut parts = Vec::new();
    if let Some(l) = o.sws_limit {
        parts.push(format!("RMS SWS at most {} mm", num(1e3 * l, 2)));
    }
    if let Some((lo, hi)) = o.bounce_band {
        parts.push(format!("body bounce {lo} to {hi} Hz"));
    }
    if let Some((lo, hi)) = o.damping_band {
        parts.push(format!("damping ratio {lo} to {hi}"));
    }
    for (on, name) in o.no_worse_than_datum.iter().zip(["BAcc", "DTL", "SWS"]) {
        if *on {
            parts.push(format!("{name} no worse than the datum"));
        }
    }
    if parts.is_empty() {
        "none".into()
    } else {
        parts.join("; ")
    }
}

/// The report's blocks with its figures in place (`figures` by section, from
/// [`super::figures::figures`]).
pub fn blocks(r: &MethodReport, figures: Vec<(usize, Vec<Figure>)>) -> Vec<Block> {
    let mut figs: Vec<Vec<Figure>> = vec![Vec::new(); 6];
    for (section, f) in figures {
        figs[section] = f;
    }
    let mut out = Vec::new();
    let s = &r.scenario;
    let car = &s.car;
    out.push(Block::Heading(
        1,
        match &s.road {
            RoadScenario::Iso(road) => format!(
                "RideLab study report: {} on an ISO 8608 class {:?} road at {} m/s",
                car.name, road.class, road.speed
            ),
            RoadScenario::Measured(m) => format!(
                "RideLab study report: {} on the measured road {} at {} m/s",
                car.name, m.file, m.speed
            ),
        },
    ));
    out.push(Block::Paragraph(format!(
        "Surrogate-based design of the front spring rate Ks and damper rate Cs, end to end: model verification, design maps, sampling, surrogates and Pareto fronts (RideLab {}). Every number below is computed by the RideLab core for this car, road and design box.",
        r.version
    )));
    // 1. Scenario and verification.
    out.push(Block::Heading(
        2,
        "1 The car, the road and the models".into(),
    ));
    out.push(Block::Table(
        vec!["quantity".into(), "value".into()],
        vec![
            vec!["car".into(), format!("{} ({})", car.name, car.source)],
            vec![
                "sprung mass, pitch and roll inertia".into(),
                format!(
                    "{} kg, {} kg m^2, {} kg m^2",
                    car.sprung_mass, car.pitch_inertia, car.roll_inertia
                ),
            ],
            vec![
                "CG to front and rear axle; tracks".into(),
                format!(
                    "{} m, {} m; {} m front, {} m rear",
                    car.a, car.b, car.track_front, car.track_rear
                ),
            ],
            vec![
                "front corner (datum design)".into(),
                format!(
                    "unsprung {} kg, Ks {} N/m, Cs {} Ns/m, tyre {} N/m",
                    car.front.unsprung_mass,
                    car.front.spring,
                    car.front.damper,
                    car.front.tire_stiffness
                ),
            ],
            vec![
                "rear corner".into(),
                format!(
                    "unsprung {} kg, Ks {} N/m, Cs {} Ns/m, tyre {} N/m",
                    car.rear.unsprung_mass,
                    car.rear.spring,
                    car.rear.damper,
                    car.rear.tire_stiffness
                ),
            ],
            vec![
                "quarter car (LoFi), ms = M b / (2 L)".into(),
                format!("{} kg sprung, {} kg unsprung", num(s.quarter.ms, 2), s.quarter.mu),
            ],
            vec![
                "road".into(),
                match &s.road {
                    RoadScenario::Measured(m) => format!(
                        "the measured profile {} at {} m/s, {} tracks; shaping filters over {}..{} Hz within {:.1} % of its Welch PSD; rear delay {} s",
                        m.file,
                        m.speed,
                        <&str>::from(m.tracks),
                        m.band_hz[0],
                        m.band_hz[1],
                        100.0 * m.fit_error,
                        num(s.delay, 4)
                    ),
                    RoadScenario::Iso(road) => format!(
                        "class {:?} at {} m/s, {:?} tracks; road velocity PSD {:.4e} m^2/s^2/Hz; rear delay {} s",
                        road.class,
                        road.speed,
                        road.tracks,
                        s.velocity_psd.unwrap_or_default(),
                        num(s.delay, 4)
                    ),
                },
            ],
            vec![
                "design box".into(),
                format!(
                    "Ks {} to {} kN/m, Cs {} to {} kNs/m",
                    s.design_box.ks_min / 1e3,
                    s.design_box.ks_max / 1e3,
                    s.design_box.cs_min / 1e3,
                    s.design_box.cs_max / 1e3
                ),
            ],
            vec!["design objectives".into(), objectives_text(&s.objectives)],
            vec![
                "static front wheel load".into(),
                format!("{} N", num(s.static_wheel_load, 1)),
            ],
        ],
    ));
    let v = &r.verification;
    out.push(Block::Heading(
        3,
        "Model verification at the datum design".into(),
    ));
    out.push(Block::Paragraph(match &s.road {
        RoadScenario::Iso(_) => format!(
            "RMS criteria at the front corner over the whole band by independent routes. The time-domain record is {} s long at a {} s step (seed {}); its RMS carries the statistical error of a finite record (a few per cent).",
            v.record.duration, v.record.dt, v.record.seed
        ),
        RoadScenario::Measured(_) => format!(
            "RMS criteria at the front corner by independent routes: exact with the road's shaping filters, in frequency on the measured PSD, and in time with the profile itself played back under the wheels from rest for {:.0} s at a {:.3e} s step (its RMS carries the start-up and the statistical error of one finite profile: a few per cent).",
            v.record.duration, v.record.dt
        ),
    }));
    out.push(Block::Paragraph("LoFi (2-DOF quarter car):".into()));
    out.push(routes_table(&v.lofi));
    out.push(Block::Paragraph("HiFi (7-DOF full car):".into()));
    out.push(routes_table(&v.hifi));
    for n in &v.notes {
        out.push(Block::Paragraph(format!("Note: {n}.")));
    }
    out.push(Block::Paragraph(
        "ISO 2631-1 frequency-weighted comfort (Wk, Annex A) at the datum design, by the exact \
         route (the Wk filter appended to the model) and by frequency integration, with Annex \
         C's likely reaction:"
            .into(),
    ));
    out.push(Block::Table(
        [
            "model",
            "BAcc [m/s^2]",
            "Wk-weighted, exact [m/s^2]",
            "Wk-weighted, frequency route [m/s^2]",
            "ISO 2631-1 Annex C",
        ]
        .map(String::from)
        .to_vec(),
        v.comfort
            .iter()
            .map(|c| {
                vec![
                    c.model.clone(),
                    format!("{:.6}", c.bacc),
                    format!("{:.6}", c.exact),
                    format!("{:.6}", c.spectral),
                    c.label.clone(),
                ]
            })
            .collect(),
    ));
    out.push(Block::Paragraph("Modes of the LoFi:".into()));
    out.push(modes_table(&v.lofi_modes));
    out.push(Block::Paragraph("Modes of the HiFi:".into()));
    out.push(modes_table(&v.hifi_modes));
    out.extend(figs[1].drain(..).map(Block::Figure));
    // 2. Maps.
    out.push(Block::Heading(
        2,
        "2 Design criteria and objective space".into(),
    ));
    for (name, m) in [("LoFi", &r.maps.lofi), ("HiFi", &r.maps.hifi)] {
        let f = &m.feasibility.summary;
        out.push(Block::Paragraph(format!(
            "{name}: {} x {} grid over the design box; {} of {} designs meet the objectives ({}).{}",
            m.grid.ks.n,
            m.grid.cs.n,
            f.feasible,
            f.total,
            objectives_text(&m.feasibility.objectives),
            f.message.as_ref().map_or(String::new(), |msg| format!(" {msg}")),
        )));
    }
    out.extend(figs[2].drain(..).map(Block::Figure));
    // 3. Sampling.
    out.push(Block::Heading(2, "3 Sampling plans".into()));
    out.push(Block::Paragraph(
        "Audze-Eglais Latin hypercubes: N points on an N-level lattice, one per row and column, minimising the potential energy E = sum 1 / L_ij^2 of their gaps (lattice units).".into(),
    ));
    out.push(Block::Table(
        ["points", "energy", "optimal", "smallest gap", "method"]
            .map(String::from)
            .to_vec(),
        r.sampling
            .iter()
            .map(|p| {
                vec![
                    p.points.to_string(),
                    num(p.energy, 6),
                    if p.optimal { "yes" } else { "no" }.into(),
                    num(p.min_gap, 4),
                    p.method.clone(),
                ]
            })
            .collect(),
    ));
    out.extend(figs[3].drain(..).map(Block::Figure));
    // 4. Fidelity study.
    let st = &r.fidelity.study;
    out.push(Block::Heading(2, "4 Surrogates: the fidelity study".into()));
    out.push(Block::Paragraph(format!(
        "Every surrogate on every plan, validated on the {n} x {n} HiFi grid ({} HiFi evaluations in all). Best = {}. The untuned LoFi's worst max RTE is {} %.",
        st.hifi_evaluations,
        st.ranking,
        num(
            st.lofi.to_array().iter().map(|m| m.rte_max).fold(0.0, f64::max),
            3
        ),
        n = st.validation_levels
    )));
    out.push(Block::Table(
        [
            "HiFi samples",
            "best surrogate",
            "plan",
            "worst max RTE [%]",
            "least R^2",
        ]
        .map(String::from)
        .to_vec(),
        st.best_per_budget
            .iter()
            .map(|b| {
                vec![
                    b.samples.to_string(),
                    b.surrogate.clone(),
                    b.plan.clone(),
                    num(b.fitted.worst_rte_max, 3),
                    num(b.fitted.min_r2, 5),
                ]
            })
            .collect(),
    ));
    out.push(Block::Paragraph("Every row of the study:".into()));
    out.push(Block::Table(
        [
            "surrogate",
            "plan",
            "samples",
            "worst max RTE [%]",
            "least R^2",
        ]
        .map(String::from)
        .to_vec(),
        st.rows
            .iter()
            .map(|row| {
                let (rte, r2) = match &row.outcome {
                    Outcome::Fitted(f) => (num(f.worst_rte_max, 3), num(f.min_r2, 5)),
                    Outcome::Skipped { reason } => (format!("skipped: {reason}"), String::new()),
                };
                vec![
                    row.surrogate.clone(),
                    row.plan.clone(),
                    row.samples.to_string(),
                    rte,
                    r2,
                ]
            })
            .collect(),
    ));
    let c = &r.fidelity.chosen;
    out.push(Block::Paragraph(format!(
        "The report goes on with {} on {} ({}): worst max RTE {} % on the validation grid.",
        c.surrogate,
        c.plan,
        r.fidelity.chosen_because,
        num(
            c.metrics
                .to_array()
                .iter()
                .map(|m| m.rte_max)
                .fold(0.0, f64::max),
            3
        )
    )));
    out.extend(figs[4].drain(..).map(Block::Figure));
    // 5. Fronts.
    let o = &r.optimisation;
    out.push(Block::Heading(
        2,
        "5 Pareto fronts and the min-max pick".into(),
    ));
    match &o.infeasible {
        Some(why) => out.push(Block::Paragraph(format!(
            "No design in the box meets the design objectives on this road, so there is no front and no pick: {why}"
        ))),
        None => {
            let mut lines = Vec::new();
            for rep in [&o.stm, &o.nsga2, &o.hifi].into_iter().flatten() {
                lines.push(format!(
                    "{} on {}: {} front points, hypervolume {} (m/s^2) N against the reference point [{}, {}], {} evaluations",
                    match rep.study.method {
                        crate::optimize::Method::Stm(_) => "STM",
                        crate::optimize::Method::Nsga2(_) => "NSGA-II",
                    },
                    rep.study.evaluator,
                    rep.study.front.len(),
                    num(rep.study.hypervolume, 4),
                    num(rep.study.reference_point[0], 4),
                    num(rep.study.reference_point[1], 2),
                    rep.study.evaluations
                ));
            }
            if let Some(d) = &o.stm_to_hifi {
                lines.push(format!(
                    "the surrogate's STM front against the HiFi's: IGD {}, GD {} (normalised plane)",
                    num(d.igd, 4),
                    num(d.gd, 4)
                ));
            }
            out.push(Block::Paragraph(lines.join(". ") + "."));
            out.push(Block::Table(
                ["design", "Ks [N/m]", "Cs [Ns/m]", "BAcc vs datum [%]", "DTL vs datum [%]", "SWS [mm]"]
                    .map(String::from)
                    .to_vec(),
                o.table
                    .iter()
                    .map(|p| {
                        vec![
                            p.design.clone(),
                            num(p.ks, 1),
                            num(p.cs, 1),
                            signed(p.bacc_percent, 2),
                            signed(p.dtl_percent, 2),
                            num(1e3 * p.sws, 3),
                        ]
                    })
                    .collect(),
            ));
            out.push(Block::Paragraph(
                "Picks beyond min-max on the surrogate's STM front: the knee (least sum of the \
                 normalised distances from the ideal point) and the weighted pick (achievement \
                 scalarising function, comfort weight W), each with its pseudo-weights and re-checked \
                 on the HiFi."
                    .into(),
            ));
            out.push(Block::Table(
                [
                    "pick",
                    "Ks [N/m]",
                    "Cs [Ns/m]",
                    "pseudo-weights (comfort, road holding)",
                    "BAcc vs datum [%], surrogate (HiFi)",
                    "DTL vs datum [%], surrogate (HiFi)",
                    "largest prediction error [%]",
                ]
                .map(String::from)
                .to_vec(),
                o.picks
                    .iter()
                    .map(|p| {
                        vec![
                            p.rule.clone(),
                            num(p.ks, 1),
                            num(p.cs, 1),
                            format!(
                                "{}, {}",
                                num(p.pseudo_weights[0], 2),
                                num(p.pseudo_weights[1], 2)
                            ),
                            format!(
                                "{} ({})",
                                signed(p.predicted_change_percent[0], 2),
                                signed(p.rechecked_change_percent[0], 2)
                            ),
                            format!(
                                "{} ({})",
                                signed(p.predicted_change_percent[1], 2),
                                signed(p.rechecked_change_percent[1], 2)
                            ),
                            num(
                                p.error_percent.iter().fold(0.0f64, |m, e| m.max(e.abs())),
                                3,
                            ),
                        ]
                    })
                    .collect(),
            ));
        }
    }
    out.extend(figs[5].drain(..).map(Block::Figure));
    adaptive_blocks(&r.adaptive, &mut out);
    let t = &r.thesis;
    out.push(Block::Heading(3, "The seed thesis's result".into()));
    out.push(Block::Table(
        [
            "design",
            "Ks [N/m]",
            "Cs [Ns/m]",
            "BAcc vs datum [%]",
            "DTL vs datum [%]",
            "SWS [mm]",
        ]
        .map(String::from)
        .to_vec(),
        vec![vec![
            "seed thesis's min-max pick (its own datum car)".into(),
            num(t.ks, 1),
            num(t.cs, 1),
            signed(t.bacc_percent, 1),
            signed(t.dtl_percent, 1),
            "under 7".into(),
        ]],
    ));
    out.push(Block::Paragraph(t.note.clone()));
    out
}

/// Section 6: the adaptive loop's samples in order with their reasons, the front's
/// hypervolume per HiFi run, and the two picks re-checked on the HiFi.
fn adaptive_blocks(a: &super::AdaptiveSection, out: &mut Vec<Block>) {
    out.push(Block::Heading(2, "6 Adaptive sampling".into()));
    let Some(run) = &a.run else {
        let why = a.skipped.as_deref().unwrap_or("not run");
        out.push(Block::Paragraph(format!("Not run: {why}.")));
        return;
    };
    let ad = &run.adaptive;
    out.push(Block::Paragraph(format!(
        "The same surrogate ({}) fitted to an Audze-Eglais plan ({}) and then to one HiFi run at a time, \
         each where the {} uncertainty gives the largest expected improvement of the feasible front's \
         hypervolume (reference point [{}, {}]); the table lists the runs in the order they were added.",
        ad.surrogate,
        ad.plan,
        ad.uncertainty.name(),
        num(ad.reference_point[0], 4),
        num(ad.reference_point[1], 2),
    )));
    out.push(Block::Table(
        ["HiFi run", "Ks [N/m]", "Cs [Ns/m]", "why"]
            .map(String::from)
            .to_vec(),
        ad.added
            .iter()
            .map(|x| {
                vec![
                    x.run.to_string(),
                    num(x.sample.ks, 1),
                    num(x.sample.cs, 1),
                    x.reason.clone(),
                ]
            })
            .collect(),
    ));
    out.push(Block::Table(
        [
            "HiFi runs",
            "front points",
            "hypervolume [(m/s^2) N]",
            "pick Ks [N/m]",
            "pick Cs [Ns/m]",
        ]
        .map(String::from)
        .to_vec(),
        ad.history
            .iter()
            .map(|h| {
                vec![
                    h.hifi_runs.to_string(),
                    h.front_points.to_string(),
                    num(h.hypervolume, 5),
                    num(h.pick.ks, 1),
                    num(h.pick.cs, 1),
                ]
            })
            .collect(),
    ));
    out.push(Block::Paragraph(
        "The plan's pick against the adaptive pick, each predicted by its surrogate and re-checked on the HiFi:".into(),
    ));
    out.push(Block::Table(
        [
            "samples",
            "HiFi runs",
            "Ks [N/m]",
            "Cs [Ns/m]",
            "BAcc error [%]",
            "DTL error [%]",
            "SWS error [%]",
            "BAcc vs datum, HiFi [%]",
            "DTL vs datum, HiFi [%]",
        ]
        .map(String::from)
        .to_vec(),
        a.comparison
            .iter()
            .map(|c| {
                vec![
                    c.samples.clone(),
                    c.hifi_runs.to_string(),
                    num(c.ks, 1),
                    num(c.cs, 1),
                    signed(c.error_percent[0], 3),
                    signed(c.error_percent[1], 3),
                    signed(c.error_percent[2], 3),
                    signed(c.rechecked_change_percent[0], 2),
                    signed(c.rechecked_change_percent[1], 2),
                ]
            })
            .collect(),
    ));
}
