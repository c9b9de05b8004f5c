//! The `ridelab` command line as users and scripts meet it: JSON fields, numbers equal
//! to the library's, one-line errors naming the option, exit code 2, never a panic.

use ridelab::analysis::{report, ModelKind};
use ridelab::road::Road;
use ridelab::Car;
use std::process::Command;

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

fn json(args: &[&str]) -> serde_json::Value {
    let (code, out, err) = ridelab(args);
    assert_eq!(code, 0, "{args:?}: {err}");
    serde_json::from_str(&out).expect("valid JSON")
}

#[test]
fn eval_json_equals_the_library() {
    for (model, kind) in [("quarter", ModelKind::Quarter), ("full", ModelKind::Full)] {
        let v = json(&[
            "eval",
            "--model",
            model,
            "--car",
            "../assets/cars/sedan.json",
            "--json",
        ]);
        let r = report(kind, &Car::datum(), &Road::default()).unwrap();
        for (k, x) in [("bacc", r.bacc), ("dtl", r.dtl), ("sws", r.sws)] {
            // JSON carries the shortest round-trip decimal; the same code gives the same number.
            let y = v[k].as_f64().unwrap();
            assert!((y / x - 1.0).abs() < 1e-14, "{model} {k}: {y} vs {x}");
        }
        assert!(!v["modes"].as_array().unwrap().is_empty());
    }
    // --ks/--cs override the front corner.
    let v = json(&[
        "eval", "--model", "full", "--ks", "25000", "--cs", "2000", "--class", "c", "--json",
    ]);
    let car = Car::datum().with_front(25_000.0, 2_000.0).unwrap();
    let road = Road {
        class: ridelab::RoadClass::C,
        ..Road::default()
    };
    let r = report(ModelKind::Full, &car, &road).unwrap();
    assert!((v["bacc"].as_f64().unwrap() / r.bacc - 1.0).abs() < 1e-14);
    assert_eq!(v["ks"].as_f64().unwrap(), 25_000.0);
}

#[test]
fn doe_map_and_optimize_print_their_fields() {
    let v = json(&["doe", "--points", "5", "--json"]);
    assert!((v["energy"].as_f64().unwrap() - 1.298_202_614_379_085).abs() < 1e-12);
    assert_eq!(v["samples"].as_array().unwrap().len(), 5);

    let v = json(&[
        "map",
        "--model",
        "quarter",
        "--ks-range",
        "10000:40000:5",
        "--cs-range",
        "500:4000:4",
        "--json",
    ]);
    assert_eq!(v["bacc"].as_array().unwrap().len(), 20);
    let (_, csv, _) = ridelab(&[
        "map",
        "--model",
        "quarter",
        "--ks-range",
        "10000:40000:3",
        "--cs-range",
        "500:4000:2",
        "--csv",
    ]);
    assert!(csv.starts_with("ks_n_per_m,cs_ns_per_m,bacc_m_per_s2,dtl_n,sws_m,feasible,broken"));
    assert_eq!(csv.lines().count(), 1 + 6);

    let v = json(&[
        "optimize",
        "--evaluator",
        "quarter",
        "--method",
        "nsga2",
        "--population",
        "20",
        "--generations",
        "10",
        "--json",
    ]);
    assert!(!v["front"].as_array().unwrap().is_empty());
    assert!(v["pick"]["ks"].as_f64().unwrap() >= 10_000.0);
    assert!(v["hifi_recheck"]["rechecked"]["bacc"].as_f64().unwrap() > 0.0);
}

#[test]
fn bad_input_is_one_line_naming_the_option_with_exit_code_2() {
    let cases: [(&[&str], &str); 12] = [
        (&["eval", "--model", "full", "--speed", "-5"], "speed"),
        (&["eval", "--model", "full", "--speed", "fast"], "speed"),
        (&["eval", "--model", "hexa"], "model"),
        (&["eval"], "model"),
        (&["eval", "--model", "full", "--class", "Z"], "class"),
        (&["eval", "--model", "full", "--cs", "0"], "cs"),
        (&["eval", "--model", "full", "--ks", "-1"], "ks"),
        (&["eval", "--model", "full", "--car", "missing.json"], "car"),
        (&["eval", "--model", "full", "--wat"], "--wat"),
        (
            &["map", "--model", "quarter", "--ks-range", "4:1:3"],
            "ks-range",
        ),
        (&["doe", "--points", "1"], "points"),
        (
            &["optimize", "--evaluator", "quarter", "--class", "C"],
            "sws_limit",
        ),
    ];
    for (args, field) in cases {
        let (code, out, err) = ridelab(args);
        assert_eq!(code, 2, "{args:?}");
        assert!(out.is_empty(), "{args:?}");
        assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
        assert!(
            err.starts_with(&format!("error: {field}")),
            "{args:?}: {err}"
        );
        assert!(!err.contains("panicked"));
    }
    // A car file with a misspelt key.
    let dir = std::env::temp_dir().join("ridelab-cli-test");
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("bad.json");
    let text = ridelab::car::PRESETS[0]
        .1
        .replace("\"sprung_mass\"", "\"sprung_mas\"");
    std::fs::write(&path, text).unwrap();
    let (code, _, err) = ridelab(&["eval", "--model", "full", "--car", path.to_str().unwrap()]);
    assert_eq!(code, 2);
    assert!(err.contains("sprung_mas"), "{err}");
}

