//! The explorer's maps, fronts and surrogate against point evaluations and the HiFi.

use super::*;
use crate::dos::{DosContext, Objective};
use crate::evaluate::Evaluator;
use crate::maps::dos_mask::objective_bit;
use crate::surrogate::Surrogate;
use std::rc::Rc;

fn session(patch: impl FnOnce(&mut State)) -> Session {
    let mut s = State::default();
    patch(&mut s);
    Session::new(s).unwrap()
}

/// Every cell of a map equals the model's point evaluation at the cell centre
/// `ks_min + (i + 1/2) (ks_max - ks_min) / nx` (to rounding of the centre), and its mask
/// equals `DesignObjectives::broken` there (exact: the same arithmetic).
fn check_map_cells<E: Evaluator + ?Sized>(s: &Scenario, model: &E, m: &ModelMap) {
    let ctx = DosContext::of_model(&s.datum, model).unwrap();
    let (nx, ny) = (m.grid().ks.n, m.grid().cs.n);
    let (planes, broken) = (m.planes(), m.broken());
    let cells = nx * ny;
    for j in 0..ny {
        for i in 0..nx {
            let (ks, cs) = m.grid().point(i, j);
            let (u, v) = s
                .dbox
                .scale((i as f64 + 0.5) / nx as f64, (j as f64 + 0.5) / ny as f64);
            assert!((ks / u - 1.0).abs() < 1e-15 && (cs / v - 1.0).abs() < 1e-15);
            let c = model.evaluate(ks, cs).unwrap();
            let k = j * nx + i;
            assert_eq!(planes[k], c.bacc);
            assert_eq!(planes[cells + k], c.dtl);
            assert_eq!(planes[2 * cells + k], c.sws);
            let mask = s
                .objectives
                .broken(&ctx, ks, cs, &c)
                .into_iter()
                .fold(0, |b, o| b | objective_bit(o));
            assert_eq!(broken[k], mask, "cell ({i}, {j})");
        }
    }
}

#[test]
fn lofi_and_hifi_maps_equal_point_evaluations() {
    // Bands on, so that more than one bit shows: bounce 1.0..1.3 Hz, damping 0.25..0.45.
    let mut x = session(|s| {
        s.bounce_band = Some([1.0, 1.3]);
        s.damping_band = Some([0.25, 0.45]);
        s.no_worse = Some([false, true, false]);
    });
    let s = x.scenario().clone();
    let lofi = x.map(Model::LoFi, 17, 13).unwrap();
    check_map_cells(&s, &s.lofi(), &lofi);
    let hifi = x.map(Model::HiFi, 6, 5).unwrap();
    check_map_cells(&s, &s.hifi().unwrap(), &hifi);
    // Each of the four objectives is broken somewhere and met somewhere on the LoFi map.
    for o in [
        Objective::SwsLimit,
        Objective::BounceBand,
        Objective::DampingBand,
        Objective::DtlDatum,
    ] {
        let b = objective_bit(o);
        let n = lofi.broken().iter().filter(|&&m| m & b != 0).count();
        assert!(n > 0 && n < lofi.broken().len(), "{o:?}: {n} cells");
    }
    let feasible = lofi.feasible();
    assert!(feasible
        .iter()
        .zip(lofi.broken())
        .all(|(&f, &b)| (f == 1) == (b == 0)));
}

#[test]
fn the_pages_hifi_map_goes_by_the_residue_route_exact_to_1e_8() {
    // The worker's map path (issue #18): the residue route, every cell within 1e-8
    // relative of the modal reference route.
    let mut x = session(|_| {});
    let s = x.scenario().clone();
    assert!(s.hifi().unwrap().has_residue_route());
    let (nx, ny) = (16, 12);
    let m = x.map(Model::HiFi, nx, ny).unwrap();
    let reference = crate::HiFi::with_modal_route(&s.datum, &s.road).unwrap();
    let planes = m.planes();
    let mut worst = 0.0f64;
    for j in 0..ny {
        for i in 0..nx {
            let (ks, cs) = m.grid().point(i, j);
            let want = reference.evaluate(ks, cs).unwrap().to_array();
            for (o, w) in want.iter().enumerate() {
                worst = worst.max((planes[o * nx * ny + j * nx + i] / w - 1.0).abs());
            }
        }
    }
    assert!(worst <= 1e-8, "{worst:e}");
}

