//! Adaptive HiFi sampling against fixed Audze-Eglais plans (issue #15): 5 Audze-Eglais +
//! 5 adaptive HiFi runs give a front at least as good on the HiFi as a 10-point
//! Audze-Eglais plan, with a pick the HiFi confirms at least as well, on four scenarios;
//! the loop is deterministic, the step-by-step API (the page's) equals `run` (the CLI's),
//! and every bound names its field.
//!
//! Every front here (the HiFi's own reference front too) is found by STM on a 101 x 101
//! grid with 3 refinement levels, a quarter of the CLI's default work, to keep the tests
//! quick; `adaptive_study` (and the README's table) uses the default 201 x 201.

use ridelab::dos::DosContext;
use ridelab::optimize::StmParams;
use ridelab::study::adaptive::{
    adaptive_study, front_check, run, AdaptiveLoop, AdaptiveOptions, Decision, FrontCheck,
    HifiFront, StudyOptions, MAX_HIFI_RUNS,
};
use ridelab::surrogate::infill::Infill;
use ridelab::surrogate::uncertainty::UncertaintyMethod;
use ridelab::surrogate::{sample_plan, LmOptions, PlanSpec, Setting, SurrogateSpec};
use ridelab::{Car, DesignBox, HiFi, Road, RoadClass};
use std::time::Instant;

fn decision(car: &Car, hifi: &HiFi, grid: usize, levels: usize) -> Decision {
    Decision {
        stm: StmParams { grid, levels },
        ..Decision::of_car(car, hifi).unwrap()
    }
}

/// The claim of the issue, with the default criterion (EHVI over the surrogate's own
/// predicted front, times the probability of meeting the SWS limit) and two surrogates:
/// gp-mul with its own predictive variance and rba-mul-rbf-mq with the leave-one-out
/// estimate. Cars: the datum sedan, the compact and the SUV presets on class B at 20 m/s,
/// and the sedan on class A at 30 m/s.
///
/// Not asserted for VBA (vba-qts): its few shared parameters are fitted by least squares
/// over all samples, so samples placed at the front re-weight one global fit instead of
/// correcting the surrogate there; in this run's exploration its 5 + 5 front lost
/// hypervolume against AE 10 on the sedan and the SUV (0.9971 vs 0.9980, 0.9986 vs 0.9992
/// of the HiFi front) while its pick re-check improved everywhere. The other infill front,
/// EHVI over the feasible HiFi samples (`ehvi`), crowds its runs at the soft-spring end of
/// the front and fell short of AE 10 by 1.5e-6 and 5.5e-6 of the HiFi hypervolume on the
/// compact car, so it is not the default.
#[test]
fn five_adaptive_runs_beat_ten_audze_eglais_points_on_four_scenarios() {
    let class_a = Road {
        class: RoadClass::A,
        speed: 30.0,
        ..Road::default()
    };
    let b = DesignBox::default();
    let start = Instant::now();
    for (car, road) in [
        (Car::datum(), Road::default()),
        (Car::preset("compact").unwrap(), Road::default()),
        (Car::preset("suv").unwrap(), Road::default()),
        (Car::datum(), class_a),
    ] {
        let setting = Setting::new(&car, &road, &b).unwrap();
        let hifi = HiFi::new(&car, &road).unwrap();
        let decision = decision(&car, &hifi, 101, 3);
        let reference = HifiFront::new(&hifi, &decision, &b).unwrap();
        let ae10 = sample_plan(&hifi, &PlanSpec::AudzeEglais(10).plan().unwrap(), &b).unwrap();
        for (name, method) in [
            ("gp-mul", UncertaintyMethod::Model),
            ("rba-mul-rbf-mq", UncertaintyMethod::Loo),
        ] {
            let spec = SurrogateSpec::parse(name).unwrap();
            let fixed = spec.fit(&setting, &ae10, &LmOptions::default()).unwrap();
            let fixed = front_check(&fixed, &hifi, &decision, &b, &reference, 10).unwrap();
            let options = AdaptiveOptions {
                runs: 5,
                uncertainty: Some(method),
                ..AdaptiveOptions::default()
            };
            assert_eq!(options.criterion, Infill::EhviFront);
            let state = run(
                spec,
                &setting,
                &hifi,
                PlanSpec::AudzeEglais(5),
                &decision,
                options,
            )
            .unwrap();
            let looped = front_check(state.model(), &hifi, &decision, &b, &reference, 10).unwrap();
            let show = |c: &FrontCheck| {
                format!(
                    "HV {:.7}, re-check {:.4} %, front error {:.3} %",
                    c.hypervolume_ratio, c.recheck_error_percent, c.front_max_error_percent
                )
            };
            eprintln!(
                "{} {:?} {} m/s, {name}: 5 + 5 {} | AE 10 {}",
                car.name,
                road.class,
                road.speed,
                show(&looped),
                show(&fixed)
            );
            assert!(
                looped.hypervolume_ratio >= fixed.hypervolume_ratio,
                "{} {name}: HV {} < {}",
                car.name,
                looped.hypervolume_ratio,
                fixed.hypervolume_ratio
            );
            assert!(
                looped.recheck_error_percent <= fixed.recheck_error_percent,
                "{} {name}: re-check {} > {}",
                car.name,
                looped.recheck_error_percent,
                fixed.recheck_error_percent
            );
            // Ten samples: the Audze-Eglais five first, then five new designs, none within
            // the minimum distance of another.
            let samples = state.samples();
            assert_eq!(samples.len(), 10);
            let ae5 = sample_plan(&hifi, &PlanSpec::AudzeEglais(5).plan().unwrap(), &b).unwrap();
            assert_eq!(&samples[..5], &ae5[..]);
            for (i, p) in samples.iter().enumerate() {
                for q in &samples[..i] {
                    let (pu, pv) = b.normalize(p.ks, p.cs);
                    let (qu, qv) = b.normalize(q.ks, q.cs);
                    assert!((pu - qu).hypot(pv - qv) >= options.min_distance);
                }
            }
            let report = state.report();
            assert_eq!(report.added.len(), 5);
            assert_eq!(report.history.len(), 6);
            assert!(report.added.iter().all(|a| a
                .reason
                .starts_with("largest expected hypervolume improvement")));
        }
    }
    eprintln!("four scenarios: {:.1} s", start.elapsed().as_secs_f64());
}

