//! The program's modules import downward only: no module reaches, through its `crate::` paths, a
//! module that reaches it back (an import circle makes the program's layers — flags, numbers,
//! tables and files, the commands — impossible to read or change one at a time).

use std::collections::{BTreeMap, BTreeSet};

/// `crate::` dependencies of every module of `src/` (comments, doc comments and `#[cfg(test)]`
/// modules left out).
fn graph() -> BTreeMap<String, BTreeSet<String>> {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/src");
    let read = |f: &str| std::fs::read_to_string(format!("{dir}/{f}")).unwrap();
    let code = |text: &str| -> String {
        let text = text.split("#[cfg(test)]").next().unwrap_or("");
        text.lines()
            .filter(|l| !l.trim_start().starts_with("//"))
            .collect::<Vec<_>>()
            .join("\n")
    };
    let words = |s: &str| -> Vec<String> {
        s.split(|c: char| !(c.is_alphanumeric() || c == '_'))
            .filter(|w| !w.is_empty())
            .map(String::from)
            .collect()
    };
    let modules: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .filter_map(|e| e.ok()?.file_name().into_string().ok())
        .filter(|f| f.ends_with(".rs") && f != "main.rs")
        .map(|f| f.trim_end_matches(".rs").to_string())
        .collect();
    // `pub use module::{A, B};` in main.rs: A and B live in module
    let mut home: BTreeMap<String, String> = BTreeMap::new();
    for stmt in code(&read("main.rs")).split(';') {
        if let Some(rest) = stmt.trim().strip_prefix("pub use ") {
            let w = words(rest);
            if let Some((m, names)) = w.split_first() {
                for n in names {
                    home.insert(n.clone(), m.clone());
                }
            }
        }
    }
    let mut g = BTreeMap::new();
    for m in &modules {
        let text = code(&read(&format!("{m}.rs")));
        let mut deps = BTreeSet::new();
        for part in text.split("crate::").skip(1) {
            // the path after `crate::`, or the braced list of a `use crate::{...}`
            let end = if part.starts_with('{') {
                part.find('}').unwrap_or(part.len())
            } else {
                part.find(|c: char| !(c.is_alphanumeric() || c == '_'))
                    .unwrap_or(part.len())
            };
            for w in words(&part[..end]) {
                let target = if modules.contains(&w) {
                    Some(w)
                } else {
                    home.get(&w).cloned()
                };
                if let Some(t) = target.filter(|t| t != m) {
                    deps.insert(t);
                }
            }
        }
        g.insert(m.clone(), deps);
    }
    g
}

#[test]
fn modules_import_downward_only() {
    let g = graph();
    assert!(g.len() > 15, "modules found: {:?}", g.keys());
    // depth-first search for a back edge
    fn visit(
        u: &str,
        g: &BTreeMap<String, BTreeSet<String>>,
        state: &mut BTreeMap<String, u8>,
        path: &mut Vec<String>,
    ) -> Option<Vec<String>> {
        state.insert(u.to_string(), 1);
        path.push(u.to_string());
        for v in &g[u] {
            match state.get(v.as_str()) {
                Some(1) => {
                    let mut cycle = path.clone();
                    cycle.push(v.clone());
                    return Some(cycle);
                }
                None => {
                    if let Some(c) = visit(v, g, state, path) {
                        return Some(c);
                    }
                }
                _ => {}
            }
        }
        path.pop();
        state.insert(u.to_string(), 2);
        None
    }
    let mut state = BTreeMap::new();
    for m in g.keys() {
        if !state.contains_key(m.as_str()) {
            if let Some(c) = visit(m, &g, &mut state, &mut Vec::new()) {
                panic!("import circle: {}", c.join(" → "));
            }
        }
    }
    // the bottom layer imports nothing of the commands above it (the tests include it alone)
    let low = &g["number_text"];
    assert!(low.is_empty(), "number_text imports {low:?}");
}

