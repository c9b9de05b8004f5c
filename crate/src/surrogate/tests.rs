//! Cross-module tests of the surrogates: manufactured cases whose "HiFi" is itself a tuned
//! LoFi (each approach must recover the tuning), the sample-count errors, and the fidelity
//! study on the real HiFi.

use super::*;
use crate::analysis::quarter_criteria;
use crate::doe::{audze_eglais, full_factorial};
use crate::model::quarter_car;
use crate::study::fidelity::{study_specs, FittedRow, Outcome, StudyRow};
use crate::study::{study, SurrogateRequest};

/// A "HiFi" that is a quarter car made by `f(ks, cs)`: a LoFi with known tuning.
struct Manufactured<F> {
    road: Road,
    f: F,
}

impl<F: Fn(f64, f64) -> QuarterCar> Evaluator for Manufactured<F> {
    fn evaluate(&self, ks: f64, cs: f64) -> Result<Criteria> {
        quarter_criteria(&(self.f)(ks, cs), &self.road)
    }
    fn name(&self) -> String {
        "manufactured".into()
    }
}

fn setting() -> Setting {
    Setting::new(&Car::datum(), &Road::default(), &DesignBox::default()).unwrap()
}

fn samples_of<E: Evaluator>(hifi: &E, plan: &Plan) -> Vec<Sample> {
    sample_plan(hifi, plan, &DesignBox::default()).unwrap()
}

/// Largest relative difference between the model and `truth` on a 7 x 7 grid.
fn max_rel_gap<A: Evaluator + ?Sized, B: Evaluator>(model: &A, truth: &B) -> f64 {
    let b = DesignBox::default();
    full_factorial(7)
        .unwrap()
        .unit
        .iter()
        .map(|p| {
            let (ks, cs) = b.scale(p[0], p[1]);
            let (m, t) = (
                model.evaluate(ks, cs).unwrap(),
                truth.evaluate(ks, cs).unwrap(),
            );
            (0..3)
                .map(|k| (m.to_array()[k] / t.to_array()[k] - 1.0).abs())
                .fold(0.0, f64::max)
        })
        .fold(0.0, f64::max)
}

fn value(tuning: &[Parameter], name: &str) -> f64 {
    tuning.iter().find(|p| p.name == name).unwrap().value
}

/// Checks each named parameter to `1e-6` relative (absolute below magnitude 1).
fn assert_params(tuning: &[Parameter], expected: &[(&str, f64)]) {
    for &(name, want) in expected {
        let got = value(tuning, name);
        assert!(
            (got - want).abs() <= 1e-6 * want.abs().max(1.0),
            "{name}: {got} vs {want}"
        );
    }
}

