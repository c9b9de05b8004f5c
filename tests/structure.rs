//! The crate's module graph has no cycle (issue #28): the algorithms (`maps`, `optimize`,
//! `surrogate`, `doe`, ...) sit below the study layer (`study`), which sits below the
//! explorer, the report and the web shell.
//!
//! Read from the source, not the compiler: a module `a` depends on `b` when a line of
//! `a`'s code (comments and `#[cfg(test)]` code left out) names `crate::b`. Two checks:
//! between the top-level modules of `crate/src`, and between the sibling files of each
//! directory module where one names another by path (`super::file::` or
//! `crate::module::file::`; a name re-exported by the parent is not followed).

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

/// The source of `path` without comment lines and without everything from the first
/// `#[cfg(test)]` on (the crate keeps its unit tests at the end of a file), or nothing for
/// a file of tests.
fn code_of(path: &Path) -> String {
    let name = path.file_name().unwrap().to_string_lossy();
    if name.starts_with("tests") {
        return String::new();
    }
    let src = fs::read_to_string(path).unwrap();
    let src = match src.find("#[cfg(test)]") {
        Some(i) => &src[..i],
        None => &src[..],
    };
    src.lines()
        .filter(|l| !l.trim_start().starts_with("//"))
        .collect::<Vec<_>>()
        .join("\n")
}

/// Every `.rs` file under `dir`.
fn rust_files(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    for entry in fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            out.extend(rust_files(&path));
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
    out
}

/// The identifiers that follow `prefix` in `code` (`crate::` gives the top-level modules
/// named), with those in a braced list after it (`crate::{a, b::c}`).
fn names_after(code: &str, prefix: &str) -> BTreeSet<String> {
    let ident = |s: &str| -> String {
        s.chars()
            .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
            .collect()
    };
    let mut out = BTreeSet::new();
    for (i, _) in code.match_indices(prefix) {
        if i > 0 {
            let before = code[..i].chars().next_back().unwrap();
            if before.is_ascii_alphanumeric() || before == '_' {
                continue;
            }
        }
        let rest = &code[i + prefix.len()..];
        if let Some(list) = rest.strip_prefix('{') {
            let mut depth = 0;
            let mut item_start = true;
            for (k, c) in list.char_indices() {
                match c {
                    '{' => depth += 1,
                    '}' if depth == 0 => break,
                    '}' => depth -= 1,
                    ',' if depth == 0 => item_start = true,
                    c if c.is_whitespace() => {}
                    _ if item_start => {
                        out.insert(ident(&list[k..]));
                        item_start = false;
                    }
                    _ => {}
                }
            }
        } else {
            out.insert(ident(rest));
        }
    }
    out.remove("");
    out
}

/// A cycle in `graph`, if there is one, as the nodes in order (first repeated last).
fn find_cycle(graph: &BTreeMap<String, BTreeSet<String>>) -> Option<Vec<String>> {
    // 0: unvisited, 1: on the current path, 2: done.
    fn visit(
        node: &str,
        graph: &BTreeMap<String, BTreeSet<String>>,
        state: &mut BTreeMap<String, u8>,
        path: &mut Vec<String>,
    ) -> Option<Vec<String>> {
        state.insert(node.to_string(), 1);
        path.push(node.to_string());
        for next in graph.get(node).into_iter().flatten() {
            match state.get(next.as_str()).copied().unwrap_or(0) {
                1 => {
                    let start = path.iter().position(|n| n == next).unwrap();
                    let mut cycle = path[start..].to_vec();
                    cycle.push(next.clone());
                    return Some(cycle);
                }
                0 => {
                    if let Some(c) = visit(next, graph, state, path) {
                        return Some(c);
                    }
                }
                _ => {}
            }
        }
        path.pop();
        state.insert(node.to_string(), 2);
        None
    }
    let mut state = BTreeMap::new();
    for node in graph.keys() {
        if state.get(node.as_str()).copied().unwrap_or(0) == 0 {
            if let Some(c) = visit(node, graph, &mut state, &mut Vec::new()) {
                return Some(c);
            }
        }
    }
    None
}

