//! The explorer's robust design (issue #16): the session's robust and per-case maps
//! against `ridelab map --cases`'s own functions, its robust front and per-case pick
//! against `ridelab optimize --cases`'s, and bad cases named.

use super::*;
use crate::analysis::ModelKind;
use crate::maps::Grid;
use crate::optimize::{Method, StmParams};
use crate::robust::CaseSet;
use crate::study::{EvaluatorSpec, OptimizeRequest};
use crate::study::{MapReport, MapRequest, MapSettings};

/// Two load cases at three operating points: six cases.
const SIX: &str = r#"{"load_cases": [{"name": "driver only", "mass": 0},
  {"name": "fully laden", "mass": 350, "x": -0.3, "y": 0.4, "z": 0.1, "weight": 2}],
  "operating": [{"class": "B", "speed": 20}, {"class": "B", "speed": 30, "weight": 3},
  {"class": "A", "speed": 35}], "combine": "COMBINE"}"#;

/// `ridelab optimize --cases` on the scenario's car, road, box, plan, objectives, comfort
/// and pick, by `method` on `kind`: what the page's robust fronts are checked against.
fn cli_front(sc: &Scenario, kind: ModelKind, method: Method) -> OptimizeRequest<'_> {
    OptimizeRequest {
        evaluator: EvaluatorSpec::Model(kind),
        plan: sc.plan,
        comfort: sc.comfort,
        pick: sc.pick,
        ..OptimizeRequest::new(&sc.datum, &sc.road, sc.dbox, method, sc.objectives.clone())
    }
}

fn cases(combine: &str) -> String {
    SIX.replace("COMBINE", combine)
}

/// A state with the six cases, "no worse than the datum" on BAcc, a DTL margin and a
/// 12 mm SWS limit (so the mask depends on each case's own datum and wheel load).
fn robust_state(combine: &str) -> State {
    State {
        cases: Some(cases(combine)),
        no_worse: Some([true, false, false]),
        sws_limit: Some(0.012),
        dtl_margin: Some(3.0),
        ..State::default()
    }
}

/// The CLI's case set and map settings for the session's scenario on its `nx` x `ny`
/// cell grid.
fn cli_setting(s: &Session, nx: usize, ny: usize) -> (CaseSet, MapSettings) {
    let sc = s.scenario();
    let text = s.state().cases.clone().unwrap();
    let set = CaseSet::from_json(&text, &sc.datum, &[], &sc.road).unwrap();
    let settings = MapSettings {
        grid: Grid::cells(&sc.dbox, nx, ny).unwrap(),
        objectives: sc.objectives.clone(),
        comfort: sc.comfort,
        ..MapSettings::default()
    };
    (set, settings)
}

/// `got`'s planes and mask against a CLI map report's, each value to `tol` relative
/// (0: bit for bit).
fn assert_map_eq(got: &ModelMap, want: &MapReport, tol: f64, what: &str) {
    let planes = got.planes();
    let n = want.bacc.len();
    for (c, w) in [&want.bacc, &want.dtl, &want.sws].iter().enumerate() {
        for k in 0..n {
            let (g, w) = (planes[c * n + k], w[k]);
            assert!(
                (g - w).abs() <= tol * w.abs(),
                "{what}: plane {c} cell {k}: {g} vs {w}"
            );
        }
    }
    assert_eq!(
        got.broken(),
        want.feasibility.mask.as_slice(),
        "{what}: mask"
    );
    assert_eq!(
        got.dos.summary.feasible, want.feasibility.summary.feasible,
        "{what}"
    );
    let d = (got.values.datum.criteria, want.datum.criteria);
    for (g, w) in d.0.to_array().iter().zip(d.1.to_array()) {
        assert!((g - w).abs() <= tol * w.abs(), "{what}: datum {g} vs {w}");
    }
}