#[test]
fn surrogate_map_and_error_map_agree_with_the_hifi() {
    let mut x = session(|_| {});
    let s = x.scenario().clone();
    let fit = x.surrogate().unwrap();
    let sur = x.map(Model::Surrogate, 7, 6).unwrap();
    check_map_cells(&s, &fit.model, &sur);
    let hifi = x.map(Model::HiFi, 7, 6).unwrap();
    let err = x.map(Model::SurrogateError, 7, 6).unwrap();
    // The error planes are 100 (S / HiFi - 1) from the two maps, to rounding.
    let mut worst = 0.0f64;
    let (sur, hifi_v, err_v) = (sur.planes(), hifi.planes(), err.planes());
    for k in 0..sur.len() {
        let expect = 100.0 * (sur[k] / hifi_v[k] - 1.0);
        assert!((err_v[k] - expect).abs() < 1e-9, "cell {k}");
        worst = worst.max(err_v[k].abs());
    }
    assert_eq!(err.broken(), hifi.broken());
    // rba-mul-rbf-mq on ae:10 stays within 0.7 % of the HiFi in the fidelity study;
    // asserted with margin: 1.5 %.
    assert!(worst < 1.5, "worst error {worst} %");
    assert!(
        worst > 1e-4,
        "a surrogate that equals the HiFi everywhere is suspicious"
    );
}

#[test]
fn the_fit_is_reused_until_what_it_depends_on_changes() {
    let mut x = session(|_| {});
    let a = x.surrogate().unwrap();
    let at = |patch: fn(&mut State)| {
        let mut s = State::default();
        patch(&mut s);
        s
    };
    // A new design point or SWS limit keeps the fit.
    x.set_state(at(|s| {
        s.ks = 25_000.0;
        s.sws_limit = Some(0.008);
    }))
    .unwrap();
    let b = x.surrogate().unwrap();
    assert!(Rc::ptr_eq(&a, &b));
    assert_eq!(a.samples.len(), 10);
    // A new plan, road or surrogate refits.
    x.set_state(at(|s| s.plan = Some("grid:3".into()))).unwrap();
    let c = x.surrogate().unwrap();
    assert!(!Rc::ptr_eq(&a, &c));
    assert_eq!(c.samples.len(), 9);
    x.set_state(at(|s| s.speed = 25.0)).unwrap();
    let d = x.surrogate().unwrap();
    assert!(!Rc::ptr_eq(&c, &d));
    x.set_state(at(|s| s.surrogate = Some("vba-qts".into())))
        .unwrap();
    let e = x.surrogate().unwrap();
    assert_eq!(e.model.spec().name(), "vba-qts");
    // A bad state leaves the session as it was (the last good state and its fit).
    let before = x.state().clone();
    assert!(x.set_state(at(|s| s.speed = -1.0)).is_err());
    assert_eq!(x.state(), &before);
    assert!(Rc::ptr_eq(&e, &x.surrogate().unwrap()));
    assert!(x.set_design(f64::NAN, 1000.0).is_err());
    assert_eq!(x.state(), &before);
}

/// The fit report on the session's kept fit is `ridelab surrogate`'s report, which fits
/// afresh, field for field (exact: the same samples, the same fit), for an RBF, a tuned
/// and a GP surrogate; and it fits nothing more.
#[test]
fn the_fit_report_on_the_kept_fit_is_the_clis_without_a_second_fit() {
    for (sur, plan) in [
        ("rba-mul-rbf-mq", "ae:10"),
        ("vba-qts", "grid:3"),
        ("gp-mul", "ae:8"),
    ] {
        let mut x = session(|s| {
            s.surrogate = Some(sur.into());
            s.plan = Some(plan.into());
        });
        let _ = x.surrogate().unwrap();
        assert_eq!(x.fit_count(), 1);
        let kept = x.fit_report(6).unwrap();
        assert_eq!(x.fit_count(), 1, "{sur}: the report reuses the fit");
        let s = x.scenario();
        let fresh = crate::study::SurrogateRequest {
            design_box: s.dbox,
            predict_grid: Some(6),
            ..crate::study::SurrogateRequest::new(s.surrogate, s.plan)
        }
        .report(&s.datum, &s.road)
        .unwrap();
        assert_eq!(kept, fresh, "{sur} on {plan}");
        assert_eq!(kept.hifi_evaluations, kept.samples.len() + 36);
    }
    // A session that has not fitted yet fits once for the report.
    let mut y = session(|_| {});
    y.fit_report(4).unwrap();
    y.surrogate().unwrap();
    assert_eq!(y.fit_count(), 1);
}