#[test]
fn map_and_optimize_write_svg_charts_and_print_the_same() {
    let dir = std::env::temp_dir().join(format!("ridelab-cli-svg-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let prefix = dir.join("map.svg");
    let grid = ["--ks-range", "10000:40000:21", "--cs-range", "500:4000:15"];
    let mut args = vec!["map", "--model", "quarter", "--json"];
    args.extend(grid);
    let (code, plain, _) = ridelab(&args);
    assert_eq!(code, 0);
    args.extend(["--svg", prefix.to_str().unwrap()]);
    let (code, with_svg, err) = ridelab(&args);
    assert_eq!(code, 0, "{err}");
    // stdout is the same JSON, byte for byte; the trailing .svg is dropped from the prefix.
    assert_eq!(with_svg, plain);
    let settings = ridelab::maps::MapSettings {
        grid: ridelab::maps::Grid::parse("10000:40000:21", "500:4000:15").unwrap(),
        ..Default::default()
    };
    let report = ridelab::maps::map_report(
        ModelKind::Quarter,
        &Car::datum(),
        &Road::default(),
        &settings,
    )
    .unwrap();
    for ((key, chart), unit) in ridelab::chart::map_report_charts(&report).into_iter().zip([
        "BAcc [m/s^2]",
        "DTL [N]",
        "SWS [mm]",
    ]) {
        let svg = std::fs::read_to_string(dir.join(format!("map-{key}.svg"))).unwrap();
        assert!(
            svg.starts_with("<svg ") && svg.ends_with("</svg>\n"),
            "{key}"
        );
        for label in [
            "Ks front spring [kN/m]",
            "Cs front damper [kNs/m]",
            unit,
            ">\ndatum\n",
        ] {
            assert!(svg.contains(label), "{key}: {label} missing");
        }
        // 21 x 15 nodes: one cell each at most, plus the bar's 64 and a few frames.
        let rects = svg.matches("<rect").count();
        assert!(rects <= 21 * 15 + 64 + 8, "{key}: {rects} rects");
        // The same chart as the library draws from the same report.
        assert_eq!(svg, ridelab::chart::map_chart_svg(&chart).unwrap(), "{key}");
    }

    // --csv with --svg: the CSV is unchanged too.
    let (_, csv, _) = ridelab(&["map", "--model", "quarter", "--csv", "--relative"]);
    let rel = dir.join("rel");
    let (code, csv2, _) = ridelab(&[
        "map",
        "--model",
        "quarter",
        "--csv",
        "--relative",
        "--svg",
        rel.to_str().unwrap(),
    ]);
    assert_eq!((code, csv2), (0, csv));
    let svg = std::fs::read_to_string(dir.join("rel-dtl.svg")).unwrap();
    assert!(svg.contains("DTL change vs datum [%]"));

    let front = dir.join("front.svg");
    let opt = [
        "optimize",
        "--evaluator",
        "quarter",
        "--method",
        "nsga2",
        "--population",
        "20",
        "--generations",
        "10",
        "--json",
    ];
    let (_, plain, _) = ridelab(&opt);
    let mut args = opt.to_vec();
    args.extend(["--svg", front.to_str().unwrap()]);
    let (code, with_svg, err) = ridelab(&args);
    assert_eq!(code, 0, "{err}");
    assert_eq!(with_svg, plain);
    let svg = std::fs::read_to_string(&front).unwrap();
    for label in [
        "BAcc [m/s^2]",
        "DTL [N]",
        "min-max pick",
        ">\ndatum\n",
        "Pareto front, NSGA-II",
    ] {
        assert!(svg.contains(label), "front: {label} missing");
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn bad_svg_targets_are_one_line_naming_the_option() {
    let missing = std::env::temp_dir()
        .join("ridelab-no-such-dir")
        .join("x.svg");
    let missing = missing.to_str().unwrap();
    let tmp = std::env::temp_dir();
    let tmp = tmp.to_str().unwrap();
    for args in [
        &["map", "--model", "quarter", "--svg", missing][..],
        &["map", "--model", "quarter", "--svg", ""][..],
        &["map", "--model", "quarter", "--svg"][..],
        &["optimize", "--evaluator", "quarter", "--svg", missing][..],
        &["map", "--model", "quarter", "--svg", tmp][..],
    ] {
        let (code, out, err) = ridelab(args);
        assert_eq!(code, 2, "{args:?}");
        assert!(out.is_empty(), "{args:?}");
        assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
        assert!(err.starts_with("error: svg: "), "{args:?}: {err}");
    }
}

#[test]
fn a_reader_that_closes_the_pipe_early_ends_the_run_quietly() {
    // `ridelab map ... --csv | head -1`: the reader takes one line and closes its end;
    // the CLI must not panic (a panic prints "failed printing to stdout" and exits 101).
    use std::io::{BufRead, BufReader};
    use std::process::Stdio;
    let mut child = Command::new(env!("CARGO_BIN_EXE_ridelab"))
        .args([
            "map",
            "--model",
            "quarter",
            "--ks-range",
            "10000:40000:200",
            "--cs-range",
            "500:4000:200",
            "--csv",
        ])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut first = String::new();
    BufReader::new(child.stdout.take().unwrap())
        .read_line(&mut first)
        .unwrap();
    // The reader is dropped here: the pipe is closed with about 40 000 rows unread.
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(first.starts_with("ks"), "{first}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert_eq!(out.status.code(), Some(0), "{stderr}");
}