/// Deterministic for a seed (VBA's Levenberg-Marquardt starts are the seeded part), and
/// the page's way (propose, run the HiFi, add) gives the CLI's `run` exactly.
#[test]
fn deterministic_and_the_step_api_equals_run() {
    let (car, road, b) = (Car::datum(), Road::default(), DesignBox::default());
    let setting = Setting::new(&car, &road, &b).unwrap();
    let hifi = HiFi::new(&car, &road).unwrap();
    let decision = decision(&car, &hifi, 61, 2);
    for name in ["vba-qts", "gp-mul"] {
        let spec = SurrogateSpec::parse(name).unwrap();
        let options = AdaptiveOptions {
            runs: 3,
            seed: 7,
            ..AdaptiveOptions::default()
        };
        let go = || {
            run(
                spec,
                &setting,
                &hifi,
                PlanSpec::AudzeEglais(6),
                &decision,
                options,
            )
        };
        let (a, b2) = (go().unwrap(), go().unwrap());
        assert_eq!(a.report(), b2.report(), "{name}");
        assert_eq!(a.samples(), b2.samples());
        // By hand, one proposal at a time.
        let initial = sample_plan(&hifi, &PlanSpec::AudzeEglais(6).plan().unwrap(), &b).unwrap();
        let mut by_hand = AdaptiveLoop::new(
            spec,
            setting.clone(),
            decision.clone(),
            "ae:6".into(),
            initial,
            options,
        )
        .unwrap();
        for _ in 0..3 {
            let p = by_hand.propose().unwrap();
            let c = ridelab::Evaluator::evaluate(&hifi, p.candidate.ks, p.candidate.cs).unwrap();
            by_hand.add(p, c).unwrap();
        }
        assert_eq!(by_hand.report(), a.report(), "{name}");
        assert_eq!(by_hand.front(), a.front());
    }
}