/// A fit handed to another session as bytes (as the page's worker receives it) is
/// adopted there without a fit, and predicts the same bits as the fit it came from, for
/// every approach kind (tuned by variables and by parameters, RBA, data fit, GP); it also
/// makes the same fit report. A scenario with other fit inputs does not take it.
#[test]
fn an_offered_fit_is_adopted_bit_for_bit_without_fitting_again() {
    for (sur, plan) in [
        ("rba-mul-rbf-mq", "ae:10"),
        ("rba-add-poly2-per-criterion", "ae:10"),
        ("vba-qts", "grid:3"),
        ("pba-smts-umts-kt-per-criterion", "ae:10"),
        ("data-rbf-gauss", "ae:10"),
        ("gp-mul", "ae:8"),
    ] {
        let state = |s: &mut State| {
            s.surrogate = Some(sur.into());
            s.plan = Some(plan.into());
        };
        let mut a = session(state);
        let record = a
            .fit_record()
            .unwrap()
            .expect("an ISO road's fit has a record");
        let bytes = record.to_bytes().unwrap();
        let cut = FitRecord::from_bytes(&bytes[..bytes.len() / 2]).unwrap_err();
        assert!(
            cut.to_string().starts_with("fit: not a fit record"),
            "{cut}"
        );
        let mut b = session(|s| {
            state(s);
            s.ks = 31_000.0;
        });
        b.offer_fit(FitRecord::from_bytes(&bytes).unwrap());
        let (fa, fb) = (a.surrogate().unwrap(), b.surrogate().unwrap());
        assert_eq!(
            (a.fit_count(), b.fit_count()),
            (1, 0),
            "{sur}: adopted, not fitted"
        );
        assert_eq!(fa.samples, fb.samples);
        assert_eq!(fa.model.tuning(), fb.model.tuning(), "{sur}");
        let dbox = a.scenario().dbox;
        for i in 0..=6 {
            for j in 0..=6 {
                // The box and 10 % beyond it, where the reach check refuses (both alike).
                let (ks, cs) =
                    dbox.scale(-0.15 + 1.3 * i as f64 / 6.0, -0.15 + 1.3 * j as f64 / 6.0);
                match (fa.model.evaluate(ks, cs), fb.model.evaluate(ks, cs)) {
                    (Ok(x), Ok(y)) => assert_eq!(x.to_array(), y.to_array(), "{sur} at {ks}, {cs}"),
                    (Err(x), Err(y)) => assert_eq!(x.to_string(), y.to_string()),
                    (x, y) => panic!("{sur} at {ks}, {cs}: {x:?} against {y:?}"),
                }
            }
        }
        assert_eq!(a.fit_report(4).unwrap(), b.fit_report(4).unwrap(), "{sur}");
        assert_eq!(b.fit_count(), 0);
        // Other fit inputs (the plan): the offer is not taken; the session fits.
        let mut c = session(|s| {
            state(s);
            s.plan = Some("grid:4".into());
        });
        c.offer_fit(FitRecord::from_bytes(&bytes).unwrap());
        assert_eq!(c.surrogate().unwrap().samples.len(), 16);
        assert_eq!(c.fit_count(), 1);
    }
}

#[test]
fn the_surrogate_front_pick_holds_on_the_hifi() {
    let mut x = session(|_| {});
    let r = x.front("stm", Model::Surrogate).unwrap();
    assert!(r.study.evaluator.contains("rba"), "{}", r.study.evaluator);
    assert!(r.study.front.len() > 50);
    // The pick's prediction error against the HiFi re-check: about 0.1 % (study), < 1 %.
    for e in r.recheck.error_percent {
        assert!(e.abs() < 1.0, "{:?}", r.recheck.error_percent);
    }
    // The LoFi front's pick misses the HiFi by more (the fidelity gap the surrogate closes).
    let l = x.front("stm", Model::LoFi).unwrap();
    let gap = |r: &FrontResult| {
        r.recheck
            .error_percent
            .iter()
            .fold(0.0f64, |m, e| m.max(e.abs()))
    };
    assert!(
        gap(&l) > gap(&r),
        "LoFi {} vs surrogate {}",
        gap(&l),
        gap(&r)
    );
}