fn src_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

/// The top-level module a file under `crate/src` belongs to (`None` for lib.rs and the
/// binary).
fn top_module(src: &Path, file: &Path) -> Option<String> {
    let rel = file.strip_prefix(src).unwrap();
    let first = rel.components().next()?.as_os_str().to_string_lossy();
    let name = first.trim_end_matches(".rs").to_string();
    (name != "lib" && name != "bin").then_some(name)
}

#[test]
fn the_top_level_modules_import_each_other_without_a_cycle() {
    let src = src_dir();
    let mut graph: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for file in rust_files(&src) {
        let Some(module) = top_module(&src, &file) else {
            continue;
        };
        let used = names_after(&code_of(&file), "crate::");
        let entry = graph.entry(module.clone()).or_default();
        entry.extend(used.into_iter().filter(|m| *m != module));
    }
    // The check reads what it should: the study layer uses the algorithms.
    assert!(graph["study"].contains("maps") && graph["study"].contains("surrogate"));
    assert!(graph.len() > 20, "{} modules read", graph.len());
    if let Some(cycle) = find_cycle(&graph) {
        panic!("import cycle between modules: {}", cycle.join(" -> "));
    }
}

#[test]
fn the_files_of_each_module_import_each_other_without_a_cycle() {
    let src = src_dir();
    let mut dirs: BTreeMap<PathBuf, Vec<PathBuf>> = BTreeMap::new();
    for file in rust_files(&src) {
        dirs.entry(file.parent().unwrap().to_path_buf())
            .or_default()
            .push(file);
    }
    let mut checked = 0;
    for (dir, files) in &dirs {
        let rel = dir.strip_prefix(&src).unwrap();
        if rel.as_os_str().is_empty() || rel.starts_with("bin") {
            continue;
        }
        let module_path = format!(
            "crate::{}::",
            rel.to_string_lossy()
                .replace(std::path::MAIN_SEPARATOR, "::")
        );
        let stem = |f: &Path| f.file_stem().unwrap().to_string_lossy().to_string();
        let siblings: BTreeSet<String> = files.iter().map(|f| stem(f)).collect();
        let mut graph: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
        for file in files {
            let me = stem(file);
            if me == "mod" {
                continue;
            }
            let code = code_of(file);
            let mut used = names_after(&code, "super::");
            used.extend(names_after(&code, &module_path));
            graph.entry(me.clone()).or_default().extend(
                used.into_iter()
                    .filter(|n| *n != me && *n != "mod" && siblings.contains(n)),
            );
        }
        checked += 1;
        if let Some(cycle) = find_cycle(&graph) {
            panic!(
                "import cycle between the files of {}: {}",
                rel.display(),
                cycle.join(" -> ")
            );
        }
    }
    assert!(checked > 10, "{checked} directory modules read");
}

#[test]
fn the_cycle_finder_finds_a_cycle_and_names_it() {
    let graph: BTreeMap<String, BTreeSet<String>> = [
        ("a", vec!["b"]),
        ("b", vec!["c"]),
        ("c", vec!["a", "d"]),
        ("d", vec![]),
    ]
    .into_iter()
    .map(|(k, v)| (k.to_string(), v.into_iter().map(String::from).collect()))
    .collect();
    assert_eq!(find_cycle(&graph).unwrap(), ["a", "b", "c", "a"]);
    let mut acyclic = graph.clone();
    acyclic.get_mut("c").unwrap().remove("a");
    assert_eq!(find_cycle(&acyclic), None);
    let code = "use crate::{maps::Grid, optimize::{a, b}};\nlet x = crate::doe::f();";
    assert_eq!(
        names_after(code, "crate::").into_iter().collect::<Vec<_>>(),
        ["doe", "maps", "optimize"]
    );
}
