//! README.md stays true: every `console` example is run and its output compared with what the
//! README shows (numbers to 1e-9 relative, wall times skipped, `...` ends a shown prefix), and
//! the SLURM example line of the sweep section runs as written.

mod common;
use common::*;

const README: &str = include_str!("../README.md");

/// Tokens of a line: numbers and words, split at CSV and prose punctuation.
fn tokens(line: &str) -> Vec<&str> {
    line.split([',', ' ', ';', '(', ')', '=', ':'])
        .filter(|t| !t.is_empty())
        .collect()
}

fn same_line(want: &str, got: &str) -> Result<(), String> {
    let (w, g) = (tokens(want), tokens(got));
    if w.len() != g.len() {
        return Err(format!("{} tokens instead of {}", g.len(), w.len()));
    }
    for i in 0..w.len() {
        // wall times ("0.9 ms") differ from run to run
        if w.get(i + 1) == Some(&"ms") {
            continue;
        }
        match (w[i].parse::<f64>(), g[i].parse::<f64>()) {
            (Ok(a), Ok(b)) => {
                if (a - b).abs() > 1e-9 * a.abs().max(1.0) {
                    return Err(format!("{} instead of {}", g[i], w[i]));
                }
            }
            _ => {
                if w[i] != g[i] {
                    return Err(format!("{:?} instead of {:?}", g[i], w[i]));
                }
            }
        }
    }
    Ok(())
}

/// A `console` example: the command line, the index of its first output line in README, the
/// output lines shown.
struct Example {
    cmd: String,
    first: usize,
    want: Vec<String>,
}

fn examples() -> Vec<Example> {
    let mut out: Vec<Example> = Vec::new();
    let mut in_block = false;
    for (i, line) in README.lines().enumerate() {
        if line.starts_with("```console") {
            in_block = true;
            continue;
        }
        if in_block && line.starts_with("```") {
            in_block = false;
            continue;
        }
        if !in_block {
            continue;
        }
        if let Some(cmd) = line.strip_prefix("$ ") {
            out.push(Example {
                cmd: cmd.to_string(),
                first: i + 1,
                want: Vec::new(),
            });
        } else if let Some(last) = out.last_mut() {
            last.want.push(line.to_string());
        }
    }
    out
}

/// Run the examples in order in one directory (later ones read files of earlier ones).
/// `VIBRISSA_UPDATE_README=1` writes the outputs of this build into README.md instead of
/// comparing (for a deliberate change of the program's output; review the diff).
#[test]
fn readme_console_examples_print_what_readme_shows() {
    let d = tmpdir("readme");
    let ex = examples();
    assert!(ex.len() >= 6, "{} examples", ex.len());
    let update = std::env::var_os("VIBRISSA_UPDATE_README").is_some();
    let mut lines: Vec<String> = README.lines().map(String::from).collect();
    let mut failures = Vec::new();
    // replaced from the end, so that earlier line numbers stay valid
    let mut edits = Vec::new();
    for e in &ex {
        let words: Vec<&str> = e.cmd.split_whitespace().collect();
        let got = match words[0] {
            "vibrissa" => {
                let o = run_in(&d, &words[1..]);
                assert_eq!(o.code, 0, "$ {}: {}", e.cmd, o.stderr);
                o.stdout
            }
            "cat" => std::fs::read_to_string(d.join(words[1])).unwrap(),
            other => panic!("README example runs {other}: not supported by this test"),
        };
        let got: Vec<&str> = got.lines().collect();
        let shown = e.want.iter().take_while(|l| l.trim() != "...").count();
        let prefix = shown < e.want.len();
        if update {
            let mut new: Vec<String> = got
                .iter()
                .take(if prefix { shown } else { got.len() })
                .map(|s| s.to_string())
                .collect();
            if prefix {
                new.push("...".into());
            }
            edits.push((e.first, e.want.len(), new));
            continue;
        }
        if (prefix && got.len() < shown) || (!prefix && got.len() != shown) {
            failures.push(format!(
                "$ {}: {} lines instead of {}{}:\n{}",
                e.cmd,
                got.len(),
                if prefix { "at least " } else { "" },
                shown,
                got.join("\n")
            ));
            continue;
        }
        for (w, g) in e.want.iter().zip(&got).take(shown) {
            if let Err(err) = same_line(w, g) {
                failures.push(format!("$ {}: {err}\n  README: {w}\n  now:    {g}", e.cmd));
            }
        }
    }
    if update {
        for (first, len, new) in edits.into_iter().rev() {
            lines.splice(first..first + len, new);
        }
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/README.md");
        std::fs::write(path, lines.join("\n") + "\n").unwrap();
        return;
    }
    assert!(
        failures.is_empty(),
        "README is out of date (rerun with VIBRISSA_UPDATE_README=1 after a deliberate change):\n{}",
        failures.join("\n")
    );
}

/// The SLURM array example of the sweep section, run as written for one array task (task 25
/// of 50: the cheapest in a debug build, 0.6 s against 8 s for task 50), with the variables
/// SLURM would set. Its grid values are exact decimals.
#[test]
fn readme_slurm_line_runs_as_written() {
    let block = README
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
    let d = tmpdir("slurm");
    let o = run_in(&d, &words[1..]);
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