/// The page's robust LoFi map is `MapRequest::run_robust`'s, cell for cell and bit for bit,
/// for the worst case and the weighted mean; its HiFi map to 1e-12 relative (the CLI's
/// HiFi grid route against the session's point evaluator); the mask is the OR of the
/// cases' masks (a case with fewer feasible cells than the robust map would be wrong).
#[test]
fn robust_maps_are_the_clis() {
    for combine in ["worst", "mean"] {
        let mut s = Session::new(robust_state(combine)).unwrap();
        assert_eq!(s.scenario().cases.as_ref().unwrap().cases.len(), 6);
        assert_eq!(s.scenario().case, None);
        for (model, kind, nx, ny, tol) in [
            (Model::LoFi, ModelKind::Quarter, 32, 24, 0.0),
            (Model::HiFi, ModelKind::Full, 8, 6, 1e-12),
        ] {
            let (set, settings) = cli_setting(&s, nx, ny);
            let sc = s.scenario().clone();
            let want = MapRequest::new(kind, &sc.datum, &sc.road, settings)
                .run_robust(&set)
                .unwrap();
            let got = s.map(model, nx, ny).unwrap();
            assert_map_eq(&got, &want.map, tol, &format!("{combine} {model:?}"));
            let feasible = got.dos.summary.feasible;
            assert!(feasible > 0 && feasible < nx * ny, "{feasible}");
            for f in &want.robust.feasible_per_case {
                assert!(*f >= feasible);
            }
        }
    }
}

/// `case` K: the maps are `ridelab map --cases --case K`'s (that case's loaded car on its
/// road against its own datum), bit for bit; switching back to "robust" reuses the kept
/// per-case values and gives the robust map again.
#[test]
fn case_k_map_is_that_cases_map() {
    let mut s = Session::new(robust_state("worst")).unwrap();
    let robust = s.map(Model::LoFi, 20, 15).unwrap();
    for k in [0, 4, 5] {
        s.set_state(State {
            case: Some(k.to_string()),
            ..s.state().clone()
        })
        .unwrap();
        assert_eq!(s.scenario().case, Some(k));
        let (set, settings) = cli_setting(&s, 20, 15);
        let sc = s.scenario();
        let want = MapRequest::new(ModelKind::Quarter, &sc.datum, &sc.road, settings)
            .run_case(&set, k)
            .unwrap();
        let got = s.map(Model::LoFi, 20, 15).unwrap();
        assert_map_eq(&got, &want.map, 0.0, &format!("case {k}"));
    }
    s.set_state(State {
        case: Some("robust".into()),
        ..s.state().clone()
    })
    .unwrap();
    assert_eq!(s.map(Model::LoFi, 20, 15).unwrap(), robust);
}

/// One case (an empty cases file: the car as given on the state's road): the robust
/// map is the plain map bit for bit, for both rules.
#[test]
fn one_case_is_the_plain_map() {
    let mut plain = Session::new(robust_state("worst")).unwrap();
    plain
        .set_state(State {
            cases: None,
            ..plain.state().clone()
        })
        .unwrap();
    let want = plain.map(Model::LoFi, 12, 9).unwrap();
    for text in ["{}", r#"{"combine": "mean"}"#] {
        let mut s = Session::new(State {
            cases: Some(text.into()),
            ..plain.state().clone()
        })
        .unwrap();
        let got = s.map(Model::LoFi, 12, 9).unwrap();
        assert_eq!(got.planes(), want.planes(), "{text}");
        assert_eq!(got.broken(), want.broken(), "{text}");
    }
}

