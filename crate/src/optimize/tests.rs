//! Both optimisers on the closed-form quarter car, against brute-force reference fronts.

use super::hypervolume::{front_distance, hypervolume, reference_point};
use super::problem::{dominates, feasible_front, Problem, Solution};
use super::test_problems::QuarterCar;
use super::*;
use crate::design::DesignBox;
use crate::dos::{DesignObjectives, DosContext};
use crate::evaluate::{Criteria, Evaluator};
use crate::study::{EvaluatorSpec, OptimizeRequest};

fn context() -> DosContext {
    DosContext {
        sprung_mass: 467.7,
        tire_stiffness: 175_500.0,
        datum: QuarterCar.evaluate(20_000.0, 1_500.0).unwrap(),
        static_wheel_load: 4_500.0,
    }
}

fn problem(sws_limit: f64) -> SuspensionProblem<QuarterCar> {
    let objectives = DesignObjectives {
        sws_limit: Some(sws_limit),
        ..Default::default()
    };
    SuspensionProblem::new(QuarterCar, DesignBox::default(), objectives, context()).unwrap()
}

/// Feasible non-dominated points of an `n x n` grid over `[ks0, ks1] x [cs0, cs1]`.
fn brute_force(sws_limit: f64, n: usize, ks: (f64, f64), cs: (f64, f64)) -> Vec<[f64; 2]> {
    let p = problem(sws_limit);
    let mut pool = Vec::with_capacity(n * n);
    for i in 0..n {
        for j in 0..n {
            let x = vec![
                ks.0 + (ks.1 - ks.0) * i as f64 / (n - 1) as f64,
                cs.0 + (cs.1 - cs.0) * j as f64 / (n - 1) as f64,
            ];
            pool.push(Solution {
                eval: p.evaluate(&x).unwrap(),
                x,
            });
        }
    }
    feasible_front(&pool).iter().map(|s| s.eval.f).collect()
}

fn default_box_reference(sws_limit: f64) -> Vec<[f64; 2]> {
    let b = DesignBox::default();
    brute_force(sws_limit, 200, (b.ks_min, b.ks_max), (b.cs_min, b.cs_max))
}

fn objectives(front: &[FrontPoint]) -> Vec<[f64; 2]> {
    front.iter().map(|p| [p.bacc, p.dtl]).collect()
}

fn run(method: Method, sws_limit: f64, reference: [f64; 2]) -> Study {
    run_study(&problem(sws_limit), &method, Some(reference)).unwrap()
}

#[test]
fn stm_and_nsga2_match_the_brute_force_front() {
    let truth = default_box_reference(0.007);
    let r = reference_point(&truth, study::REFERENCE_MARGIN);
    let hv_ref = hypervolume(&truth, r);
    for method in [
        Method::Stm(StmParams::default()),
        Method::Nsga2(Nsga2Params::default()),
    ] {
        let s = run(method.clone(), 0.007, r);
        let ratio = s.hypervolume / hv_ref;
        let d = front_distance(&objectives(&s.front), &truth);
        println!(
            "{method:?}: {} points, {} evaluations, HV ratio {ratio:.5}, IGD {:.2e} (max {:.2e}), GD {:.2e} (max {:.2e})",
            s.front.len(),
            s.evaluations,
            d.igd,
            d.igd_max,
            d.gd,
            d.gd_max
        );
        assert!(ratio >= 0.995, "{method:?}: HV ratio {ratio}");
        assert!(s.front.iter().all(|p| p.sws <= 0.007 * (1.0 + 1e-12)));
    }
}