#[test]
fn bad_surrogate_plan_and_bands_name_their_field() {
    let field = |patch: fn(&mut State)| {
        let mut s = State::default();
        patch(&mut s);
        match s.scenario().unwrap_err() {
            crate::RideError::Field { field, .. } => field,
            e => panic!("{e}"),
        }
    };
    assert_eq!(field(|s| s.surrogate = Some("kriging".into())), "approach");
    assert_eq!(field(|s| s.plan = Some("ae:0".into())), "plan");
    assert_eq!(field(|s| s.plan = Some("grid:11".into())), "plan");
    assert_eq!(field(|s| s.plan = Some("lhs:5".into())), "plan");
    assert_eq!(field(|s| s.bounce_band = Some([1.5, 1.0])), "bounce_band");
    assert_eq!(
        field(|s| s.damping_band = Some([f64::NAN, 1.0])),
        "damping_band"
    );
    assert!(Model::parse_among("model", "kriging", Model::MAP).is_err());
    assert!(Model::parse_among("frontModel", "hifi", Model::FRONT).is_err());
}

#[test]
fn kept_map_values_are_rejudged_when_only_the_objectives_change() {
    // First map at 7 mm fills the cache; the second, at 6 mm with a damping band, reuses
    // the values and must equal a fresh evaluation cell for cell, mask included.
    let mut x = session(|_| {});
    let loose = x.map(Model::LoFi, 9, 8).unwrap();
    let _ = x.map(Model::Surrogate, 9, 8).unwrap();
    let _ = x.map(Model::SurrogateError, 5, 4).unwrap();
    let tighter = |s: &mut State| {
        s.sws_limit = Some(0.006);
        s.damping_band = Some([0.2, 0.3]);
    };
    let mut b = State::default();
    tighter(&mut b);
    x.set_state(b).unwrap();
    let mut fresh = session(tighter);
    for model in [Model::LoFi, Model::Surrogate] {
        let kept = x.map(model, 9, 8).unwrap();
        assert_eq!(kept, fresh.map(model, 9, 8).unwrap(), "{model:?}");
    }
    let err = x.map(Model::SurrogateError, 5, 4).unwrap();
    let hifi = fresh.map(Model::HiFi, 5, 4).unwrap();
    assert_eq!(err.broken(), hifi.broken());
    // More of the box breaks the tighter limit than the looser one.
    let tight = x.map(Model::LoFi, 9, 8).unwrap();
    // The kept values are the very same (not recomputed).
    assert!(Rc::ptr_eq(&loose.values, &tight.values));
    let count = |m: &ModelMap| m.broken().iter().filter(|&&x| x & 1 != 0).count();
    assert!(
        count(&tight) > count(&loose),
        "{} vs {}",
        count(&tight),
        count(&loose)
    );
}