/// The robust front on the page's settings (STM, `STM_GRID` levels `STM_LEVELS`, the
/// quarter car) is `OptimizeRequest::run_robust`'s: front, hypervolume, pick, robust HiFi
/// re-check and each case's prediction, re-check and broken objectives, exactly. The
/// robust criteria the page gives the design at the pick are the pick's (the plane's
/// design marker and the front agree), and the plane's feasible set has the pick's cell
/// values by the same normalisation.
#[test]
fn robust_front_is_the_clis() {
    let mut s = Session::new(State {
        pick: Some("knee".into()),
        ..robust_state("worst")
    })
    .unwrap();
    let sc = s.scenario().clone();
    let set = sc.cases.clone().unwrap();
    let want = cli_front(
        &sc,
        ModelKind::Quarter,
        Method::Stm(StmParams {
            grid: studies::STM_GRID,
            levels: studies::STM_LEVELS,
        }),
    )
    .run_robust(&set)
    .unwrap();
    for model in [Model::Robust, Model::LoFi] {
        let got = s.front("stm", model).unwrap();
        assert_eq!(got.study, want.study);
        assert_eq!(got.datum, want.datum);
        assert_eq!(got.recheck, want.hifi_recheck);
        let r = got.robust.as_ref().unwrap();
        assert_eq!(r.cases, want.cases);
        assert_eq!(r.cases.len(), 6);
        assert_eq!(got.pseudo_weights.len(), got.study.front.len());
    }
    // The page's NSGA-II (population 60, 60 generations, seed 1) with cases is
    // `ridelab optimize --cases --method nsga2`'s.
    let nsga = cli_front(&sc, ModelKind::Quarter, studies::method("nsga2").unwrap())
        .run_robust(&set)
        .unwrap();
    let got = s.front("nsga2", Model::LoFi).unwrap();
    assert_eq!(got.study, nsga.study);
    assert_eq!(got.robust.as_ref().unwrap().cases, nsga.cases);
    assert!(
        nsga.study.front.len() > 10,
        "{} points",
        nsga.study.front.len()
    );
    let p = &want.study.pick;
    s.set_design(p.ks, p.cs).unwrap();
    assert_eq!(s.criteria(Model::Robust).unwrap(), p.criteria);
    let per = s.case_criteria(ModelKind::Quarter).unwrap();
    for (c, w) in per.iter().zip(&want.cases) {
        assert_eq!(*c, w.hifi_recheck.predicted, "{}", w.case.name);
    }
    // The plane's feasible set: its datum is the front's, and no feasible cell beats the
    // front's ideal point (the front's extremes bound the feasible set) by more than the
    // STM's grid resolution (0.5 %).
    let cloud = s.map(Model::Robust, 40, 30).unwrap();
    assert_eq!(cloud.values.datum.criteria, want.datum);
    let f = &want.study.front;
    let min_b = f.iter().map(|q| q.bacc).fold(f64::INFINITY, f64::min);
    let min_d = f.iter().map(|q| q.dtl).fold(f64::INFINITY, f64::min);
    assert!(!cloud.dos.feasible_set.is_empty());
    for q in &cloud.dos.feasible_set {
        assert!(q.bacc >= min_b * 0.995 && q.dtl >= min_d * 0.995, "{q:?}");
    }
}

