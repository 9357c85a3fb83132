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