#[test]
fn vba_recovers_manufactured_transforms() {
    let s = setting();
    let base = s.lofi.car.quarter();
    let b = s.design_box;
    // ks' from u' = 0.05 + 0.9 u + 0.1 u^2, cs' from v' = -0.03 + 1.1 v - 0.08 v^2.
    let (k, c) = ([0.05, 0.9, 0.1], [-0.03, 1.1, -0.08]);
    let truth = Manufactured {
        road: s.lofi.road,
        f: |ks: f64, cs: f64| {
            let (u, v) = b.normalize(ks, cs);
            let (ks, cs) = b.scale(k[0] + (k[1] + k[2] * u) * u, c[0] + (c[1] + c[2] * v) * v);
            QuarterCar { ks, cs, ..base }
        },
    };
    let samples = samples_of(&truth, &audze_eglais(10, 1).unwrap());
    for scheme in [Scheme::Shared, Scheme::PerCriterion] {
        let params = VbaParams {
            transform: Transform::Qts,
            scheme,
            options: LmOptions::default(),
        };
        let model = params.fit(&s, &samples).unwrap();
        let gap = max_rel_gap(&model, &truth);
        assert!(gap < 1e-8, "{scheme:?}: predictions off by {gap:e}");
        // SWS depends on Cs alone, so its own fit cannot see the Ks transform.
        let prefixes: &[&str] = match scheme {
            Scheme::Shared => &[""],
            Scheme::PerCriterion => &["bacc.", "dtl."],
        };
        for p in prefixes {
            let names: Vec<String> = ["ks.a0", "ks.a1", "ks.a2", "cs.a0", "cs.a1", "cs.a2"]
                .iter()
                .map(|n| format!("{p}{n}"))
                .collect();
            let want = [k, c].concat();
            let expected: Vec<(&str, f64)> = names.iter().map(String::as_str).zip(want).collect();
            assert_params(&model.tuning(), &expected);
        }
        assert!(model
            .diagnostics()
            .iter()
            .all(|d| d.converged && d.cost < 1e-20));
    }

    // LTS and MTS, shared scheme.
    for (transform, k, c) in [
        (Transform::Lts, vec![0.04, 0.92], vec![-0.02, 1.07]),
        (Transform::Mts, vec![0.93], vec![1.08]),
    ] {
        let (kk, cc) = (k.clone(), c.clone());
        let map = move |coef: &[f64], x: f64| match coef {
            [a1] => a1 * x,
            [a0, a1] => a0 + a1 * x,
            _ => unreachable!(),
        };
        let truth = Manufactured {
            road: s.lofi.road,
            f: move |ks: f64, cs: f64| {
                let (u, v) = b.normalize(ks, cs);
                let (ks, cs) = b.scale(map(&kk, u), map(&cc, v));
                QuarterCar { ks, cs, ..base }
            },
        };
        let samples = samples_of(&truth, &audze_eglais(5, 1).unwrap());
        let model = VbaParams {
            transform,
            scheme: Scheme::Shared,
            options: LmOptions::default(),
        }
        .fit(&s, &samples)
        .unwrap();
        let names: &[&str] = match transform {
            Transform::Mts => &["ks.a1", "cs.a1"],
            _ => &["ks.a0", "ks.a1", "cs.a0", "cs.a1"],
        };
        let expected: Vec<(&str, f64)> = names.iter().copied().zip([k, c].concat()).collect();
        assert_params(&model.tuning(), &expected);
        assert!(max_rel_gap(&model, &truth) < 1e-8, "{transform:?}");
    }
}

#[test]
fn pba_recovers_scaled_masses_and_tyre() {
    let s = setting();
    let base = s.lofi.car.quarter();
    let truth = Manufactured {
        road: s.lofi.road,
        f: |ks, cs| QuarterCar {
            ks,
            cs,
            ms: 1.13 * base.ms,
            mu: 0.9 * base.mu,
            ..base
        },
    };
    let samples = samples_of(&truth, &audze_eglais(4, 1).unwrap());
    let fit = |scaling: Scaling, scheme| {
        PbaParams {
            scaling,
            scheme,
            options: LmOptions::default(),
        }
        .fit(&s, &samples)
        .unwrap()
    };
    let both = Scaling {
        sprung: true,
        unsprung: true,
        tyre: false,
    };
    let model = fit(both, Scheme::Shared);
    assert_params(&model.tuning(), &[("ms_scale", 1.13), ("mu_scale", 0.9)]);
    assert!(max_rel_gap(&model, &truth) < 1e-8);
    // The tuned quarter car is a real car: its masses are the manufactured ones.
    let q = model.tuned_quarters(20_000.0, 1_500.0).unwrap().unwrap();
    assert!((q[0].ms / base.ms - 1.13).abs() < 1e-6 && q[0] == q[2]);
    assert!(quarter_car(&q[1]).modes().unwrap().len() == 2);

    // Per criterion: BAcc and DTL each determine both masses; SWS sees only ms + mu.
    let model = fit(both, Scheme::PerCriterion);
    assert_params(
        &model.tuning(),
        &[("bacc.ms_scale", 1.13), ("dtl.mu_scale", 0.9)],
    );
    assert!(max_rel_gap(&model, &truth) < 1e-8);

    // With the tyre rate as a third parameter the truth is kt scale 1.
    let model = fit(Scaling { tyre: true, ..both }, Scheme::Shared);
    assert_params(
        &model.tuning(),
        &[("ms_scale", 1.13), ("mu_scale", 0.9), ("kt_scale", 1.0)],
    );
}

