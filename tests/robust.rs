//! Robust design over load cases and operating points (issue #16): the loaded car on both
//! models, the robust map and front against the single cases, the CLI's cases file.

use ridelab::analysis::{quarter_criteria, ModelKind};
use ridelab::car::QuarterCar;
use ridelab::design::DesignBox;
use ridelab::dos::{DesignObjectives, DosContext};
use ridelab::gpu::Compute;
use ridelab::maps::Grid;
use ridelab::optimize::{non_dominated, Method, PickRule, StmParams};
use ridelab::robust::{CaseSet, Combine, LoadCase, Operating};
use ridelab::study::{EvaluatorSpec, OptimizeRequest};
use ridelab::study::{MapRequest, MapSettings};
use ridelab::surrogate::PlanSpec;
use ridelab::{Car, Evaluator, HiFi, LoFi, Road, RoadClass};
use serde_json::Value;
use std::process::Command;

fn load(name: &str, mass: f64, x: f64) -> LoadCase {
    LoadCase {
        name: name.into(),
        mass,
        x,
        y: 0.0,
        z: 0.0,
        weight: 1.0,
    }
}

fn op(class: RoadClass, speed: f64) -> Operating {
    Operating {
        class,
        speed,
        weight: 1.0,
    }
}

const DESIGNS: [(f64, f64); 3] = [(12_000.0, 700.0), (24_000.0, 2100.0), (37_000.0, 3800.0)];

/// A load case with zero extra mass (placed anywhere) gives the base car's criteria bit
/// for bit on the LoFi and the HiFi, on correlated and independent tracks.
#[test]
fn zero_extra_mass_is_the_base_car_bit_for_bit() {
    let car = Car::datum();
    let zero = LoadCase {
        y: 0.5,
        z: 0.3,
        ..load("empty", 0.0, 1.1)
    };
    for tracks in [ridelab::Tracks::Correlated, ridelab::Tracks::Independent] {
        let road = Road {
            tracks,
            ..Road::default()
        };
        let set = CaseSet::new(
            &car,
            &road,
            std::slice::from_ref(&zero),
            &[],
            Combine::Worst,
        )
        .unwrap();
        let case = &set.cases[0].car;
        let (lo_case, lo_base) = (LoFi::new(case, &road), LoFi::new(&car, &road));
        let (hi_case, hi_base) = (
            HiFi::new(case, &road).unwrap(),
            HiFi::new(&car, &road).unwrap(),
        );
        for (ks, cs) in DESIGNS {
            assert_eq!(
                lo_case.evaluate(ks, cs).unwrap(),
                lo_base.evaluate(ks, cs).unwrap()
            );
            assert_eq!(
                hi_case.evaluate(ks, cs).unwrap(),
                hi_base.evaluate(ks, cs).unwrap()
            );
        }
    }
}

/// The loaded car drives both models consistently: the LoFi is the quarter car with
/// `ms = (M + m) b' / (2 L)` built by hand (criteria to 1e-12), the HiFi is the full car
/// with the loaded mass, CG and inertias written out by hand (1e-12); a rearward load
/// raises the front corner's share only through `b' = b + m x / (M + m)`.
#[test]
fn the_loaded_car_is_the_same_on_both_models() {
    let car = Car::datum();
    let road = Road::default();
    let (m, x) = (350.0, -0.3);
    let set = CaseSet::new(&car, &road, &[load("laden", m, x)], &[], Combine::Worst).unwrap();
    let loaded = &set.cases[0].car;
    let total = car.sprung_mass + m;
    let dx = m * x / total;
    let b = car.b + dx;
    let reduced = car.sprung_mass * m / total;
    let by_hand = Car {
        sprung_mass: total,
        a: car.a - dx,
        b,
        pitch_inertia: car.pitch_inertia + reduced * x * x,
        ..car.clone()
    };
    let q = QuarterCar {
        ms: total * b / (2.0 * car.wheelbase()),
        ..car.quarter()
    };
    let lofi = LoFi::new(loaded, &road);
    let hifi = HiFi::new(loaded, &road).unwrap();
    let hifi_hand = HiFi::new(&by_hand, &road).unwrap();
    for (ks, cs) in DESIGNS {
        let got = lofi.evaluate(ks, cs).unwrap().to_array();
        let want = quarter_criteria(&QuarterCar { ks, cs, ..q }, &road)
            .unwrap()
            .to_array();
        let h = hifi.evaluate(ks, cs).unwrap().to_array();
        let hw = hifi_hand.evaluate(ks, cs).unwrap().to_array();
        for j in 0..3 {
            assert!((got[j] / want[j] - 1.0).abs() < 1e-12, "lofi {j}");
            assert!((h[j] / hw[j] - 1.0).abs() < 1e-12, "hifi {j}");
        }
    }
    // The DOS context follows: the static wheel load is (ms + mu) g of the loaded car.
    let ctx = DosContext::new(loaded, lofi.evaluate(20_000.0, 1500.0).unwrap());
    let f = (q.ms + car.front.unsprung_mass) * 9.80665;
    assert!((ctx.static_wheel_load / f - 1.0).abs() < 1e-12);
}

