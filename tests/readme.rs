//! The console examples of README.md and of the command reference, docs/reference.md, are run
//! and compared with what they show, so they cannot drift, and the SLURM example line of the
//! sweep section (docs/reference.md) runs as written. Every other markdown file under docs/ is
//! checked to have no console block, so an example moved there is not left unchecked.
//!
//! Every ```` ```console ```` block of these documents is a session: lines starting with `$ ` are
//! commands, the lines up to the next command are the output the block shows. Each block runs in
//! a fresh empty directory (files one command writes are there for the next). Supported commands:
//! `vibrissa ARGS` (the built binary; arguments split at spaces, no quoting) and `cat FILE`.
//! stdout and stderr go to one file, in the order they are written, as on a terminal.
//!
//! Comparison, line by line, after splitting each line at `,` `;` `:` `=` `(` `)` and spaces:
//! - a token that is a number in both lines matches when the two agree to 1e-9 relative or
//!   1e-12 absolute (last-digit noise of the floating-point results is not drift; a changed
//!   value is);
//! - a timing is not compared: the number before `ms`, and the value of `time_ms`;
//! - every other token must be equal;
//! - a shown line `...` stands for any number of omitted lines.
//!
//! After a deliberate change of the program's output, `README_BLESS=1 cargo test --test readme`
//! rewrites the shown output of every example with what the program prints (a block ending in
//! `...` keeps as many lines as it showed) instead of comparing; review the diff of the documents.

mod common;

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

/// The documents whose console blocks are run, each with the least number of blocks and of
/// commands it must hold (so that a parser finding nothing, or a lost block, fails).
const DOCUMENTS: [(&str, usize, usize); 2] = [("README.md", 5, 8), ("docs/reference.md", 9, 18)];

/// One `$ command` of a console block and the output lines shown under it.
#[derive(Debug)]
struct Example {
    /// the document (path relative to the repository root) and the command's line in it (1-based)
    doc: String,
    line: usize,
    command: String,
    shown: Vec<String>,
}

/// The console blocks of the markdown text of document `doc`, each a list of examples.
fn console_blocks(doc: &str, md: &str) -> Vec<Vec<Example>> {
    let mut blocks = Vec::new();
    let mut cur: Option<Vec<Example>> = None;
    for (i, l) in md.lines().enumerate() {
        let t = l.trim_end();
        match &mut cur {
            None if t.trim_start() == "```console" => cur = Some(Vec::new()),
            None => {}
            Some(_) if t.trim_start() == "```" => blocks.extend(cur.take()),
            Some(b) => {
                if let Some(c) = t.strip_prefix("$ ") {
                    b.push(Example {
                        doc: doc.to_string(),
                        line: i + 1,
                        command: c.trim().to_string(),
                        shown: Vec::new(),
                    });
                } else {
                    let e = b
                        .last_mut()
                        .unwrap_or_else(|| panic!("{doc}:{}: output before any `$ `", i + 1));
                    e.shown.push(t.to_string());
                }
            }
        }
    }
    assert!(cur.is_none(), "{doc}: unterminated console block");
    blocks
}

/// Run one command in `dir`; returns stdout and stderr as written (one file for both).
fn run(dir: &Path, ex: &Example) -> String {
    assert!(
        !ex.command.contains(['"', '\'', '|', '>', '<', '&', '$']),
        "{}:{}: quoting, pipes and redirections are not supported here: {}",
        ex.doc,
        ex.line,
        ex.command
    );
    let words: Vec<&str> = ex.command.split_whitespace().collect();
    match words[0] {
        "vibrissa" => {
            let out = dir.join(".out");
            let f = std::fs::File::create(&out).unwrap();
            let status = Command::new(env!("CARGO_BIN_EXE_vibrissa"))
                .args(&words[1..])
                .current_dir(dir)
                .stdin(Stdio::null())
                .stdout(f.try_clone().unwrap())
                .stderr(f)
                .status()
                .expect("run vibrissa");
            let text = std::fs::read_to_string(&out).unwrap();
            std::fs::remove_file(&out).unwrap();
            assert!(
                status.code().is_some(),
                "{}:{}: killed by a signal",
                ex.doc,
                ex.line
            );
            text
        }
        "cat" => words[1..]
            .iter()
            .map(|f| {
                std::fs::read_to_string(dir.join(f))
                    .unwrap_or_else(|e| panic!("{}:{}: cat {f}: {e}", ex.doc, ex.line))
            })
            .collect(),
        w => panic!(
            "{}:{}: unsupported command `{w}` in a console block (vibrissa, cat)",
            ex.doc, ex.line
        ),
    }
}