/// Every `.rs` file under `dir` (recursively), with its path.
fn sources(dir: &std::path::Path, out: &mut Vec<(String, String)>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for e in entries.flatten() {
        let p = e.path();
        if p.is_dir() {
            sources(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push((
                p.display().to_string(),
                std::fs::read_to_string(&p).unwrap(),
            ));
        }
    }
}

/// The functions of `text` longer than `max` lines (from the `fn` line to the closing brace at
/// its indentation; rustfmt's layout), as `(line, length, signature)`.
fn long_functions(text: &str, max: usize) -> Vec<(usize, usize, String)> {
    let lines: Vec<&str> = text.lines().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < lines.len() {
        let l = lines[i];
        let t = l.trim_start();
        let head = [
            "pub(crate) ",
            "pub(super) ",
            "pub ",
            "const ",
            "unsafe ",
            "async ",
        ]
        .iter()
        .fold(t, |t, p| t.strip_prefix(p).unwrap_or(t));
        if !head.starts_with("fn ") {
            i += 1;
            continue;
        }
        let indent = &l[..l.len() - t.len()];
        // the signature ends at `{` (a body) or `;` (a trait's declaration)
        // (or at `}` on the line that opened it: a body of one line)
        let ends =
            |l: &str| l.ends_with('{') || l.ends_with(';') || (l.ends_with('}') && l.contains('{'));
        let mut j = i;
        while j < lines.len() && !ends(lines[j]) {
            j += 1;
        }
        if j == lines.len() || !lines[j].ends_with('{') {
            i = j + 1;
            continue;
        }
        let close = format!("{indent}}}");
        let mut k = j + 1;
        while k < lines.len() && lines[k] != close {
            k += 1;
        }
        if k - i + 1 > max {
            out.push((i + 1, k - i + 1, t.chars().take(60).collect()));
        }
        i = k + 1;
    }
    out
}

/// The types `Result<…>` in `text` whose error is a `String`.
fn string_errors(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    for (at, _) in text.match_indices("Result<") {
        let rest = &text[at + "Result<".len()..];
        let (mut depth, mut last_comma, mut end) = (0i32, None, None);
        for (i, c) in rest.char_indices() {
            match c {
                '<' | '(' | '[' => depth += 1,
                ')' | ']' => depth -= 1,
                '>' if depth == 0 => {
                    end = Some(i);
                    break;
                }
                '>' => depth -= 1,
                ',' if depth == 0 => last_comma = Some(i),
                _ => {}
            }
        }
        if let (Some(c), Some(e)) = (last_comma, end) {
            if rest[c + 1..e].trim() == "String" {
                out.push(format!("Result<{}>", &rest[..e]));
            }
        }
    }
    out
}

/// Issue 35's shape of the code: no function longer than 150 lines in the rod library and the
/// program, no stop reason told by its name in the program, no `Box::leak` and no
/// `Result<_, String>` in the library crates (states and errors are typed). Comments and strings are read as code: a counted line is a line.
#[test]
fn functions_are_short_and_errors_typed() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut long = Vec::new();
    for dir in ["crates/vibrissa/src", "src"] {
        let mut files = Vec::new();
        sources(&root.join(dir), &mut files);
        assert!(files.len() > 10, "{dir}: {} files", files.len());
        for (path, text) in &files {
            for (line, n, sig) in long_functions(text, 150) {
                long.push(format!("{path}:{line}: {n} lines: {sig}"));
            }
        }
    }
    assert!(
        long.is_empty(),
        "functions over 150 lines:\n{}",
        long.join("\n")
    );
    // the program decides on the library's typed stop reasons, never on their names
    let mut program = Vec::new();
    sources(&root.join("src"), &mut program);
    for (path, text) in &program {
        for pat in ["reason == \"", "reason != \""] {
            assert!(
                !text.contains(pat),
                "{path}: compares a stop reason's name ({pat})"
            );
        }
    }
    let mut libs = Vec::new();
    for e in std::fs::read_dir(root.join("crates")).unwrap().flatten() {
        sources(&e.path().join("src"), &mut libs);
    }
    assert!(libs.len() > 30, "{} library files", libs.len());
    let mut bad = Vec::new();
    for (path, text) in &libs {
        if text.contains(concat!("Box::", "leak")) {
            bad.push(format!("{path}: Box::leak"));
        }
        for r in string_errors(text) {
            bad.push(format!("{path}: {r}"));
        }
    }
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}

#[test]
fn the_shape_checks_find_what_they_look_for() {
    let body = (0..151).map(|_| "    x += 1;\n").collect::<String>();
    let text = format!("fn g() {{}}\npub(crate) fn f(\n    a: u8,\n) -> u8 {{\n{body}}}\n");
    assert_eq!(long_functions(&text, 150).len(), 1);
    assert!(long_functions(&text, 160).is_empty());
    assert_eq!(
        string_errors("fn a() -> Result<(Vec<u8>, Option<String>), String> {}"),
        vec!["Result<(Vec<u8>, Option<String>), String>".to_string()]
    );
    assert!(string_errors("fn a() -> Result<Option<String>, E> {}").is_empty());
}