#[test]
fn surrogate_spectra_carry_the_surrogate_rms() {
    // VBA: each criterion's tuned quarter car has that criterion's surrogate RMS (closed
    // form of the tuned car, an independent route), and its PSD integrates to it.
    let mut x = session(|s| {
        s.surrogate = Some("vba-qts".into());
        s.ks = 26_000.0;
        s.cs = 2_100.0;
    });
    let s = x.scenario().clone();
    let fit = x.surrogate().unwrap();
    let sur = fit.model.evaluate(26_000.0, 2_100.0).unwrap().to_array();
    let quarters = fit
        .model
        .tuned_quarters(26_000.0, 2_100.0)
        .unwrap()
        .unwrap();
    for k in 0..3 {
        let q = crate::analysis::quarter_criteria(&quarters[k], &s.road)
            .unwrap()
            .to_array();
        assert!(
            (q[k] / sur[k] - 1.0).abs() < 1e-9,
            "criterion {k}: {} vs {}",
            q[k],
            sur[k]
        );
    }
    let sp = x.spectra(4000).unwrap();
    assert_eq!(sp.surrogate_route, "tuned quarter car");
    // Trapezoid in ln f over 0.1..100 Hz: the band holds all but the DTL's f^-2 tail
    // beyond 100 Hz (about 1.4 % of its square, see criteria::spectral), so 3 % bounds it.
    let area = |p: &[f64]| {
        (1..sp.f.len())
            .map(|i| 0.5 * (p[i] * sp.f[i] + p[i - 1] * sp.f[i - 1]) * (sp.f[i] / sp.f[i - 1]).ln())
            .sum::<f64>()
    };
    for (k, (psd, s)) in sp.surrogate.psd.iter().zip(sur).enumerate() {
        let rms = area(psd).sqrt();
        assert!(
            (rms / s - 1.0).abs() < 0.03,
            "criterion {k}: PSD RMS {rms} vs {s}"
        );
    }
    // RBA: the LoFi's spectra scaled by S / LoFi.
    let mut x = session(|_| {});
    let s = x.scenario().clone();
    let sp = x.spectra(50).unwrap();
    assert_eq!(sp.surrogate_route, "LoFi scaled by S / LoFi");
    let fit = x.surrogate().unwrap();
    let (ks, cs) = (s.design.front.spring, s.design.front.damper);
    let r = fit.model.evaluate(ks, cs).unwrap().bacc / s.lofi().evaluate(ks, cs).unwrap().bacc;
    for i in 0..50 {
        assert!((sp.surrogate.frf[0][i] / sp.lofi.frf[0][i] - r).abs() < 1e-12);
        assert!((sp.surrogate.psd[0][i] / sp.lofi.psd[0][i] - r * r).abs() < 1e-12);
    }
}