fn tokens(line: &str) -> Vec<&str> {
    let mut out = Vec::new();
    let mut start = 0;
    for (i, c) in line.char_indices() {
        if matches!(c, ',' | ';' | ':' | '=' | '(' | ')' | ' ') {
            if start < i {
                out.push(&line[start..i]);
            }
            out.push(&line[i..i + c.len_utf8()]);
            start = i + c.len_utf8();
        }
    }
    if start < line.len() {
        out.push(&line[start..]);
    }
    out
}

fn number(t: &str) -> Option<f64> {
    // "inf", "nan", "e" are words here, not numbers
    if !t.starts_with(|c: char| c.is_ascii_digit() || c == '-' || c == '.') {
        return None;
    }
    t.parse().ok()
}

/// Whether an output line matches the shown line (see the module comment).
fn line_matches(shown: &str, got: &str) -> bool {
    let (a, b) = (tokens(shown), tokens(got));
    if a.len() != b.len() {
        return false;
    }
    let timing = |v: &[&str], i: usize| -> bool {
        let next_word = v[i + 1..].iter().find(|t| **t != " ");
        let prev_word = v[..i].iter().rev().find(|t| !matches!(**t, " " | ":"));
        next_word == Some(&"ms") || prev_word.is_some_and(|p| p.trim_matches('"') == "time_ms")
    };
    (0..a.len()).all(|i| match (number(a[i]), number(b[i])) {
        (Some(_), Some(_)) if timing(&a, i) => true,
        (Some(x), Some(y)) => (x - y).abs() <= 1e-9 * x.abs().max(y.abs()) + 1e-12,
        _ => a[i] == b[i],
    })
}