#[test]
fn rba_and_data_fits_recover_manufactured_corrections() {
    let s = setting();
    let b = s.design_box;
    let lofi = s.lofi.clone();
    // HiFi = LoFi * tau with tau = 1 + 0.1 u - 0.05 v + 0.02 u v (shared gain).
    let tau = move |ks: f64, cs: f64| {
        let (u, v) = b.normalize(ks, cs);
        1.0 + 0.1 * u - 0.05 * v + 0.02 * u * v
    };
    struct Scaled<F>(SurrogateLoFi, F);
    impl<F: Fn(f64, f64) -> [f64; 3]> Evaluator for Scaled<F> {
        fn evaluate(&self, ks: f64, cs: f64) -> Result<Criteria> {
            let f = self.0.evaluate(ks, cs)?.to_array();
            let g = (self.1)(ks, cs);
            Ok(Criteria::from_array(std::array::from_fn(|k| f[k] * g[k])))
        }
        fn name(&self) -> String {
            "scaled".into()
        }
    }
    let truth = Scaled(lofi.clone(), |ks: f64, cs: f64| [tau(ks, cs); 3]);
    let samples = samples_of(&truth, &audze_eglais(7, 1).unwrap());
    for scheme in [Scheme::Shared, Scheme::PerCriterion] {
        let model = RbaParams {
            form: Form::Multiplicative,
            response: ResponseKind::Poly(2),
            scheme,
        }
        .fit(&s, &samples)
        .unwrap();
        let p = scheme.prefix(2);
        assert_params(
            &model.tuning(),
            &[
                (&format!("{p}c_1"), 1.0),
                (&format!("{p}c_uv"), 0.02),
                (&format!("{p}c_vv"), 0.0),
            ],
        );
        assert!(max_rel_gap(&model, &truth) < 1e-10);
    }

    // Additive: HiFi = LoFi + d_k with d_k linear in (u, v), per criterion.
    let scale = [0.1, 20.0, 1e-4];
    let d = move |ks: f64, cs: f64| {
        let (u, v) = b.normalize(ks, cs);
        std::array::from_fn(|k| scale[k] * (0.5 + u - 0.3 * v))
    };
    let lofi2 = lofi.clone();
    let truth = Scaled(lofi.clone(), move |ks: f64, cs: f64| {
        let f = lofi2.evaluate(ks, cs).unwrap().to_array();
        let d: [f64; 3] = d(ks, cs);
        std::array::from_fn(|k| 1.0 + d[k] / f[k])
    });
    let samples = samples_of(&truth, &audze_eglais(5, 1).unwrap());
    let model = RbaParams {
        form: Form::Additive,
        response: ResponseKind::Poly(1),
        scheme: Scheme::PerCriterion,
    }
    .fit(&s, &samples)
    .unwrap();
    assert_params(&model.tuning(), &[("dtl.c_u", 20.0), ("sws.c_v", -0.3e-4)]);
    assert!(max_rel_gap(&model, &truth) < 1e-10);
    assert!(model.tuned_quarters(2e4, 1e3).unwrap().is_none());

    // RBF corrections and data fits interpolate the samples.
    for spec in ["rba-mul-rbf-gauss", "rba-add-rbf-tps", "data-rbf-mq"] {
        let spec = SurrogateSpec::parse(spec).unwrap();
        let model = spec.fit(&s, &samples, &LmOptions::default()).unwrap();
        for smp in &samples {
            let p = model.evaluate(smp.ks, smp.cs).unwrap().to_array();
            let f = smp.hifi.to_array();
            assert!(
                (0..3).all(|k| (p[k] / f[k] - 1.0).abs() < 1e-8),
                "{}",
                spec.name()
            );
        }
    }

    // A quadratic response surface recovers a quadratic "HiFi" exactly.
    let quad = move |ks: f64, cs: f64| {
        let (u, v) = b.normalize(ks, cs);
        let q = 2.0 + u - v + 0.5 * u * u + 0.25 * u * v + v * v;
        let f = lofi.evaluate(ks, cs).unwrap().to_array();
        [q / f[0], 100.0 * q / f[1], 1e-3 * q / f[2]]
    };
    let truth = Scaled(s.lofi.clone(), quad);
    let samples = samples_of(&truth, &full_factorial(3).unwrap());
    let model = DataFitParams {
        response: ResponseKind::Poly(2),
    }
    .fit(&s, &samples)
    .unwrap();
    assert_params(&model.tuning(), &[("bacc.c_uv", 0.25), ("dtl.c_vv", 100.0)]);
    assert!(max_rel_gap(&model, &truth) < 1e-10);
}

