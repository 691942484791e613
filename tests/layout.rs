//! The crate's layout, checked: no import circle between the files of `src/` (issue 37). A file
//! that names another (`use crate::a::b`, `super::b::C`, `crate::a::b::f(…)` in code) depends
//! on it; the files that depend on each other round a circle are named. An operation
//! (`src/operations/*.rs`) depends on no other operation, only on machinery.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// Every `.rs` file under `dir`, by its module path (`machining::levels`; `mod.rs` and `lib.rs`
/// stand for their folder's module).
fn modules(root: &Path, dir: &Path, out: &mut BTreeMap<String, PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            if path.file_name().unwrap() != "bin" {
                modules(root, &path, out);
            }
        } else if path.extension().is_some_and(|e| e == "rs") {
            let rel = path.strip_prefix(root).unwrap().with_extension("");
            let mut parts: Vec<String> = rel.iter().map(|p| p.to_string_lossy().into_owned()).collect();
            if matches!(parts.last().map(String::as_str), Some("mod" | "lib")) {
                parts.pop();
            }
            out.insert(parts.join("::"), path);
        }
    }
}

/// The code of a file without its comments, its string literals and its `#[cfg(test)]` module
/// (tests may reach anywhere).
fn code(text: &str) -> String {
    let text = match text.find("#[cfg(test)]\nmod tests") {
        Some(k) => &text[..k],
        None => text,
    };
    let mut out = String::new();
    for line in text.lines() {
        let line = line.trim_start();
        if line.starts_with("//") {
            continue;
        }
        let mut in_string = false;
        let mut prev = ' ';
        for c in line.chars() {
            if c == '"' && prev != '\\' {
                in_string = !in_string;
            } else if !in_string {
                // A comment after the code ends the line.
                if c == '/' && prev == '/' {
                    out.pop();
                    break;
                }
                out.push(c);
            }
            prev = c;
        }
        out.push('\n');
    }
    out
}

/// The paths a file names: `crate::…` and `super::…` chains of identifiers, `use` groups
/// expanded one level (`crate::a::{b, c::d}`).
fn named_paths(code: &str) -> Vec<Vec<String>> {
    let mut out = Vec::new();
    let bytes: Vec<char> = code.chars().collect();
    let ident = |c: char| c.is_alphanumeric() || c == '_';
    let mut i = 0;
    while i < bytes.len() {
        let starts = ["crate::", "super::", "self::"].iter().find(|p| bytes[i..].iter().take(p.len()).copied().eq(p.chars()));
        let boundary = i == 0 || !ident(bytes[i - 1]) && bytes[i - 1] != ':';
        let Some(start) = starts.filter(|_| boundary) else {
            i += 1;
            continue;
        };
        let mut path = vec![start.trim_end_matches("::").to_string()];
        i += start.len();
        loop {
            let from = i;
            while i < bytes.len() && ident(bytes[i]) {
                i += 1;
            }
            if i > from {
                path.push(bytes[from..i].iter().collect());
            }
            if bytes[i..].starts_with(&[':', ':']) {
                i += 2;
                if bytes.get(i) == Some(&'{') {
                    // A group: each item's first name.
                    let close = (i..bytes.len()).find(|&k| bytes[k] == '}').unwrap_or(bytes.len());
                    let group: String = bytes[i + 1..close].iter().collect();
                    for item in group.split(',') {
                        let first: String = item.trim().chars().take_while(|&c| ident(c)).collect();
                        if !first.is_empty() && first != "self" {
                            let mut p = path.clone();
                            p.push(first);
                            out.push(p);
                        }
                    }
                    i = close;
                    path.clear();
                    break;
                }
                continue;
            }
            break;
        }
        if !path.is_empty() {
            out.push(path);
        }
    }
    out
}

/// The module a path names from the module `here`: its longest prefix that is a file.
fn target(here: &str, path: &[String], known: &BTreeMap<String, PathBuf>) -> Option<String> {
    let mut base: Vec<String> = if here.is_empty() { Vec::new() } else { here.split("::").map(String::from).collect() };
    let mut rest = path;
    match rest.first().map(String::as_str) {
        Some("crate") => {
            base.clear();
            rest = &rest[1..];
        }
        // A module's `super` is its parent (a folder's `mod.rs` is the folder's module).
        Some("super") => {
            while rest.first().map(String::as_str) == Some("super") {
                base.pop();
                rest = &rest[1..];
            }
        }
        Some("self") => rest = &rest[1..],
        _ => return None,
    }
    let mut best = None;
    let mut m = base.clone();
    if known.contains_key(&m.join("::")) {
        best = Some(m.join("::"));
    }
    for p in rest {
        m.push(p.clone());
        let key = m.join("::");
        if known.contains_key(&key) {
            best = Some(key);
        }
    }
    best
}