/// The stop rule (issue #30): with a threshold `r`, `run` adds runs while the best
/// candidate's `EHVI x PoF` is at least `r` times the front's hypervolume before it, and
/// stops at the first proposal below, saying so; the same loop with `r = 0` runs all `K`
/// and its first runs are the stopped loop's (the rule only ends the loop). Checked here
/// from the report's own candidates and history, not from the loop's flag.
#[test]
fn the_loop_stops_when_the_expected_improvement_is_negligible() {
    let (car, road, b) = (Car::datum(), Road::default(), DesignBox::default());
    let setting = Setting::new(&car, &road, &b).unwrap();
    let hifi = HiFi::new(&car, &road).unwrap();
    let decision = decision(&car, &hifi, 61, 2);
    let spec = SurrogateSpec::parse("gp-mul").unwrap();
    let go = |stop_below| {
        run(
            spec,
            &setting,
            &hifi,
            PlanSpec::AudzeEglais(5),
            &decision,
            AdaptiveOptions {
                runs: 8,
                candidates: 21,
                stop_below,
                ..AdaptiveOptions::default()
            },
        )
        .unwrap()
    };
    let all = go(0.0).report();
    assert_eq!(all.added.len(), 8);
    assert!(all.stopped.is_none());
    // A threshold between the 3rd and the 4th run's relative criterion stops after 3.
    let rel: Vec<f64> = all
        .added
        .iter()
        .zip(&all.history)
        .map(|(a, h)| a.candidate.value / h.hypervolume)
        .collect();
    let k = (1..rel.len())
        .find(|&k| rel[k] < rel[..k].iter().cloned().fold(f64::INFINITY, f64::min))
        .expect("the criterion falls at some run");
    let r = (rel[k] * rel[..k].iter().cloned().fold(f64::INFINITY, f64::min)).sqrt();
    let stopped = go(r).report();
    assert_eq!(
        stopped.added.len(),
        k,
        "relative criteria {rel:?}, threshold {r:e}"
    );
    assert_eq!(stopped.added[..], all.added[..k]);
    let why = stopped.stopped.expect("it says why it stopped");
    assert!(
        why.starts_with(&format!("stopped after {k} of 8 adaptive runs")),
        "{why}"
    );
    assert!(why.contains("converged"), "{why}");
    // A threshold out of range is refused naming the field.
    let bad = run(
        spec,
        &setting,
        &hifi,
        PlanSpec::AudzeEglais(5),
        &decision,
        AdaptiveOptions {
            runs: 1,
            stop_below: 0.5,
            ..AdaptiveOptions::default()
        },
    );
    assert!(
        matches!(bad, Err(ridelab::RideError::Field { ref field, .. }) if field == "stop-below")
    );
}

