//! The crate's module graph has no cycle (issue #28): the algorithms (`maps`, `optimize`,
//! `surrogate`, `doe`, ...) sit below the study layer (`study`), which sits below the
//! explorer, the report and the web shell.
//!
//! Read from the source, not the compiler: a module `a` depends on `b` when a line of
//! `a`'s code (comments, string literals and `#[cfg(test)]` items left out) names
//! `crate::b`. Two checks: between the top-level modules of `crate/src`, and between the
//! sibling files (and sub-directories) of each directory module, where one names another
//! by path (`super::file::`, `crate::module::file::`) or names an item the parent's
//! `mod.rs` re-exports from it (`super::Item` with `pub use file::Item` in `mod.rs`).

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

/// The code of `path`, its comments and the insides of its string and character literals
/// blanked and its `#[cfg(test)]` items left out, or nothing for a file of tests.
fn code_of(path: &Path) -> String {
    let name = path.file_name().unwrap().to_string_lossy();
    if name.starts_with("tests") {
        return String::new();
    }
    without_test_items(&blank_comments_and_literals(
        &fs::read_to_string(path).unwrap(),
    ))
}

/// `src` with its comments and the insides of its string, raw string and character
/// literals replaced by blanks (line breaks kept), so that a brace or a path in a message
/// or a doc comment is not read as code.
fn blank_comments_and_literals(src: &str) -> String {
    let c: Vec<char> = src.chars().collect();
    let mut out = c.clone();
    let blank = |out: &mut Vec<char>, from: usize, to: usize| {
        for ch in out.iter_mut().take(to.min(c.len())).skip(from) {
            if *ch != '\n' {
                *ch = ' ';
            }
        }
    };
    let at = |k: usize| c.get(k).copied().unwrap_or('\0');
    let mut i = 0;
    while i < c.len() {
        let end = if at(i) == '/' && at(i + 1) == '/' {
            (i..c.len()).find(|&k| c[k] == '\n').unwrap_or(c.len())
        } else if at(i) == '/' && at(i + 1) == '*' {
            (i + 2..c.len())
                .find(|&k| c[k] == '*' && at(k + 1) == '/')
                .map_or(c.len(), |k| k + 2)
        } else if at(i) == 'r'
            && (at(i + 1) == '"' || at(i + 1) == '#')
            && !ident_char(at(i.wrapping_sub(1)))
        {
            // r"..." or r#"..."#: ends at the quote followed by as many hashes.
            let hashes = (i + 1..c.len()).take_while(|&k| c[k] == '#').count();
            let open = i + 1 + hashes;
            if at(open) != '"' {
                i += 1;
                continue;
            }
            let close = (open + 1..c.len())
                .find(|&k| c[k] == '"' && (1..=hashes).all(|h| at(k + h) == '#'))
                .unwrap_or(c.len());
            blank(&mut out, open + 1, close);
            i = close + 1 + hashes;
            continue;
        } else if at(i) == '"' {
            let mut k = i + 1;
            while k < c.len() && c[k] != '"' {
                k += if c[k] == '\\' { 2 } else { 1 };
            }
            blank(&mut out, i + 1, k);
            i = k + 1;
            continue;
        } else if at(i) == '\'' && at(i + 2) == '\'' {
            i + 3
        } else if at(i) == '\'' && at(i + 1) == '\\' {
            // '\n', '\'', '\u{..}': to the closing quote.
            (i + 3..c.len())
                .find(|&k| c[k] == '\'')
                .map_or(c.len(), |k| k + 1)
        } else {
            i += 1;
            continue;
        };
        blank(&mut out, i, end);
        i = end;
    }
    out.into_iter().collect()
}

/// Whether `c` can be part of an identifier.
fn ident_char(c: char) -> bool {
    c.is_ascii_alphanumeric() || c == '_'
}

/// `code` without each item that follows a `#[cfg(test)]` (to its `;` or the brace that
/// closes its block).
fn without_test_items(code: &str) -> String {
    const MARK: &str = "#[cfg(test)]";
    let mut out = String::new();
    let mut rest = code;
    while let Some(at) = rest.find(MARK) {
        out.push_str(&rest[..at]);
        let item = &rest[at + MARK.len()..];
        let mut depth = 0;
        let mut end = item.len();
        for (k, c) in item.char_indices() {
            match c {
                '{' => depth += 1,
                '}' => {
                    depth -= 1;
                    if depth == 0 {
                        end = k + 1;
                        break;
                    }
                }
                ';' if depth == 0 => {
                    end = k + 1;
                    break;
                }
                _ => {}
            }
        }
        rest = &item[end..];
    }
    out.push_str(rest);
    out
}