fn settings(n: usize) -> MapSettings {
    MapSettings {
        grid: Grid::over_box(&DesignBox::default(), n, n).unwrap(),
        objectives: DesignObjectives {
            dtl_margin: Some(6.0),
            no_worse_than_datum: [false, false, true],
            ..DesignObjectives::default()
        },
        ..MapSettings::default()
    }
}

/// The robust map of one case is that case's map: fields, datum and mask bit for bit
/// (worst and mean); and `--case K` is case K's own map.
#[test]
fn the_robust_map_of_one_case_is_that_case() {
    let car = Car::datum();
    let road = Road::default();
    let s = settings(9);
    for model in [ModelKind::Quarter, ModelKind::Full] {
        for combine in [Combine::Worst, Combine::Mean] {
            let set = CaseSet::new(
                &car,
                &road,
                &[load("laden", 300.0, -0.4)],
                &[op(RoadClass::C, 25.0)],
                combine,
            )
            .unwrap();
            let c = &set.cases[0];
            let single = MapRequest::new(model, &c.car, &c.road, s.clone())
                .run()
                .unwrap();
            let request = MapRequest::new(model, &car, &road, s.clone());
            let r = request.run_robust(&set).unwrap();
            assert_eq!(r.map.bacc, single.bacc);
            assert_eq!(r.map.dtl, single.dtl);
            assert_eq!(r.map.sws, single.sws);
            assert_eq!(r.map.datum, single.datum);
            assert_eq!(r.map.feasibility, single.feasibility);
            assert_eq!(r.map.contours, single.contours);
            let k = request.run_case(&set, 0).unwrap();
            assert_eq!(k.map, single);
        }
    }
}

/// Two load cases x three speeds (worst case, LoFi, 41 x 41): each robust point's mask is
/// the OR of the cases' masks, so every robust front point is feasible in every case; and
/// the robust front lies on or above every case's front: for each robust front point `x`
/// and each case `k` some point `f` of case k's front (scaled to case 0's datum,
/// `s_k f`) has `s_k f <= R(x)` in both BAcc and DTL, exactly (no tolerance: `R` is the
/// largest scaled value and `c_k(x)` is in case k's feasible set).
#[test]
fn the_robust_front_lies_on_or_above_every_case_front() {
    let car = Car::datum();
    let road = Road::default();
    let s = settings(41);
    let set = CaseSet::new(
        &car,
        &road,
        &[
            load("driver only", 0.0, 0.0),
            load("fully laden", 350.0, -0.3),
        ],
        &[
            op(RoadClass::B, 10.0),
            op(RoadClass::B, 20.0),
            op(RoadClass::B, 30.0),
        ],
        Combine::Worst,
    )
    .unwrap();
    let request = MapRequest::new(ModelKind::Quarter, &car, &road, s);
    let r = request.run_robust(&set).unwrap();
    let cases: Vec<_> = (0..6).map(|k| request.run_case(&set, k).unwrap()).collect();
    let d0 = cases[0].map.datum.criteria.to_array();
    let front_of = |bacc: &[f64], dtl: &[f64], mask: &[u8]| -> Vec<usize> {
        let idx: Vec<usize> = (0..mask.len()).filter(|&k| mask[k] == 0).collect();
        let f: Vec<[f64; 2]> = idx.iter().map(|&k| [bacc[k], dtl[k]]).collect();
        non_dominated(&f).into_iter().map(|i| idx[i]).collect()
    };
    let robust = front_of(&r.map.bacc, &r.map.dtl, &r.map.feasibility.mask);
    assert!(robust.len() > 3, "robust front has {} points", robust.len());
    let mut binding = 0;
    for c in &cases {
        let m = &c.map;
        let dk = m.datum.criteria.to_array();
        let s = [d0[0] / dk[0], d0[1] / dk[1]];
        let front = front_of(&m.bacc, &m.dtl, &m.feasibility.mask);
        for &p in &robust {
            assert_eq!(
                m.feasibility.mask[p], 0,
                "robust point {p} infeasible in {}",
                c.case.name
            );
            let below = front
                .iter()
                .any(|&q| s[0] * m.bacc[q] <= r.map.bacc[p] && s[1] * m.dtl[q] <= r.map.dtl[p]);
            assert!(below, "robust point {p} beats case {}'s front", c.case.name);
            binding += usize::from(s[0] * m.bacc[p] == r.map.bacc[p]);
        }
    }
    // Each robust point's BAcc is some case's scaled BAcc (the worst case binds).
    assert!(binding >= robust.len());
    // The cases differ: the robust feasible set is smaller than the driver-only case's at 20 m/s.
    assert!(r.map.feasibility.summary.feasible < cases[1].map.feasibility.summary.feasible);
    assert_eq!(r.robust.feasible_per_case.len(), 6);
}