#[test]
fn too_few_samples_and_bad_inputs_are_field_errors() {
    let s = setting();
    let hifi = s.lofi.clone();
    let two = samples_of(&hifi, &audze_eglais(2, 1).unwrap());
    let five = samples_of(&hifi, &audze_eglais(5, 1).unwrap());
    let fit = |name: &str, samples: &[Sample]| {
        SurrogateSpec::parse(name)
            .unwrap()
            .fit(&s, samples, &LmOptions::default())
            .err()
            .map(|e| e.to_string())
    };
    // QTS: 3 coefficients per variable need 3 levels of each.
    let e = fit("vba-qts", &two).unwrap();
    assert!(e.starts_with("plan: ") && e.contains("levels"), "{e}");
    // Per criterion, 6 parameters need 6 samples.
    let e = fit("vba-qts-per-criterion", &five).unwrap();
    assert!(
        e.starts_with("plan: ") && e.contains("at least 6 samples"),
        "{e}"
    );
    assert!(fit("vba-qts", &five).is_none());
    let e = fit("rba-mul-poly2", &five).unwrap();
    assert!(e.starts_with("plan: ") && e.contains("at least 6"), "{e}");
    let e = fit("pba-smts-umts-kt-per-criterion", &two).unwrap();
    assert!(e.starts_with("plan: "), "{e}");
    let e = fit("data-rbf-tps", &two[..1]).unwrap();
    assert!(e.starts_with("plan: "), "{e}");
    assert!(fit("pba-smts-umts-kt", &two).is_none());

    // A shared additive correction is not offered; zero starts are refused.
    let e = RbaParams {
        form: Form::Additive,
        response: ResponseKind::Poly(1),
        scheme: Scheme::Shared,
    }
    .check(&five)
    .unwrap_err();
    assert!(e.to_string().starts_with("scheme: "));
    let e = VbaParams {
        transform: Transform::Lts,
        scheme: Scheme::Shared,
        options: LmOptions {
            starts: 0,
            ..Default::default()
        },
    }
    .check(&five)
    .unwrap_err();
    assert!(e.to_string().starts_with("starts: "));
    let mut bad = five.clone();
    bad[3].hifi.dtl = f64::NAN;
    assert!(fit("vba-lts", &bad).unwrap().starts_with("samples[3]: "));

    let car = Car::datum();
    let road = Road::default();
    for (a, p, field) in [
        ("vba-xyz", "ae:10", "approach"),
        ("vba-qts", "lhs:10", "plan"),
        ("vba-qts", "ae:0", "plan"),
    ] {
        let e = SurrogateRequest::parse(a, p)
            .and_then(|r| r.report(&car, &road))
            .unwrap_err()
            .to_string();
        assert!(e.starts_with(&format!("{field}: ")), "{e}");
    }
    let e = SurrogateRequest::parse("vba-lts", "ae:3")
        .and_then(|r| {
            SurrogateRequest {
                predict_grid: Some(1),
                ..r
            }
            .report(&car, &road)
        })
        .unwrap_err();
    assert!(e.to_string().starts_with("predict-grid: "), "{e}");
}

#[test]
fn vba_guard_keeps_transformed_design_positive() {
    let s = setting();
    let t = vba::VariableTuning::new(Transform::Qts, s.design_box, s.lofi.car.quarter());
    // u' = -0.2 + 0.1 u: ks' = 10 kN/m + 30 kN/m * u' >= 4 kN/m > 0: admissible.
    assert!(t.admissible(&[-0.2, 0.1, 0.0, 0.0, 1.0, 0.0]));
    // u' = -0.4 at u = 0: ks' = -2 kN/m.
    assert!(!t.admissible(&[-0.4, 1.0, 0.0, 0.0, 1.0, 0.0]));
    // A vertex inside [0, 1]: v' = 0.3 - 2 v + 2 v^2 has its least value -0.2 at v = 0.5,
    // cs' = 500 - 0.2 * 3500 = -200 N s/m.
    assert!(!t.admissible(&[0.0, 1.0, 0.0, 0.3, -2.0, 2.0]));
    let e = t.quarter(&[-0.4, 1.0, 0.0, 0.0, 1.0, 0.0], 10_000.0, 1_000.0);
    assert!(e.unwrap_err().to_string().contains("must be > 0"));
}