/// Bad cases name the field under `cases` and leave the session at its last good state;
/// a bad `case` names `case`; the surrogate's front is refused naming `cases`.
#[test]
fn bad_cases_are_named_and_the_last_good_state_kept() {
    let mut s = Session::new(robust_state("worst")).unwrap();
    let good = s.state().clone();
    let err = |s: &mut Session, patch: &dyn Fn(&mut State)| {
        let mut st = s.state().clone();
        patch(&mut st);
        let e = s.set_state(st).unwrap_err();
        assert_eq!(s.state(), &good, "last good state kept");
        e
    };
    let field = |e: &crate::error::RideError| match e {
        crate::error::RideError::Field { field, .. } => field.clone(),
        other => panic!("not a field error: {other}"),
    };
    let heavy = cases("worst").replace("\"mass\": 350", "\"mass\": -5000");
    let e = err(&mut s, &|st| st.cases = Some(heavy.clone()));
    assert_eq!(field(&e), "cases.load_cases[1].mass");
    assert_eq!(ui_field(&field(&e)), "cases");
    let e = err(&mut s, &|st| st.cases = Some("{\"operating\": [".into()));
    assert!(field(&e).starts_with("cases"), "{e}");
    let e = err(&mut s, &|st| {
        st.cases = Some(r#"{"operating": [{"class": "B", "speed": -2}]}"#.into())
    });
    assert_eq!(field(&e), "cases.operating[0].speed");
    let e = err(&mut s, &|st| {
        st.cases = Some(r#"{"combine": "median"}"#.into())
    });
    assert_eq!(field(&e), "cases.combine");
    let ops: Vec<String> = (0..9)
        .map(|i| format!(r#"{{"class": "B", "speed": {}}}"#, 10 + i))
        .collect();
    let many = cases("worst").replace(
        &cases("worst")[cases("worst").find("\"operating\"").unwrap()
            ..cases("worst").find(", \"combine\"").unwrap()],
        &format!("\"operating\": [{}]", ops.join(",")),
    );
    let e = err(&mut s, &|st| st.cases = Some(many.clone()));
    assert_eq!(field(&e), "cases.operating");
    assert!(e.to_string().contains("= 18 cases; at most 16"), "{e}");
    let long = format!("{{\"combine\": \"worst\"{}}}", " ".repeat(20_000));
    let e = err(&mut s, &|st| st.cases = Some(long.clone()));
    assert_eq!(field(&e), "cases");
    let e = err(&mut s, &|st| st.case = Some("6".into()));
    assert_eq!(field(&e), "case");
    let e = err(&mut s, &|st| st.case = Some("first".into()));
    assert_eq!(field(&e), "case");
    let e = s.front("stm", Model::Surrogate).unwrap_err();
    assert_eq!(field(&e), "cases");
    // The page's first-screen wasm asks for a single scenario's front only; with cases it
    // is refused, and the robust front (the workers') is `front`'s.
    assert_eq!(
        field(&s.single_front("stm", Model::LoFi).unwrap_err()),
        "cases"
    );
    assert_eq!(
        s.robust_front("stm", Model::Robust).unwrap().study.front,
        s.front("stm", Model::Robust).unwrap().study.front
    );
    // The robust HiFi front runs on the CPU: GPU values (one case's grid) are refused.
    let planes = vec![1.0; 3 * studies::STM_GRID * studies::STM_GRID];
    assert_eq!(field(&s.hifi_front(Some(&planes)).unwrap_err()), "cases");
    let mut plain = Session::new(State::default()).unwrap();
    let e = plain
        .set_state(State {
            case: Some("1".into()),
            ..State::default()
        })
        .unwrap_err();
    assert_eq!(field(&e), "case");
    assert_eq!(
        field(&plain.front("stm", Model::Robust).unwrap_err()),
        "cases"
    );
    assert_eq!(
        field(&plain.robust_front("stm", Model::LoFi).unwrap_err()),
        "cases"
    );
    assert_eq!(field(&plain.criteria(Model::Robust).unwrap_err()), "cases");
}

/// The design's criteria as the maps show them (`map_criteria`, what the page's map
/// captions read) equal the robust and per-case LoFi and HiFi maps' cells at that point,
/// both rules; without cases the car's own criteria.
#[test]
fn map_criteria_are_the_maps_cells() {
    for combine in ["worst", "mean"] {
        let mut s = Session::new(robust_state(combine)).unwrap();
        for (kind, model) in [
            (ModelKind::Quarter, Model::LoFi),
            (ModelKind::Full, Model::HiFi),
        ] {
            for case in [None, Some("4")] {
                let mut st = s.state().clone();
                st.case = case.map(str::to_string);
                s.set_state(st).unwrap();
                let map = s.map(model, 3, 2).unwrap();
                let v = &map.values;
                for k in [0, 4] {
                    let (i, j) = v.grid.indices(k);
                    let (ks, cs) = v.grid.point(i, j);
                    s.set_design(ks, cs).unwrap();
                    let got = s.map_criteria(kind).unwrap().to_array();
                    let want = [v.bacc[k], v.dtl[k], v.sws[k]];
                    for (g, w) in got.iter().zip(want) {
                        assert!(
                            (g / w - 1.0).abs() < 1e-12,
                            "{combine} {model:?} case {case:?} cell {k}: {g} vs {w}"
                        );
                    }
                }
            }
        }
    }
    let mut plain = Session::new(State::default()).unwrap();
    assert_eq!(
        plain.map_criteria(ModelKind::Quarter).unwrap(),
        plain.criteria(Model::LoFi).unwrap()
    );
}

/// A custom car file that lists load cases, as `ridelab map --car FILE --cases C` reads
/// it: the cases file's `load_cases` default to the file's; a cases file with its own
/// replaces them; a new car file brings its own (the kept case set is not reused).
#[test]
fn a_car_files_load_cases_are_the_cases_default() {
    let mut file: serde_json::Value = serde_json::from_str(crate::car::PRESETS[0].1).unwrap();
    file["load_cases"] = serde_json::json!([
        {"name": "driver only", "mass": 0},
        {"name": "roof box", "mass": 60, "x": -0.2, "z": 0.9}
    ]);
    let text = file.to_string();
    let cases = r#"{"operating": [{"class": "B", "speed": 20}, {"class": "C", "speed": 15}]}"#;
    let mut s = Session::new(State {
        car: "custom".into(),
        car_json: Some(text.clone()),
        cases: Some(cases.into()),
        ..State::default()
    })
    .unwrap();
    let sc = s.scenario().clone();
    let cli = crate::robust::CarFile::from_json(&text).unwrap();
    assert_eq!(cli.load_cases.len(), 2);
    let want = CaseSet::from_json(cases, &cli.car, &cli.load_cases, &sc.road).unwrap();
    let got = sc.cases.clone().unwrap();
    assert_eq!(got.cases.len(), 4);
    for (g, w) in got.cases.iter().zip(&want.cases) {
        assert_eq!((&g.name, &g.car, g.road), (&w.name, &w.car, w.road));
    }
    let settings = MapSettings {
        grid: Grid::cells(&sc.dbox, 16, 12).unwrap(),
        objectives: sc.objectives.clone(),
        ..MapSettings::default()
    };
    let map = MapRequest::new(ModelKind::Quarter, &cli.car, &sc.road, settings)
        .run_robust(&want)
        .unwrap();
    assert_map_eq(
        &s.map(Model::LoFi, 16, 12).unwrap(),
        &map.map,
        0.0,
        "car file's load cases",
    );
    // The cases file's own load cases replace the car file's.
    let own = r#"{"load_cases": [{"name": "laden", "mass": 300}], "combine": "mean"}"#;
    let mut st = s.state().clone();
    st.cases = Some(own.into());
    s.set_state(st).unwrap();
    assert_eq!(s.scenario().cases.as_ref().unwrap().cases.len(), 1);
    // The same cases text with a car file of other load cases: re-read, not kept.
    let mut st = s.state().clone();
    st.cases = Some(cases.into());
    s.set_state(st).unwrap();
    file["load_cases"] = serde_json::json!([{"name": "empty", "mass": 0}]);
    let mut st = s.state().clone();
    st.car_json = Some(file.to_string());
    s.set_state(st).unwrap();
    assert_eq!(s.scenario().cases.as_ref().unwrap().cases.len(), 2);
    // A bad load case in the car file names it.
    file["load_cases"] = serde_json::json!([{"name": "x", "mass": -5000}]);
    let mut st = s.state().clone();
    st.car_json = Some(file.to_string());
    let e = s.set_state(st).unwrap_err();
    assert!(e.to_string().contains("load_cases[0].mass"), "{e}");
}

/// With cases the HiFi front is the robust one, `ridelab optimize --cases --evaluator
/// full` bit for bit, and the plane's LoFi robust front is judged against it: each of its
/// designs re-run on every case's HiFi through the session's per-case readout, combined
/// with the cases' HiFi datums and kept where no case breaks an objective (`broken`, a
/// second function from the optimiser's constraints), to 1e-12. One case "as given" on
/// the scenario's road gives the single-case HiFi front exactly (the limiting case).
#[test]
fn robust_hifi_front_is_optimize_cases_on_the_full_car() {
    let mut s = Session::new(robust_state("worst")).unwrap();
    let view = s.hifi_front(None).unwrap();
    let sc = s.scenario().clone();
    let set = sc.cases.clone().unwrap();
    let want = cli_front(&sc, ModelKind::Full, studies::method("stm").unwrap())
        .run_robust(&set)
        .unwrap();
    assert_eq!(view.front.study, want.study);
    assert_eq!(view.front.datum, want.datum);
    assert_eq!(view.hifi_runs, want.study.evaluations + 6);
    assert_eq!(view.plane.model, "robust");
    assert_eq!(view.plane.hifi_runs, 12);
    assert!(
        want.study.front.len() > 10,
        "{} points",
        want.study.front.len()
    );
    // The plane's front, judged independently.
    let plane = s.front("stm", Model::Robust).unwrap();
    let (combination, datums) =
        crate::study::robust::optimize::hifi_combination(&set, sc.comfort).unwrap();
    let mut kept = Vec::new();
    for p in &plane.study.front {
        s.set_design(p.ks, p.cs).unwrap();
        let per = s.case_criteria(ModelKind::Full).unwrap();
        let ok = set.cases.iter().zip(&per).zip(&datums).all(|((c, h), d)| {
            let ctx = crate::dos::DosContext::new(&c.car, *d);
            sc.objectives.broken(&ctx, p.ks, p.cs, h).is_empty()
        });
        if ok {
            let r = combination.apply(&per);
            kept.push([r.bacc, r.dtl]);
        }
    }
    let reference = want.study.reference_point;
    let hv = crate::optimize::hypervolume(&kept, reference);
    assert_eq!(view.plane.front_points, plane.study.front.len());
    assert_eq!(view.plane.hifi_feasible_points, kept.len());
    assert!(
        (view.plane.hypervolume_on_hifi / hv - 1.0).abs() < 1e-12,
        "{} vs {hv}",
        view.plane.hypervolume_on_hifi
    );
    assert!((view.plane.hypervolume_ratio - hv / want.study.hypervolume).abs() < 1e-12);
    assert!(
        view.plane.hypervolume_ratio > 0.5 && view.plane.hypervolume_ratio <= 1.0 + 1e-9,
        "{}",
        view.plane.hypervolume_ratio
    );
    let (a, b) = (
        plane.recheck.rechecked.to_array(),
        want.study.pick.criteria.to_array(),
    );
    for k in 0..3 {
        assert!((view.plane.pick_gap_percent[k] - 100.0 * (a[k] / b[k] - 1.0)).abs() < 1e-12);
    }
    // One case, the car as given on the scenario's road: the single-case HiFi front.
    let mut one = Session::new(State {
        cases: Some(r#"{"combine": "worst"}"#.into()),
        ..State::default()
    })
    .unwrap();
    let robust = one.hifi_front(None).unwrap();
    let mut plain = Session::new(State::default()).unwrap();
    let single = plain.hifi_front(None).unwrap();
    assert_eq!(robust.front.study.front, single.front.study.front);
    assert_eq!(
        robust.front.study.hypervolume,
        single.front.study.hypervolume
    );
    assert_eq!(robust.front.study.pick, single.front.study.pick);
    assert_eq!(robust.hifi_runs, single.hifi_runs);
}
