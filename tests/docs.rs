//! What makes the library docs show the libraries: `cargo doc --no-deps` at the root documents
//! the default members (the program and the three libraries), and the program's binary, named
//! like the library `vibrissa`, is left out of the docs (else the two collide). Each library
//! has a README whose example runs as a doc test, and every example program runs in
//! `tests/examples.rs`.

use std::path::Path;

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

#[test]
fn cargo_doc_at_the_root_documents_the_libraries() {
    let text = std::fs::read_to_string(root().join("Cargo.toml")).unwrap();
    let manifest: toml::Value = toml::from_str(&text).unwrap();
    let members: Vec<&str> = manifest["workspace"]["default-members"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_str().unwrap())
        .collect();
    for lib in ["crates/bvp", "crates/elastica", "crates/vibrissa"] {
        assert!(members.contains(&lib), "{lib} not in {members:?}");
    }
    let bins = manifest["bin"].as_array().unwrap();
    let vibrissa = bins
        .iter()
        .find(|b| b["name"].as_str() == Some("vibrissa"))
        .unwrap();
    assert_eq!(vibrissa.get("doc").and_then(|d| d.as_bool()), Some(false));
}

#[test]
fn each_library_runs_its_readme() {
    for lib in ["bvp", "elastica", "vibrissa"] {
        let dir = root().join("crates").join(lib);
        let readme = std::fs::read_to_string(dir.join("README.md")).unwrap();
        assert!(
            readme.contains("```rust"),
            "{lib}: README without a Rust example"
        );
        let src = std::fs::read_to_string(dir.join("src/lib.rs")).unwrap();
        assert!(
            src.contains("#[cfg(doctest)]\n#[doc = include_str!(\"../README.md\")]"),
            "{lib}: README example not run as a doc test"
        );
    }
}

#[test]
fn every_example_runs_in_the_tests() {
    let tests = std::fs::read_to_string(root().join("tests/examples.rs")).unwrap();
    for e in std::fs::read_dir(root().join("examples")).unwrap() {
        let name = e.unwrap().file_name().into_string().unwrap();
        // the work-precision study takes minutes: its runs are the committed data
        if name == "work_precision.rs" {
            continue;
        }
        assert!(
            tests.contains(&format!("#[path = \"../examples/{name}\"]")),
            "examples/{name} is not run by tests/examples.rs"
        );
    }
}

/// The markdown files whose links are checked: the README, the library and Python READMEs and
/// everything under docs/.
fn markdown_files() -> Vec<std::path::PathBuf> {
    fn walk(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
        for e in std::fs::read_dir(dir).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                walk(&p, out);
            } else if p.extension().is_some_and(|x| x == "md") {
                out.push(p);
            }
        }
    }
    let mut files = vec![root().join("README.md"), root().join("python/README.md")];
    for lib in ["bvp", "elastica", "vibrissa"] {
        files.push(root().join("crates").join(lib).join("README.md"));
    }
    walk(&root().join("docs"), &mut files);
    files
}

/// The anchors of a markdown text's headings, as GitHub makes them: lower case, letters, digits,
/// `-` and `_` kept, spaces turned into `-`, everything else dropped. Lines in code blocks are
/// not headings.
fn anchors(md: &str) -> Vec<String> {
    let mut fenced = false;
    let mut out = Vec::new();
    for l in md.lines() {
        if l.trim_start().starts_with("```") {
            fenced = !fenced;
            continue;
        }
        if fenced || !l.starts_with('#') {
            continue;
        }
        let title = l.trim_start_matches('#').trim();
        let slug: String = title
            .to_lowercase()
            .chars()
            .filter(|c| c.is_alphanumeric() || matches!(c, '-' | '_' | ' '))
            .map(|c| if c == ' ' { '-' } else { c })
            .collect();
        out.push(slug);
    }
    out
}

/// The relative link targets `](target)` of a markdown text, outside code blocks and spans.
fn links(md: &str) -> Vec<(usize, String)> {
    let mut fenced = false;
    let mut out = Vec::new();
    for (i, l) in md.lines().enumerate() {
        if l.trim_start().starts_with("```") {
            fenced = !fenced;
            continue;
        }
        if fenced {
            continue;
        }
        let mut rest = l;
        while let Some(k) = rest.find("](") {
            let after = &rest[k + 2..];
            let Some(end) = after.find(')') else { break };
            let target = &after[..end];
            if !target.contains("://") && !target.starts_with("mailto:") {
                out.push((i + 1, target.to_string()));
            }
            rest = &after[end..];
        }
    }
    out
}

/// Every relative link of the documentation names a file of the repository (never a path
/// outside it), and every `#anchor` a heading of the linked markdown file: links to sections
/// that moved (README to docs/reference.md, docs/performance.md) cannot dangle.
#[test]
fn documentation_links_resolve_inside_the_repository() {
    let root = root().canonicalize().unwrap();
    let mut bad = Vec::new();
    let mut checked = 0;
    for f in markdown_files() {
        let text = std::fs::read_to_string(&f).unwrap();
        let name = f.strip_prefix(&root).unwrap_or(&f).display().to_string();
        for (line, target) in links(&text) {
            checked += 1;
            let (path, anchor) = match target.split_once('#') {
                Some((p, a)) => (p, Some(a)),
                None => (target.as_str(), None),
            };
            let file = if path.is_empty() {
                f.clone()
            } else {
                f.parent().unwrap().join(path)
            };
            let Ok(file) = file.canonicalize() else {
                bad.push(format!("{name}:{line}: {target}: no such file"));
                continue;
            };
            if !file.starts_with(&root) {
                bad.push(format!("{name}:{line}: {target}: outside the repository"));
                continue;
            }
            if let Some(a) = anchor {
                if file.extension().is_some_and(|x| x == "md") {
                    let md = std::fs::read_to_string(&file).unwrap();
                    if !anchors(&md).iter().any(|h| h == a) {
                        bad.push(format!(
                            "{name}:{line}: {target}: no heading with that anchor"
                        ));
                    }
                }
            }
        }
    }
    assert!(checked >= 30, "only {checked} links found");
    assert!(bad.is_empty(), "broken links:\n{}", bad.join("\n"));
}

/// The anchor and link readers find what they should (so the link test can fail).
#[test]
fn the_link_check_reads_headings_and_links() {
    let md = "# Top\n## fit — μs and μk, `x`\n```sh\n# not a heading\n```\nsee [a](b.md#c) and [d](https://e/f)\n";
    assert_eq!(anchors(md), ["top", "fit--μs-and-μk-x"]);
    assert_eq!(links(md), [(6, "b.md#c".to_string())]);
}

/// README.md is what a user reads first: short, the two commands of the quick start in its first
/// screen, the command reference under its own heading (its details in docs/reference.md).
#[test]
fn readme_is_short_and_starts_with_the_two_commands() {
    let readme = std::fs::read_to_string(root().join("README.md")).unwrap();
    let n = readme.lines().count();
    assert!(n <= 450, "README.md has {n} lines");
    let first_screen: String = readme.lines().take(40).collect::<Vec<_>>().join("\n");
    for cmd in ["cargo run --release -- scan", "cargo test --workspace"] {
        assert!(
            first_screen.contains(cmd),
            "{cmd} not in README's first screen"
        );
    }
    assert!(readme.contains("\n## Command reference\n"));
    assert!(readme.contains("docs/reference.md"));
}