fn graph() -> BTreeMap<String, BTreeSet<String>> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut known = BTreeMap::new();
    modules(&root, &root, &mut known);
    let mut edges: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for (name, path) in &known {
        let text = code(&std::fs::read_to_string(path).unwrap());
        let deps = edges.entry(name.clone()).or_default();
        for p in named_paths(&text) {
            if let Some(t) = target(name, &p, &known) {
                // A module naming its own items is no edge, nor one naming the crate's root
                // (its re-exports: `crate::Result`).
                if t != *name && !t.is_empty() {
                    deps.insert(t);
                }
            }
        }
    }
    edges
}

/// The strongly connected groups of more than one module (Tarjan's algorithm).
fn circles(edges: &BTreeMap<String, BTreeSet<String>>) -> Vec<Vec<String>> {
    struct State<'a> {
        edges: &'a BTreeMap<String, BTreeSet<String>>,
        index: BTreeMap<&'a str, usize>,
        low: BTreeMap<&'a str, usize>,
        stack: Vec<&'a str>,
        on: BTreeSet<&'a str>,
        out: Vec<Vec<String>>,
    }
    fn visit<'a>(s: &mut State<'a>, v: &'a str) {
        let k = s.index.len();
        s.index.insert(v, k);
        s.low.insert(v, k);
        s.stack.push(v);
        s.on.insert(v);
        for w in s.edges.get(v).into_iter().flatten() {
            let w = w.as_str();
            if !s.index.contains_key(w) {
                visit(s, w);
                let lw = s.low[w];
                let lv = s.low.get_mut(v).unwrap();
                *lv = (*lv).min(lw);
            } else if s.on.contains(w) {
                let iw = s.index[w];
                let lv = s.low.get_mut(v).unwrap();
                *lv = (*lv).min(iw);
            }
        }
        if s.low[v] == s.index[v] {
            let mut group = Vec::new();
            while let Some(w) = s.stack.pop() {
                s.on.remove(w);
                group.push(w.to_string());
                if w == v {
                    break;
                }
            }
            if group.len() > 1 {
                group.sort();
                s.out.push(group);
            }
        }
    }
    let mut s = State { edges, index: BTreeMap::new(), low: BTreeMap::new(), stack: Vec::new(), on: BTreeSet::new(), out: Vec::new() };
    for v in edges.keys() {
        if !s.index.contains_key(v.as_str()) {
            visit(&mut s, v);
        }
    }
    s.out
}

#[test]
fn the_files_of_src_import_in_no_circle() {
    let edges = graph();
    // The check sees imports at all: the operations name the machinery.
    assert!(edges["operations::rough_zlevel"].contains("machining::levels"), "{:?}", edges["operations::rough_zlevel"]);
    let found = circles(&edges);
    assert!(found.is_empty(), "import circles in src/ (each a group of files that import each other round a circle):\n{}", found.iter().map(|g| g.join(" ↔ ")).collect::<Vec<_>>().join("\n"));
}

#[test]
fn an_operation_imports_no_other_operation() {
    let edges = graph();
    for (name, deps) in &edges {
        if let Some(op) = name.strip_prefix("operations::") {
            let others: Vec<&String> = deps.iter().filter(|d| d.starts_with("operations::") && d.as_str() != name).collect();
            assert!(others.is_empty(), "the operation {op} imports {others:?}");
            assert!(!deps.contains("job") && !deps.iter().any(|d| d.starts_with("job::")), "the operation {op} imports the job: {deps:?}");
        }
    }
}

#[test]
fn the_checker_finds_a_circle() {
    let mut edges: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    edges.entry("a".into()).or_default().insert("b".into());
    edges.entry("b".into()).or_default().insert("c".into());
    edges.entry("c".into()).or_default().insert("a".into());
    edges.entry("d".into()).or_default().insert("a".into());
    assert_eq!(circles(&edges), vec![vec!["a".to_string(), "b".into(), "c".into()]]);
    let paths = named_paths(&code("use crate::machining::{levels::Level, settings};\nlet x = super::rings::f(); // crate::job::x\n"));
    assert_eq!(
        paths,
        vec![vec!["crate", "machining", "levels"], vec!["crate", "machining", "settings"], vec!["super", "rings", "f"]]
            .into_iter()
            .map(|p| p.into_iter().map(String::from).collect::<Vec<_>>())
            .collect::<Vec<_>>()
    );
}
