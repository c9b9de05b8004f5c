//! The CLI under hostile input (issue #27): every numeric option and car or cases key at
//! 0, negative, tiny, huge, NaN, infinite, text and empty, the issue's own cases and
//! combinations. Each ends in a finite result (exit 0, no NaN or infinity in the output)
//! or in one line on stderr naming the right option or field (exit 2), within a time
//! bound, and never in a panic. The README quotes this suite's counts.

use std::path::PathBuf;
use std::process::Command;
use std::time::{Duration, Instant};

/// The longest any one case may take (a debug build; the slowest passing case here is a
/// small optimisation).
const TIME_BOUND: Duration = Duration::from_secs(30);

struct Run {
    code: i32,
    out: String,
    err: String,
    took: Duration,
}

fn ridelab(args: &[String]) -> Run {
    let start = Instant::now();
    let out = Command::new(env!("CARGO_BIN_EXE_ridelab"))
        .args(args)
        .output()
        .expect("runs");
    Run {
        code: out.status.code().unwrap_or(-1),
        out: String::from_utf8_lossy(&out.stdout).into_owned(),
        err: String::from_utf8_lossy(&out.stderr).into_owned(),
        took: start.elapsed(),
    }
}

/// What a case must end in.
#[derive(Clone, Debug)]
enum Expect {
    /// Exit 0, a finite result.
    Ok,
    /// Exit 2, one line `error: <one of these>: ...`.
    Refused(Vec<String>),
}

fn refused(fields: &[&str]) -> Expect {
    Expect::Refused(fields.iter().map(|s| s.to_string()).collect())
}

struct Case {
    args: Vec<String>,
    expect: Expect,
    /// Text the message must not contain (a wrong cause).
    never: Vec<&'static str>,
    /// Text the message must contain.
    says: Vec<&'static str>,
}

fn case(args: &[&str], expect: Expect) -> Case {
    Case {
        args: args.iter().map(|s| s.to_string()).collect(),
        expect,
        never: Vec::new(),
        says: Vec::new(),
    }
}