#[test]
fn surrogate_report_is_serialisable_and_attachable() {
    let car = Car::datum();
    let road = Road::default();
    let r = SurrogateRequest {
        predict_grid: Some(4),
        ..SurrogateRequest::parse("vba-qts", "ae:10").unwrap()
    }
    .report(&car, &road)
    .unwrap();
    assert_eq!(r.hifi_evaluations, 10 + 16);
    assert_eq!(r.samples.len(), 10);
    assert_eq!(r.tuning.len(), 6);
    let q = r.tuned_quarters.unwrap();
    assert!(q[0] == q[1] && q[0].ks > 0.0 && q[0].ms == car.quarter().ms);
    assert_eq!(r.error_map.ks.len(), 16);
    let p = r.predictions.as_ref().unwrap();
    assert_eq!(p.surrogate.len(), 16);
    // Each prediction names its point: the error map's points, and the HiFi value there
    // is the HiFi's at that point.
    assert_eq!((&p.ks, &p.cs), (&r.error_map.ks, &r.error_map.cs));
    let direct = crate::analysis::HiFi::new(&car, &road)
        .unwrap()
        .evaluate(p.ks[5], p.cs[5])
        .unwrap();
    assert!((p.hifi[5].bacc / direct.bacc - 1.0).abs() < 1e-12);
    assert!((p.hifi[5].dtl / direct.dtl - 1.0).abs() < 1e-12);
    let json = serde_json::to_string(&r).unwrap();
    assert!(json.contains("\"surrogate\":\"vba-qts\"") && !json.contains("NaN"));

    // A fitted surrogate goes wherever an evaluator goes, e.g. the optimiser's counter.
    let s = setting();
    let hifi = crate::analysis::HiFi::new(&Car::datum(), &Road::default()).unwrap();
    let samples = samples_of(&hifi, &audze_eglais(5, 1).unwrap());
    let model = SurrogateSpec::parse("pba-smts-umts")
        .unwrap()
        .fit(&s, &samples, &LmOptions::default())
        .unwrap();
    let counted = crate::optimize::Counted::new(model);
    counted.evaluate(25_000.0, 2_000.0).unwrap();
    assert_eq!(
        (counted.count(), counted.name()),
        (1, "pba-smts-umts".to_string())
    );
}