/// The exact front of the closed-form quarter car in the default box with SWS <= limit,
/// `levels` points. At a BAcc level `b`, `M ks^2 / cs + kt cs = 2 ms^2 b^2 / W` gives the
/// largest spring `ks_b(cs)`; DTL falls with `ks` up to `ks* = kt mu ms / M^2`, so the
/// best spring is `min(ks_b, ks*)` and DTL is minimised over `cs` alone (dense samples,
/// then golden section around the best one).
fn exact_front(sws_limit: f64, levels: usize) -> Vec<[f64; 2]> {
    let (ms, mu, kt, w) = (
        QuarterCar::MS,
        QuarterCar::MU,
        QuarterCar::KT,
        QuarterCar::w(),
    );
    let m = ms + mu;
    let b = DesignBox::default();
    let cs_lo = b.cs_min.max(w * m / (2.0 * sws_limit * sws_limit));
    let ks_star = kt * mu * ms / (m * m);
    let at = |ks: f64, cs: f64| QuarterCar.evaluate(ks, cs).unwrap();
    // DTL minimum: d/dcs of (A + B ks*^2 - D ks*) / cs + C cs = 0
    let num =
        kt * kt * mu + (m / ms).powi(2) * m * ks_star.powi(2) - 2.0 * ks_star * kt * mu * m / ms;
    let cs_star = (num / ((m / ms).powi(2) * kt)).sqrt().max(cs_lo);
    let (b_lo, b_hi) = (at(b.ks_min, cs_lo).bacc, at(ks_star, cs_star).bacc);
    let mut points = Vec::with_capacity(levels);
    for l in 0..levels {
        let bacc = b_lo + (b_hi - b_lo) * l as f64 / (levels - 1) as f64;
        let e = 2.0 * ms * ms * bacc * bacc / w;
        let design = |cs: f64| {
            let ks_b = ((e - kt * cs) * cs / m).max(0.0).sqrt();
            (ks_b >= b.ks_min * (1.0 - 1e-12)).then(|| at(ks_b.min(ks_star).max(b.ks_min), cs))
        };
        let dtl = |cs: f64| design(cs).map_or(f64::INFINITY, |c| c.dtl);
        let n = 2000;
        let cs_k = |k: usize| cs_lo + (b.cs_max - cs_lo) * k as f64 / n as f64;
        let best = (0..=n)
            .min_by(|&i, &j| dtl(cs_k(i)).total_cmp(&dtl(cs_k(j))))
            .unwrap();
        let (mut lo, mut hi) = (cs_k(best.saturating_sub(1)), cs_k((best + 1).min(n)));
        for _ in 0..60 {
            let (c1, c2) = (hi - 0.618 * (hi - lo), lo + 0.618 * (hi - lo));
            if dtl(c1) <= dtl(c2) {
                hi = c2;
            } else {
                lo = c1;
            }
        }
        let cs = if dtl(0.5 * (lo + hi)) <= dtl(cs_k(best)) {
            0.5 * (lo + hi)
        } else {
            cs_k(best)
        };
        if let Some(c) = design(cs) {
            points.push([c.bacc, c.dtl]);
        }
    }
    let keep = super::problem::non_dominated(&points);
    keep.into_iter().map(|i| points[i]).collect()
}

/// Mean and largest distance from `front` to the polyline through `truth` (sorted by
/// `f1`), in objectives normalised by the truth's range.
fn distance_to_polyline(front: &[[f64; 2]], truth: &[[f64; 2]]) -> (f64, f64) {
    let (lo, hi) = super::hypervolume::ideal_nadir(truth);
    let n = |p: &[f64; 2]| {
        [
            (p[0] - lo[0]) / (hi[0] - lo[0]),
            (p[1] - lo[1]) / (hi[1] - lo[1]),
        ]
    };
    let t: Vec<[f64; 2]> = truth.iter().map(n).collect();
    let d: Vec<f64> = front
        .iter()
        .map(|p| {
            let p = n(p);
            t.windows(2)
                .map(|s| {
                    let (a, b) = (s[0], s[1]);
                    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
                    let u = (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / (dx * dx + dy * dy))
                        .clamp(0.0, 1.0);
                    (p[0] - a[0] - u * dx).hypot(p[1] - a[1] - u * dy)
                })
                .fold(f64::INFINITY, f64::min)
        })
        .collect();
    (
        d.iter().sum::<f64>() / d.len() as f64,
        d.iter().copied().fold(0.0, f64::max),
    )
}

#[test]
fn refinement_brings_stm_onto_the_exact_front() {
    let truth = exact_front(0.007, 400);
    let r = reference_point(&truth, study::REFERENCE_MARGIN);
    let hv_true = hypervolume(&truth, r);
    let mut gaps = Vec::new();
    for levels in [0, 1, 2, 3] {
        let s = run(
            Method::Stm(StmParams {
                levels,
                ..Default::default()
            }),
            0.007,
            r,
        );
        let gap = distance_to_polyline(&objectives(&s.front), &truth);
        println!(
            "levels {levels}: {} points, {} evaluations, distance to exact front mean {:.2e} max {:.2e}, HV ratio {:.6}",
            s.front.len(),
            s.evaluations,
            gap.0,
            gap.1,
            s.hypervolume / hv_true
        );
        gaps.push(gap);
    }
    // Each level halves the lattice step; points filling the notches between front
    // points sit off the front by about that step, so the distance falls about 2x a level.
    for l in 1..4 {
        assert!(
            gaps[l].0 < 0.5 * gaps[l - 1].0 && gaps[l].1 < 0.51 * gaps[l - 1].1,
            "{gaps:?}"
        );
    }
    assert!(gaps[3].0 < 2e-4 && gaps[3].1 < 2e-3, "{gaps:?}");
}