/// The robust optimisation of one case is that case's optimisation (front bit for bit,
/// same pick and HiFi re-check); over two load cases every STM front point meets the
/// objectives in every case (each case's criteria at the point, against its own datum).
#[test]
fn robust_optimize_of_one_case_and_feasibility_in_every_case() {
    let car = Car::datum();
    let road = Road::default();
    let method = Method::Stm(StmParams {
        grid: 31,
        levels: 2,
    });
    let objectives = DesignObjectives {
        dtl_margin: Some(6.0),
        ..DesignObjectives::default()
    };
    let laden = load("laden", 350.0, -0.3);
    let one = CaseSet::new(
        &car,
        &road,
        std::slice::from_ref(&laden),
        &[],
        Combine::Worst,
    )
    .unwrap();
    let spec = EvaluatorSpec::Model(ModelKind::Quarter);
    let plan = PlanSpec::parse("ae:10").unwrap();
    // One request, run over the cases of a set or on one car.
    let request = OptimizeRequest {
        evaluator: spec,
        plan,
        ..OptimizeRequest::new(
            &car,
            &road,
            DesignBox::default(),
            method.clone(),
            objectives.clone(),
        )
    };
    let r = request.run_robust(&one).unwrap();
    let single = OptimizeRequest {
        car: &one.cases[0].car,
        ..request.clone()
    }
    .run_cpu()
    .unwrap();
    assert_eq!(r.study.front, single.study.front);
    assert_eq!(r.study.pick, single.study.pick);
    assert_eq!(r.datum, single.datum);
    assert_eq!(r.hifi_recheck.rechecked, single.hifi_recheck.rechecked);
    assert_eq!(
        r.cases[0].hifi_recheck.rechecked,
        single.hifi_recheck.rechecked
    );

    let two = CaseSet::new(
        &car,
        &road,
        &[load("driver only", 0.0, 0.0), laden],
        &[op(RoadClass::B, 20.0), op(RoadClass::B, 30.0)],
        Combine::Worst,
    )
    .unwrap();
    let r = OptimizeRequest {
        pick: PickRule::Knee,
        ..request.clone()
    }
    .run_robust(&two)
    .unwrap();
    assert_eq!(r.cases.len(), 4);
    let datums: Vec<_> = two
        .cases
        .iter()
        .map(|c| {
            HiFi::new(&c.car, &c.road)
                .unwrap()
                .evaluate(car.front.spring, car.front.damper)
                .unwrap()
        })
        .collect();
    for p in &r.study.front {
        let mut worst = [0.0f64; 2];
        for (c, d) in two.cases.iter().zip(&datums) {
            let crit = LoFi::new(&c.car, &c.road).evaluate(p.ks, p.cs).unwrap();
            let ctx = DosContext::new(&c.car, *d);
            assert!(
                objectives.broken(&ctx, p.ks, p.cs, &crit).is_empty(),
                "{} at {p:?}",
                c.name
            );
            worst[0] = worst[0].max(crit.bacc * (datums[0].bacc / d.bacc));
            worst[1] = worst[1].max(crit.dtl * (datums[0].dtl / d.dtl));
        }
        // R = max_k s_k c_k with s_k = d_0 / d_k, exactly as documented.
        assert_eq!([p.bacc, p.dtl], worst);
    }
    // Each case reports the pick: its prediction and its HiFi re-check at the pick.
    for (cp, c) in r.cases.iter().zip(&two.cases) {
        let h = HiFi::new(&c.car, &c.road)
            .unwrap()
            .evaluate(r.study.pick.ks, r.study.pick.cs)
            .unwrap();
        assert_eq!(cp.hifi_recheck.rechecked, h);
        assert_eq!(cp.case.name, c.name);
    }
}