/// The page's "next HiFi run" is the CLI's loop: two steps from the state's gp-mul on
/// `ae:5` give the samples, reasons and history of `adaptive::run` with the default
/// decision (`ridelab surrogate --approach gp-mul --plan ae:5 --adaptive 2`), exactly; each
/// step's re-check is the pick re-run on the HiFi, and the uncertainty map is the estimate
/// at the cell centres in the maps' layout.
#[test]
fn the_pages_adaptive_loop_is_the_clis() {
    use crate::study::adaptive::{run, AdaptiveOptions, Decision};
    use crate::surrogate::{PlanSpec, Setting, SurrogateSpec};
    let s = session(|s| {
        s.surrogate = Some("gp-mul".into());
        s.plan = Some("ae:5".into());
    });
    let sc = s.scenario();
    // `runs` is only recorded by the page's loop (the page steps), as the CLI's.
    let options = AdaptiveOptions {
        runs: 2,
        candidates: 11,
        ..AdaptiveOptions::default()
    };
    let mut page = PageLoop::new(sc, options).unwrap();
    let hifi = sc.hifi().unwrap();
    let mut steps = Vec::new();
    for _ in 0..2 {
        let p = page.propose().unwrap();
        let st = page.step().unwrap();
        assert_eq!(st.added.candidate, p.candidate);
        let c = hifi.evaluate(st.step.pick.ks, st.step.pick.cs).unwrap();
        assert_eq!(st.recheck.rechecked, c);
        steps.push(st);
    }
    let setting = Setting::new(&sc.datum, &sc.road, &sc.dbox).unwrap();
    let cli = run(
        SurrogateSpec::parse("gp-mul").unwrap(),
        &setting,
        &hifi,
        PlanSpec::AudzeEglais(5),
        &Decision::of_car(&sc.datum, &hifi).unwrap(),
        options,
    )
    .unwrap();
    assert_eq!(page.report(), cli.report());
    assert_eq!(page.front(), cli.front());
    assert_eq!(steps[1].step, cli.report().history[2]);
    let (nx, ny) = (5, 4);
    let map = page.uncertainty_map(nx, ny).unwrap();
    let grid = crate::maps::Grid::cells(&sc.dbox, nx, ny).unwrap();
    for j in 0..ny {
        for i in 0..nx {
            let (ks, cs) = grid.point(i, j);
            let want = cli.uncertain().relative_std(ks, cs).unwrap();
            for k in 0..3 {
                assert_eq!(map[k * nx * ny + j * nx + i], 100.0 * want[k]);
            }
        }
    }
    let e = page.uncertainty_map(1, 4).unwrap_err().to_string();
    assert!(e.starts_with("nx: "), "{e}");

    // The check against the truth, re-derived point by point on a 6 x 6 HiFi grid (Ks
    // level outer): the estimate of the CLI's loop and |S / F - 1| of its surrogate, %;
    // correlations to 1e-12.
    let levels = 6;
    let u = page.uncertainty_check(levels).unwrap();
    let (mut sigma, mut truth) = ([vec![], vec![], vec![]], [vec![], vec![], vec![]]);
    for i in 0..levels {
        for j in 0..levels {
            let t = |l: usize| l as f64 / (levels - 1) as f64;
            let (ks, cs) = sc.dbox.scale(t(i), t(j));
            let s = cli.uncertain().relative_std(ks, cs).unwrap();
            let p = cli.model().evaluate(ks, cs).unwrap().to_array();
            let f = hifi.evaluate(ks, cs).unwrap().to_array();
            for k in 0..3 {
                sigma[k].push(100.0 * s[k]);
                truth[k].push(100.0 * (p[k] / f[k] - 1.0).abs());
            }
        }
    }
    use crate::surrogate::metrics::{pearson, spearman};
    for k in 0..3 {
        let (r, rho) = (
            pearson(&sigma[k], &truth[k]),
            spearman(&sigma[k], &truth[k]),
        );
        let (got_r, got_rho) = (
            u.check.pearson.to_array()[k],
            u.check.spearman.to_array()[k],
        );
        assert!(
            (got_r.unwrap() - r.unwrap()).abs() < 1e-12,
            "{k}: {got_r:?} vs {r:?}"
        );
        assert!(
            (got_rho.unwrap() - rho.unwrap()).abs() < 1e-12,
            "{k}: {got_rho:?} vs {rho:?}"
        );
        // The grid's points are scaled from the plan's unit levels: equal to 1e-12.
        for (got, want) in u.check.map_percent.to_array()[k].iter().zip(&sigma[k]) {
            assert!(
                (got - want).abs() <= 1e-12 * want.abs(),
                "{k}: {got} vs {want}"
            );
        }
    }
    assert_eq!(u.levels, levels);
    // gp-mul interpolates: at its 7 samples the estimate is at the nugget's floor, below
    // 1e-4 of its largest value on the map (the estimator's own test bounds the same).
    let peak = map.iter().copied().fold(0.0, f64::max);
    for k in 0..3 {
        let floor = *u.at_samples_percent.to_array()[k];
        assert!(
            floor >= 0.0 && floor <= 1e-4 * peak,
            "{k}: {floor} % vs peak {peak} %"
        );
    }
    // The grid is run once and kept; a bad size names `levels`.
    assert_eq!(page.uncertainty_check(levels).unwrap(), u);
    for bad in [1, MAX_CHECK_LEVELS + 1] {
        let e = page.uncertainty_check(bad).unwrap_err().to_string();
        assert!(e.starts_with("levels: "), "{e}");
    }
}

/// The page's list of state keys (unknown keys are refused against it) is exactly the
/// keys a state serialises to, every optional field set.
#[test]
fn state_fields_are_the_serialised_keys() {
    let state = State {
        car_json: Some("{}".into()),
        bounce_band: Some([0.8, 1.5]),
        damping_band: Some([0.2, 0.5]),
        no_worse: Some([false; 3]),
        dtl_margin: Some(3.0),
        travel: Some([0.025, 3.0]),
        road_profile: Some("road.csv#0".into()),
        ..State::default()
    };
    let v = serde_json::to_value(&state).unwrap();
    let mut keys: Vec<&str> = v.as_object().unwrap().keys().map(|k| k.as_str()).collect();
    let mut want = crate::explorer::STATE_FIELDS.to_vec();
    keys.sort();
    want.sort();
    assert_eq!(keys, want);
}