#[test]
fn front_on_the_sws_boundary_is_traced_exactly() {
    // SWS depends on Cs only; a 5 mm limit needs Cs >= 2566 N s/m, above the DTL
    // optimum, so the whole front lies on SWS = 5 mm.
    let truth = default_box_reference(0.005);
    let r = reference_point(&truth, study::REFERENCE_MARGIN);
    let s = run(Method::Stm(StmParams::default()), 0.005, r);
    let worst = s
        .front
        .iter()
        .map(|p| (p.sws / 0.005 - 1.0).abs())
        .fold(0.0, f64::max);
    println!(
        "5 mm: {} points, worst |SWS/limit - 1| = {worst:.1e}",
        s.front.len()
    );
    assert!(worst < 1e-6, "{worst}");
    assert!(s.hypervolume / hypervolume(&truth, r) >= 0.995);
}

#[test]
fn min_max_pick_is_on_the_front_and_balanced() {
    let s = run_study(&problem(0.007), &Method::Stm(StmParams::default()), None).unwrap();
    let front = &s.front;
    let pick = &s.pick;
    let f = [pick.criteria.bacc, pick.criteria.dtl];
    assert!(front.iter().all(|p| !dominates([p.bacc, p.dtl], f)));
    // Every front point's score, computed here from its definition (not by
    // `normalised_distances`): r_i = f_i / f_i(datum), the distance of each ratio from its
    // least value over the front in units of its spread, the larger of the two.
    let datum = context().datum;
    let ratios: Vec<[f64; 2]> = front
        .iter()
        .map(|p| [p.bacc / datum.bacc, p.dtl / datum.dtl])
        .collect();
    let lo = [0, 1].map(|k| ratios.iter().map(|r| r[k]).fold(f64::INFINITY, f64::min));
    let hi = [0, 1].map(|k| {
        ratios
            .iter()
            .map(|r| r[k])
            .fold(f64::NEG_INFINITY, f64::max)
    });
    let score = |r: &[f64; 2]| {
        [0, 1]
            .map(|k| (r[k] - lo[k]) / (hi[k] - lo[k]))
            .into_iter()
            .fold(0.0, f64::max)
    };
    let scores: Vec<f64> = ratios.iter().map(score).collect();
    let least = scores.iter().copied().fold(f64::INFINITY, f64::min);
    // The pick's score is the least of all (1e-12: the same arithmetic in another order),
    // and on ties the pick is the first point with the least score.
    assert!(
        (pick.score - least).abs() < 1e-12 && (scores[pick.index] - least).abs() < 1e-12,
        "pick {} scores {} vs least {least}",
        pick.index,
        pick.score
    );
    let first = scores.iter().position(|&v| v - least < 1e-12).unwrap();
    assert_eq!(pick.index, first, "ties: the first of {scores:?}");
    assert!(front.len() > 50, "a dense front: {} points", front.len());
    // both distances close to balanced on a dense front
    assert!(
        (pick.distance[0] - pick.distance[1]).abs() < 0.02,
        "{:?}",
        pick.distance
    );
    println!(
        "pick: Ks {:.1} N/m, Cs {:.1} N s/m, change {:?} %, distances {:?}",
        pick.ks, pick.cs, pick.change_percent, pick.distance
    );
}

#[test]
fn over_tight_sws_limit_names_the_limit() {
    for method in [
        Method::Stm(StmParams {
            grid: 51,
            levels: 0,
        }),
        Method::Nsga2(Nsga2Params {
            generations: 10,
            ..Default::default()
        }),
    ] {
        let e = run_study(&problem(0.0001), &method, None)
            .unwrap_err()
            .to_string();
        println!("{e}");
        assert!(
            e.starts_with("sws_limit: no feasible design: SWS limit 0.1 mm is exceeded everywhere"),
            "{e}"
        );
        // the smallest SWS is at Cs = 4000 N s/m: sqrt(W M / (2 * 4000)) = 4.0 mm
        assert!(e.contains("smallest SWS 4."), "{e}");
    }
}

