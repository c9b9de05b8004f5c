//! `ridelab map` on the study's one model type (issue #28): `--model` takes what
//! `ridelab optimize --evaluator` takes, the quarter car, the full car or a surrogate of
//! the full car fitted at `--plan`'s points, on an ISO class, a measured road and over
//! load cases alike.
//!
//! Checked against the full car's own map: an interpolating surrogate (the multiquadric
//! RBF correction, `rba-mul-rbf-mq`) fitted at a `grid:n` plan whose points are the map's
//! grid reproduces the full car at every grid point, up to the conditioning of its
//! interpolation system (measured 2.7e-10 on the sedan); fitted at an Audze-Eglais plan of
//! 10 points it stays within 1 % of the full car on a 9 x 9 grid (measured 0.67 %).

use serde_json::Value;
use std::process::Command;

/// Runs the CLI: exit code, stdout, stderr.
fn ridelab(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_ridelab"))
        .args(args)
        .current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
        .output()
        .expect("runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// `ridelab map --json` with `args`, parsed.
fn map(args: &[&str]) -> Value {
    let mut all = vec!["map", "--json"];
    all.extend_from_slice(args);
    let (code, out, err) = ridelab(&all);
    assert_eq!(code, 0, "{all:?}: {err}");
    serde_json::from_str(&out).expect("valid JSON")
}

/// The largest relative difference between the criteria fields of two map reports.
fn worst(a: &Value, b: &Value) -> f64 {
    let mut worst = 0.0f64;
    for key in ["bacc", "dtl", "sws"] {
        let (x, y) = (a[key].as_array().unwrap(), b[key].as_array().unwrap());
        assert_eq!(x.len(), y.len(), "{key}");
        for (x, y) in x.iter().zip(y) {
            let (x, y) = (x.as_f64().unwrap(), y.as_f64().unwrap());
            worst = worst.max((x / y - 1.0).abs());
        }
    }
    worst
}

/// A 5 x 5 grid over the default box: the points of the plan `grid:5`.
const GRID_5: [&str; 4] = ["--ks-range", "10000:40000:5", "--cs-range", "500:4000:5"];

#[test]
fn an_interpolating_surrogate_at_the_grids_points_is_the_full_cars_map() {
    let full = map(&[&["--model", "full"][..], &GRID_5].concat());
    let sur = map(&[
        &["--model", "rba-mul-rbf-mq", "--plan", "grid:5"][..],
        &GRID_5,
    ]
    .concat());
    assert_eq!(sur["evaluator"], "rba-mul-rbf-mq");
    let e = worst(&sur, &full);
    assert!(e < 1e-8, "interpolation at the samples: {e}");
    // The mask follows: the same designs are feasible.
    assert_eq!(sur["feasibility"]["mask"], full["feasibility"]["mask"]);
    // The datum (off the grid) is the surrogate's own, close to the full car's.
    let (d, f) = (
        sur["datum"]["criteria"]["bacc"].as_f64().unwrap(),
        full["datum"]["criteria"]["bacc"].as_f64().unwrap(),
    );
    assert!(d != f && (d / f - 1.0).abs() < 1e-3, "{d} vs {f}");
}

#[test]
fn a_surrogate_fitted_at_ten_points_maps_within_one_percent_of_the_full_car() {
    let grid = ["--ks-range", "10000:40000:9", "--cs-range", "500:4000:9"];
    let full = map(&[&["--model", "full"][..], &grid].concat());
    let sur = map(&[&["--model", "rba-mul-rbf-mq", "--plan", "ae:10"][..], &grid].concat());
    let e = worst(&sur, &full);
    assert!(e > 1e-6 && e < 0.01, "ae:10 against the full car: {e}");
}

#[test]
fn a_surrogate_maps_a_measured_road_and_robust_cases_as_the_full_car_does() {
    // A measured road: the surrogate fitted to the full car there (its LoFi the quarter
    // car there) reproduces that car's map at the samples.
    let road = ["--road", "assets/roads/concrete-slab-5m.csv"];
    let grid = ["--ks-range", "10000:40000:3", "--cs-range", "500:4000:3"];
    let full = map(&[&["--model", "full"][..], &road, &grid].concat());
    let sur = map(&[
        &["--model", "rba-mul-rbf-mq", "--plan", "grid:3"][..],
        &road,
        &grid,
    ]
    .concat());
    assert_eq!(sur["road"], full["road"]);
    let e = worst(&sur, &full);
    assert!(e < 1e-8, "measured road: {e}");
    // Over three speeds: one surrogate per case. Each case's map is that case's full
    // car at the samples; the robust map divides each case by its own datum (the
    // surrogate's, off the grid), so it follows the full car's to the datums' 1e-3.
    let cases = ["--cases", "assets/examples/cases-b-10-20-30.json"];
    for k in ["0", "1", "2"] {
        let full = map(&[&["--model", "full", "--case", k][..], &cases, &GRID_5].concat());
        let sur = map(&[
            &["--model", "rba-mul-rbf-mq", "--plan", "grid:5", "--case", k][..],
            &cases,
            &GRID_5,
        ]
        .concat());
        assert_eq!(sur["case"]["road"], full["case"]["road"]);
        let e = worst(&sur, &full);
        assert!(e < 1e-8, "case {k}: {e}");
    }
    let full = map(&[&["--model", "full"][..], &cases, &GRID_5].concat());
    let sur = map(&[
        &["--model", "rba-mul-rbf-mq", "--plan", "grid:5"][..],
        &cases,
        &GRID_5,
    ]
    .concat());
    let e = worst(&sur, &full);
    assert!(e < 1e-3, "robust: {e}");
    assert_eq!(
        sur["robust"]["feasible_per_case"],
        full["robust"]["feasible_per_case"]
    );
}

#[test]
fn what_a_surrogates_map_cannot_do_is_refused_naming_the_option() {
    for (args, field) in [
        (&["--model", "gibberish"][..], "model"),
        (&["--model", "gp-mul", "--comfort", "wk"][..], "comfort"),
        (&["--model", "gp-mul", "--compute", "gpu"][..], "compute"),
        (&["--model", "gp-mul", "--plan", "ae:1"][..], "plan"),
    ] {
        let mut all = vec!["map"];
        all.extend_from_slice(args);
        let (code, _, err) = ridelab(&all);
        assert_eq!(code, 2, "{all:?}: {err}");
        assert!(
            err.starts_with(&format!("error: {field}")),
            "{all:?}: {err}"
        );
    }
}

/// The page's surrogate map (the explorer's session: its fit over the design box, its
/// map at the cells' centres inside it) and `ridelab map --model SURROGATE` fitted over
/// the same box (`--fit-ks-range`, `--fit-cs-range`) at the same points are one
/// computation: equal bit for bit.
#[test]
fn the_pages_surrogate_map_is_the_clis_bit_for_bit() {
    use ridelab::explorer::{Model, Session, State};
    let mut session = Session::new(State::default()).unwrap();
    let page = session.map(Model::Surrogate, 8, 6).unwrap();
    let s = session.scenario();
    let (g, b) = (page.grid(), s.dbox);
    // Shortest round-trip decimals: the CLI reads back exactly these numbers.
    let axis = |a: &ridelab::maps::Axis| format!("{:?}:{:?}:{}", a.min, a.max, a.n);
    let range = |lo: f64, hi: f64| format!("{lo:?}:{hi:?}");
    let cli = map(&[
        "--model",
        &s.surrogate.name(),
        "--plan",
        &s.plan.name(),
        "--ks-range",
        &axis(&g.ks),
        "--cs-range",
        &axis(&g.cs),
        "--fit-ks-range",
        &range(b.ks_min, b.ks_max),
        "--fit-cs-range",
        &range(b.cs_min, b.cs_max),
    ]);
    let values = &page.values;
    for (name, field) in [
        ("bacc", &values.bacc),
        ("dtl", &values.dtl),
        ("sws", &values.sws),
    ] {
        let got: Vec<f64> = serde_json::from_value(cli[name].clone()).unwrap();
        assert_eq!(&got, field, "{name}");
    }
    // Fitted over the grid's own (smaller) box instead, the map differs.
    let own = map(&[
        "--model",
        &s.surrogate.name(),
        "--ks-range",
        &axis(&g.ks),
        "--cs-range",
        &axis(&g.cs),
    ]);
    assert_ne!(own["bacc"], cli["bacc"]);
    let bad = ridelab(&["map", "--model", "gp-mul", "--fit-ks-range", "40000:10000"]);
    assert_eq!(bad.0, 2, "{}", bad.2);
    assert!(bad.2.starts_with("error: fit-ks-range"), "{}", bad.2);
}
