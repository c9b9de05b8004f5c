//! The `ridelab` command line as users and scripts meet it: JSON fields, numbers equal
//! to the library's, one-line errors naming the option, exit code 2, never a panic.

use ridelab::analysis::{report, ModelKind};
use ridelab::car::PRESETS;
use ridelab::dos::{DesignObjectives, DosContext};
use ridelab::maps::{Grid, Scale};
use ridelab::optimize::{recheck, run_study, Method, Nsga2Params, StmParams, SuspensionProblem};
use ridelab::road::Road;
use ridelab::study::{map_csv, MapRequest, MapSettings};
use ridelab::study::{study, OptimizeRequest, SurrogateRequest};
use ridelab::surrogate::{sample_plan, LmOptions, PlanSpec, Setting, SurrogateSpec};
use ridelab::time_domain::{simulate, TimeOptions};
use ridelab::{Car, Evaluator, HiFi, LoFi};
use serde_json::Value;
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

/// `ridelab ARGS --json` parsed, once its `units` object is known to name the unit of
/// every numeric field (by the field's name, or `parent.name` where the name alone does
/// not say, as for `positions.body_pitch_theta`).
fn json(args: &[&str]) -> Value {
    let mut args = args.to_vec();
    if !args.contains(&"--json") {
        args.push("--json");
    }
    let (code, out, err) = ridelab(&args);
    assert_eq!(code, 0, "{args:?}: {err}");
    let v: Value = serde_json::from_str(&out).expect("valid JSON");
    let units = v["units"]
        .as_object()
        .unwrap_or_else(|| panic!("{args:?}: no units object"));
    let mut missing = std::collections::BTreeSet::new();
    numbers_without_units(&v, &mut Vec::new(), units, &mut missing);
    assert!(missing.is_empty(), "{args:?}: no unit for {missing:?}");
    v
}

/// `eval --model full --road road` at the design `(ks, cs)` (JSON numbers).
fn full_on_road(road: &str, ks: &Value, cs: &Value) -> Value {
    let (ks, cs) = (ks.to_string(), cs.to_string());
    json(&[
        "eval", "--model", "full", "--road", road, "--ks", &ks, "--cs", &cs,
    ])
}

/// Every sample's HiFi criteria equal `eval --road`'s full car at its design (the same
/// exact route: 1e-12).
fn samples_equal_eval(samples: &[Value], road: &str) {
    for s in samples {
        let e = full_on_road(road, &s["ks"], &s["cs"]);
        for key in ["bacc", "dtl", "sws"] {
            let (a, b) = (s["hifi"][key].as_f64().unwrap(), e[key].as_f64().unwrap());
            assert!((a / b - 1.0).abs() < 1e-12, "{key}: {a} vs eval {b}");
        }
    }
}

/// Runs `args` and checks that the CLI refuses them: exit 2, the error naming `field`.
fn refused(args: &[&str], field: &str) {
    let (code, _, err) = ridelab(args);
    assert_eq!(code, 2, "{args:?}: {err}");
    assert!(
        err.starts_with(&format!("error: {field}")),
        "{args:?}: {err}"
    );
}

fn numbers_without_units(
    v: &Value,
    path: &mut Vec<String>,
    units: &serde_json::Map<String, Value>,
    missing: &mut std::collections::BTreeSet<String>,
) {
    match v {
        Value::Number(_) => {
            let leaf = path.last().cloned().unwrap_or_default();
            let qualified = match path.len() {
                0 | 1 => leaf.clone(),
                n => format!("{}.{leaf}", path[n - 2]),
            };
            if !units.contains_key(&leaf) && !units.contains_key(&qualified) {
                missing.insert(path.join("."));
            }
        }
        Value::Array(items) => items
            .iter()
            .for_each(|i| numbers_without_units(i, path, units, missing)),
        Value::Object(map) => {
            for (k, item) in map.iter().filter(|(k, _)| *k != "units") {
                path.push(k.clone());
                numbers_without_units(item, path, units, missing);
                path.pop();
            }
        }
        _ => {}
    }
}

/// The page's maps (the explorer's session, cell centres of the design box) and the
/// CLI's maps over the same points are one computation: equal bit for bit, values and
/// objective masks.
#[test]
fn the_page_and_the_cli_maps_are_the_same_numbers() {
    use ridelab::explorer::{Model, Session, State};
    let mut session = Session::new(State {
        no_worse: Some([false, true, false]),
        ..State::default()
    })
    .unwrap();
    for (model, kind, nx, ny) in [
        (Model::LoFi, "quarter", 16, 12),
        (Model::HiFi, "full", 5, 4),
    ] {
        let page = session.map(model, nx, ny).unwrap();
        let g = page.grid();
        // Shortest round-trip decimals: the CLI reads back exactly these axes.
        let range = |a: &ridelab::maps::Axis| format!("{:?}:{:?}:{}", a.min, a.max, a.n);
        let v = json(&[
            "map",
            "--model",
            kind,
            "--ks-range",
            &range(&g.ks),
            "--cs-range",
            &range(&g.cs),
            "--compute",
            "cpu",
            "--json",
        ]);
        let values = &page.values;
        for (name, field) in [
            ("bacc", &values.bacc),
            ("dtl", &values.dtl),
            ("sws", &values.sws),
        ] {
            let cli: Vec<f64> = serde_json::from_value(v[name].clone()).unwrap();
            assert_eq!(&cli, field, "{kind} {name}");
        }
        // The page judges "DTL no worse than the datum" too; the CLI's default objectives
        // are the SWS limit only, so compare that bit.
        let cli_mask: Vec<u8> = serde_json::from_value(v["feasibility"]["mask"].clone()).unwrap();
        let sws_bit: Vec<u8> = page.broken().iter().map(|m| m & 1).collect();
        assert_eq!(cli_mask, sws_bit, "{kind} mask");
        assert!(
            page.broken().iter().any(|m| m & 16 != 0),
            "{kind}: the DTL objective shows"
        );
    }
}