#[test]
fn objectives_that_conflict_are_named_together() {
    // Each of "SWS <= 3 mm" (Cs >= 7127 N s/m) and "BAcc no worse than a soft datum"
    // can be met alone in a box reaching Cs = 8000, but not both.
    let objectives = DesignObjectives {
        sws_limit: Some(0.003),
        no_worse_than_datum: [true, false, false],
        ..Default::default()
    };
    let design = DesignBox {
        cs_max: 8_000.0,
        ..Default::default()
    };
    let p = SuspensionProblem::new(QuarterCar, design, objectives, context()).unwrap();
    let e = stm(
        &p,
        &StmParams {
            grid: 51,
            levels: 0,
        },
    )
    .unwrap_err()
    .to_string();
    println!("{e}");
    assert!(
        e.contains(": no feasible design: SWS limit and BAcc no worse than datum are each met"),
        "{e}"
    );
    assert!(
        e.contains("SWS limit") && e.contains("BAcc no worse than datum"),
        "{e}"
    );
}

#[test]
fn study_counts_evaluations_and_serialises() {
    let p = problem(0.007);
    let params = Nsga2Params {
        generations: 20,
        ..Default::default()
    };
    let s = run_study(&p, &Method::Nsga2(params), None).unwrap();
    assert_eq!(s.evaluations, 100 * 21);
    let again = run_study(
        &p,
        &Method::Stm(StmParams {
            grid: 11,
            levels: 0,
        }),
        None,
    )
    .unwrap();
    assert_eq!(again.evaluations, 11 * 11);
    let json = serde_json::to_value(&s).unwrap();
    assert_eq!(json["method"]["method"], "nsga2");
    assert_eq!(json["evaluations"], 2100);
    for key in ["ks", "cs", "bacc", "dtl", "sws"] {
        assert!(json["front"][0][key].is_f64(), "{key}");
    }
    assert!(json["reference_rule"]
        .as_str()
        .unwrap()
        .starts_with("nadir + 0.1"));
    assert!(json["pick"]["change_percent"].is_array());
}

#[test]
fn recheck_on_another_evaluator_reports_the_difference() {
    /// The closed form with 5 % more BAcc, standing in for a HiFi model.
    struct Hifi;
    impl Evaluator for Hifi {
        fn evaluate(&self, ks: f64, cs: f64) -> crate::error::Result<Criteria> {
            let c = QuarterCar.evaluate(ks, cs)?;
            Ok(Criteria {
                bacc: 1.05 * c.bacc,
                ..c
            })
        }
        fn name(&self) -> String {
            "hifi".into()
        }
    }
    let s = run_study(&problem(0.007), &Method::Stm(StmParams::default()), None).unwrap();
    let datum = Hifi.evaluate(20_000.0, 1_500.0).unwrap();
    let r = recheck(&s.pick, &Hifi, &datum).unwrap();
    assert!(
        (r.error_percent[0] - (100.0 / 1.05 - 100.0)).abs() < 1e-9,
        "{:?}",
        r.error_percent
    );
    assert!(r.error_percent[1].abs() < 1e-12);
    for k in 0..3 {
        assert!((r.rechecked_change_percent[k] - s.pick.change_percent[k]).abs() < 1e-9);
    }
}