fn ridelab(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_ridelab"))
        .args(args)
        .output()
        .expect("runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn write(dir: &std::path::Path, name: &str, text: &str) -> String {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p.to_string_lossy().into_owned()
}

fn tmp() -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("ridelab-robust-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Bad cases, on map and optimize: exit 2, one line on stderr naming the field.
#[test]
fn bad_cases_exit_2_naming_the_field() {
    let dir = tmp();
    let mut car: Value = serde_json::from_str(ridelab::car::PRESETS[0].1).unwrap();
    car["load_cases"] = serde_json::json!([{"name": "a", "mass": 0}, {"name": "b", "mass": -1500}]);
    let bad_car = write(&dir, "bad-car.json", &car.to_string());
    car["load_cases"] =
        serde_json::json!([{"name": "a", "mass": 0}, {"name": "b", "mass": 900, "x": 3}]);
    let cg_car = write(&dir, "cg-car.json", &car.to_string());
    let many: Vec<String> = (0..17)
        .map(|i| format!(r#"{{"class": "B", "speed": {}}}"#, 5 + i))
        .collect();
    let cases = [
        (
            r#"{"load_cases": [{"name": "a", "mass": 0}, {"name": "b", "mass": -2000}]}"#,
            "load_cases[1].mass: ",
        ),
        (r#"{"load_cases": []}"#, "load_cases: "),
        (r#"{"operating": []}"#, "operating: "),
        (
            r#"{"operating": [{"class": "B", "speed": 20, "weight": 0}]}"#,
            "weight: ",
        ),
        (
            r#"{"operating": [{"class": "B", "speed": 0}]}"#,
            "operating[0].speed: ",
        ),
        (
            &format!(r#"{{"operating": [{}]}}"#, many.join(",")),
            "operating: at most 16",
        ),
        (r#"{"combine": "best"}"#, "combine: "),
        (
            r#"{"load_cases": [{"name": "a", "mass": 10, "weight": -1}]}"#,
            "load_cases[0].weight: ",
        ),
    ];
    for (k, (text, want)) in cases.iter().enumerate() {
        let f = write(&dir, &format!("cases-{k}.json"), text);
        for cmd in [
            vec!["map", "--model", "quarter", "--cases", &f],
            vec!["optimize", "--evaluator", "quarter", "--cases", &f],
        ] {
            let (code, out, err) = ridelab(&cmd);
            assert_eq!(code, 2, "{cmd:?}: {err}");
            assert!(out.is_empty());
            assert_eq!(err.lines().count(), 1, "{err}");
            assert!(err.starts_with(&format!("error: {want}")), "{text}: {err}");
        }
    }
    for (file, want) in [
        (&bad_car, "load_cases[1].mass: "),
        (&cg_car, "load_cases[1].x: "),
    ] {
        for cmd in ["eval", "map"] {
            let (code, _, err) = ridelab(&[cmd, "--model", "quarter", "--car", file]);
            assert_eq!(code, 2, "{err}");
            assert!(err.starts_with(&format!("error: {want}")), "{err}");
        }
    }
    let (code, _, err) = ridelab(&["map", "--model", "quarter", "--case", "1"]);
    assert_eq!(code, 2);
    assert!(err.starts_with("error: case: 1 is not a case"), "{err}");
    let (code, _, err) = ridelab(&["map", "--model", "quarter", "--cases", "/no/such/file.json"]);
    assert_eq!(code, 2);
    assert!(err.starts_with("error: cases: cannot read"), "{err}");
    let f = write(
        &dir,
        "ok.json",
        r#"{"operating": [{"class": "B", "speed": 20}]}"#,
    );
    let (code, _, err) = ridelab(&[
        "optimize",
        "--evaluator",
        "rba-mul-rbf-mq",
        "--cases",
        &f,
        "--adaptive",
        "2",
    ]);
    assert_eq!(code, 2);
    assert!(err.starts_with("error: adaptive: "), "{err}");
}

/// JSON text parsed, its top-level `units` object (the CLI's, issue #32) left out.
fn without_units(text: &str) -> Value {
    let mut v: Value = serde_json::from_str(text).unwrap();
    v.as_object_mut().unwrap().remove("units");
    v
}

/// Without cases the map and optimize print what they printed before, byte for byte (a
/// car file without load cases is the preset); the CLI's robust map is the library's.
#[test]
fn default_outputs_unchanged_and_robust_json_is_the_library() {
    let dir = tmp();
    let car_file = write(&dir, "sedan.json", ridelab::car::PRESETS[0].1);
    let base = [
        "map",
        "--model",
        "quarter",
        "--ks-range",
        "10000:40000:7",
        "--cs-range",
        "500:4000:6",
        "--json",
    ];
    let (c1, plain, _) = ridelab(&base);
    let mut with_file = base.to_vec();
    with_file.extend(["--car", &car_file]);
    let (c2, from_file, _) = ridelab(&with_file);
    assert_eq!((c1, c2), (0, 0));
    assert_eq!(plain, from_file);
    assert!(!plain.contains("robust"));
    let lib = MapRequest::new(
        ModelKind::Quarter,
        &Car::datum(),
        &Road::default(),
        MapSettings {
            grid: Grid::parse("10000:40000:7", "500:4000:6").unwrap(),
            ..MapSettings::default()
        },
    )
    .run()
    .unwrap();
    assert_eq!(
        without_units(&plain),
        without_units(&serde_json::to_string(&lib).unwrap())
    );

    let cases = r#"{"load_cases": [{"name": "driver only", "mass": 0}, {"name": "fully laden", "mass": 350, "x": -0.3}],
                    "operating": [{"class": "B", "speed": 10}, {"class": "C", "speed": 30, "weight": 2}], "combine": "mean"}"#;
    let f = write(&dir, "cases.json", cases);
    let mut robust = base.to_vec();
    robust.extend(["--cases", &f]);
    let (code, out, err) = ridelab(&robust);
    assert_eq!(code, 0, "{err}");
    let set = CaseSet::from_json(cases, &Car::datum(), &[], &Road::default()).unwrap();
    let lib = MapRequest {
        compute: Compute::Auto,
        ..MapRequest::new(
            ModelKind::Quarter,
            &Car::datum(),
            &Road::default(),
            MapSettings {
                grid: Grid::parse("10000:40000:7", "500:4000:6").unwrap(),
                ..MapSettings::default()
            },
        )
    }
    .run_robust(&set)
    .unwrap();
    assert_eq!(
        without_units(&out),
        without_units(&serde_json::to_string(&lib).unwrap())
    );
    let v: Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["robust"]["cases"].as_array().unwrap().len(), 4);
    assert_eq!(v["robust"]["combine"], "mean");
    // --case 3: the fully laden car on class C at 30 m/s alone.
    robust.extend(["--case", "3"]);
    let (code, out, _) = ridelab(&robust);
    assert_eq!(code, 0);
    let v: Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["case"]["name"], "fully laden / C at 30 m/s");
    assert_eq!(v["road"]["class"], "C");

    // The car file's load cases alone make optimize robust over them at --class/--speed.
    let mut car: Value = serde_json::from_str(ridelab::car::PRESETS[0].1).unwrap();
    car["load_cases"] = serde_json::json!([{"name": "driver only", "mass": 0}, {"name": "fully laden", "mass": 350, "x": -0.3}]);
    let laden_car = write(&dir, "laden.json", &car.to_string());
    let (code, out, err) = ridelab(&[
        "optimize",
        "--evaluator",
        "quarter",
        "--grid",
        "21",
        "--car",
        &laden_car,
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(out.starts_with("robust over 2 cases (Worst"), "{out}");
    assert!(out.contains("case 1 fully laden / B at 20 m/s"), "{out}");
}