/// A scratch directory for this suite's files.
fn scratch() -> PathBuf {
    let dir = std::env::temp_dir().join(format!("ridelab-hostile-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The datum car file with `key` (a dotted path) set to the JSON text `value`.
fn car_file(dir: &std::path::Path, name: &str, key: &str, value: &str) -> String {
    let mut v: serde_json::Value = serde_json::from_str(ridelab::car::PRESETS[0].1).unwrap();
    let parts: Vec<&str> = key.split('.').collect();
    let mut at = &mut v;
    for p in &parts[..parts.len() - 1] {
        at = &mut at[*p];
    }
    // Written as text so that values JSON cannot hold (1e999) reach the parser as such.
    at[parts[parts.len() - 1]] = serde_json::Value::String(format!("@@{name}@@"));
    let text = serde_json::to_string_pretty(&v)
        .unwrap()
        .replace(&format!("\"@@{name}@@\""), value);
    let path = dir.join(format!("{name}.json"));
    std::fs::write(&path, text).unwrap();
    path.to_string_lossy().into_owned()
}

fn write(dir: &std::path::Path, name: &str, text: &str) -> String {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path.to_string_lossy().into_owned()
}

/// Every case of the suite.
fn cases() -> Vec<Case> {
    let dir = scratch();
    let mut cs = Vec::new();
    let bad_numbers = ["0", "-1", "1e-300", "1e300", "NaN", "inf", "abc", ""];
    // Physical quantities: every bad value refused naming the option.
    let physical: [(&[&str], &str); 12] = [
        (&["eval", "--model", "full"], "ks"),
        (&["eval", "--model", "quarter"], "cs"),
        (&["eval", "--model", "full"], "speed"),
        (&["map", "--model", "quarter"], "sws-limit"),
        (
            &["optimize", "--evaluator", "quarter", "--grid", "21"],
            "dtl-margin",
        ),
        (&["simulate", "--model", "quarter"], "duration"),
        (&["simulate", "--model", "quarter"], "dt"),
        (
            &["simulate", "--model", "quarter", "--rebound", "2000"],
            "bump",
        ),
        (
            &["surrogate", "--approach", "rba-mul-poly1", "--plan", "ae:5"],
            "speed",
        ),
        (
            &[
                "map",
                "--model",
                "full",
                "--ks-range",
                "10000:40000:3",
                "--cs-range",
                "500:4000:3",
            ],
            "ks",
        ),
        (
            &[
                "optimize",
                "--evaluator",
                "rba-mul-poly1",
                "--plan",
                "ae:5",
                "--adaptive",
                "1",
                "--grid",
                "21",
            ],
            "min-distance",
        ),
        (&["map", "--model", "quarter"], "dtl-margin"),
    ];
    for (base, option) in physical {
        for v in bad_numbers {
            let mut args: Vec<&str> = base.to_vec();
            args.extend([format!("--{option}").leak() as &str, v]);
            // --min-distance 1e-300 is a distance > 0 that a grid simply never meets:
            // allowed (the loop places runs anyway).
            let expect = if option == "min-distance" && v == "1e-300" {
                Expect::Ok
            } else {
                refused(&[option])
            };
            cs.push(case(&args, expect));
        }
    }
    // Counts: zero, negative, huge and text refused.
    let counts: [(&[&str], &str, &[&str]); 10] = [
        (
            &["optimize", "--evaluator", "quarter"],
            "grid",
            &["0", "-1", "1e300", "abc", "99999999999999999999"],
        ),
        (
            &["optimize", "--evaluator", "quarter"],
            "levels",
            &["-1", "11", "abc"],
        ),
        (
            &["optimize", "--evaluator", "quarter", "--method", "nsga2"],
            "population",
            &["0", "3", "-1", "abc"],
        ),
        (
            &["optimize", "--evaluator", "quarter", "--method", "nsga2"],
            "generations",
            &["0", "-1", "abc"],
        ),
        (&["doe"], "points", &["0", "1", "1001", "-1", "abc"]),
        (
            &["simulate", "--model", "full"],
            "decimate",
            &["0", "-1", "abc"],
        ),
        (
            &["study", "--adaptive", "rba-mul-poly1"],
            "initial",
            &["0", "1", "abc"],
        ),
        (
            &["study", "--adaptive", "rba-mul-poly1"],
            "max-runs",
            &["0", "101", "abc"],
        ),
        (
            &[
                "optimize",
                "--evaluator",
                "rba-mul-poly1",
                "--plan",
                "ae:5",
                "--adaptive",
                "1",
            ],
            "candidates",
            &["0", "1", "202", "abc"],
        ),
        (&["map", "--model", "quarter"], "case", &["1", "-1", "abc"]),
    ];
    for (base, option, values) in counts {
        for v in values {
            let mut args: Vec<&str> = base.to_vec();
            args.extend([format!("--{option}").leak() as &str, v]);
            cs.push(case(&args, refused(&[option])));
        }
    }
    // Ranges of the design box, the maps' axes and the travel budget.
    for (base, option, values) in [
        (
            &["map", "--model", "quarter"][..],
            "ks-range",
            &[
                "1:1e9:5",
                "0:40000:5",
                "40000:10000:5",
                "10000:40000:1",
                "a:b:c",
                "10000:40000:1002",
            ][..],
        ),
        (
            &["map", "--model", "quarter"][..],
            "cs-range",
            &["1:4000:5", "500:1e9:5", "NaN:4000:5", ""][..],
        ),
        (
            &["report", "--out", "/nonexistent/x"][..],
            "ks-range",
            &["1e3:1e12", "10000", "-1:5"][..],
        ),
        (
            &["map", "--model", "quarter"][..],
            "travel",
            &["0.02", "0:3", "0.025:0", "1e300:3", "x:y"][..],
        ),
        (
            &["map", "--model", "quarter"][..],
            "bounce-band",
            &["-1:1.5", "1.5:0.8", "0.8:100", "x:y", "1"][..],
        ),
        (
            &["optimize", "--evaluator", "quarter", "--grid", "21"][..],
            "damping-band",
            &["-1:0.5", "0.5:0.2", "0.2:50"][..],
        ),
    ] {
        for v in values {
            let mut args: Vec<&str> = base.to_vec();
            args.extend([format!("--{option}").leak() as &str, v]);
            cs.push(case(&args, refused(&[option])));
        }
    }
    // Menus and names.
    for (args, option) in [
        (&["eval", "--model", "half"][..], "model"),
        (&["eval", "--model", "full", "--class", "Z"][..], "class"),
        (
            &["eval", "--model", "full", "--tracks", "both"][..],
            "tracks",
        ),
        (&["eval", "--model", "full", "--car", "truck"][..], "car"),
        (&["optimize", "--pick", "asf:2"][..], "pick"),
        (&["optimize", "--evaluator", "magic"][..], "evaluator"),
        (
            &["optimize", "--evaluator", "rba-mul-poly1", "--plan", "ae:0"][..],
            "plan",
        ),
        (
            &[
                "surrogate",
                "--approach",
                "rba-mul-rbf-mq",
                "--plan",
                "grid:1",
            ][..],
            "plan",
        ),
        (
            &[
                "surrogate",
                "--approach",
                "rba-mul-rbf-mq",
                "--predict",
                "grid:101",
            ][..],
            "predict",
        ),
        (&["frobnicate"][..], "command"),
        (
            &["map", "--model", "quarter", "--no-worse", "comfort"][..],
            "no-worse",
        ),
        (&["completions", "tcsh"][..], "shell"),
    ] {
        cs.push(case(args, refused(&[option])));
    }
    // Car files: each key at hostile values names `front.key` / `key`.
    for (key, values) in [
        (
            "sprung_mass",
            &["0", "-5", "1e9", "1e-300", "1e999", "\"heavy\"", "null"][..],
        ),
        ("pitch_inertia", &["0", "1e9", "1"][..]),
        ("front.tire_stiffness", &["1e300", "0", "-1"][..]),
        ("front.unsprung_mass", &["1e-300", "1e9"][..]),
        ("rear.damper", &["0", "1e9", "5"][..]),
        ("track_rear", &["0.1", "100"][..]),
        ("a", &["0", "50"][..]),
    ] {
        for (k, v) in values.iter().enumerate() {
            let name = format!("car-{}-{k}", key.replace('.', "-"));
            let path = car_file(&dir, &name, key, v);
            for command in [
                &["eval", "--model", "full"][..],
                &[
                    "map",
                    "--model",
                    "quarter",
                    "--ks-range",
                    "10000:40000:3",
                    "--cs-range",
                    "500:4000:3",
                ][..],
            ] {
                let mut args: Vec<&str> = command.to_vec();
                args.extend(["--car", path.as_str()]);
                cs.push(case(&args, refused(&[key])));
            }
        }
    }
    // The issue's car-file case on every command that reads a car.
    let stiff = car_file(&dir, "tire-1e300", "front.tire_stiffness", "1e300");
    let out = dir.join("report-out").to_string_lossy().into_owned();
    for command in [
        &["eval", "--model", "quarter"][..],
        &["map", "--model", "full"][..],
        &["optimize", "--evaluator", "quarter"][..],
        &["simulate", "--model", "full"][..],
        &["surrogate", "--approach", "vba-qts"][..],
        &["study", "--markdown"][..],
        &["report", "--out", out.as_str()][..],
    ] {
        let mut args: Vec<&str> = command.to_vec();
        args.extend(["--car", stiff.as_str()]);
        cs.push(case(&args, refused(&["front.tire_stiffness"])));
    }
    // Files that are not car files.
    let empty = write(&dir, "empty.json", "");
    let array = write(&dir, "array.json", "[1, 2]");
    let number = write(&dir, "number.json", "42");
    let mut c = case(
        &["eval", "--model", "full", "--car", empty.as_str()],
        refused(&["car"]),
    );
    c.says = vec!["is empty"];
    c.never = vec!["EOF"];
    cs.push(c);
    for f in [&array, &number] {
        let mut c = case(
            &["eval", "--model", "full", "--car", f.as_str()],
            refused(&["car"]),
        );
        c.says = vec!["one JSON object"];
        c.never = vec!["invalid type", "[0]"];
        cs.push(c);
    }
    let misspelt = car_file(&dir, "misspelt", "sprung_mas", "1460");
    let mut c = case(
        &["eval", "--model", "full", "--car", misspelt.as_str()],
        refused(&["sprung_mas"]),
    );
    c.says = vec!["`load_cases`"];
    cs.push(c);
    // Load cases and cases files.
    let far = car_file(
        &dir,
        "load-far",
        "load_cases",
        r#"[{"name": "far", "mass": 100, "x": 1e308}]"#,
    );
    let mut c = case(
        &["eval", "--model", "full", "--car", far.as_str()],
        refused(&["load_cases[0].x"]),
    );
    c.never = vec!["inf"];
    cs.push(c);
    for (name, text, field) in [
        ("cases-empty", "", "cases"),
        ("cases-array", "[]", "cases"),
        (
            "cases-speed",
            r#"{"operating": [{"class": "B", "speed": 1e-320}]}"#,
            "operating[0].speed",
        ),
        (
            "cases-weight",
            r#"{"operating": [{"class": "B", "speed": 20, "weight": -1}]}"#,
            "operating[0].weight",
        ),
        (
            "cases-mass",
            r#"{"load_cases": [{"name": "x", "mass": 1e300}]}"#,
            "load_cases[0].mass",
        ),
        (
            "cases-z",
            r#"{"load_cases": [{"name": "x", "mass": 100, "z": "high"}]}"#,
            "load_cases[0].z",
        ),
    ] {
        let f = write(&dir, &format!("{name}.json"), text);
        cs.push(case(
            &["map", "--model", "quarter", "--cases", f.as_str()],
            refused(&[field]),
        ));
    }
    // The issue's cases: nonsense refused with the real cause.
    let mut c = case(
        &[
            "map",
            "--model",
            "quarter",
            "--relative",
            "--speed",
            "1e-320",
        ],
        refused(&["speed"]),
    );
    c.never = vec!["NaN", "frequency integral"];
    cs.push(c);
    for (args, field, never) in [
        (
            &["eval", "--model", "quarter", "--ks", "1e12"][..],
            "ks",
            "road warp",
        ),
        (
            &["eval", "--model", "full", "--ks", "1e308"][..],
            "ks",
            "road warp",
        ),
        (
            &["eval", "--model", "full", "--cs", "1e9"][..],
            "cs",
            "stable",
        ),
        (
            &["simulate", "--model", "full", "--speed", "1e-320"][..],
            "speed",
            "diverged",
        ),
        (
            &["surrogate", "--approach", "vba-qts", "--speed", "1e-320"][..],
            "speed",
            "samples",
        ),
        (
            &["optimize", "--evaluator", "full", "--speed", "1e-320"][..],
            "speed",
            "datum",
        ),
    ] {
        let mut c = case(args, refused(&[field]));
        c.never = vec![never];
        cs.push(c);
    }
    // A damper law too steep for the time step: the step is named, with one that works.
    let mut c = case(
        &[
            "simulate",
            "--model",
            "full",
            "--bump",
            "100000",
            "--rebound",
            "100000",
            "--dt",
            "0.01",
        ],
        refused(&["dt"]),
    );
    c.says = vec!["give a step of 5e-4 s or less"];
    c.never = vec!["diverged"];
    cs.push(c);
    for (args, field) in [
        (
            &[
                "simulate",
                "--model",
                "quarter",
                "--bump",
                "500",
                "--rebound",
                "3000",
                "--knee",
                "1e-300",
                "--bump-high",
                "100",
                "--rebound-high",
                "100",
            ][..],
            "knee",
        ),
        (
            &[
                "simulate",
                "--model",
                "quarter",
                "--bump",
                "1e300",
                "--rebound",
                "3000",
            ][..],
            "bump",
        ),
        (
            &[
                "simulate",
                "--model",
                "quarter",
                "--bump",
                "500",
                "--rebound",
                "NaN",
            ][..],
            "rebound",
        ),
    ] {
        cs.push(case(args, refused(&[field])));
    }
    let mut c = case(
        &["map", "--model", "quarter", "--travel", "0.02"],
        refused(&["travel"]),
    );
    c.says = vec!["0.025:3"];
    c.never = vec!["10000:40000"];
    cs.push(c);
    // Work without a bound, and conflicting outputs.
    for (args, fields) in [
        (
            &[
                "optimize",
                "--evaluator",
                "quarter",
                "--grid",
                "1001",
                "--levels",
                "10",
            ][..],
            &["levels", "grid"][..],
        ),
        (
            &[
                "optimize",
                "--evaluator",
                "full",
                "--grid",
                "2001",
                "--levels",
                "0",
            ][..],
            &["grid"][..],
        ),
        (
            &[
                "optimize",
                "--evaluator",
                "quarter",
                "--method",
                "nsga2",
                "--population",
                "10000",
                "--generations",
                "10000",
            ][..],
            &["generations"][..],
        ),
        (
            &["study", "--adaptive", "gp-mul", "--grid", "2001"][..],
            &["grid"][..],
        ),
        (
            &["study", "--adaptive", "gp-mul", "--grid", "1001"][..],
            &["grid"][..],
        ),
        (
            &["map", "--model", "quarter", "--json", "--csv"][..],
            &["json", "csv"][..],
        ),
        (
            &["simulate", "--model", "quarter", "--json", "--csv"][..],
            &["json", "csv"][..],
        ),
        (
            &["study", "--json", "--markdown"][..],
            &["json", "markdown"][..],
        ),
        (
            &["eval", "--model", "full", "--speed", "3", "--speed", "4"][..],
            &["speed"][..],
        ),
    ] {
        cs.push(case(args, refused(fields)));
    }
    // Inside the domain, at its ends: finite results.
    for args in [
        &[
            "eval", "--model", "full", "--ks", "1800000", "--cs", "100000", "--json",
        ][..],
        &[
            "eval", "--model", "quarter", "--ks", "1000", "--cs", "20", "--json",
        ][..],
        &[
            "eval", "--model", "full", "--speed", "1", "--class", "H", "--json",
        ][..],
        &[
            "eval",
            "--model",
            "full",
            "--speed",
            "100",
            "--tracks",
            "independent",
            "--json",
        ][..],
        &[
            "map",
            "--model",
            "full",
            "--ks-range",
            "5000:1000000:4",
            "--cs-range",
            "500:15000:4",
            "--json",
        ][..],
        &[
            "map",
            "--model",
            "quarter",
            "--relative",
            "--speed",
            "1",
            "--csv",
        ][..],
        &[
            "optimize",
            "--evaluator",
            "quarter",
            "--grid",
            "21",
            "--levels",
            "0",
            "--sws-limit",
            "1",
        ][..],
        &["simulate", "--model", "quarter", "--duration", "1", "--csv"][..],
        &["doe", "--points", "2", "--json"][..],
    ] {
        cs.push(case(args, Expect::Ok));
    }
    cs
}

/// No NaN or infinity among the output's words (JSON, CSV or text). A JSON `null` is an
/// absent optional value: the CLI checks every number is finite before it writes JSON.
fn finite_text(out: &str) -> bool {
    out.split(|c: char| !(c.is_alphanumeric() || c == '.' || c == '-' || c == '+'))
        .all(|w| {
            !matches!(
                w.trim_start_matches(['-', '+']),
                "NaN" | "nan" | "inf" | "Infinity"
            )
        })
}

/// Whether run `r` ends as case `c` expects; why not.
fn judge(c: &Case, r: &Run) -> Result<(), String> {
    let check = |ok: bool, why: String| if ok { Ok(()) } else { Err(why) };
    check(!r.err.contains("panicked"), format!("panicked: {}", r.err))?;
    check(r.took < TIME_BOUND, format!("took {:?}", r.took))?;
    match &c.expect {
        Expect::Ok => {
            check(r.code == 0, format!("exit {}: {}", r.code, r.err))?;
            check(
                finite_text(&r.out),
                "output holds a NaN, an infinity or a null".into(),
            )
        }
        Expect::Refused(fields) => {
            let head: String = r.out.chars().take(200).collect();
            check(r.code == 2, format!("exit {}: {}{head}", r.code, r.err))?;
            check(r.out.is_empty(), format!("wrote {head}"))?;
            check(
                r.err.lines().count() == 1,
                format!("not one line: {}", r.err),
            )?;
            // Options are written with '-', core fields with '_': either names it.
            let err = r.err.replace('_', "-");
            let named = fields.iter().any(|f| {
                let f = f.replace('_', "-");
                err.starts_with(&format!("error: {f}: "))
                    || err.starts_with(&format!("error: {f} "))
            });
            check(named, format!("should name {fields:?}: {}", r.err))?;
            for s in &c.says {
                check(r.err.contains(s), format!("should say {s}: {}", r.err))?;
            }
            for s in &c.never {
                check(!r.err.contains(s), format!("blames {s}: {}", r.err))?;
            }
            check(
                !r.err.contains("inf m") && !r.err.contains("NaN m"),
                format!("prints a non-finite length: {}", r.err),
            )
        }
    }
}

#[test]
fn every_hostile_input_ends_in_a_finite_result_or_a_message_naming_its_field() {
    let cases = cases();
    assert!(cases.len() >= 100, "only {} cases", cases.len());
    let (mut refused_n, mut ok_n, mut slowest) = (0, 0, (Duration::ZERO, String::new()));
    let mut failures = Vec::new();
    for c in &cases {
        let r = ridelab(&c.args);
        let what = format!("{:?}", c.args);
        if let Err(why) = judge(c, &r) {
            failures.push(format!("{what}: {why}"));
            continue;
        }
        if r.took > slowest.0 {
            slowest = (r.took, what.clone());
        }
        match c.expect {
            Expect::Ok => ok_n += 1,
            Expect::Refused(_) => refused_n += 1,
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {} cases failed:\n{}",
        failures.len(),
        cases.len(),
        failures.join("\n")
    );
    // The README quotes these counts.
    let readme = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../README.md"))
        .expect("README.md");
    let quoted = format!(
        "`tests/hostile.rs` runs the CLI on {} hostile inputs",
        cases.len()
    );
    assert!(readme.contains(&quoted), "README should say: {quoted}");
    let outcome = format!("{refused_n} refused, {ok_n} finite results");
    assert!(readme.contains(&outcome), "README should say: {outcome}");
    eprintln!(
        "hostile CLI suite: {} cases, {refused_n} refused naming the field, {ok_n} finite results; slowest {:?} ({})",
        cases.len(),
        slowest.0,
        slowest.1
    );
}