/// The study's figures on the datum car, class B at 20 m/s (debug build, this run): the
/// untuned LoFi's worst max RTE is 5.06 % (min R^2 0.984); the best surrogate per budget
/// (an RBA with an RBF correction, except gp-mul at 3 samples) has worst max RTE 3.61, 2.48,
/// 0.78, 1.50, 0.32, 0.67, 0.19, 0.093, 0.048 % and min R^2 0.9930, 0.9981, 0.99926, 0.99939, 0.99998, 0.99998,
/// 0.999997, 0.999999, 0.9999998 at 2, 3, 4, 5, 9, 10, 16, 25, 100 samples. The bounds below
/// leave a margin of about 1.3 to 2 on each figure (1 - R^2 for R^2).
#[test]
fn fidelity_study_on_the_real_hifi() {
    let report = study(&Car::datum(), &Road::default(), &DesignBox::default()).unwrap();
    let n_rows = study_specs().len() * PlanSpec::study().len();
    assert_eq!(report.rows.len(), n_rows);
    // HiFi runs: the validation grid once plus every plan's samples once.
    let plan_samples: usize = [2, 3, 4, 5, 10].iter().map(|n| n + n * n).sum();
    assert_eq!(
        report.hifi_evaluations,
        VALIDATION_LEVELS.pow(2) + plan_samples
    );
    let lofi = report.lofi.to_array();
    let lofi_worst = lofi.iter().map(|m| m.rte_max).fold(0.0, f64::max);
    eprintln!("untuned LoFi: worst max RTE {lofi_worst:.3} %");
    // The untuned LoFi misses the HiFi by a few per cent (the fidelity gap the study closes).
    assert!((2.0..10.0).contains(&lofi_worst), "{lofi_worst}");
    let fitted: Vec<(&StudyRow, &FittedRow)> = report
        .rows
        .iter()
        .filter_map(|r| match &r.outcome {
            Outcome::Fitted(f) => Some((r, f)),
            Outcome::Skipped { reason } => {
                assert!(reason.starts_with("plan: "), "{}: {reason}", r.surrogate);
                None
            }
        })
        .collect();
    for (row, f) in &fitted {
        let all = f.metrics.to_array();
        for m in &all {
            // Consistent measures: an RMS never exceeds the largest error, a mean RTE the
            // largest RTE, and R^2 = 1 - SS_res / SS_tot is at most 1 (1e-12: rounding).
            assert!(
                m.rmse <= m.mae * (1.0 + 1e-12) && m.rte_mean <= m.rte_max * (1.0 + 1e-12),
                "{} {}: {m:?}",
                row.surrogate,
                row.plan
            );
            assert!(m.r2 <= 1.0 && m.r2.is_finite(), "{}: {m:?}", row.surrogate);
        }
        let worst = all.iter().map(|m| m.rte_max).fold(0.0, f64::max);
        let min_r2 = all.iter().map(|m| m.r2).fold(f64::INFINITY, f64::min);
        assert_eq!(
            (f.worst_rte_max, f.min_r2),
            (worst, min_r2),
            "{}",
            row.surrogate
        );
        // A surrogate built on the LoFi (RBA, VBA, PBA) fitted to 5 or more samples stays
        // within 10 % of the untuned LoFi's error or better: the fit starts from the untuned
        // model and samples over the box keep it from bending away elsewhere (worst such row
        // 4.96 %, pba-umts; with 2 to 4 samples vba-lts reaches 37 %, so no bound there).
        if !row.surrogate.starts_with("data-") && row.samples >= 5 {
            assert!(
                f.worst_rte_max <= 1.1 * lofi_worst,
                "{} on {}: {} % vs LoFi {lofi_worst} %",
                row.surrogate,
                row.plan,
                f.worst_rte_max
            );
        }
    }
    let md = report.to_markdown();
    assert!(md.contains("| 10 | ") && md.contains("skipped: plan: "));

    // Per sample budget: (samples, bound on the best worst max RTE %, bound on its min R^2).
    // With 2 and 3 samples the bound is relative: at least 20 % better than the untuned LoFi.
    let bounds: [(usize, f64, f64); 9] = [
        (2, 0.8 * lofi_worst, 0.99),
        (3, 0.8 * lofi_worst, 0.99),
        (4, 1.2, 0.999),
        (5, 2.0, 0.999),
        (9, 0.5, 0.9999),
        (10, 1.0, 0.9999),
        (16, 0.3, 0.99999),
        (25, 0.15, 0.99999),
        (100, 0.08, 0.99999),
    ];
    assert_eq!(report.best_per_budget.len(), bounds.len());
    for (b, (samples, rte, r2)) in report.best_per_budget.iter().zip(bounds) {
        eprintln!(
            "budget {:>3}: {:<28} {:<8} worst max RTE {:7.3} %  min R2 {:.7}",
            b.samples, b.surrogate, b.plan, b.fitted.worst_rte_max, b.fitted.min_r2
        );
        assert_eq!(b.samples, samples);
        assert!(
            b.fitted.worst_rte_max <= rte,
            "{samples}: {} %",
            b.fitted.worst_rte_max
        );
        assert!(b.fitted.min_r2 >= r2, "{samples}: R2 {}", b.fitted.min_r2);
        // The best is the least worst max RTE of the fitted rows of that budget.
        let least = fitted
            .iter()
            .filter(|(r, _)| r.samples == samples)
            .map(|(_, f)| f.worst_rte_max)
            .fold(f64::INFINITY, f64::min);
        assert_eq!(b.fitted.worst_rte_max, least, "{samples}");
        // The physics beats a pure data fit of the same samples by far (22x at least here;
        // 5x asserted): the seed's case for tuning the LoFi rather than replacing it.
        let best_data = fitted
            .iter()
            .filter(|(r, _)| r.samples == samples && r.surrogate.starts_with("data-"))
            .map(|(_, f)| f.worst_rte_max)
            .fold(f64::INFINITY, f64::min);
        assert!(
            5.0 * b.fitted.worst_rte_max <= best_data,
            "{samples}: best {} % vs data fit {best_data} %",
            b.fitted.worst_rte_max
        );
    }
    // Within each plan family more samples (a shorter fill distance) give a smaller best
    // error: each step at least 10 % lower (observed ratios 0.41 to 0.77).
    for family in ["ae", "grid"] {
        let best: Vec<f64> = [2, 3, 4, 5, 10]
            .iter()
            .map(|n| {
                let plan = format!("{family}:{n}");
                fitted
                    .iter()
                    .filter(|(r, _)| r.plan == plan)
                    .map(|(_, f)| f.worst_rte_max)
                    .fold(f64::INFINITY, f64::min)
            })
            .collect();
        for w in best.windows(2) {
            assert!(w[1] <= 0.9 * w[0], "{family}: {best:?}");
        }
    }
}