/// Match the shown lines against the output; `...` matches any run of lines (also none).
fn block_matches(shown: &[String], got: &[&str]) -> bool {
    match shown.split_first() {
        None => got.is_empty(),
        Some((s, rest)) if s.trim() == "..." => {
            (0..=got.len()).any(|k| block_matches(rest, &got[k..]))
        }
        Some((s, rest)) => {
            !got.is_empty() && line_matches(s, got[0]) && block_matches(rest, &got[1..])
        }
    }
}

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// The text of a document, by its path relative to the repository root.
fn document(doc: &str) -> String {
    let p = root().join(doc);
    std::fs::read_to_string(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

fn block_dir(d: usize, k: usize) -> PathBuf {
    let d = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("readme-{}-{d}-{k}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

#[test]
fn console_examples_show_what_the_program_prints() {
    let bless = std::env::var("README_BLESS").is_ok_and(|v| v == "1");
    let mut failures = Vec::new();
    for (d, (doc, min_blocks, min_commands)) in DOCUMENTS.into_iter().enumerate() {
        let md = document(doc);
        let blocks = console_blocks(doc, &md);
        assert!(
            blocks.len() >= min_blocks,
            "{doc} has {} console blocks, expected at least {min_blocks}",
            blocks.len()
        );
        let mut lines: Vec<String> = md.lines().map(String::from).collect();
        // (line of the command, shown lines, printed lines) for README_BLESS
        let mut blessed: Vec<(usize, usize, Vec<String>)> = Vec::new();
        let mut ran = 0;
        for (k, block) in blocks.iter().enumerate() {
            let dir = block_dir(d, k);
            for ex in block {
                let got = run(&dir, ex);
                let got_lines: Vec<&str> = got.lines().collect();
                ran += 1;
                if bless {
                    let mut new: Vec<String> = got_lines.iter().map(|l| l.to_string()).collect();
                    if ex.shown.last().is_some_and(|l| l.trim() == "...") {
                        new.truncate(ex.shown.len() - 1);
                        new.push("...".into());
                    }
                    blessed.push((ex.line, ex.shown.len(), new));
                    continue;
                }
                if !block_matches(&ex.shown, &got_lines) {
                    failures.push(format!(
                        "{doc}:{}: $ {}\n--- shown\n{}\n--- printed\n{}",
                        ex.line,
                        ex.command,
                        ex.shown.join("\n"),
                        got.trim_end()
                    ));
                }
            }
            let _ = std::fs::remove_dir_all(&dir);
        }
        assert!(
            ran >= min_commands,
            "only {ran} commands found in {doc}, expected at least {min_commands}"
        );
        if bless {
            // from the last example, so that earlier line numbers stay valid
            for (line, n, new) in blessed.into_iter().rev() {
                lines.splice(line..line + n, new);
            }
            std::fs::write(root().join(doc), lines.join("\n") + "\n").unwrap();
        }
    }
    assert!(
        failures.is_empty(),
        "{} console example(s) disagree with the program:\n\n{}",
        failures.len(),
        failures.join("\n\n")
    );
}

/// Every markdown file under docs/ with a console block is one of `DOCUMENTS`: an example moved
/// into another document would otherwise never run.
#[test]
fn every_console_block_is_checked() {
    fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
        for e in std::fs::read_dir(dir).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                walk(&p, out);
            } else if p.extension().is_some_and(|x| x == "md") {
                out.push(p);
            }
        }
    }
    let mut files = Vec::new();
    walk(&root().join("docs"), &mut files);
    assert!(files.len() >= 4, "docs/ has {} markdown files", files.len());
    for f in files {
        let rel = f
            .strip_prefix(root())
            .unwrap()
            .to_str()
            .unwrap()
            .replace('\\', "/");
        let text = std::fs::read_to_string(&f).unwrap();
        let n = console_blocks(&rel, &text).len();
        assert!(
            n == 0 || DOCUMENTS.iter().any(|(doc, _, _)| *doc == rel),
            "{rel} has {n} console block(s) that tests/readme.rs does not run: add it to DOCUMENTS"
        );
    }
}

/// The matcher can fail: changed values, words, row counts and timings are told apart.
#[test]
fn the_comparison_tells_changes_from_noise() {
    // last-digit noise and timings pass
    assert!(line_matches(
        "0.1,0.7183848759893053,1",
        "0.1,0.7183848759893054,1"
    ));
    assert!(line_matches("x; 6 points; 0.9 ms", "x; 6 points; 12.5 ms"));
    assert!(line_matches(r#"  "time_ms": 3.1,"#, r#"  "time_ms": 0.4,"#));
    assert!(line_matches("residual 2.6e-15", "residual 3.1e-15"));
    // changed values, words and columns fail
    assert!(!line_matches(
        "0.1,0.7183848759893053,1",
        "0.1,0.7183848859893053,1"
    ));
    assert!(!line_matches("residual 2.6e-15", "residual 2.0e-11"));
    assert!(!line_matches("x; 6 points; 0.9 ms", "x; 7 points; 0.9 ms"));
    assert!(!line_matches("stopped: d_max", "stopped: slip"));
    assert!(!line_matches("d,mu,alpha", "d,mu,alpha,event"));
    assert!(!line_matches("0.0,,1", "0.0,1,1"));
    // `...` stands for any lines, other lines are all required
    let shown: Vec<String> = ["a", "b", "..."].iter().map(|s| s.to_string()).collect();
    assert!(block_matches(&shown, &["a", "b", "c", "d"]));
    assert!(block_matches(&shown, &["a", "b"]));
    assert!(!block_matches(&shown, &["a", "c"]));
    let exact: Vec<String> = ["a", "b"].iter().map(|s| s.to_string()).collect();
    assert!(!block_matches(&exact, &["a", "b", "c"]));
    assert!(!block_matches(&exact, &["a"]));
    // blocks and commands are found
    let md = "text\n```console\n$ vibrissa x\nout 1\n$ cat f\nrow\n```\n```sh\n$ no\n```\n";
    let b = console_blocks("x.md", md);
    assert_eq!(b.len(), 1);
    assert_eq!(b[0].len(), 2);
    assert_eq!(b[0][0].command, "vibrissa x");
    assert_eq!(b[0][0].shown, ["out 1"]);
    assert_eq!(b[0][1].line, 5);
}

/// The SLURM array example of the sweep section (docs/reference.md), run as written for one array task (task 25
/// of 50: the cheapest in a debug build, 0.6 s against 8 s for task 50), with the variables
/// SLURM would set. Its grid values are exact decimals.
#[test]
fn slurm_line_runs_as_written() {
    let reference = document("docs/reference.md");
    let block = reference
        .split("```sh")
        .find(|b| b.contains("#SBATCH"))
        .expect("the SLURM example");
    let block = &block[..block.find("```").unwrap()];
    // join the continuation lines of the command
    let cmd = block
        .lines()
        .skip_while(|l| !l.contains("vibrissa sweep"))
        .take_while(|l| !l.trim_start().starts_with('#'))
        .map(|l| l.trim_end().trim_end_matches('\\'))
        .collect::<Vec<_>>()
        .join(" ");
    let (k, n) = (25usize, 50usize);
    let cmd = cmd
        .replace("$(printf %04d ${K})", &format!("{k:04}"))
        .replace("${SLURM_CPUS_PER_TASK}", "2")
        .replace("${K}", &k.to_string())
        .replace("${N}", &n.to_string());
    assert!(!cmd.contains('$'), "unexpanded variable in {cmd}");
    let words: Vec<&str> = cmd.split_whitespace().collect();
    assert_eq!(words[0], "target/release/vibrissa", "{cmd}");
    let d = common::tmpdir("slurm");
    let o = common::run_in(&d, &words[1..]);
    assert_eq!(o.code, 0, "{cmd}: {}", o.stderr);
    let text = std::fs::read_to_string(d.join("part-0025.csv")).unwrap();
    // 46 × 20 × 3 = 2760 scenes in 50 shards: shard k has rows (k-1)·2760/50 .. k·2760/50
    // (integer division), and no header unless k = 1
    let (lo, hi) = ((k - 1) * 2760 / n, k * 2760 / n);
    let rows: Vec<Vec<&str>> = text.lines().map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), hi - lo);
    assert_eq!(rows[0][0], lo.to_string());
    for r in &rows {
        let idx: usize = r[0].parse().unwrap();
        // eta = 0.5 + 0.01 i (i = idx / 60), taper = 0.05 (j + 1) (j = idx / 3 % 20),
        // precurvature -1, 0, 1: each the nearest double of its decimal
        let (i, j, m) = (idx / 60, idx / 3 % 20, idx % 3);
        assert_eq!(
            r[1].parse::<f64>().unwrap(),
            (50 + i) as f64 / 100.0,
            "{r:?}"
        );
        assert_eq!(
            r[2].parse::<f64>().unwrap(),
            (5 * (j + 1)) as f64 / 100.0,
            "{r:?}"
        );
        assert_eq!(r[3].parse::<f64>().unwrap(), m as f64 - 1.0, "{r:?}");
        assert!(!r.contains(&"NaN"));
    }
}