/// The picks beyond min-max on one STM front: the knee is the least `d_1 + d_2` computed
/// here from the ratios' definition; the weighted pick at W = 0.5 is the min-max pick, at
/// W = 1 the front's best comfort and at W = 0 its best road holding; pseudo-weights sum
/// to 1 and are (1, 0) and (0, 1) at the extremes.
#[test]
fn knee_weighted_pick_and_pseudo_weights() {
    use super::{pick, PickRule};
    let s = run_study(&problem(0.007), &Method::Stm(StmParams::default()), None).unwrap();
    let (front, datum) = (&s.front, context().datum);
    let r: Vec<[f64; 2]> = front
        .iter()
        .map(|p| [p.bacc / datum.bacc, p.dtl / datum.dtl])
        .collect();
    let lo = [0, 1].map(|k| r.iter().map(|x| x[k]).fold(f64::INFINITY, f64::min));
    let hi = [0, 1].map(|k| r.iter().map(|x| x[k]).fold(f64::NEG_INFINITY, f64::max));
    let d = |x: &[f64; 2]| [0, 1].map(|k| (x[k] - lo[k]) / (hi[k] - lo[k]));
    let knee_by_hand = (0..front.len())
        .min_by(|&a, &b| {
            let (da, db) = (d(&r[a]), d(&r[b]));
            (da[0] + da[1]).total_cmp(&(db[0] + db[1]))
        })
        .unwrap();
    let knee = pick(front, &datum, PickRule::Knee).unwrap();
    assert_eq!(knee.index, knee_by_hand);
    assert_eq!(knee.rule, "knee");
    // The knee trades: both distances well inside (0, 1).
    assert!(
        knee.distance.iter().all(|&x| x > 0.01 && x < 0.99),
        "{:?}",
        knee.distance
    );
    let w = knee.pseudo_weights;
    assert!((w[0] + w[1] - 1.0).abs() < 1e-15 && w.iter().all(|&x| x > 0.0 && x < 1.0));
    assert_eq!(
        pick(front, &datum, PickRule::Asf(0.5)).unwrap().index,
        s.pick.index
    );
    let best = |k: usize| {
        (0..front.len())
            .min_by(|&a, &b| r[a][k].total_cmp(&r[b][k]))
            .unwrap()
    };
    let comfort = pick(front, &datum, PickRule::Asf(1.0)).unwrap();
    assert_eq!(comfort.index, best(0));
    assert!((comfort.pseudo_weights[0] - 1.0).abs() < 1e-12);
    let holding = pick(front, &datum, PickRule::Asf(0.0)).unwrap();
    assert_eq!(holding.index, best(1));
    assert!((holding.pseudo_weights[1] - 1.0).abs() < 1e-12);
    // A heavier comfort weight never picks a less comfortable design.
    let bacc: Vec<f64> = [0.0, 0.25, 0.5, 0.75, 1.0]
        .iter()
        .map(|&w| pick(front, &datum, PickRule::Asf(w)).unwrap().criteria.bacc)
        .collect();
    assert!(bacc.windows(2).all(|x| x[1] <= x[0]), "{bacc:?}");
    for bad in ["asf:2", "asf:x", "median"] {
        let e = bad.parse::<PickRule>().unwrap_err().to_string();
        assert!(e.starts_with("pick:"), "{e}");
    }
}

/// A front drawn on the LoFi reports its pick against the LoFi's own datum as well
/// (`same_model`): `100 (c - d) / d` with both from the quarter car evaluated here, and
/// `pick.change_percent` against the HiFi datum differs from it by the LoFi's bias
/// (more than 1 % on the sedan's BAcc); on the HiFi there is no `same_model`.
#[test]
fn lofi_pick_is_also_judged_against_the_lofi_datum() {
    use crate::analysis::{HiFi, LoFi, ModelKind};
    use crate::car::Car;
    use crate::road::Road;
    use crate::surrogate::PlanSpec;
    let (car, road) = (Car::preset("sedan").unwrap(), Road::default());
    let stm = Method::Stm(StmParams {
        grid: 41,
        levels: 1,
    });
    let run = |kind| {
        OptimizeRequest {
            evaluator: EvaluatorSpec::Model(kind),
            plan: PlanSpec::AudzeEglais(10),
            ..OptimizeRequest::new(
                &car,
                &road,
                DesignBox::default(),
                stm.clone(),
                DesignObjectives::default(),
            )
        }
        .run_cpu()
        .unwrap()
    };
    let r = run(ModelKind::Quarter);
    let lofi = LoFi::new(&car, &road);
    let d = lofi.evaluate(car.front.spring, car.front.damper).unwrap();
    let p = lofi.evaluate(r.study.pick.ks, r.study.pick.cs).unwrap();
    let m = r.same_model.expect("a LoFi front has a same-model datum");
    assert_eq!(m.datum, d);
    for (k, (c, dk)) in [(p.bacc, d.bacc), (p.dtl, d.dtl), (p.sws, d.sws)]
        .into_iter()
        .enumerate()
    {
        assert!(
            (m.change_percent[k] - 100.0 * (c - dk) / dk).abs() < 1e-9,
            "{k}: {:?}",
            m.change_percent
        );
    }
    let hd = HiFi::new(&car, &road)
        .unwrap()
        .evaluate(car.front.spring, car.front.damper)
        .unwrap();
    assert!(
        (d.bacc - hd.bacc).abs() / hd.bacc > 0.01,
        "the LoFi's BAcc bias at the datum"
    );
    assert!((m.change_percent[0] - r.study.pick.change_percent[0]).abs() > 0.5);
    assert!(run(ModelKind::Full).same_model.is_none());
}