#[test]
fn bounds_and_bad_options_name_the_field() {
    let (car, road, b) = (Car::datum(), Road::default(), DesignBox::default());
    let setting = Setting::new(&car, &road, &b).unwrap();
    let hifi = HiFi::new(&car, &road).unwrap();
    let decision = decision(&car, &hifi, 41, 1);
    let spec = SurrogateSpec::parse("gp-mul").unwrap();
    assert_eq!(MAX_HIFI_RUNS, 100);
    let cases = [
        (
            AdaptiveOptions {
                runs: 96,
                ..AdaptiveOptions::default()
            },
            "adaptive",
        ),
        (
            AdaptiveOptions {
                runs: usize::MAX,
                ..AdaptiveOptions::default()
            },
            "adaptive",
        ),
        (
            AdaptiveOptions {
                candidates: 1,
                ..AdaptiveOptions::default()
            },
            "candidates",
        ),
        (
            AdaptiveOptions {
                candidates: 202,
                ..AdaptiveOptions::default()
            },
            "candidates",
        ),
        (
            AdaptiveOptions {
                min_distance: 0.0,
                ..AdaptiveOptions::default()
            },
            "min-distance",
        ),
        (
            AdaptiveOptions {
                min_distance: f64::NAN,
                ..AdaptiveOptions::default()
            },
            "min-distance",
        ),
        (
            AdaptiveOptions {
                min_distance: 0.6,
                ..AdaptiveOptions::default()
            },
            "min-distance",
        ),
    ];
    for (options, field) in cases {
        let e = run(
            spec,
            &setting,
            &hifi,
            PlanSpec::AudzeEglais(5),
            &decision,
            options,
        )
        .err()
        .unwrap()
        .to_string();
        assert!(e.starts_with(&format!("{field}: ")), "{e}");
    }
    // 95 + 5 is the most allowed: the check passes (the runs are not made here).
    assert!(AdaptiveOptions {
        runs: 5,
        ..AdaptiveOptions::default()
    }
    .check(95)
    .is_ok());
    // Too small a plan for the surrogate, and a model variance a surrogate lacks.
    let e = run(
        spec,
        &setting,
        &hifi,
        PlanSpec::AudzeEglais(2),
        &decision,
        AdaptiveOptions::default(),
    )
    .err()
    .unwrap()
    .to_string();
    assert!(e.starts_with("plan: "), "{e}");
    let vba = SurrogateSpec::parse("vba-qts").unwrap();
    let options = AdaptiveOptions {
        uncertainty: Some(UncertaintyMethod::Model),
        ..AdaptiveOptions::default()
    };
    let e = run(
        vba,
        &setting,
        &hifi,
        PlanSpec::AudzeEglais(5),
        &decision,
        options,
    )
    .err()
    .unwrap()
    .to_string();
    assert!(e.starts_with("uncertainty: "), "{e}");
    // A minimum distance that covers the box: nothing left to propose.
    let options = AdaptiveOptions {
        runs: 1,
        min_distance: 0.5,
        ..AdaptiveOptions::default()
    };
    let e = run(spec, &setting, &hifi, PlanSpec::Grid(3), &decision, options)
        .err()
        .unwrap()
        .to_string();
    assert!(e.starts_with("adaptive: every candidate"), "{e}");
    // An infeasible scenario names the binding objective.
    let infeasible = Decision {
        objectives: ridelab::dos::DesignObjectives {
            sws_limit: Some(0.001),
            ..Default::default()
        },
        ctx: DosContext::of_model(&car, &hifi).unwrap(),
        ..decision
    };
    let e = run(
        spec,
        &setting,
        &hifi,
        PlanSpec::AudzeEglais(5),
        &infeasible,
        AdaptiveOptions::default(),
    )
    .err()
    .unwrap()
    .to_string();
    assert!(e.starts_with("sws_limit: "), "{e}");
}