/// A surrogate on a measured road (its LoFi the quarter car on the shaped road, its HiFi
/// the full car there) is the ISO pipeline's when the road is ISO class C shaped with
/// waviness 2 (constant filters, so the same road): the two pipelines share no route
/// (closed forms and the residue route against the modal route with the filters), and
/// every approach kind (RBA, VBA, PBA, GP, a data fit) gives the same tuning, error map
/// and validation measures to 1e-5 (Levenberg-Marquardt stops within its tolerance of
/// the optimum from either route's values; seen: 5.8e-7).
#[test]
fn a_surrogate_on_a_shaped_iso_road_is_the_iso_surrogate() {
    use crate::analysis::ModelKind;
    use crate::road_profile::{MeasuredModel, ShapedRoad};
    let car = Car::datum();
    let road = Road {
        class: crate::road::RoadClass::C,
        speed: 25.0,
        ..Road::default()
    };
    let b = DesignBox::default();
    let shaped = ShapedRoad::iso(&road, 2.0).unwrap();
    let measured = Setting::measured(&car, shaped.clone(), &b).unwrap();
    let rel = |a: f64, b: f64| (a / b - 1.0).abs();
    let mut worst = 0.0_f64;
    for name in [
        "rba-mul-rbf-mq",
        "vba-qts",
        "pba-smts",
        "gp-mul",
        "data-quad",
    ] {
        let spec = SurrogateSpec::parse(name).unwrap();
        let plan = PlanSpec::parse("ae:10").unwrap();
        let request = SurrogateRequest {
            design_box: b,
            predict_grid: Some(6),
            ..SurrogateRequest::new(spec, plan)
        };
        let iso = request.report(&car, &road).unwrap();
        let hifi = MeasuredModel::new(ModelKind::Full, &car, shaped.clone());
        let on = request.report_on(&car, &measured, hifi).unwrap();
        assert_eq!(iso.tuning.len(), on.tuning.len(), "{name}");
        for (a, b) in iso.tuning.iter().zip(&on.tuning) {
            assert_eq!(a.name, b.name);
            // Dimensionless, of order 1: relative above 1, absolute below (a small
            // coefficient of the normalised design is weakly determined).
            worst = worst.max((a.value - b.value).abs() / a.value.abs().max(1.0));
        }
        let (a, b) = (&iso.error_map.relative_error, &on.error_map.relative_error);
        for (a, b) in [(&a.bacc, &b.bacc), (&a.dtl, &b.dtl), (&a.sws, &b.sws)] {
            for (x, y) in a.iter().zip(b) {
                // Relative errors in %, compared against 1 %.
                worst = worst.max((x - y).abs() / 100.0);
            }
        }
        for (a, b) in [
            (&iso.metrics.bacc, &on.metrics.bacc),
            (&iso.metrics.dtl, &on.metrics.dtl),
            (&iso.metrics.sws, &on.metrics.sws),
        ] {
            worst = worst
                .max(rel(a.rmse, b.rmse))
                .max(rel(a.rte_max, b.rte_max));
        }
    }
    eprintln!("measured vs ISO pipeline: worst {worst:e}");
    assert!(worst < 1e-5, "worst difference {worst:e}");
}
