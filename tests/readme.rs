//! README.md's console examples are run and compared with what they show, so they cannot drift,
//! and the SLURM example line of the sweep section runs as written.
//!
//! Every ```` ```console ```` block of README.md is a session: lines starting with `$ ` are
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
//! `...` keeps as many lines as it showed) instead of comparing; review the diff of README.md.

mod common;

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

/// One `$ command` of a console block and the output lines shown under it.
#[derive(Debug)]
struct Example {
    /// line number of the command in README.md (1-based)
    line: usize,
    command: String,
    shown: Vec<String>,
}

/// The console blocks of a markdown text, each a list of examples.
fn console_blocks(md: &str) -> Vec<Vec<Example>> {
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
                        line: i + 1,
                        command: c.trim().to_string(),
                        shown: Vec::new(),
                    });
                } else {
                    let e = b
                        .last_mut()
                        .unwrap_or_else(|| panic!("README.md:{}: output before any `$ `", i + 1));
                    e.shown.push(t.to_string());
                }
            }
        }
    }
    assert!(cur.is_none(), "README.md: unterminated console block");
    blocks
}

/// Run one command in `dir`; returns stdout and stderr as written (one file for both).
fn run(dir: &Path, ex: &Example) -> String {
    assert!(
        !ex.command.contains(['"', '\'', '|', '>', '<', '&', '$']),
        "README.md:{}: quoting, pipes and redirections are not supported here: {}",
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
                "README.md:{}: killed by a signal",
                ex.line
            );
            text
        }
        "cat" => words[1..]
            .iter()
            .map(|f| {
                std::fs::read_to_string(dir.join(f))
                    .unwrap_or_else(|e| panic!("README.md:{}: cat {f}: {e}", ex.line))
            })
            .collect(),
        w => panic!(
            "README.md:{}: unsupported command `{w}` in a console block (vibrissa, cat)",
            ex.line
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

fn readme() -> String {
    let p = Path::new(env!("CARGO_MANIFEST_DIR")).join("README.md");
    std::fs::read_to_string(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

fn block_dir(k: usize) -> PathBuf {
    let d = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("readme-{}-{k}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

#[test]
fn readme_console_examples_show_what_the_program_prints() {
    let md = readme();
    let blocks = console_blocks(&md);
    assert!(
        blocks.len() >= 5,
        "README.md has {} console blocks",
        blocks.len()
    );
    let bless = std::env::var("README_BLESS").is_ok_and(|v| v == "1");
    let mut lines: Vec<String> = md.lines().map(String::from).collect();
    let mut failures = Vec::new();
    // (line of the command, shown lines, printed lines) for README_BLESS
    let mut blessed: Vec<(usize, usize, Vec<String>)> = Vec::new();
    let mut ran = 0;
    for (k, block) in blocks.iter().enumerate() {
        let dir = block_dir(k);
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
                    "README.md:{}: $ {}\n--- shown\n{}\n--- printed\n{}",
                    ex.line,
                    ex.command,
                    ex.shown.join("\n"),
                    got.trim_end()
                ));
            }
        }
        let _ = std::fs::remove_dir_all(&dir);
    }
    assert!(ran >= 8, "only {ran} README commands found");
    if bless {
        // from the last example, so that earlier line numbers stay valid
        for (line, n, new) in blessed.into_iter().rev() {
            lines.splice(line..line + n, new);
        }
        let p = Path::new(env!("CARGO_MANIFEST_DIR")).join("README.md");
        std::fs::write(&p, lines.join("\n") + "\n").unwrap();
        return;
    }
    assert!(
        failures.is_empty(),
        "{} README example(s) disagree with the program:\n\n{}",
        failures.len(),
        failures.join("\n\n")
    );
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
    let b = console_blocks(md);
    assert_eq!(b.len(), 1);
    assert_eq!(b[0].len(), 2);
    assert_eq!(b[0][0].command, "vibrissa x");
    assert_eq!(b[0][0].shown, ["out 1"]);
    assert_eq!(b[0][1].line, 5);
}

/// The SLURM array example of the sweep section, run as written for one array task (task 25
/// of 50: the cheapest in a debug build, 0.6 s against 8 s for task 50), with the variables
/// SLURM would set. Its grid values are exact decimals.
#[test]
fn readme_slurm_line_runs_as_written() {
    let readme = readme();
    let block = readme
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