/// Each state field but `carJson`, `roadProfile` and `case` with another valid value than
/// [`State::default`]'s (what the key-list and tag tests change one at a time).
pub(super) fn other_values() -> Vec<(&'static str, serde_json::Value)> {
    vec![
        ("car", "compact".into()),
        ("ks", 21_000.0.into()),
        ("cs", 1_500.0.into()),
        ("class", "A".into()),
        ("speed", 25.0.into()),
        ("tracks", "independent".into()),
        ("ksMin", 12_000.0.into()),
        ("ksMax", 38_000.0.into()),
        ("csMin", 600.0.into()),
        ("csMax", 3_800.0.into()),
        ("swsLimit", 0.008.into()),
        ("bounceBand", serde_json::json!([0.9, 1.4])),
        ("dampingBand", serde_json::json!([0.25, 0.45])),
        ("noWorse", serde_json::json!([true, false, false])),
        ("dtlMargin", 3.0.into()),
        ("travel", serde_json::json!([0.08, 3.0])),
        ("surrogate", "vba-qts".into()),
        ("plan", "ae:8".into()),
        ("comfort", "wk".into()),
        ("pick", "knee".into()),
        (
            "cases",
            r#"{"operating": [{"class": "C", "speed": 25}]}"#.into(),
        ),
    ]
}

/// `FIT_FIELDS` and `REPORT_FIELDS` are what the page keys fits and reports by: every
/// state field changed alone (to another valid value) changes the fit key exactly when it
/// is a fit field, and the design's LoFi report (its numbers, car or road) exactly when it
/// is a report field.
#[test]
fn the_key_field_lists_are_what_fits_and_reports_depend_on() {
    use crate::analysis::{report, ModelKind};
    let others = other_values();
    let base = State::default();
    let base_s = base.scenario().unwrap();
    let base_report = report(ModelKind::Quarter, &base_s.design, &base_s.road).unwrap();
    // A measured road (`roadProfile`) is a fit and report field: tested with its
    // resolver in tests_measured (the fit key there, the report's road and numbers here).
    let mut seen = vec!["carJson", "case", "roadProfile"];
    // The case the maps show picks among kept values: neither the fit nor the values change.
    let with_cases = State {
        cases: Some(
            r#"{"load_cases": [{"name": "a", "mass": 0}, {"name": "b", "mass": 90}]}"#.into(),
        ),
        ..State::default()
    };
    let case1 = State {
        case: Some("1".into()),
        ..with_cases.clone()
    };
    assert!(!FIT_FIELDS.contains(&"case"));
    assert_eq!(
        FitKey::of(&case1.scenario().unwrap()),
        FitKey::of(&with_cases.scenario().unwrap())
    );
    for (field, value) in others {
        let mut v = serde_json::to_value(&base).unwrap();
        v[field] = value;
        let state: State = serde_json::from_value(v).unwrap();
        let s = state.scenario().unwrap_or_else(|e| panic!("{field}: {e}"));
        let fit_changed = FitKey::of(&s) != FitKey::of(&base_s);
        assert_eq!(fit_changed, FIT_FIELDS.contains(&field), "{field}: fit key");
        let r = report(ModelKind::Quarter, &s.design, &s.road).unwrap();
        // The quarter car sees one track: the road itself says whether the tracks changed.
        let report_changed =
            r.bacc != base_report.bacc || r.car != base_report.car || r.road != base_report.road;
        assert_eq!(
            report_changed,
            REPORT_FIELDS.contains(&field),
            "{field}: report"
        );
        seen.push(field);
    }
    seen.sort_unstable();
    let mut all = STATE_FIELDS.to_vec();
    all.sort_unstable();
    assert_eq!(
        seen, all,
        "every state field is tried (carJson goes with car)"
    );
}