#[test]
fn help_and_version_go_to_stdout() {
    let (code, out, _) = ridelab(&["--help"]);
    assert_eq!(code, 0);
    for command in [
        "eval",
        "doe",
        "optimize",
        "map",
        "surrogate",
        "study",
        "simulate",
        "presets",
    ] {
        assert!(out.contains(command), "{command} in --help");
    }
    let (code, out, _) = ridelab(&["simulate", "--help"]);
    assert_eq!(code, 0);
    assert!(out.contains("--rebound-high"), "{out}");
    let (code, out, _) = ridelab(&["--version"]);
    assert_eq!(
        (code, out.trim()),
        (0, format!("ridelab {}", env!("CARGO_PKG_VERSION")).as_str())
    );
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
        for (k, x) in [
            ("bacc", r.bacc),
            ("dtl", r.dtl),
            ("sws", r.sws),
            ("bacc_wk", r.bacc_wk),
        ] {
            // JSON carries the shortest round-trip decimal; the same code gives the same number.
            let y = v[k].as_f64().unwrap();
            assert!((y / x - 1.0).abs() < 1e-14, "{model} {k}: {y} vs {x}");
        }
        assert!(!v["modes"].as_array().unwrap().is_empty());
        // The weighted comfort by the exact route (an independent computation).
        let wk =
            ridelab::criteria::bacc_wk_exact(&kind.build(&Car::datum()), &Road::default()).unwrap();
        assert!(
            (r.bacc_wk / wk - 1.0).abs() < 1e-8,
            "{model}: {} vs {wk}",
            r.bacc_wk
        );
        assert_eq!(v["comfort"], ridelab::criteria::comfort_label(r.bacc_wk));
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

/// Compares two JSON trees in full: the same keys, lengths, strings and booleans, and
/// numbers equal to 1e-14 relative (the CLI prints the library's f64s as shortest round-trip
/// decimals, so equal computations give equal numbers; 1e-14 only allows for the last digit).
fn assert_same_json(got: &Value, want: &Value, path: &str) {
    match (got, want) {
        (Value::Number(a), Value::Number(b)) => {
            let (x, y) = (a.as_f64().unwrap(), b.as_f64().unwrap());
            assert!(
                x == y || (x - y).abs() <= 1e-14 * x.abs().max(y.abs()),
                "{path}: {x} vs {y}"
            );
        }
        (Value::Array(a), Value::Array(b)) => {
            assert_eq!(a.len(), b.len(), "{path}: length");
            for (i, (x, y)) in a.iter().zip(b).enumerate() {
                assert_same_json(x, y, &format!("{path}[{i}]"));
            }
        }
        (Value::Object(a), Value::Object(b)) => {
            // The CLI's `units` object is the CLI's own (issue #32).
            let keep = |k: &&String| *k != "units";
            let mut ka: Vec<&String> = a.keys().filter(keep).collect();
            let mut kb: Vec<&String> = b.keys().filter(keep).collect();
            ka.sort();
            kb.sort();
            assert_eq!(ka, kb, "{path}: keys");
            for (k, x) in a.iter().filter(|(k, _)| keep(k)) {
                assert_same_json(x, &b[k], &format!("{path}.{k}"));
            }
        }
        _ => assert_eq!(got, want, "{path}"),
    }
}

/// Counts the numbers in a JSON tree (to show a comparison covered the data).
fn numbers_in(v: &Value) -> usize {
    match v {
        Value::Number(_) => 1,
        Value::Array(a) => a.iter().map(numbers_in).sum(),
        Value::Object(o) => o.values().map(numbers_in).sum(),
        _ => 0,
    }
}

fn to_json<T: serde::Serialize>(v: &T) -> Value {
    serde_json::to_value(v).unwrap()
}

#[test]
fn doe_json_equals_the_library() {
    let v = json(&["doe", "--points", "5", "--json"]);
    // N = 5 optimum [1, 3, 0, 4, 2] by hand: squared gaps 5 (4 pairs), 10 and 17 (2 each),
    // 8 and 18, so E = 4/5 + 2/10 + 2/17 + 1/8 + 1/18 = 1.298202614379085.
    let hand = 0.8 + 0.2 + 2.0 / 17.0 + 0.125 + 1.0 / 18.0;
    assert!((v["energy"].as_f64().unwrap() - hand).abs() < 1e-12);
    let lib = ridelab::doe::doe_report(5, 1, &ridelab::DesignBox::default()).unwrap();
    assert_same_json(&v, &to_json(&lib), "doe");
    let v = json(&["doe", "--points", "17", "--seed", "4", "--json"]);
    let lib = ridelab::doe::doe_report(17, 4, &ridelab::DesignBox::default()).unwrap();
    assert_same_json(&v, &to_json(&lib), "doe 17");
}

#[test]
fn map_json_and_csv_equal_the_library() {
    for (model, kind) in [("quarter", ModelKind::Quarter), ("full", ModelKind::Full)] {
        for relative in [false, true] {
            let mut args = vec![
                "map",
                "--model",
                model,
                "--ks-range",
                "10000:40000:5",
                "--cs-range",
                "500:4000:4",
                "--class",
                "c",
                "--speed",
                "25",
                "--compute",
                "cpu",
            ];
            if relative {
                args.push("--relative");
            }
            let settings = MapSettings {
                grid: Grid::parse("10000:40000:5", "500:4000:4").unwrap(),
                scale: if relative {
                    Scale::Relative
                } else {
                    Scale::Absolute
                },
                ..MapSettings::default()
            };
            let road = Road {
                class: ridelab::RoadClass::C,
                speed: 25.0,
                ..Road::default()
            };
            let lib = MapRequest::new(kind, &Car::datum(), &road, settings)
                .run()
                .unwrap();
            let mut json_args = args.clone();
            json_args.push("--json");
            let v = json(&json_args);
            let want = to_json(&lib);
            assert_same_json(&v, &want, &format!("map {model} {relative}"));
            // Every field value, the feasible set and the contours are in the comparison.
            assert_eq!(v["bacc"].as_array().unwrap().len(), 20);
            assert!(numbers_in(&want) > 3 * 20, "{model}: {}", numbers_in(&want));
            args.push("--csv");
            let (code, csv, err) = ridelab(&args);
            assert_eq!(code, 0, "{err}");
            assert_eq!(csv, map_csv(&lib), "{model} {relative}");
            // The CSV's numbers are the map's: row k is Ks index k % 5, Cs index k / 5.
            let rows: Vec<&str> = csv.lines().skip(1).collect();
            assert_eq!(rows.len(), 20);
            for (k, row) in rows.iter().enumerate() {
                let cells: Vec<f64> = row.split(',').take(5).map(|c| c.parse().unwrap()).collect();
                let i = lib.grid.index(k % 5, k / 5);
                let want = [
                    lib.ks_values[k % 5],
                    lib.cs_values[k / 5],
                    lib.bacc[i],
                    lib.dtl[i],
                    lib.sws[i],
                ];
                for (c, w) in cells.iter().zip(want) {
                    assert!(
                        (c - w).abs() <= 1e-14 * w.abs(),
                        "{model} row {k}: {c} vs {w}"
                    );
                }
            }
        }
    }
}

/// `--compute`: `cpu` is the library's CPU map and says so; `gpu` is the GPU route
/// (within 1e-4 of it on every cell) where there is an adapter, and one line naming the
/// option, exit code 2, where there is none (no adapter: `WGPU_BACKEND` names a backend
/// this platform lacks) or the build has no GPU path.
#[test]
fn map_compute_says_which_path_ran() {
    let args = [
        "map",
        "--model",
        "full",
        "--ks-range",
        "10000:40000:4",
        "--cs-range",
        "500:4000:3",
        "--json",
        "--compute",
    ];
    let with = |path: &'static str| [&args[..], &[path]].concat();
    let cpu = json(&with("cpu"));
    assert_eq!(cpu["compute"], "cpu");
    assert!(cpu.get("adapter").is_none());
    let no_adapter = Command::new(env!("CARGO_BIN_EXE_ridelab"))
        .args(with("gpu"))
        .env(
            "WGPU_BACKEND",
            if cfg!(target_os = "macos") {
                "dx12"
            } else {
                "metal"
            },
        )
        .output()
        .expect("runs");
    let err = String::from_utf8_lossy(&no_adapter.stderr);
    assert_eq!(no_adapter.status.code(), Some(2), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    let why = if cfg!(feature = "gpu") {
        "error: compute: gpu: no GPU adapter"
    } else {
        "error: compute: gpu: this build has no GPU path"
    };
    assert!(err.starts_with(why), "{err}");
    let (code, out, err) = ridelab(&with("gpu"));
    if code != 0 {
        // Past the harness's capture, so the skip shows in a passing run.
        use std::io::Write;
        let _ = writeln!(
            std::io::stderr(),
            "map --compute gpu: SKIPPED ({})",
            err.trim()
        );
        return;
    }
    let gpu: Value = serde_json::from_str(&out).unwrap();
    assert_eq!(gpu["compute"], "gpu");
    assert!(gpu["adapter"].as_str().is_some_and(|a| !a.is_empty()));
    for name in ["bacc", "dtl", "sws"] {
        let (g, c) = (gpu[name].as_array().unwrap(), cpu[name].as_array().unwrap());
        assert_eq!(g.len(), 12);
        for (g, c) in g.iter().zip(c) {
            let (g, c) = (g.as_f64().unwrap(), c.as_f64().unwrap());
            assert!((g / c - 1.0).abs() <= 1e-4, "{name}: {g} vs {c}");
        }
    }
}

/// `optimize --compute` (issue #13): the default prints no `compute` where auto finds no
/// hardware GPU (lavapipe is software), and `--compute cpu` is that output plus
/// `"compute": "cpu"`; `--compute gpu` without an adapter, or off STM on the full car, is
/// one line naming the option, exit code 2; with an adapter (lavapipe here) STM's grid runs
/// on the GPU: every front point within 1e-4 relative of the CPU HiFi at its design, at
/// least 90 % of the front's designs the CPU front's own, the hypervolume within 1e-4
/// relative and the pick within one grid cell (Ks and Cs) of the CPU's.
#[test]
fn optimize_compute_says_which_path_ran_and_the_gpu_front_is_the_cpus() {
    let base = [
        "optimize",
        "--evaluator",
        "full",
        "--method",
        "stm",
        "--grid",
        "41",
        "--json",
    ];
    let with = |extra: &[&'static str]| -> Vec<&'static str> { [&base[..], extra].concat() };
    let default = json(&base);
    let mut cpu = json(&with(&["--compute", "cpu"]));
    assert_eq!(cpu["compute"], "cpu");
    assert!(cpu.get("adapter").is_none());
    if default.get("compute").is_none() {
        cpu.as_object_mut().unwrap().remove("compute");
        assert_eq!(
            cpu, default,
            "--compute cpu is the default output plus `compute`"
        );
    } else {
        // A hardware GPU: auto took it.
        assert_eq!(default["compute"], "gpu");
    }
    let fails = |args: &[&str], env: Option<(&str, &str)>, why: &str| {
        let mut cmd = Command::new(env!("CARGO_BIN_EXE_ridelab"));
        cmd.args(args);
        if let Some((k, v)) = env {
            cmd.env(k, v);
        }
        let out = cmd.output().expect("runs");
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(err.starts_with(why), "{args:?}: {err}");
    };
    let other = if cfg!(target_os = "macos") {
        "dx12"
    } else {
        "metal"
    };
    let no_adapter = if cfg!(feature = "gpu") {
        "error: compute: gpu: no GPU adapter"
    } else {
        "error: compute: gpu: this build has no GPU path"
    };
    fails(
        &with(&["--compute", "gpu"]),
        Some(("WGPU_BACKEND", other)),
        no_adapter,
    );
    fails(
        &[
            "optimize",
            "--evaluator",
            "quarter",
            "--compute",
            "gpu",
            "--json",
        ],
        None,
        "error: compute: gpu: the GPU path evaluates STM's grid on the full car",
    );
    fails(
        &[
            "optimize",
            "--evaluator",
            "full",
            "--method",
            "nsga2",
            "--compute",
            "gpu",
        ],
        None,
        "error: compute: gpu:",
    );
    let (code, out, err) = ridelab(&with(&["--compute", "gpu"]));
    if code != 0 {
        use std::io::Write;
        let _ = writeln!(
            std::io::stderr(),
            "optimize --compute gpu: SKIPPED ({})",
            err.trim()
        );
        return;
    }
    let gpu: Value = serde_json::from_str(&out).unwrap();
    assert_eq!(gpu["compute"], "gpu");
    assert!(gpu["adapter"].as_str().is_some_and(|a| !a.is_empty()));
    let hifi = HiFi::new(&Car::datum(), &Road::default()).unwrap();
    let point = |p: &Value, k: &str| p[k].as_f64().unwrap();
    let (gf, cf) = (
        gpu["front"].as_array().unwrap(),
        cpu["front"].as_array().unwrap(),
    );
    assert!(gf.len() >= 5, "{} GPU front points", gf.len());
    let mut shared = 0;
    for p in gf {
        let (ks, cs) = (point(p, "ks"), point(p, "cs"));
        let want = hifi.evaluate(ks, cs).unwrap();
        for (k, w) in [("bacc", want.bacc), ("dtl", want.dtl), ("sws", want.sws)] {
            let e = (point(p, k) / w - 1.0).abs();
            assert!(e <= 1e-4, "front point ({ks}, {cs}) {k}: {e:.2e}");
        }
        shared += usize::from(
            cf.iter()
                .any(|q| point(q, "ks") == ks && point(q, "cs") == cs),
        );
    }
    assert!(
        10 * shared >= 9 * gf.len(),
        "{shared} of {} GPU front designs on the CPU front",
        gf.len()
    );
    let (hg, hc) = (
        gpu["hypervolume"].as_f64().unwrap(),
        cpu["hypervolume"].as_f64().unwrap(),
    );
    assert!((hg / hc - 1.0).abs() <= 1e-4, "hypervolume {hg} vs {hc}");
    let b = ridelab::DesignBox::default();
    let (pg, pc) = (&gpu["pick"], &cpu["pick"]);
    assert!((point(pg, "ks") - point(pc, "ks")).abs() <= (b.ks_max - b.ks_min) / 40.0);
    assert!((point(pg, "cs") - point(pc, "cs")).abs() <= (b.cs_max - b.cs_min) / 40.0);
}

/// The CLI's `optimize` output through the library: the datum on the HiFi, the problem on
/// the chosen evaluator, the study, and the pick re-checked on the HiFi.
fn optimize_by_library(evaluator: &str, method: Method) -> Value {
    let car = Car::datum();
    let road = Road::default();
    let hifi = HiFi::new(&car, &road).unwrap();
    let datum = hifi.evaluate(car.front.spring, car.front.damper).unwrap();
    let q = car.quarter();
    let ctx = DosContext {
        sprung_mass: q.ms,
        tire_stiffness: q.kt,
        datum,
        static_wheel_load: car.front_wheel_load(),
    };
    let design_box = ridelab::DesignBox::default();
    let eval: Box<dyn Evaluator> = match evaluator {
        "quarter" => Box::new(LoFi {
            car: car.clone(),
            road,
        }),
        "full" => Box::new(hifi.clone()),
        name => {
            let plan = PlanSpec::parse("ae:5").unwrap().plan().unwrap();
            let samples = sample_plan(&hifi, &plan, &design_box).unwrap();
            let setting = Setting::new(&car, &road, &design_box).unwrap();
            Box::new(
                SurrogateSpec::parse(name)
                    .unwrap()
                    .fit(&setting, &samples, &LmOptions::default())
                    .unwrap(),
            )
        }
    };
    // The datum design on the front's own model, where that is not the HiFi.
    let own =
        (evaluator != "full").then(|| eval.evaluate(car.front.spring, car.front.damper).unwrap());
    let problem =
        SuspensionProblem::new(eval, design_box, DesignObjectives::default(), ctx).unwrap();
    let study = run_study(&problem, &method, None).unwrap();
    let check = recheck(&study.pick, &hifi, &datum).unwrap();
    let mut v = to_json(&study);
    if let Some(d) = own {
        let p = &study.pick.criteria;
        let pc = |c: f64, d: f64| 100.0 * (c / d - 1.0);
        v["same_model"] = serde_json::json!({
            "datum": to_json(&d),
            "change_percent": [pc(p.bacc, d.bacc), pc(p.dtl, d.dtl), pc(p.sws, d.sws)],
        });
    }
    v["datum"] = to_json(&datum);
    v["hifi_recheck"] = to_json(&check);
    v["warnings"] = to_json(&ridelab::optimize::pick_warnings(
        &study.pick,
        &check,
        &design_box,
    ));
    v
}

#[test]
fn optimize_json_equals_the_library() {
    let nsga = Method::Nsga2(Nsga2Params {
        population: 20,
        generations: 10,
        seed: 3,
        ..Nsga2Params::default()
    });
    let stm = Method::Stm(StmParams {
        grid: 41,
        ..StmParams::default()
    });
    let cases: [(&[&str], &str, Method); 3] = [
        (
            &[
                "--evaluator",
                "quarter",
                "--method",
                "nsga2",
                "--population",
                "20",
            ],
            "quarter",
            nsga,
        ),
        (
            &["--evaluator", "full", "--method", "stm", "--grid", "41"],
            "full",
            stm.clone(),
        ),
        (
            &["--evaluator", "vba-qts", "--plan", "ae:5", "--grid", "41"],
            "vba-qts",
            stm,
        ),
    ];
    for (extra, evaluator, method) in cases {
        let mut args = vec!["optimize", "--json"];
        args.extend(extra);
        if evaluator == "quarter" {
            args.extend(["--generations", "10", "--seed", "3"]);
        }
        let v = json(&args);
        let want = optimize_by_library(evaluator, method);
        assert_same_json(&v, &want, &format!("optimize {evaluator}"));
        // The whole front, the pick and the re-check are compared, not a length.
        let front = want["front"].as_array().unwrap().len();
        assert!(front >= 5, "{evaluator}: {front} front points");
        assert_eq!(v["evaluator"], evaluator);
    }
}

/// `--plan ae:5 --adaptive 2` (issue #15): the CLI's JSON is the library's loop; the
/// samples come in the order added (the plan's five, then the two adaptive runs, each
/// with its reason), each holds the HiFi's criteria at its design, and the optimisation
/// runs on the surrogate refitted here to exactly those samples.
#[test]
fn adaptive_json_equals_the_library_and_lists_the_samples_in_order() {
    use ridelab::study::adaptive::AdaptiveOptions;
    use ridelab::study::SurrogateRequest;
    let (car, road, b) = (Car::datum(), Road::default(), ridelab::DesignBox::default());
    let hifi = HiFi::new(&car, &road).unwrap();
    let options = AdaptiveOptions {
        runs: 2,
        candidates: 11,
        ..AdaptiveOptions::default()
    };
    let spec = SurrogateSpec::parse("gp-mul").unwrap();
    let ae5 = PlanSpec::AudzeEglais(5);
    // ridelab surrogate
    let v = json(&[
        "surrogate",
        "--approach",
        "gp-mul",
        "--plan",
        "ae:5",
        "--adaptive",
        "2",
        "--candidates",
        "11",
        "--predict",
        "grid:4",
    ]);
    let request = SurrogateRequest {
        predict_grid: Some(4),
        adaptive: Some(options),
        ..SurrogateRequest::new(spec, ae5)
    };
    let lib = request.report(&car, &road).unwrap();
    assert_same_json(&v, &to_json(&lib), "surrogate --adaptive");
    let samples = v["samples"].as_array().unwrap();
    assert_eq!(samples.len(), 7);
    let initial = sample_plan(&hifi, &ae5.plan().unwrap(), &b).unwrap();
    assert_same_json(
        &Value::Array(samples[..5].to_vec()),
        &to_json(&initial),
        "plan",
    );
    let added = v["adaptive"]["added"].as_array().unwrap();
    assert_eq!(added.len(), 2);
    for (i, a) in added.iter().enumerate() {
        assert_eq!(a["run"], 6 + i);
        assert_same_json(&a["sample"], &samples[5 + i], "added sample");
        assert!(a["reason"]
            .as_str()
            .unwrap()
            .starts_with("largest expected hypervolume improvement"));
        let (ks, cs) = (
            a["sample"]["ks"].as_f64().unwrap(),
            a["sample"]["cs"].as_f64().unwrap(),
        );
        let c = hifi.evaluate(ks, cs).unwrap();
        assert_same_json(&a["sample"]["hifi"], &to_json(&c), "added HiFi");
    }
    // 7 samples, the 4 x 4 validation grid and the datum (the SWS limit's context).
    assert_eq!(v["hifi_evaluations"], 7 + 16 + 1);
    assert_eq!(v["uncertainty"][0]["method"], "model");
    assert_eq!(v["uncertainty"][1]["method"], "loo");
    // ridelab optimize
    let v = json(&[
        "optimize",
        "--json",
        "--evaluator",
        "gp-mul",
        "--plan",
        "ae:5",
        "--adaptive",
        "2",
        "--candidates",
        "11",
        "--grid",
        "41",
    ]);
    let method = Method::Stm(StmParams {
        grid: 41,
        ..StmParams::default()
    });
    let request = OptimizeRequest {
        evaluator: "gp-mul".parse().unwrap(),
        plan: ae5,
        ..OptimizeRequest::new(&car, &road, b, method.clone(), DesignObjectives::default())
    };
    let lib = request.run_adaptive(options).unwrap();
    assert_same_json(&v, &to_json(&lib), "optimize --adaptive");
    let mut samples = initial;
    for a in &lib.adaptive.added {
        samples.push(a.sample);
    }
    let setting = Setting::new(&car, &road, &b).unwrap();
    let model = spec.fit(&setting, &samples, &LmOptions::default()).unwrap();
    let datum = hifi.evaluate(car.front.spring, car.front.damper).unwrap();
    let ctx = DosContext::new(&car, datum);
    let problem = SuspensionProblem::new(model, b, DesignObjectives::default(), ctx).unwrap();
    let study = run_study(&problem, &method, None).unwrap();
    assert_same_json(&v["front"], &to_json(&study.front), "front on the refit");
    assert_same_json(&v["pick"], &to_json(&study.pick), "pick on the refit");
    let check = recheck(&study.pick, &hifi, &datum).unwrap();
    assert_same_json(&v["hifi_recheck"], &to_json(&check), "re-check");
    // Text output names each added run.
    let (code, text, err) = ridelab(&[
        "optimize",
        "--evaluator",
        "gp-mul",
        "--plan",
        "ae:5",
        "--adaptive",
        "2",
        "--candidates",
        "11",
        "--grid",
        "41",
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(text.contains("adaptive: ae:5 + 2 HiFi runs (ehvi-front, model uncertainty)"));
    assert!(text.contains("  run   7: Ks "), "{text}");
}

#[test]
fn simulate_json_and_csv_equal_the_library() {
    // The linear model only (no --bump/--rebound): the time-domain record and its RMS.
    for (model, kind) in [("quarter", ModelKind::Quarter), ("full", ModelKind::Full)] {
        let args = [
            "simulate",
            "--model",
            model,
            "--duration",
            "3",
            "--dt",
            "0.004",
            "--seed",
            "9",
            "--decimate",
            "5",
            "--tracks",
            "independent",
        ];
        let car = Car::datum();
        let road = Road {
            tracks: ridelab::Tracks::Independent,
            ..Road::default()
        };
        let opt = TimeOptions {
            duration: 3.0,
            dt: 0.004,
            seed: 9,
            decimate: 5,
            // The CLI keeps the road below 0.4 / dt (80 % of the Nyquist frequency): 100 Hz.
            f_max: TimeOptions::default().f_max.min(0.4 / 0.004),
            ..TimeOptions::default()
        };
        let lib = simulate(kind, &car, &road, &opt).unwrap();
        let mut json_args = args.to_vec();
        json_args.push("--json");
        let v = json(&json_args);
        // The JSON names every series (issue #32); the numbers are the library's.
        let series =
            |name: &str| -> Vec<f64> { serde_json::from_value(v["series"][name].clone()).unwrap() };
        assert_eq!(series("t"), lib.t, "{model} t");
        assert_eq!(series("road"), lib.road, "{model} road");
        for (k, name) in ["bacc", "dtl", "sws"].iter().enumerate() {
            assert_eq!(series(name), lib.outputs[k], "{model} {name}");
            assert_eq!(
                v["rms"][name].as_f64(),
                Some(lib.rms[k]),
                "{model} rms {name}"
            );
            assert!(lib.rms[k] > 0.0);
        }
        let dofs = kind.build(&car).dof_names;
        for (d, name) in dofs.iter().enumerate() {
            let key = name.replace([' ', '-'], "_");
            let p: Vec<f64> = serde_json::from_value(v["positions"][&key].clone()).unwrap();
            let a: Vec<f64> = serde_json::from_value(v["accelerations"][&key].clone()).unwrap();
            assert_eq!(
                (p, a),
                (lib.positions[d].clone(), lib.accelerations[d].clone()),
                "{model} {key}"
            );
        }
        assert_eq!(v["t"], Value::Null);
        assert_eq!(v["series"]["t"].as_array().unwrap().len(), 750 / 5);
        let mut csv_args = args.to_vec();
        csv_args.push("--csv");
        let (code, csv, err) = ridelab(&csv_args);
        assert_eq!(code, 0, "{err}");
        let mut lines = csv.lines();
        assert_eq!(lines.next(), Some("t_s,road_m,bacc_m_per_s2,dtl_n,sws_m"));
        let rows: Vec<Vec<f64>> = lines
            .map(|l| l.split(',').map(|c| c.parse().unwrap()).collect())
            .collect();
        assert_eq!(rows.len(), lib.t.len());
        for (i, row) in rows.iter().enumerate() {
            let want = [
                lib.t[i],
                lib.road[i],
                lib.outputs[0][i],
                lib.outputs[1][i],
                lib.outputs[2][i],
            ];
            for (c, w) in row.iter().zip(want) {
                assert!(
                    (c - w).abs() <= 1e-14 * w.abs(),
                    "{model} row {i}: {c} vs {w}"
                );
            }
        }
    }
}

#[test]
fn surrogate_json_equals_the_library() {
    for (approach, plan) in [
        ("vba-qts", "ae:5"),
        ("pba-smts", "grid:3"),
        ("rba-mul-poly2", "ae:10"),
    ] {
        let v = json(&[
            "surrogate",
            "--approach",
            approach,
            "--plan",
            plan,
            "--predict",
            "grid:4",
            "--speed",
            "15",
        ]);
        let road = Road {
            speed: 15.0,
            ..Road::default()
        };
        let lib = SurrogateRequest {
            predict_grid: Some(4),
            ..SurrogateRequest::parse(approach, plan).unwrap()
        }
        .report(&Car::datum(), &road)
        .unwrap();
        let want = to_json(&lib);
        assert_same_json(&v, &want, &format!("surrogate {approach}"));
        // Metrics and tuning are part of it; spelled out so a renamed key cannot slip by.
        assert_same_json(&v["metrics"], &to_json(&lib.metrics), "metrics");
        assert_same_json(&v["tuning"], &to_json(&lib.tuning), "tuning");
        assert!(!lib.tuning.is_empty());
    }
}

#[test]
fn study_json_equals_the_library_and_its_rows_the_single_fits() {
    // The whole study is about 2 s in the test profile (300 fits on 400 + 155 HiFi runs).
    let v = json(&["study", "--json"]);
    let lib = study(
        &Car::datum(),
        &Road::default(),
        &ridelab::DesignBox::default(),
    )
    .unwrap();
    assert_same_json(&v, &to_json(&lib), "study");
    // A few rows again through `ridelab surrogate`'s library route (the same plan, fit and
    // 20 x 20 validation grid): the same metrics.
    let rows = v["rows"].as_array().unwrap();
    let mut checked = 0;
    for (approach, plan) in [
        ("vba-qts", "ae:10"),
        ("rba-mul-rbf-gauss", "grid:3"),
        ("pba-smts", "ae:4"),
    ] {
        let row = rows
            .iter()
            .find(|r| r["surrogate"] == approach && r["plan"] == plan)
            .unwrap_or_else(|| panic!("{approach} {plan} missing"));
        assert_eq!(row["outcome"]["status"], "fitted", "{approach} {plan}");
        let single = SurrogateRequest::parse(approach, plan)
            .and_then(|r| r.report(&Car::datum(), &Road::default()))
            .unwrap();
        assert_same_json(
            &row["outcome"]["metrics"],
            &to_json(&single.metrics),
            &format!("{approach} {plan}"),
        );
        checked += 1;
    }
    assert_eq!(checked, 3);
    let (code, md, _) = ridelab(&["study", "--markdown"]);
    assert_eq!((code, md), (0, lib.to_markdown()));
}

#[test]
fn presets_list_every_preset_with_its_name_and_source() {
    let v = json(&["presets", "--json"]);
    let cars = v["cars"].as_array().unwrap();
    assert_eq!(cars.len(), PRESETS.len());
    let (code, text, _) = ridelab(&["presets"]);
    assert_eq!(code, 0);
    for ((stem, file), car) in PRESETS.iter().zip(cars) {
        let lib = Car::preset(stem).unwrap();
        assert_same_json(car, &to_json(&lib), stem);
        // The file's own name and source, read here from the shipped JSON text.
        let raw: Value = serde_json::from_str(file).unwrap();
        assert_eq!(car["name"], raw["name"], "{stem}");
        assert_eq!(car["source"], raw["source"], "{stem}");
        assert!(!lib.source.is_empty(), "{stem} has no source");
        assert!(
            text.contains(&format!("{stem:<8} {}\n", lib.name))
                && text.contains(&format!("source: {}\n", lib.source)),
            "{stem} missing from:\n{text}"
        );
    }
    assert_eq!(text.lines().count(), 2 * PRESETS.len());
}

#[test]
fn bad_input_is_one_line_naming_the_option_with_exit_code_2() {
    let cases: &[(&[&str], &str)] = &[
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
        (&["optimize", "--method", "simplex"], "method"),
        (&["optimize", "--evaluator", "oracle"], "evaluator"),
        (
            &["optimize", "--evaluator", "quarter", "--grid", "x"],
            "grid",
        ),
        (
            &["map", "--model", "quarter", "--cs-range", "1:2"],
            "cs-range",
        ),
        (&["map", "--ks-range", "10000:40000:5"], "model"),
        (&["map", "--model", "full", "--compute", "tpu"], "compute"),
        (
            &["map", "--model", "quarter", "--compute", "gpu"],
            "compute",
        ),
        (
            &["map", "--model", "quarter", "--comfort", "foo"],
            "comfort",
        ),
        (&["optimize", "--comfort", "foo"], "comfort"),
        (&["optimize", "--comfort", ""], "comfort"),
        (
            &[
                "map",
                "--model",
                "full",
                "--comfort",
                "wk",
                "--compute",
                "gpu",
            ],
            "comfort",
        ),
        (
            &["optimize", "--evaluator", "vba-qts", "--comfort", "wk"],
            "comfort",
        ),
        (
            &[
                "optimize",
                "--evaluator",
                "vba-qts",
                "--comfort",
                "wk",
                "--adaptive",
                "2",
            ],
            "comfort",
        ),
        (&["simulate"], "model"),
        (
            &["simulate", "--model", "full", "--duration", "-1"],
            "duration",
        ),
        (
            &["simulate", "--model", "full", "--duration", "5000"],
            "duration",
        ),
        (&["simulate", "--model", "full", "--dt", "0.5"], "dt"),
        (
            &["simulate", "--model", "full", "--decimate", "0"],
            "decimate",
        ),
        (&["simulate", "--model", "full", "--seed", "x"], "seed"),
        (&["simulate", "--model", "quarter", "--ks", "0"], "ks"),
        (&["simulate", "--model", "full", "--cs", "nan"], "cs"),
        (&["surrogate"], "approach"),
        (&["surrogate", "--approach", "nonsense"], "approach"),
        (
            &["surrogate", "--approach", "vba-qts", "--plan", "ae:1"],
            "plan",
        ),
        (
            &["surrogate", "--approach", "vba-qts", "--predict", "grid:x"],
            "predict",
        ),
        // The adaptive loop (issue #15): ae:10 + 91 exceeds the 100 HiFi runs allowed.
        (
            &["surrogate", "--approach", "gp-mul", "--adaptive", "91"],
            "adaptive",
        ),
        (
            &["surrogate", "--approach", "gp-mul", "--adaptive", "x"],
            "adaptive",
        ),
        (
            &["surrogate", "--approach", "gp-mul", "--infill", "ehvi"],
            "adaptive",
        ),
        (
            &[
                "surrogate",
                "--approach",
                "gp-mul",
                "--adaptive",
                "1",
                "--infill",
                "best",
            ],
            "infill",
        ),
        (
            &[
                "surrogate",
                "--approach",
                "gp-mul",
                "--adaptive",
                "1",
                "--uncertainty",
                "sure",
            ],
            "uncertainty",
        ),
        (
            &[
                "surrogate",
                "--approach",
                "vba-qts",
                "--adaptive",
                "1",
                "--uncertainty",
                "model",
            ],
            "uncertainty",
        ),
        (
            &[
                "surrogate",
                "--approach",
                "gp-mul",
                "--adaptive",
                "1",
                "--candidates",
                "202",
            ],
            "candidates",
        ),
        (
            &[
                "surrogate",
                "--approach",
                "gp-mul",
                "--adaptive",
                "1",
                "--min-distance",
                "0",
            ],
            "min-distance",
        ),
        (
            &["optimize", "--evaluator", "full", "--adaptive", "2"],
            "adaptive",
        ),
        (
            &[
                "optimize",
                "--evaluator",
                "gp-mul",
                "--plan",
                "ae:1",
                "--adaptive",
                "2",
            ],
            "plan",
        ),
        (&["study", "--adaptive", "nonsense"], "adaptive"),
        (&["study", "--initial", "3"], "adaptive"),
        (
            &["study", "--adaptive", "gp-mul", "--max-runs", "101"],
            "max-runs",
        ),
        (
            &["study", "--adaptive", "gp-mul", "--min-runs", "5"],
            "min-runs",
        ),
        (&["study", "--class", "Z"], "class"),
        (&["study", "--tracks", "both"], "tracks"),
        (&["presets", "--wat"], "--wat"),
        (&["presets", "extra"], "extra"),
        (&["eval", "--model", "full", "--ks", "inf"], "ks"),
        (&["frobnicate"], "command"),
        (&["report", "--ks-range", "40000:10000"], "ks-range"),
        (&["optimize", "--dtl-margin", "0"], "dtl-margin"),
        (&["optimize", "--pick", "asf:2"], "pick"),
        (&["optimize", "--travel", "25"], "travel"),
        (
            &["map", "--model", "quarter", "--travel", "0.025:-3"],
            "travel",
        ),
        // Class C: RMS DTL is about 770 N at the datum; F_static / 10 = 498 N is out of reach
        // in the whole box.
        (
            &[
                "optimize",
                "--evaluator",
                "quarter",
                "--class",
                "C",
                "--sws-limit",
                "1",
                "--dtl-margin",
                "10",
            ],
            "dtl_margin",
        ),
        (&["report", "--seed", "-1"], "seed"),
        (&["report", "--approach", "pba-ml"], "approach"),
        (&["report", "--out", "/proc/ridelab-report"], "out"),
        (&["doe", "--points", "-3"], "points"),
        // Every size has a bound with a message (this one once aborted on a 14 GB allocation).
        (
            &["optimize", "--method", "nsga2", "--population", "100000000"],
            "population",
        ),
        (
            &["optimize", "--method", "nsga2", "--generations", "100000"],
            "generations",
        ),
        (&["optimize", "--grid", "5000"], "grid"),
        (&["doe", "--points", "5000"], "points"),
        (
            &["map", "--model", "quarter", "--ks-range", "1:2:2000"],
            "ks-range",
        ),
        (
            &[
                "surrogate",
                "--approach",
                "vba-qts",
                "--predict",
                "grid:1000",
            ],
            "predict",
        ),
        (
            &["surrogate", "--approach", "vba-qts", "--plan", "ae:5000"],
            "plan",
        ),
        (
            &[
                "simulate",
                "--model",
                "full",
                "--duration",
                "3600",
                "--dt",
                "0.0001",
            ],
            "dt",
        ),
        // The asymmetric damper: rates come together, and the design's Cs is their mean.
        (&["simulate", "--model", "full", "--bump", "500"], "rebound"),
        (
            &[
                "simulate",
                "--model",
                "full",
                "--bump",
                "500",
                "--rebound",
                "-1",
            ],
            "rebound",
        ),
        (
            &[
                "simulate",
                "--model",
                "full",
                "--bump",
                "500",
                "--rebound",
                "900",
                "--cs",
                "1000",
            ],
            "cs",
        ),
        (
            &[
                "simulate",
                "--model",
                "full",
                "--bump",
                "1",
                "--rebound",
                "2",
                "--knee",
                "0.1",
            ],
            "bump-high",
        ),
        (
            &[
                "simulate",
                "--model",
                "full",
                "--bump",
                "1",
                "--rebound",
                "2",
                "--knee",
                "-0.1",
                "--bump-high",
                "1",
                "--rebound-high",
                "1",
            ],
            "knee",
        ),
        (
            &["eval", "--model", "full", "--speed", "3", "--speed", "4"],
            "speed",
        ),
    ];
    for &(args, field) in cases {
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
    let settings = ridelab::study::MapSettings {
        grid: ridelab::maps::Grid::parse("10000:40000:21", "500:4000:15").unwrap(),
        ..Default::default()
    };
    let report = MapRequest::new(
        ModelKind::Quarter,
        &Car::datum(),
        &Road::default(),
        settings,
    )
    .run()
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

/// `ridelab report` writes the library's report: report.json is the library's build of
/// the same inputs (to 1e-14), the HTML, the Markdown, every figure and every CSV table are
/// the library's text byte for byte, and stderr times each section.
#[test]
fn report_writes_the_library_report() {
    use ridelab::report::{build, ReportInputs, SECTIONS};
    let dir = std::env::temp_dir().join("ridelab-cli-report");
    let _ = std::fs::remove_dir_all(&dir);
    let out_dir = dir.to_str().unwrap();
    let (code, out, err) = ridelab(&["report", "--car", "suv", "--class", "C", "--out", out_dir]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("report.html"), "{out}");
    for s in SECTIONS {
        assert!(err.contains(&format!("report: {s} took ")), "{s}: {err}");
    }
    let read = |name: &str| std::fs::read_to_string(dir.join(name)).unwrap();
    let road = Road {
        class: ridelab::road::RoadClass::C,
        ..Road::default()
    };
    let lib = build(
        &ReportInputs::new(Car::preset("suv").unwrap(), road),
        |_| {},
    )
    .unwrap();
    let got: Value = serde_json::from_str(&read("report.json")).unwrap();
    let want = to_json(&lib);
    assert_same_json(&got, &want, "report");
    assert!(numbers_in(&want) > 1000);
    let docs = lib.documents().unwrap();
    assert_eq!(read("report.html"), docs.html);
    assert_eq!(read("report.md"), docs.markdown);
    assert!(!docs.figures.is_empty());
    for f in &docs.figures {
        assert_eq!(read(&format!("figures/{}.svg", f.key)), f.svg, "{}", f.key);
    }
    for (name, text) in lib.csv_files() {
        assert_eq!(read(name), text, "{name}");
    }
}

/// The tyre-load margin and the travel budget shape the front: every front point and the
/// pick meet both (RMS DTL <= F_static / 14, 3 RMS SWS <= 20 mm), while the default front
/// has points that break them.
#[test]
fn optimize_meets_the_tyre_load_margin_and_the_travel_budget() {
    let f_static = Car::datum().front_wheel_load();
    let ok = |p: &Value| {
        p["dtl"].as_f64().unwrap() * 14.0 <= f_static * (1.0 + 1e-12)
            && 3.0 * p["sws"].as_f64().unwrap() <= 0.02 * (1.0 + 1e-12)
    };
    let base = json(&["optimize", "--evaluator", "quarter", "--json"]);
    let front = base["front"].as_array().unwrap();
    assert!(front.iter().any(|p| !ok(p)), "the limits should bind");
    let v = json(&[
        "optimize",
        "--evaluator",
        "quarter",
        "--dtl-margin",
        "14",
        "--travel",
        "0.02:3",
        "--json",
    ]);
    let front = v["front"].as_array().unwrap();
    assert!(front.len() > 10);
    assert!(front.iter().all(ok));
    assert!(ok(&v["pick"]["criteria"]));
}

/// `--pick knee` and `--pick asf:W` print the library's repick of the same front with its
/// HiFi re-check.
#[test]
fn optimize_pick_rules_equal_the_library() {
    use ridelab::optimize::PickRule;
    use ridelab::study::EvaluatorSpec;
    for rule in ["knee", "asf:0.8"] {
        let v = json(&[
            "optimize",
            "--evaluator",
            "quarter",
            "--pick",
            rule,
            "--json",
        ]);
        let car = Car::datum();
        let road = Road::default();
        let mut lib = OptimizeRequest {
            evaluator: EvaluatorSpec::Model(ModelKind::Quarter),
            plan: PlanSpec::parse("ae:10").unwrap(),
            ..OptimizeRequest::new(
                &car,
                &road,
                ridelab::DesignBox::default(),
                Method::Stm(StmParams::default()),
                ridelab::dos::DesignObjectives::default(),
            )
        }
        .run_cpu()
        .unwrap();
        lib.repick(
            rule.parse::<PickRule>().unwrap(),
            &car,
            &road,
            &ridelab::DesignBox::default(),
        )
        .unwrap();
        assert_same_json(&v, &to_json(&lib), rule);
        assert_eq!(v["pick"]["rule"], rule);
    }
}

/// `map --comfort wk` (issue #16): the BAcc plane holds the ISO 2631-1 Wk-weighted RMS
/// body acceleration of each design, equal to the frequency route and to the Kronecker
/// route of that design to 1e-8 (the datum's too); DTL and SWS are the unweighted map's
/// bit for bit; the JSON says `"comfort": "wk"`, the CSV names the column.
#[test]
fn map_comfort_wk_is_the_exact_weighted_acceleration() {
    use ridelab::criteria::{bacc_wk_exact, bacc_wk_spectral};
    let car = Car::datum();
    let road = Road::default();
    for (kind, model) in [("quarter", ModelKind::Quarter), ("full", ModelKind::Full)] {
        let base = [
            "map",
            "--model",
            kind,
            "--ks-range",
            "10000:40000:5",
            "--cs-range",
            "500:4000:4",
        ];
        let wk = json(&[&base[..], &["--comfort", "wk"]].concat());
        let plain = json(&base);
        assert_eq!(wk["comfort"], "wk");
        assert!(plain.get("comfort").is_none());
        assert_eq!(wk["units"]["bacc"], "m/s^2");
        assert_eq!(wk["dtl"], plain["dtl"]);
        assert_eq!(wk["sws"], plain["sws"]);
        // SWS decides the mask here; the feasible set carries the weighted BAcc.
        assert_eq!(wk["feasibility"]["mask"], plain["feasibility"]["mask"]);
        assert_eq!(
            wk["feasibility"]["summary"],
            plain["feasibility"]["summary"]
        );
        for p in wk["feasibility"]["feasible_set"].as_array().unwrap() {
            let k = wk["ks_values"]
                .as_array()
                .unwrap()
                .iter()
                .position(|v| *v == p["ks"])
                .unwrap()
                + 5 * wk["cs_values"]
                    .as_array()
                    .unwrap()
                    .iter()
                    .position(|v| *v == p["cs"])
                    .unwrap();
            assert_eq!(p["bacc"], wk["bacc"][k]);
        }
        let f = |v: &Value, k: usize| v.as_array().unwrap()[k].as_f64().unwrap();
        let mut worst = 0.0f64;
        for k in [0, 7, 13, 19] {
            let (i, j) = (k % 5, k / 5);
            let ks = f(&wk["ks_values"], i);
            let cs = f(&wk["cs_values"], j);
            let m = model.build(&car.with_front(ks, cs).unwrap());
            let spectral = bacc_wk_spectral(&m, &road, 1e-11).unwrap();
            let exact = bacc_wk_exact(&m, &road).unwrap();
            let got = f(&wk["bacc"], k);
            worst = worst.max((got / spectral - 1.0).abs());
            assert!(
                (got / spectral - 1.0).abs() < 1e-8,
                "{kind} {k}: {got} vs {spectral}"
            );
            assert!(
                (got / exact - 1.0).abs() < 1e-8,
                "{kind} {k}: {got} vs {exact}"
            );
            // Not the unweighted value: the weighting is on.
            assert!(
                (got / f(&plain["bacc"], k) - 1.0).abs() > 0.05,
                "{kind} {k}"
            );
        }
        let datum = bacc_wk_spectral(&model.build(&car), &road, 1e-11).unwrap();
        let got = wk["datum"]["criteria"]["bacc"].as_f64().unwrap();
        assert!((got / datum - 1.0).abs() < 1e-8, "{kind} datum");
        println!("{kind}: Wk map plane vs frequency route, worst relative difference {worst:.1e}");
        let (code, csv, err) = ridelab(&[&base[..], &["--comfort", "wk", "--csv"]].concat());
        assert_eq!(code, 0, "{err}");
        assert!(
            csv.starts_with("ks_n_per_m,cs_ns_per_m,bacc_wk_m_per_s2,dtl_n,sws_m,"),
            "{csv}"
        );
    }
}

/// `--comfort bacc` is the default: the output is the same bytes as without the option
/// (map JSON and CSV, optimize text and JSON).
#[test]
fn comfort_bacc_is_the_output_without_the_option() {
    let map = [
        "map",
        "--model",
        "quarter",
        "--ks-range",
        "10000:40000:7",
        "--cs-range",
        "500:4000:6",
    ];
    let opt = ["optimize", "--evaluator", "quarter", "--grid", "41"];
    for (args, extra) in [
        (&map[..], &["--json"][..]),
        (&map[..], &["--csv"][..]),
        (&opt[..], &[][..]),
        (&opt[..], &["--json"][..]),
    ] {
        let without = ridelab(&[args, extra].concat());
        let with = ridelab(&[args, extra, &["--comfort", "bacc"]].concat());
        assert_eq!(without.0, 0, "{args:?} {extra:?}: {}", without.2);
        assert_eq!(with, without, "{args:?} {extra:?}");
        assert!(!without.1.contains("comfort\""), "{args:?} {extra:?}");
    }
}

/// `optimize --comfort wk` on the HiFi (issue #16): the JSON is the library's; the front,
/// the datum and the re-check hold Wk-weighted values (equal to the frequency route to
/// 1e-8 at the datum and the pick); the min-max pick differs from the unweighted one; on
/// the LoFi the pick is re-checked on the HiFi with the Wk measure too.
#[test]
fn optimize_comfort_wk_picks_and_rechecks_with_the_weighted_measure() {
    use ridelab::comfort::Comfort;
    use ridelab::criteria::bacc_wk_spectral;
    use ridelab::study::EvaluatorSpec;
    let car = Car::datum();
    let road = Road::default();
    let wk_of = |ks: f64, cs: f64| {
        bacc_wk_spectral(
            &ModelKind::Full.build(&car.with_front(ks, cs).unwrap()),
            &road,
            1e-11,
        )
        .unwrap()
    };
    let close = |a: f64, b: f64| (a / b - 1.0).abs() < 1e-8;
    let num = |v: &Value| v.as_f64().unwrap();
    for (kind, model) in [("full", ModelKind::Full), ("quarter", ModelKind::Quarter)] {
        let args = ["optimize", "--evaluator", kind, "--grid", "41", "--json"];
        let wk = json(&[&args[..], &["--comfort", "wk"]].concat());
        let plain = json(&args);
        let lib = OptimizeRequest {
            evaluator: EvaluatorSpec::Model(model),
            plan: PlanSpec::parse("ae:10").unwrap(),
            comfort: Comfort::Wk,
            ..OptimizeRequest::new(
                &car,
                &road,
                ridelab::DesignBox::default(),
                Method::Stm(StmParams {
                    grid: 41,
                    ..StmParams::default()
                }),
                DesignObjectives::default(),
            )
        }
        .run_cpu()
        .unwrap();
        assert_same_json(&wk, &to_json(&lib), &format!("optimize {kind} wk"));
        assert_eq!(wk["comfort"], "wk");
        assert!(close(
            num(&wk["datum"]["bacc"]),
            wk_of(car.front.spring, car.front.damper)
        ));
        assert_eq!(wk["datum"]["dtl"], plain["datum"]["dtl"]);
        let (ks, cs) = (num(&wk["pick"]["ks"]), num(&wk["pick"]["cs"]));
        let check = &wk["hifi_recheck"];
        assert_eq!(check["evaluator"], "full");
        assert!(
            close(num(&check["rechecked"]["bacc"]), wk_of(ks, cs)),
            "{kind}"
        );
        if kind == "full" {
            assert!(close(num(&wk["pick"]["criteria"]["bacc"]), wk_of(ks, cs)));
        }
        let (pks, pcs) = (num(&plain["pick"]["ks"]), num(&plain["pick"]["cs"]));
        assert!(
            (ks - pks).abs() > 1.0 || (cs - pcs).abs() > 1.0,
            "{kind}: the Wk pick ({ks}, {cs}) is the BAcc pick ({pks}, {pcs})"
        );
        println!(
            "{kind}: BAcc pick Ks {pks:.1} Cs {pcs:.1}; Wk pick Ks {ks:.1} Cs {cs:.1}, re-checked Wk {:+.2} %, DTL {:+.2} %",
            num(&check["rechecked_change_percent"][0]),
            num(&check["rechecked_change_percent"][1])
        );
        let (code, text, err) = ridelab(&[
            "optimize",
            "--evaluator",
            kind,
            "--grid",
            "41",
            "--comfort",
            "wk",
        ]);
        assert_eq!(code, 0, "{err}");
        assert!(
            text.contains("  BAcc (Wk) ") && text.contains("re-check: BAcc (Wk) "),
            "{text}"
        );
    }
}

/// The README's command table names every top-level field of each command's JSON (issue
/// #32): a field added to an output without a word in the README fails here.
#[test]
fn readme_names_every_top_level_json_field() {
    let readme = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../README.md"))
        .expect("README.md");
    let common = readme
        .split("\n\n")
        .find(|p| p.starts_with("Common JSON fields:"))
        .expect("a 'Common JSON fields:' paragraph")
        .to_string();
    let grid = ["--ks-range", "10000:40000:3", "--cs-range", "500:4000:3"];
    let runs: Vec<(&str, Vec<&str>)> = vec![
        ("eval", vec!["eval", "--model", "quarter"]),
        ("doe", vec!["doe", "--points", "5"]),
        ("map", [&["map", "--model", "quarter"][..], &grid].concat()),
        (
            "optimize",
            vec![
                "optimize",
                "--evaluator",
                "quarter",
                "--grid",
                "11",
                "--levels",
                "0",
            ],
        ),
        (
            "surrogate",
            vec![
                "surrogate",
                "--approach",
                "vba-lts",
                "--plan",
                "ae:3",
                "--predict",
                "grid:3",
            ],
        ),
        (
            "simulate",
            vec!["simulate", "--model", "quarter", "--duration", "1"],
        ),
        ("presets", vec!["presets"]),
    ];
    for (command, args) in runs {
        let row = readme
            .lines()
            .find(|l| {
                l.starts_with(&format!("| `{command} "))
                    || l.starts_with(&format!("| `{command}` "))
            })
            .unwrap_or_else(|| panic!("no README row for {command}"));
        let v = json(&args);
        let keys: Vec<String> = match &v {
            Value::Object(m) => m.keys().cloned().collect(),
            _ => panic!("{command}: not an object"),
        };
        let missing: Vec<&String> = keys
            .iter()
            .filter(|k| {
                let quoted = format!("`{k}`");
                !row.contains(&quoted) && !common.contains(&quoted)
            })
            .collect();
        assert!(
            missing.is_empty(),
            "README row of {command} does not name {missing:?}"
        );
    }
}

/// `ridelab completions SHELL` prints a script naming every command.
#[test]
fn completions_generate_for_each_shell() {
    for shell in ["bash", "zsh", "fish"] {
        let (code, out, err) = ridelab(&["completions", shell]);
        assert_eq!(code, 0, "{shell}: {err}");
        for command in ["eval", "map", "optimize", "simulate", "report"] {
            assert!(out.contains(command), "{shell}: {command} missing");
        }
        assert!(out.contains("ks-range"), "{shell}: options missing");
    }
}

/// Text is the default output of every command; JSON only when asked.
#[test]
fn text_is_the_default_output() {
    let grid = ["--ks-range", "10000:40000:3", "--cs-range", "500:4000:3"];
    for args in [
        vec!["eval", "--model", "quarter"],
        [&["map", "--model", "quarter"][..], &grid].concat(),
        vec![
            "surrogate",
            "--approach",
            "vba-lts",
            "--plan",
            "ae:3",
            "--predict",
            "grid:3",
        ],
        vec!["simulate", "--model", "quarter", "--duration", "1"],
        vec![
            "optimize",
            "--evaluator",
            "quarter",
            "--grid",
            "11",
            "--levels",
            "0",
        ],
        vec!["presets"],
    ] {
        let (code, out, err) = ridelab(&args);
        assert_eq!(code, 0, "{args:?}: {err}");
        assert!(
            serde_json::from_str::<Value>(&out).is_err() && !out.trim_start().starts_with('{'),
            "{args:?} printed JSON by default: {}",
            &out[..out.len().min(200)]
        );
        assert!(
            !out.contains("NaN") && !out.contains("inf "),
            "{args:?}: {out}"
        );
    }
    // The map's text names the units it shows.
    let (_, out, _) = ridelab(&[&["map", "--model", "quarter"][..], &grid].concat());
    for unit in ["kN/m", "kNs/m", "m/s^2", "mm", "feasible:"] {
        assert!(out.contains(unit), "map text lacks {unit}: {out}");
    }
}

/// `simulate --json`: every series named, the step stated, positions by coordinate.
#[test]
fn simulate_json_names_its_series() {
    let v = json(&[
        "simulate",
        "--model",
        "full",
        "--duration",
        "1",
        "--decimate",
        "5",
    ]);
    assert_eq!(
        v["dt"].as_f64(),
        Some(ridelab::time_domain::TimeOptions::default().dt)
    );
    assert!(
        (v["sample_interval"].as_f64().unwrap() - 5.0 * v["dt"].as_f64().unwrap()).abs() < 1e-15
    );
    let n = v["series"]["t"].as_array().unwrap().len();
    for k in ["road", "bacc", "dtl", "sws"] {
        assert_eq!(v["series"][k].as_array().unwrap().len(), n, "{k}");
        assert!(v["rms"][k].as_f64().is_some() || k == "road", "{k}");
    }
    for dof in [
        "body_heave_z",
        "body_pitch_theta",
        "body_roll_phi",
        "wheel_hop_front_right",
    ] {
        assert_eq!(v["positions"][dof].as_array().unwrap().len(), n, "{dof}");
        assert_eq!(
            v["accelerations"][dof].as_array().unwrap().len(),
            n,
            "{dof}"
        );
    }
    assert_eq!(v["units"]["positions.body_pitch_theta"], "rad");
    assert_eq!(v["units"]["accelerations.body_heave_z"], "m/s^2");
    assert_eq!(v["units"]["sws"], "m");
}

/// `--comfort wk` on a measured road (issue #31): every cell of the Wk map is `eval --road
/// FILE`'s `bacc_wk` at that design (the same exact route: 1e-12) and within 3 % of eval's
/// frequency route on the raw PSD weighted by Wk (`spectral_bacc_wk`, independent); DTL
/// and SWS are the unweighted map's, bit for bit; the JSON says `comfort: wk` and the text
/// "BAcc (Wk)". The front
/// on the Wk axis takes the LoFi or the HiFi (its datum is eval's `bacc_wk`); a surrogate
/// evaluator is refused naming `comfort` (it is fitted to the unweighted BAcc).
#[test]
fn wk_comfort_takes_a_measured_road() {
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/..");
    let road = format!("{root}/assets/roads/concrete-slab-5m.csv");
    let rel = |a: f64, b: f64| (a / b - 1.0).abs();
    for model in ["quarter", "full"] {
        let map = |comfort: &str| {
            json(&[
                "map",
                "--model",
                model,
                "--road",
                &road,
                "--comfort",
                comfort,
                "--ks-range",
                "10000:40000:3",
                "--cs-range",
                "500:4000:2",
            ])
        };
        let (wk, plain) = (map("wk"), map("bacc"));
        assert_eq!(wk["comfort"], "wk");
        assert_eq!(wk["dtl"], plain["dtl"]);
        assert_eq!(wk["sws"], plain["sws"]);
        let (ks, cs) = (
            wk["ks_values"].as_array().unwrap(),
            wk["cs_values"].as_array().unwrap(),
        );
        let (mut exact, mut spectral) = (0.0f64, 0.0f64);
        for (j, c) in cs.iter().enumerate() {
            for (i, k) in ks.iter().enumerate() {
                let (k, c) = (k.to_string(), c.to_string());
                let e = json(&[
                    "eval", "--model", model, "--road", &road, "--ks", &k, "--cs", &c,
                ]);
                let cell = wk["bacc"][j * ks.len() + i].as_f64().unwrap();
                exact = exact.max(rel(cell, e["bacc_wk"].as_f64().unwrap()));
                spectral = spectral.max(rel(cell, e["spectral_bacc_wk"].as_f64().unwrap()));
                assert!(cell < plain["bacc"][j * ks.len() + i].as_f64().unwrap());
            }
        }
        let (code, text, _) = ridelab(&[
            "map",
            "--model",
            model,
            "--road",
            &road,
            "--comfort",
            "wk",
            "--ks-range",
            "10000:40000:3",
            "--cs-range",
            "500:4000:2",
        ]);
        assert_eq!(code, 0);
        assert!(
            text.contains("datum Ks 19.960 kN/m, Cs 1.2900 kNs/m: BAcc (Wk) ")
                && text.contains("BAcc (Wk) in m/s^2: least"),
            "the text names the weighted comfort: {text}"
        );
        assert!(exact < 1e-12, "{model}: Wk map vs eval: {exact:e}");
        assert!(
            spectral < 3e-2,
            "{model}: Wk map vs the frequency route: {spectral:e}"
        );
    }
    let o = json(&[
        "optimize",
        "--evaluator",
        "full",
        "--road",
        &road,
        "--comfort",
        "wk",
        "--grid",
        "21",
        "--levels",
        "1",
    ]);
    assert_eq!(o["comfort"], "wk");
    let datum = json(&["eval", "--model", "full", "--road", &road]);
    assert!(
        rel(
            o["datum"]["bacc"].as_f64().unwrap(),
            datum["bacc_wk"].as_f64().unwrap()
        ) < 1e-12
    );
}

/// `surrogate --road FILE --adaptive K` (issue #31): the loop runs on the measured road as
/// on an ISO class: the plan's and the added samples' HiFi values are `eval --road`'s at
/// their designs (the same exact route: 1e-12), the added runs are numbered after the
/// plan's, and the HiFi evaluations are the samples, the validation grid and the datum.
#[test]
fn the_adaptive_loop_takes_a_measured_road() {
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/..");
    let road = format!("{root}/assets/roads/concrete-slab-5m.csv");
    let v = json(&[
        "surrogate",
        "--approach",
        "gp-mul",
        "--plan",
        "ae:5",
        "--adaptive",
        "2",
        "--candidates",
        "11",
        "--predict",
        "grid:4",
        "--road",
        &road,
    ]);
    assert_eq!(v["road"]["file"], road.as_str());
    let samples = v["samples"].as_array().unwrap();
    assert_eq!(samples.len(), 7);
    let added = v["adaptive"]["added"].as_array().unwrap();
    assert_eq!(added.len(), 2);
    for (i, a) in added.iter().enumerate() {
        assert_eq!(a["run"], 6 + i);
        assert_eq!(a["sample"], samples[5 + i]);
    }
    samples_equal_eval(samples, &road);
    // 7 samples, the 4 x 4 validation grid and the datum (the SWS limit's context).
    assert_eq!(v["hifi_evaluations"], 7 + 16 + 1);
}

/// `report --road FILE` (issue #31): every section on the measured road. Section 1's first
/// rows are `eval --road`'s quarter and full car (the same exact routes: 1e-12), the
/// Lyapunov routes agree with them (1e-8), the frequency route on the raw PSD is within
/// the slab road's filter error (4 %) and the profile played back within 3 %; the maps'
/// datums, the chosen surrogate's HiFi samples, the HiFi front's datum and the adaptive
/// loop's added runs are `eval --road`'s full car at those designs (1e-12); the JSON and
/// the documents name the road file, and carry no ISO velocity PSD.
#[test]
fn the_report_takes_a_measured_road() {
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/..");
    let road = format!("{root}/assets/roads/concrete-slab-5m.csv");
    let dir = std::env::temp_dir().join(format!("ridelab-report-road-{}", std::process::id()));
    let out = dir.to_str().unwrap();
    let (code, _, err) = ridelab(&["report", "--road", &road, "--out", out]);
    assert_eq!(code, 0, "{err}");
    let text = |name: &str| std::fs::read_to_string(dir.join(name)).unwrap();
    let r: Value = serde_json::from_str(&text("report.json")).unwrap();
    let s = &r["scenario"];
    assert_eq!(s["road"]["file"], road.as_str());
    assert!(s.get("velocity_psd").is_none());
    let md = text("report.md");
    assert!(
        md.starts_with(&format!(
            "# RideLab study report: Mid-size sedan (datum) on the measured road {road} at 20 m/s"
        )),
        "{}",
        &md[..200]
    );
    let eval = |model: &str, ks: &Value, cs: &Value| {
        let (ks, cs) = (ks.to_string(), cs.to_string());
        json(&[
            "eval", "--model", model, "--road", &road, "--ks", &ks, "--cs", &cs,
        ])
    };
    let rel = |a: &Value, b: &Value, key: &str| {
        (a[key].as_f64().unwrap() / b[key].as_f64().unwrap() - 1.0).abs()
    };
    let keys = ["bacc", "dtl", "sws"];
    let (k0, c0) = (&s["car"]["front"]["spring"], &s["car"]["front"]["damper"]);
    let v = &r["verification"];
    for (rows, model) in [(&v["lofi"], "quarter"), (&v["hifi"], "full")] {
        let rows = rows.as_array().unwrap();
        let e = eval(model, k0, c0);
        for key in keys {
            assert!(rel(&rows[0]["criteria"], &e, key) < 1e-12, "{model} {key}");
        }
        for row in rows {
            let (route, d) = (
                row["route"].as_str().unwrap(),
                row["difference"].as_f64().unwrap(),
            );
            let bound = if route.starts_with("frequency") {
                0.04
            } else if route.starts_with("time domain") {
                0.03
            } else {
                1e-8
            };
            assert!(d < bound, "{model} {route}: {d}");
        }
    }
    let same = |a: &Value, b: &Value, what: &str| {
        for key in keys {
            assert!(
                rel(a, b, key) < 1e-12,
                "{what} {key}: {} vs {}",
                a[key],
                b[key]
            );
        }
    };
    for (map, model) in [
        (&r["maps"]["lofi"], "quarter"),
        (&r["maps"]["hifi"], "full"),
    ] {
        assert_eq!(map["road"]["file"], road.as_str());
        let d = &map["datum"];
        same(
            &d["criteria"],
            &eval(model, &d["ks"], &d["cs"]),
            "map datum",
        );
    }
    let chosen = &r["fidelity"]["chosen"];
    assert_eq!(chosen["road"]["file"], road.as_str());
    assert_eq!(r["fidelity"]["study"]["road"]["file"], road.as_str());
    for sample in chosen["samples"].as_array().unwrap().iter().take(3) {
        same(
            &sample["hifi"],
            &eval("full", &sample["ks"], &sample["cs"]),
            "sample",
        );
    }
    let hifi_front = &r["optimisation"]["hifi"];
    same(
        &hifi_front["datum"],
        &eval("full", k0, c0),
        "HiFi front's datum",
    );
    let run = &r["adaptive"]["run"];
    let added = run["adaptive"]["added"].as_array().unwrap();
    assert!(!added.is_empty());
    for a in added {
        let s = &a["sample"];
        same(
            &s["hifi"],
            &eval("full", &s["ks"], &s["cs"]),
            "adaptive run",
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// `study --road FILE` (issue #31): the fidelity study on the measured road. Its best
/// surrogate at 10 samples, fitted alone by `surrogate --road` on the same plan, has the
/// same validation metrics (the same HiFi samples, LoFi and 20 x 20 grid: 1e-12); it
/// makes as many HiFi runs as the study on an ISO class (every plan and the grid once);
/// the JSON names the road; a car file's load cases are refused.
#[test]
fn the_fidelity_study_takes_a_measured_road() {
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/..");
    let road = format!("{root}/assets/roads/concrete-slab-5m.csv");
    let v = json(&["study", "--road", &road]);
    assert_eq!(v["road"]["file"], road.as_str());
    assert_eq!(v["hifi_evaluations"], json(&["study"])["hifi_evaluations"]);
    let best = v["best_per_budget"]
        .as_array()
        .unwrap()
        .iter()
        .find(|b| b["samples"] == 10)
        .unwrap();
    let (approach, plan) = (
        best["surrogate"].as_str().unwrap(),
        best["plan"].as_str().unwrap(),
    );
    let alone = json(&[
        "surrogate",
        "--road",
        &road,
        "--approach",
        approach,
        "--plan",
        plan,
    ]);
    for c in ["bacc", "dtl", "sws"] {
        for m in ["rmse", "rte_max_percent", "r2"] {
            let (a, b) = (
                best["fitted"]["metrics"][c][m].as_f64().unwrap(),
                alone["metrics"][c][m].as_f64().unwrap(),
            );
            assert!(
                (a / b - 1.0).abs() < 1e-12,
                "{approach} {plan} {c} {m}: {a} vs {b}"
            );
        }
    }
    let laden = format!("{root}/assets/examples/sedan-laden.json");
    for (args, field) in [
        (vec!["study", "--road", &road, "--car", &laden], "road"),
        (
            vec![
                "study",
                "--road",
                &road,
                "--car",
                &laden,
                "--adaptive",
                "gp-mul",
            ],
            "road",
        ),
        (
            vec![
                "study",
                "--road",
                &road,
                "--adaptive",
                "gp-mul",
                "--max-runs",
                "101",
            ],
            "max-runs",
        ),
    ] {
        refused(&args, field);
    }
}

/// `study --road FILE --adaptive SURROGATE` (issue #31): the adaptive study on the measured
/// road. Its initial plan is `surrogate --road`'s Audze-Eglais plan there and every sample's
/// HiFi value is `eval --road`'s full car at its design (the same exact route: 1e-12); one
/// row per total of HiFi runs, each front re-checked on that HiFi within a few per cent of
/// its own front; the JSON and the table name the road file.
#[test]
fn the_adaptive_study_takes_a_measured_road() {
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/..");
    let road = format!("{root}/assets/roads/concrete-slab-5m.csv");
    let args = [
        "study",
        "--road",
        &road,
        "--adaptive",
        "vba-qts",
        "--max-runs",
        "7",
        "--grid",
        "41",
    ];
    let v = json(&[&args[..], &["--json"]].concat());
    assert_eq!(v["road"]["file"], road.as_str());
    let rows = v["rows"].as_array().unwrap();
    assert_eq!(
        rows.iter()
            .map(|r| r["hifi_runs"].as_u64().unwrap())
            .collect::<Vec<_>>(),
        [6, 7]
    );
    for r in rows {
        for side in ["adaptive", "audze_eglais"] {
            let hv = r[side]["hypervolume_ratio"].as_f64().unwrap();
            assert!(
                hv > 0.9 && hv < 1.02,
                "{side} at {}: HV ratio {hv}",
                r["hifi_runs"]
            );
        }
    }
    let samples = v["samples"].as_array().unwrap();
    assert_eq!(samples.len(), 7);
    let plan = json(&[
        "surrogate",
        "--road",
        &road,
        "--approach",
        "vba-qts",
        "--plan",
        "ae:5",
    ]);
    assert_eq!(samples[..5], plan["samples"].as_array().unwrap()[..]);
    samples_equal_eval(samples, &road);
    let (code, table, err) = ridelab(&args);
    assert_eq!(code, 0, "{err}");
    assert!(table.contains(&format!("({road} at 20 m/s)")), "{table}");
}

/// The box and objectives wherever they apply (issue #28): `study` takes a box (its plans,
/// grid and fronts span it) and, with `--adaptive`, objectives; `surrogate --adaptive`
/// takes objectives. On the rough class C profile the default 7 mm SWS limit holds
/// nowhere, so the adaptive study is refused naming `sws_limit`; with `--sws-limit 0.012`
/// it runs, and each row's pick sits on that limit: its predicted SWS (the HiFi's at the
/// pick, `eval --road`, times the row's re-check error) at most 12 mm, the HiFi's within
/// 3 % of it. Objectives where nothing judges designs exit 2 naming them.
#[test]
fn the_box_and_objectives_apply_to_study_and_surrogate() {
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/..");
    let road = format!("{root}/assets/roads/class-c-waviness-2.5.csv");
    let base = [
        "study",
        "--road",
        &road,
        "--adaptive",
        "gp-mul",
        "--max-runs",
        "7",
        "--grid",
        "41",
    ];
    let (code, _, err) = ridelab(&base);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.starts_with("error: sws_limit: no feasible design"),
        "{err}"
    );
    let v = json(
        &[
            &base[..],
            &["--sws-limit", "0.012", "--ks-range", "12000:38000"],
        ]
        .concat(),
    );
    assert_eq!(v["options"]["objectives"]["sws_limit"], 0.012);
    assert_eq!(v["options"]["design_box"]["ks_min"], 12000.0);
    for s in v["samples"].as_array().unwrap() {
        let ks = s["ks"].as_f64().unwrap();
        assert!((12000.0..=38000.0).contains(&ks), "sample at Ks {ks}");
    }
    for r in v["rows"].as_array().unwrap() {
        let pick = &r["adaptive"]["pick"];
        let (ks, cs) = (&pick[0], &pick[1]);
        let e = full_on_road(&road, ks, cs);
        let sws = e["sws"].as_f64().unwrap();
        let error = r["adaptive"]["recheck_percent"][2].as_f64().unwrap();
        let predicted = sws * (1.0 + error / 100.0);
        assert!(
            predicted <= 0.012 * (1.0 + 1e-9),
            "pick ({ks}, {cs}): predicted SWS {predicted} m"
        );
        assert!(
            (sws / 0.012 - 1.0).abs() < 0.03,
            "pick ({ks}, {cs}): HiFi SWS {sws} m"
        );
    }
    // The fidelity study over a box.
    let f = json(&["study", "--ks-range", "15000:30000"]);
    assert_eq!(f["design_box"]["ks_max"], 30000.0);
    for (args, field) in [
        (vec!["study", "--sws-limit", "0.01"], "sws-limit"),
        (vec!["study", "--no-worse", "bacc"], "no-worse"),
        (
            vec!["surrogate", "--approach", "gp-mul", "--dtl-margin", "3"],
            "dtl-margin",
        ),
        (
            vec!["study", "--adaptive", "gp-mul", "--sws-limit", "-1"],
            "sws-limit",
        ),
        (vec!["study", "--ks-range", "30000:20000"], "ks-range"),
    ] {
        refused(&args, field);
    }
}

/// `optimize --road FILE --adaptive K` (issue #31): the loop runs on the measured road, so
/// every added sample's HiFi value is `eval --road`'s full car at its design and the pick's
/// re-check is `eval --road`'s at the pick (the same exact route: 1e-12); the runs are
/// numbered after the plan's, and the JSON names the road file.
#[test]
fn an_adaptive_optimisation_takes_a_measured_road() {
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/..");
    let road = format!("{root}/assets/roads/concrete-slab-5m.csv");
    let v = json(&[
        "optimize",
        "--evaluator",
        "gp-mul",
        "--plan",
        "ae:5",
        "--adaptive",
        "2",
        "--candidates",
        "11",
        "--grid",
        "41",
        "--levels",
        "2",
        "--road",
        &road,
    ]);
    assert_eq!(v["road"]["file"], road.as_str());
    let eval = |ks: &Value, cs: &Value| full_on_road(&road, ks, cs);
    let close = |a: &Value, b: &Value, what: &str| {
        for key in ["bacc", "dtl", "sws"] {
            let (a, b) = (a[key].as_f64().unwrap(), b[key].as_f64().unwrap());
            assert!((a / b - 1.0).abs() < 1e-12, "{what} {key}: {a} vs eval {b}");
        }
    };
    let added = v["adaptive"]["added"].as_array().unwrap();
    assert_eq!(added.len(), 2);
    for (i, a) in added.iter().enumerate() {
        assert_eq!(a["run"], 6 + i);
        let s = &a["sample"];
        close(&s["hifi"], &eval(&s["ks"], &s["cs"]), "added sample");
    }
    let pick = &v["pick"];
    close(
        &v["hifi_recheck"]["rechecked"],
        &eval(&pick["ks"], &pick["cs"]),
        "re-check",
    );
}

/// `map --road FILE`, `optimize --road FILE` and `surrogate --road FILE` (issue #31): every map cell is
/// `eval --road FILE` at that design (the same exact route: 1e-12) and within 3 % of the
/// frequency route on the raw measured PSD (an independent route: the shipped class C
/// profile's routes differ by 4e-4, the slab road's by 2e-2 where its filter's PSD error
/// is 13 %); the optimisation's datum and re-check are eval's HiFi on the same road, its
/// front points eval's LoFi; the surrogate's HiFi samples are eval's HiFi; the JSON
/// names the road file; a surrogate evaluator's pick is re-checked on eval's HiFi; one
/// scenario, so cases (a car file's load cases on the report too), an adaptive loop on a
/// model evaluator, an oversized grid or validation grid and Wk comfort with a surrogate
/// are refused naming the option.
#[test]
fn map_optimize_and_surrogate_take_a_measured_road() {
    let road = "assets/roads/class-c-waviness-2.5.csv";
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/..");
    let laden = format!("{root}/assets/examples/sedan-laden.json");
    let road_path = format!("{root}/{road}");
    // `eval --road` at 25 m/s, with the profile's own tracks or `--tracks`.
    let eval_on = |tracks: Option<&str>, model: &str, ks: f64, cs: f64| {
        let (ks, cs) = (ks.to_string(), cs.to_string());
        let mut args = vec![
            "eval", "--model", model, "--road", &road_path, "--speed", "25", "--ks", &ks, "--cs",
            &cs,
        ];
        if let Some(t) = tracks {
            args.extend(["--tracks", t]);
        }
        json(&args)
    };
    let eval = |model: &str, ks: f64, cs: f64| eval_on(None, model, ks, cs);
    let rel = |a: f64, b: f64| (a / b - 1.0).abs();
    let m = json(&[
        "map",
        "--model",
        "full",
        "--road",
        &road_path,
        "--speed",
        "25",
        "--ks-range",
        "10000:40000:4",
        "--cs-range",
        "500:4000:3",
    ]);
    assert_eq!(m["road"]["file"], road_path.as_str());
    assert_eq!(m["road"]["speed"], 25.0);
    let (ks, cs) = (
        m["ks_values"].as_array().unwrap(),
        m["cs_values"].as_array().unwrap(),
    );
    let (mut exact, mut spectral) = (0.0f64, 0.0f64);
    for (j, c) in cs.iter().enumerate() {
        for (i, k) in ks.iter().enumerate() {
            let e = eval("full", k.as_f64().unwrap(), c.as_f64().unwrap());
            for key in ["bacc", "dtl", "sws"] {
                let cell = m[key][j * ks.len() + i].as_f64().unwrap();
                exact = exact.max(rel(cell, e[key].as_f64().unwrap()));
                spectral = spectral.max(rel(cell, e["spectral"][key].as_f64().unwrap()));
            }
        }
    }
    assert!(exact < 1e-12, "map vs eval: {exact:e}");
    assert!(
        spectral < 3e-2,
        "map vs the frequency route on the raw PSD: {spectral:e}"
    );
    let (code, text, _) = ridelab(&[
        "map",
        "--model",
        "quarter",
        "--road",
        &road_path,
        "--ks-range",
        "10000:40000:3",
        "--cs-range",
        "500:4000:3",
    ]);
    assert_eq!(code, 0);
    assert!(
        text.contains("on the measured road") && text.contains("class-c-waviness-2.5.csv"),
        "{text}"
    );

    // Class C at 25 m/s breaks the default 7 mm SWS limit everywhere: 20 mm.
    let o = json(&[
        "optimize",
        "--evaluator",
        "quarter",
        "--road",
        &road_path,
        "--speed",
        "25",
        "--sws-limit",
        "0.02",
        "--grid",
        "41",
        "--levels",
        "2",
    ]);
    assert_eq!(o["road"]["file"], road_path.as_str());
    let datum = eval("full", 19960.0, 1290.0);
    let pick = &o["pick"];
    let at_pick = eval(
        "full",
        pick["ks"].as_f64().unwrap(),
        pick["cs"].as_f64().unwrap(),
    );
    let lofi_datum = eval("quarter", 19960.0, 1290.0);
    for key in ["bacc", "dtl", "sws"] {
        assert!(
            rel(
                o["datum"][key].as_f64().unwrap(),
                datum[key].as_f64().unwrap()
            ) < 1e-12,
            "datum {key}"
        );
        assert!(
            rel(
                o["hifi_recheck"]["rechecked"][key].as_f64().unwrap(),
                at_pick[key].as_f64().unwrap()
            ) < 1e-12,
            "re-check {key}"
        );
        assert!(
            rel(
                o["same_model"]["datum"][key].as_f64().unwrap(),
                lofi_datum[key].as_f64().unwrap()
            ) < 1e-12,
            "LoFi datum {key}"
        );
    }
    let front = o["front"].as_array().unwrap();
    assert!(front.len() > 10, "{} front points", front.len());
    for p in front.iter().step_by(front.len() / 5) {
        let e = eval(
            "quarter",
            p["ks"].as_f64().unwrap(),
            p["cs"].as_f64().unwrap(),
        );
        for key in ["bacc", "dtl", "sws"] {
            assert!(
                rel(p[key].as_f64().unwrap(), e[key].as_f64().unwrap()) < 1e-12,
                "front {key}"
            );
        }
    }
    // `surrogate --road`: its HiFi samples and validation grid are eval's HiFi on the
    // road, the JSON and the text name the road file. With both tracks seeing the
    // profile the tuned LoFi follows the HiFi within 5 % (seen: 1.2 % on 20 x 20; with
    // the measured tracks' roll 13 %, as with independent tracks on an ISO class: 22 %).
    let r = json(&[
        "surrogate",
        "--approach",
        "vba-qts",
        "--plan",
        "ae:10",
        "--road",
        &road_path,
        "--speed",
        "25",
        "--tracks",
        "correlated",
        "--predict",
        "grid:3",
    ]);
    assert_eq!(r["road"]["file"], road_path.as_str());
    assert_eq!(r["hifi_evaluations"], 10 + 9);
    let p = &r["predictions"];
    for i in [0, 4, 8] {
        let e = eval_on(
            Some("correlated"),
            "full",
            p["ks"][i].as_f64().unwrap(),
            p["cs"][i].as_f64().unwrap(),
        );
        for key in ["bacc", "dtl", "sws"] {
            assert!(
                rel(
                    p["hifi"][i][key].as_f64().unwrap(),
                    e[key].as_f64().unwrap()
                ) < 1e-12,
                "surrogate's HiFi {key} at point {i}"
            );
        }
    }
    for key in ["bacc", "dtl", "sws"] {
        let rte = r["metrics"][key]["rte_max_percent"].as_f64().unwrap();
        assert!(rte.is_finite() && rte < 5.0, "{key}: {rte} %");
    }
    let (code, text, _) = ridelab(&["surrogate", "--approach", "pba-smts", "--road", &road_path]);
    assert_eq!(code, 0);
    assert!(
        text.contains("on the measured road") && text.contains("class-c-waviness-2.5.csv"),
        "{text}"
    );
    // `optimize --evaluator SURROGATE --road`: the surrogate fitted on the road, its
    // pick re-checked on eval's HiFi there, the prediction within 5 % (seen: 2.0 %).
    let o = json(&[
        "optimize",
        "--evaluator",
        "vba-qts",
        "--road",
        &road_path,
        "--speed",
        "25",
        "--tracks",
        "correlated",
        "--sws-limit",
        "0.02",
        "--grid",
        "41",
        "--levels",
        "2",
    ]);
    assert_eq!(o["evaluator"], "vba-qts");
    let pick = &o["pick"];
    let at_pick = eval_on(
        Some("correlated"),
        "full",
        pick["ks"].as_f64().unwrap(),
        pick["cs"].as_f64().unwrap(),
    );
    for key in ["bacc", "dtl", "sws"] {
        let rechecked = o["hifi_recheck"]["rechecked"][key].as_f64().unwrap();
        assert!(
            rel(rechecked, at_pick[key].as_f64().unwrap()) < 1e-12,
            "surrogate re-check {key}"
        );
        let predicted = pick["criteria"][key].as_f64().unwrap();
        assert!(
            rel(predicted, rechecked) < 0.05,
            "surrogate prediction {key}"
        );
    }
    // `simulate --road` plays the profile itself back: its RMS over the 200 s run
    // (a long time-domain record, from rest) within 6 % of the exact route (seen:
    // 2.5 % on the LoFi, 4 % on the HiFi; the record is one 4 km realisation).
    for model in ["quarter", "full"] {
        let sim = json(&[
            "simulate", "--model", model, "--road", &road_path, "--speed", "25",
        ]);
        let e = eval(model, 19960.0, 1290.0);
        assert_eq!(sim["road_file"], road_path.as_str());
        assert!(sim["duration"].as_f64().unwrap() > 150.0);
        for key in ["bacc", "dtl", "sws"] {
            let d = rel(sim["rms"][key].as_f64().unwrap(), e[key].as_f64().unwrap());
            assert!(d < 0.06, "{model} {key}: playback vs exact route {d:e}");
        }
    }
    // Refused, naming the option, exit 2.
    for (args, field) in [
        (
            vec![
                "map",
                "--model",
                "full",
                "--road",
                road,
                "--cases",
                "assets/examples/cases-b-10-20-30.json",
            ],
            "road",
        ),
        (
            vec![
                "optimize",
                "--evaluator",
                "full",
                "--road",
                road,
                "--adaptive",
                "2",
            ],
            "adaptive",
        ),
        (
            vec![
                "optimize",
                "--evaluator",
                "full",
                "--road",
                road,
                "--grid",
                "400",
            ],
            "grid",
        ),
        (
            vec![
                "map",
                "--model",
                "full",
                "--road",
                road,
                "--ks-range",
                "10000:40000:400",
                "--cs-range",
                "500:4000:400",
            ],
            "ks-range",
        ),
        (
            vec![
                "optimize",
                "--evaluator",
                "vba-qts",
                "--road",
                road,
                "--comfort",
                "wk",
            ],
            "comfort",
        ),
        (vec!["report", "--road", road, "--car", &laden], "road"),
        (
            vec![
                "surrogate",
                "--approach",
                "vba-qts",
                "--road",
                road,
                "--predict",
                "grid:400",
            ],
            "plan",
        ),
        (
            vec![
                "simulate",
                "--model",
                "full",
                "--road",
                road,
                "--tracks",
                "independent",
            ],
            "tracks",
        ),
    ] {
        let mut full = args.clone();
        let p = format!("{root}/{road}");
        for a in full.iter_mut() {
            if *a == road {
                *a = &p;
            }
        }
        refused(&full, field);
    }
}