/// The items `mod_code` (a `mod.rs`) re-exports from its children, each with the child
/// that defines it: `pub use record::ModelRecord;` gives `ModelRecord -> record`, and
/// `pub use spec::{Form, PlanSpec as Plan};` gives `Form -> spec` and `Plan -> spec`.
fn reexports(mod_code: &str, children: &BTreeSet<String>) -> BTreeMap<String, String> {
    let mut out = BTreeMap::new();
    for (at, _) in mod_code.match_indices("use ") {
        if at > 0 {
            let before = mod_code[..at].chars().next_back().unwrap();
            if before.is_ascii_alphanumeric() || before == '_' {
                continue;
            }
        }
        let statement = &mod_code[at + 4..];
        let statement = &statement[..statement.find(';').unwrap_or(statement.len())];
        let statement = statement.trim().trim_start_matches("self::");
        let Some((child, items)) = statement.split_once("::") else {
            continue;
        };
        if !children.contains(child) {
            continue;
        }
        // The names a statement brings in: the last segment of each path, or its alias.
        let flat: String = items
            .chars()
            .map(|c| if "{},".contains(c) { ' ' } else { c })
            .collect();
        let words: Vec<&str> = flat.split_whitespace().collect();
        for (k, word) in words.iter().enumerate() {
            let renamed = words.get(k + 1) == Some(&"as");
            let alias = k > 0 && words[k - 1] == "as";
            if *word == "as" || renamed {
                continue;
            }
            let leaf = word.rsplit("::").next().unwrap();
            if alias || !leaf.is_empty() && !word.ends_with("::") {
                out.insert(leaf.to_string(), child.to_string());
            }
        }
    }
    out
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

/// The graph between the children of the directory module at `dir` (`src`-relative
/// `rel`): its files but `mod.rs`, and its sub-directories, each one node (a sub-directory
/// names its parent's children by `super::super::`). A child depends on another where it
/// names it by path or names an item `mod.rs` re-exports from it.
fn children_graph(dir: &Path, rel: &Path) -> BTreeMap<String, BTreeSet<String>> {
    let module_path = format!(
        "crate::{}::",
        rel.to_string_lossy()
            .replace(std::path::MAIN_SEPARATOR, "::")
    );
    let mut children: BTreeMap<String, String> = BTreeMap::new();
    for entry in fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_stem().unwrap().to_string_lossy().to_string();
        if path.is_dir() {
            let code: Vec<String> = rust_files(&path).iter().map(|f| code_of(f)).collect();
            let code = code.join("\n");
            let mut used = names_after(&code, "super::super::");
            used.extend(names_after(&code, &module_path));
            children.insert(name, used.into_iter().collect::<Vec<_>>().join(" "));
        } else if path.extension().is_some_and(|e| e == "rs") && name != "mod" {
            let code = code_of(&path);
            let mut used = names_after(&code, "super::");
            used.extend(names_after(&code, &module_path));
            children.insert(name, used.into_iter().collect::<Vec<_>>().join(" "));
        }
    }
    let names: BTreeSet<String> = children.keys().cloned().collect();
    let exported = reexports(&code_of(&dir.join("mod.rs")), &names);
    children
        .into_iter()
        .map(|(me, used)| {
            let deps = used
                .split_whitespace()
                .filter_map(|n| {
                    if names.contains(n) {
                        Some(n.to_string())
                    } else {
                        exported.get(n).cloned()
                    }
                })
                .filter(|n| *n != me)
                .collect();
            (me, deps)
        })
        .collect()
}

#[test]
fn the_files_of_each_module_import_each_other_without_a_cycle() {
    let src = src_dir();
    let dirs: BTreeSet<PathBuf> = rust_files(&src)
        .into_iter()
        .filter(|f| f.ends_with("mod.rs"))
        .map(|f| f.parent().unwrap().to_path_buf())
        .collect();
    let mut checked = 0;
    for dir in &dirs {
        let rel = dir.strip_prefix(&src).unwrap();
        if rel.starts_with("bin") {
            continue;
        }
        let graph = children_graph(dir, rel);
        checked += 1;
        if let Some(cycle) = find_cycle(&graph) {
            panic!(
                "import cycle between the files of {}: {}",
                rel.display(),
                cycle.join(" -> ")
            );
        }
        // The check reads what it should: a re-exported item is followed to its file.
        if rel == Path::new("surrogate") {
            assert!(graph["dispatch"].contains("record") && graph["guard"].contains("record"));
            assert!(graph["rba"].contains("spec"), "{:?}", graph["rba"]);
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

#[test]
fn the_reader_skips_comments_literals_and_test_items_and_follows_re_exports() {
    let src = r##"use super::a::X; // super::b::Y
/* super::c */ let s = "super::d {"; let r = r#"super::e"#; let c = '{';
#[cfg(test)]
mod tests {
    use super::f::Z;
    fn g() { if true { super::h::W; } }
}
fn after() { super::k::V; }
#[cfg(test)]
use super::m::T;
"##;
    let dir = std::env::temp_dir().join(format!("structure-{}", std::process::id()));
    fs::create_dir_all(&dir).unwrap();
    let file = dir.join("one.rs");
    fs::write(&file, src).unwrap();
    let code = code_of(&file);
    fs::remove_dir_all(&dir).unwrap();
    assert_eq!(
        names_after(&code, "super::")
            .into_iter()
            .collect::<Vec<_>>(),
        ["a", "k"],
        "{code}"
    );
    let children: BTreeSet<String> = ["record", "spec", "gp"].map(String::from).into();
    let mod_code = "pub use record::ModelRecord;\npub use spec::{Approach, Form as F, sub::{A, B}};\npub use crate::x::Y;";
    let got = reexports(mod_code, &children);
    let want: BTreeMap<String, String> = [
        ("A", "spec"),
        ("Approach", "spec"),
        ("B", "spec"),
        ("F", "spec"),
        ("ModelRecord", "record"),
    ]
    .into_iter()
    .map(|(a, b)| (a.to_string(), b.to_string()))
    .collect();
    assert_eq!(got, want);
}