/// The study as a library function, small: its rows are the loop's prefixes and fresh
/// Audze-Eglais plans judged by `front_check`, re-derived here.
#[test]
fn the_study_rows_are_the_loop_and_the_plans() {
    let (car, road, b) = (Car::datum(), Road::default(), DesignBox::default());
    let options = StudyOptions {
        initial: 5,
        min_runs: 7,
        max_runs: 8,
        stm: StmParams {
            grid: 61,
            levels: 2,
        },
        ..StudyOptions::default()
    };
    let spec = SurrogateSpec::parse("gp-mul").unwrap();
    let study = adaptive_study(&car, &road, spec, &options).unwrap();
    assert_eq!(
        study.rows.iter().map(|r| r.hifi_runs).collect::<Vec<_>>(),
        [7, 8]
    );
    assert_eq!(study.samples.len(), 8);
    assert_eq!(study.reasons.len(), 3);
    assert!(study.seconds.is_some_and(|t| t > 0.0));
    let hifi = HiFi::new(&car, &road).unwrap();
    let setting = Setting::new(&car, &road, &b).unwrap();
    let decision = decision(&car, &hifi, 61, 2);
    let reference = HifiFront::new(&hifi, &decision, &b).unwrap();
    assert_eq!(reference.hypervolume, study.hifi_front.hypervolume);
    let state = run(
        spec,
        &setting,
        &hifi,
        PlanSpec::AudzeEglais(5),
        &decision,
        AdaptiveOptions {
            runs: 2,
            ..AdaptiveOptions::default()
        },
    )
    .unwrap();
    assert_eq!(state.samples(), &study.samples[..7]);
    let looped = front_check(state.model(), &hifi, &decision, &b, &reference, 7).unwrap();
    assert_eq!(looped, study.rows[0].adaptive);
    let ae = sample_plan(&hifi, &PlanSpec::AudzeEglais(8).plan().unwrap(), &b).unwrap();
    let fixed = spec.fit(&setting, &ae, &LmOptions::default()).unwrap();
    let fixed = front_check(&fixed, &hifi, &decision, &b, &reference, 8).unwrap();
    assert_eq!(fixed, study.rows[1].audze_eglais);
    let md = study.to_markdown();
    assert!(md.contains("| 8 | "), "{md}");
    for (field, o) in [
        (
            "initial",
            StudyOptions {
                initial: 1,
                ..options.clone()
            },
        ),
        (
            "min_runs",
            StudyOptions {
                min_runs: 5,
                ..options.clone()
            },
        ),
        (
            "max_runs",
            StudyOptions {
                max_runs: 101,
                ..options.clone()
            },
        ),
    ] {
        let e = adaptive_study(&car, &road, spec, &o)
            .err()
            .unwrap()
            .to_string();
        assert!(e.starts_with(&format!("{field}: ")), "{e}");
    }
}

/// The loop's bound is the explorer's plan bound.
#[test]
fn the_bound_is_the_explorers() {
    assert_eq!(MAX_HIFI_RUNS, ridelab::explorer::state::MAX_PLAN_POINTS);
}

/// `front_check`'s HiFi feasibility tolerance: the loop's front ends on the SWS limit by
/// bisection, and on the HiFi that end lies within `HIFI_FEASIBILITY_TOLERANCE` (1e-4
/// relative) of the limit, so every point of the 5 + 5 gp-mul front counts as feasible
/// on the HiFi (its largest error is 8e-5) and none drops out for a hair.
#[test]
fn the_front_end_on_the_sws_limit_counts_on_the_hifi() {
    use ridelab::study::adaptive::HIFI_FEASIBILITY_TOLERANCE;
    assert_eq!(HIFI_FEASIBILITY_TOLERANCE, 1e-4);
    let (car, road, b) = (Car::datum(), Road::default(), DesignBox::default());
    let setting = Setting::new(&car, &road, &b).unwrap();
    let hifi = HiFi::new(&car, &road).unwrap();
    let decision = decision(&car, &hifi, 101, 3);
    let state = run(
        SurrogateSpec::parse("gp-mul").unwrap(),
        &setting,
        &hifi,
        PlanSpec::AudzeEglais(5),
        &decision,
        AdaptiveOptions {
            runs: 5,
            ..AdaptiveOptions::default()
        },
    )
    .unwrap();
    let limit = decision.objectives.sws_limit.unwrap();
    let end = state
        .front()
        .iter()
        .max_by(|p, q| p.sws.total_cmp(&q.sws))
        .unwrap();
    // The surrogate's end is on the limit (bisection to 2^-30 of a lattice step).
    assert!((end.sws / limit - 1.0).abs() < 1e-6, "{}", end.sws);
    let c = ridelab::Evaluator::evaluate(&hifi, end.ks, end.cs).unwrap();
    let g = c.sws / limit - 1.0;
    assert!(g.abs() < HIFI_FEASIBILITY_TOLERANCE, "{g}");
    let reference = HifiFront::new(&hifi, &decision, &b).unwrap();
    let check = front_check(state.model(), &hifi, &decision, &b, &reference, 10).unwrap();
    assert!(check.front_max_error_percent < 100.0 * HIFI_FEASIBILITY_TOLERANCE);
    assert_eq!(check.hifi_feasible_points, check.front_points);
}