/// HiFi values from the GPU path (here the kernel's f32 arithmetic run on the CPU,
/// `MapInput::map_cpu::<f32>`) kept in the session: the HiFi map shows them exactly,
/// the error map is `100 (S / HiFi - 1)` of them, both say `Gpu`; they are within 1e-4 of
/// the session's own CPU map; bad planes are refused naming `values`, and a road change
/// drops them (the CPU computes again).
#[test]
fn hifi_values_from_the_gpu_path_are_kept_and_shown() {
    use crate::gpu::{ComputePath, MapInput};
    use crate::maps::Grid;
    let (nx, ny) = (8, 6);
    let mut x = session(|_| {});
    let s = x.scenario().clone();
    let cpu = x.map(Model::HiFi, nx, ny).unwrap();
    assert_eq!(x.hifi_path(nx, ny), Some(ComputePath::Cpu));
    let grid = Grid::cells(&s.dbox, nx, ny).unwrap();
    let cells = MapInput::new(&s.datum, &s.road, &grid)
        .unwrap()
        .map_cpu::<f32>()
        .unwrap();
    let n = cells.len();
    let mut planes = vec![0.0; 3 * n];
    for (k, c) in cells.iter().enumerate() {
        planes[k] = c.bacc;
        planes[n + k] = c.dtl;
        planes[2 * n + k] = c.sws;
    }
    let field_of = |e: crate::error::RideError| match e {
        crate::error::RideError::Field { field, .. } => field,
        other => panic!("{other}"),
    };
    assert_eq!(
        field_of(x.keep_hifi_planes(nx, ny, &planes[1..]).unwrap_err()),
        "values"
    );
    let mut bad = planes.clone();
    bad[5] = f64::NAN;
    assert_eq!(
        field_of(x.keep_hifi_planes(nx, ny, &bad).unwrap_err()),
        "values"
    );
    assert_eq!(
        x.hifi_path(nx, ny),
        Some(ComputePath::Cpu),
        "a refused hand-in keeps the CPU values"
    );
    x.keep_hifi_planes(nx, ny, &planes).unwrap();
    assert_eq!(x.hifi_path(nx, ny), Some(ComputePath::Gpu));
    let gpu = x.map(Model::HiFi, nx, ny).unwrap();
    assert_eq!(gpu.planes(), planes);
    assert_eq!(
        gpu.values.datum, cpu.values.datum,
        "the datum stays the CPU HiFi's"
    );
    let worst = gpu
        .planes()
        .iter()
        .zip(cpu.planes())
        .map(|(g, c)| (g / c - 1.0).abs())
        .fold(0.0, f64::max);
    assert!(worst <= 1e-4, "GPU route vs CPU HiFi: {worst:e}");
    let sur = x.map(Model::Surrogate, nx, ny).unwrap().planes();
    let err = x.map(Model::SurrogateError, nx, ny).unwrap().planes();
    for k in 0..3 * n {
        assert!(
            (err[k] - 100.0 * (sur[k] / planes[k] - 1.0)).abs() < 1e-9,
            "cell {k}"
        );
    }
    let faster = State {
        speed: 25.0,
        ..x.state().clone()
    };
    x.set_state(faster).unwrap();
    assert_eq!(x.hifi_path(nx, ny), None);
    x.map(Model::HiFi, nx, ny).unwrap();
    assert_eq!(x.hifi_path(nx, ny), Some(ComputePath::Cpu));
}

/// A slider step's one call gives what the separate calls give: the LoFi and HiFi
/// readouts the full reports' numbers (BAcc, DTL, SWS bit for bit, the same routes; the
/// Wk-weighted BAcc by the modal route within 1e-8 of the report's frequency route, as
/// `tests/models.rs` states), the surrogate's and the plane's criteria the session's, and
/// the session's tags.
#[test]
fn a_slider_step_is_the_separate_calls() {
    use crate::analysis::ModelKind;
    for comfort in ["bacc", "wk"] {
        let mut s = session(|st| st.comfort = Some(comfort.into()));
        s.set_design(23_000.0, 1_900.0).unwrap();
        let step = s.design_step(Model::LoFi, true).unwrap();
        let hifi = step.hifi.as_ref().unwrap();
        for (got, kind) in [(&step.lofi, ModelKind::Quarter), (hifi, ModelKind::Full)] {
            let want = s.report(kind).unwrap();
            assert!(
                want.route_difference.unwrap() < 1e-6,
                "{kind:?}: the report checks its route"
            );
            assert_eq!(
                [got.bacc, got.dtl, got.sws],
                [want.bacc, want.dtl, want.sws],
                "{comfort} {kind:?}"
            );
            let wk = (got.bacc_wk / want.bacc_wk - 1.0).abs();
            assert!(
                wk < 1e-8,
                "{comfort} {kind:?}: Wk {} against {}",
                got.bacc_wk,
                want.bacc_wk
            );
            assert_eq!((got.ks, got.cs, got.route), (23_000.0, 1_900.0, want.route));
            assert_eq!(got.modes, want.modes);
        }
        assert_eq!(step.surrogate, s.criteria(Model::Surrogate).unwrap());
        assert_eq!(step.plane, Some(s.criteria(Model::LoFi).unwrap()));
        assert_eq!(step.tags, s.tags());
    }
}
