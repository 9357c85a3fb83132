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
