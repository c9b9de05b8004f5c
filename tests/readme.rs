//! The README cannot drift (issue #32): every `ridelab` command line in its code blocks
//! runs, as written, from a directory that holds the repository's `assets/` (so the
//! README's example files are the ones shipped), and exits as the README says: 0, or 2
//! where its comment says "exit 2". Each command is bounded by [`LIMIT`].

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// The longest a README command may run in the debug build.
const LIMIT: Duration = Duration::from_secs(180);

/// `(line number, command words after "ridelab", expected exit code)` of every command
/// line in the README's code blocks (indented or fenced).
fn readme_commands(text: &str) -> Vec<(usize, Vec<String>, i32)> {
    let mut fenced = false;
    let mut out = Vec::new();
    for (i, line) in text.lines().enumerate() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
            continue;
        }
        let in_block = fenced || line.starts_with("    ");
        let Some(rest) = line.trim().strip_prefix("ridelab ") else {
            continue;
        };
        if !in_block {
            continue;
        }
        let (command, comment) = rest.split_once('#').unwrap_or((rest, ""));
        assert!(
            !command.contains(['"', '\'', '|', '>', '<']),
            "README line {}: quote or redirection in '{line}'",
            i + 1
        );
        let expected = if comment.contains("exit 2") { 2 } else { 0 };
        out.push((
            i + 1,
            command.split_whitespace().map(str::to_string).collect(),
            expected,
        ));
    }
    out
}

fn scratch() -> PathBuf {
    let dir = std::env::temp_dir().join(format!("ridelab-readme-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let assets = Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets");
    let link = dir.join("assets");
    if !link.exists() {
        #[cfg(unix)]
        std::os::unix::fs::symlink(assets.canonicalize().unwrap(), &link).unwrap();
    }
    dir
}

#[test]
fn every_readme_command_line_runs_as_the_readme_says() {
    let readme = Path::new(env!("CARGO_MANIFEST_DIR")).join("../README.md");
    let text = std::fs::read_to_string(readme).unwrap();
    let commands = readme_commands(&text);
    assert!(commands.len() >= 20, "{} command lines", commands.len());
    let dir = scratch();
    let mut failures = Vec::new();
    for (line, args, expected) in &commands {
        let start = Instant::now();
        let mut child = Command::new(env!("CARGO_BIN_EXE_ridelab"))
            .args(args)
            .current_dir(&dir)
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        let status = loop {
            if let Some(s) = child.try_wait().unwrap() {
                break Some(s);
            }
            if start.elapsed() > LIMIT {
                let _ = child.kill();
                break None;
            }
            std::thread::sleep(Duration::from_millis(20));
        };
        let mut err = String::new();
        use std::io::Read;
        let _ = child.stderr.take().unwrap().read_to_string(&mut err);
        let code = status.and_then(|s| s.code());
        eprintln!(
            "README line {line}: ridelab {} -> {code:?} in {:.1} s",
            args.join(" "),
            start.elapsed().as_secs_f64()
        );
        if code != Some(*expected) {
            failures.push(format!(
                "line {line}: ridelab {}: exit {code:?}, README says {expected}: {}",
                args.join(" "),
                err.lines().last().unwrap_or_default()
            ));
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn commands_are_read_from_code_blocks_only() {
    let text = "ridelab eval\n\n    ridelab eval --model full\n    ridelab map --model quarter --grid 1   # exit 2: bad\n```\nridelab presets\n```\n";
    let c = readme_commands(text);
    assert_eq!(c.len(), 3);
    assert_eq!(
        c[0],
        (3, vec!["eval".into(), "--model".into(), "full".into()], 0)
    );
    assert_eq!(c[1].2, 2);
    assert_eq!(c[2].1, vec!["presets".to_string()]);
}
