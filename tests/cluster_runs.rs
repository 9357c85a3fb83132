//! Sweeps at cluster scale (issue 19): a killed sweep keeps its finished rows in a journal and the
//! same command resumes it to the bytes of an uninterrupted run (also per shard); a changed
//! command is refused; grid sizes are checked by arithmetic; mu0, d_max and the point count are
//! axes; a sweep whose every row failed exits 1 with its file written; a failed scan is never a
//! result row.

mod common;
use common::*;
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

fn vib() -> Command {
    Command::new(env!("CARGO_BIN_EXE_vibrissa"))
}

/// A sweep of 600 scenes that takes a second or two (debug build): long enough to be killed part
/// way.
const GRID: [&str; 9] = [
    "sweep",
    "--eta",
    "0.6:0.9:300",
    "--taper",
    "1,0.5",
    "--points",
    "11",
    "--d-max",
    "0.3",
];

/// Rows in a journal (the lines after `# rows`, complete or not).
fn journal_rows(p: &Path) -> usize {
    let t = std::fs::read_to_string(p).unwrap_or_default();
    t.split_once("# rows\n")
        .map_or(0, |(_, r)| r.lines().count())
}

/// Start `args` in `dir`, wait until its journal holds at least `rows` rows, send SIGTERM.
/// Returns the rows the journal holds afterwards.
#[cfg(unix)]
fn kill_part_way(dir: &Path, args: &[&str], journal: &Path, rows: usize) -> usize {
    let child = vib()
        .args(args)
        .current_dir(dir)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let t0 = Instant::now();
    while journal_rows(journal) < rows {
        assert!(t0.elapsed() < Duration::from_secs(60), "no rows appeared");
        std::thread::sleep(Duration::from_millis(2));
    }
    let st = Command::new("kill")
        .args(["-TERM", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(st.success());
    let o = wait_at_most(child, 60, "killed sweep");
    use std::os::unix::process::ExitStatusExt;
    assert_eq!(o.status.signal(), Some(15), "{:?}", o.status);
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(
        e.contains("finished rows are kept in") && e.contains("out.csv.journal"),
        "{e}"
    );
    journal_rows(journal)
}

/// Kill a sweep part way with SIGTERM (a cluster's time limit), rerun the same command: the file
/// is byte-identical to an uninterrupted run, whole and per shard; the user's old file stays as
/// it was until then, and nothing is left behind.
#[cfg(unix)]
#[test]
fn a_killed_sweep_resumes_to_the_bytes_of_an_uninterrupted_run() {
    let d = tmpdir("resume");
    for shard in [None, Some("2/3")] {
        let mut args: Vec<&str> = GRID.to_vec();
        if let Some(s) = shard {
            args.extend(["--shard", s]);
        }
        let whole = ok(&args).stdout;
        let total = whole.lines().count() - (shard.is_none() as usize);
        args.extend(["--out", "out.csv"]);
        std::fs::write(d.join("out.csv"), "precious\n").unwrap();
        let journal = d.join("out.csv.journal");
        let kept = kill_part_way(&d, &args, &journal, 10);
        assert!(
            kept >= 10 && kept < total,
            "{shard:?}: {kept} of {total} rows"
        );
        assert_eq!(listing(&d), ["out.csv", "out.csv.journal"], "{shard:?}");
        assert_eq!(
            std::fs::read_to_string(d.join("out.csv")).unwrap(),
            "precious\n"
        );
        // the journal's rows are the output's rows, in order
        let jt = std::fs::read_to_string(&journal).unwrap();
        let rows = jt.split_once("# rows\n").unwrap().1;
        let body: String =
            whole
                .lines()
                .skip(shard.is_none() as usize)
                .fold(String::new(), |mut s, l| {
                    s.push_str(l);
                    s.push('\n');
                    s
                });
        let complete = &rows[..rows.rfind('\n').map_or(0, |i| i + 1)];
        assert!(body.starts_with(complete), "{shard:?}: journal rows differ");
        // a row cut short by the kill is dropped
        let mut f = std::fs::OpenOptions::new()
            .append(true)
            .open(&journal)
            .unwrap();
        std::io::Write::write_all(&mut f, b"999,0.7,1.0,0.0,cut sh").unwrap();
        drop(f);
        // a dry run says what is there, and changes nothing
        let o = run_in(&d, &[&args[..], &["--dry-run"]].concat());
        assert_eq!(o.code, 0, "{}", o.stderr);
        assert!(
            o.stderr.contains(&format!(
                "{} of {total} rows done",
                complete.lines().count()
            )),
            "{}",
            o.stderr
        );
        // the same command (another --jobs is the same sweep) resumes and completes
        let o = run_in(&d, &[&args[..], &["--jobs", "1"]].concat());
        assert_eq!(o.code, 0, "{shard:?}: {}", o.stderr);
        assert_eq!(
            std::fs::read_to_string(d.join("out.csv")).unwrap(),
            whole,
            "{shard:?}: the resumed file differs from an uninterrupted run"
        );
        assert_eq!(listing(&d), ["out.csv"], "{shard:?}: the journal stays");
    }
}

/// A journal of another sweep is never mixed in: the command is refused before any work, naming
/// each difference; a file that is not a journal is never touched.
#[cfg(unix)]
#[test]
fn a_changed_command_does_not_resume() {
    let d = tmpdir("changed");
    let args = [&GRID[..], &["--out", "out.csv"]].concat();
    let journal = d.join("out.csv.journal");
    kill_part_way(&d, &args, &journal, 5);
    let before = std::fs::read(&journal).unwrap();
    let scene = d.join("s.toml");
    std::fs::write(&scene, "support_compliance = 0.5\n").unwrap();
    let scene = scene.to_str().unwrap();
    for (change, want) in [
        (&["--taper", "1,0.4"][..], "(--taper was 1,0.5, now 1,0.4)"),
        (&["--points", "12"], "--points was 11, now 12"),
        (&["--mu0", "0.5"], "--mu0 was not given, now 0.5"),
        (&["--timing"], "--timing was false, now true"),
        (&["--shard", "1/2"], "--shard was not given, now 1/2"),
        (&["--scene", scene], "base scene was"),
    ] {
        let mut a: Vec<&str> = args.clone();
        // replace a flag's value, or add the flag
        match a.iter().position(|x| *x == change[0]) {
            Some(i) => a[i + 1] = change[1],
            None => a.extend(change),
        }
        let m = bad_in(&d, &a, 2);
        assert!(
            m.contains("holds the finished rows of a different sweep")
                && m.contains(want)
                && m.contains("delete"),
            "{change:?}: {m}"
        );
        assert_eq!(std::fs::read(&journal).unwrap(), before, "{change:?}");
        assert_eq!(listing(&d), ["out.csv.journal", "s.toml"], "{change:?}");
    }
    // not a journal: refused, untouched
    std::fs::write(&journal, "my notes\n").unwrap();
    let m = bad_in(&d, &args, 2);
    assert!(m.contains("is not a sweep journal"), "{m}");
    assert_eq!(std::fs::read_to_string(&journal).unwrap(), "my notes\n");
}

/// `bad` in a directory.
fn bad_in(dir: &Path, args: &[&str], code: i32) -> String {
    let o = run_in(dir, args);
    assert_eq!(o.code, code, "{args:?}: {}", o.stderr);
    let lines: Vec<&str> = o.stderr.lines().collect();
    assert_eq!(lines.len(), 1, "{args:?}: {:?}", o.stderr);
    assert!(lines[0].starts_with("error: "), "{:?}", lines[0]);
    lines[0].to_string()
}

/// The size of a grid is the product of its axes' lengths: a 10^21-scene grid is refused at
/// once, and a 10^9-scene one accepted, in an address space of 256 MB (the grid used to be built
/// to count it: 0.94 GB and 11 s for 10^21).
#[cfg(unix)]
#[test]
fn grid_sizes_are_arithmetic() {
    let limited = |args: &[&str]| {
        let o = Command::new("sh")
            .arg("-c")
            .arg("ulimit -v 262144 && exec \"$0\" \"$@\"")
            .arg(env!("CARGO_BIN_EXE_vibrissa"))
            .args(args)
            .output()
            .unwrap();
        (
            o.status.code(),
            String::from_utf8_lossy(&o.stderr).into_owned(),
        )
    };
    let (code, e) = limited(&[
        "sweep",
        "--eta",
        "0.5:0.9:10000000",
        "--taper",
        "0.1:1:10000000",
        "--precurvature",
        "-1:1:10000000",
        "--dry-run",
    ]);
    assert_eq!(code, Some(2), "{e}");
    assert!(
        e.starts_with("error: the grid has 10000000 (--eta) × 10000000 (--taper) × 10000000 (--precurvature) = 1e21 scenes, more than the limit of 1e9"),
        "{e}"
    );
    let (code, e) = limited(&[
        "sweep",
        "--eta",
        "0.5:0.9:10000000",
        "--taper",
        "0.1:1:100",
        "--dry-run",
    ]);
    assert_eq!(code, Some(0), "{e}");
    assert!(e.contains("sweep: 1000000000 scenes"), "{e}");
    // the ends of a range are checked, so a value outside is found without listing the range
    let (code, e) = limited(&["sweep", "--eta", "0.5:1.5:10000000", "--dry-run"]);
    assert_eq!(code, Some(2), "{e}");
    assert!(e.contains("--eta 1.5 is outside"), "{e}");
}

/// `--mu0`, `--d-max` and `--points` are axes like the others: their columns, grid order (the
/// point count fastest), and each row is the scan of its settings.
#[test]
fn mu0_d_max_and_points_are_axes() {
    let o = ok(&[
        "sweep",
        "--mu0",
        "0.3,inf",
        "--d-max",
        "0.05:0.1:2",
        "--points",
        "3,6",
    ]);
    let (h, rows) = csv(&o.stdout);
    assert_eq!(rows.len(), 8);
    let cell = |r: &Vec<String>, c: &str| r[h.iter().position(|x| x == c).unwrap()].clone();
    let mut seen = Vec::new();
    for r in &rows {
        let (mu0, d_max, n) = (cell(r, "mu0"), cell(r, "d_max"), cell(r, "grid_points"));
        seen.push(format!("{mu0}/{d_max}/{n}"));
        // the same scan by `scan`
        let mut a = vec!["scan", "--d-max", &d_max, "--points", &n, "--json"];
        if !mu0.is_empty() {
            a.extend(["--mu0", &mu0]);
        }
        let v = json(&ok(&a).stdout);
        assert_eq!(cell(r, "stop_reason"), v["stop_reason"].as_str().unwrap());
        assert_eq!(col(&h, r, "mu_max"), v["mu_max"].as_f64().unwrap(), "{r:?}");
        assert_eq!(col(&h, r, "points"), v["points"].as_f64().unwrap(), "{r:?}");
    }
    assert_eq!(
        seen,
        [
            "0.3/0.05/3",
            "0.3/0.05/6",
            "0.3/0.1/3",
            "0.3/0.1/6",
            "/0.05/3",
            "/0.05/6",
            "/0.1/3",
            "/0.1/6"
        ]
    );
    // mu0 = 0.3 slips before d = 0.021, where 0.5 does (docs/reference.md, scan), inside both ranges
    assert!(rows[..4].iter().all(|r| cell(r, "stop_reason") == "slip"));
    assert!(rows[4..].iter().all(|r| cell(r, "stop_reason") == "d_max"));
    for (args, want) in [
        (
            &["--points", "11:200:3"][..],
            "--points 11:200:3 gives 105.5, not a whole number",
        ),
        (
            &["--points", "1,5"],
            "--points 1 is outside the valid range [2, 1000000]",
        ),
        (&["--points", "2000000"], "--points 2000000"),
        (&["--d-max", "0:1:3"], "--d-max 0 is outside"),
        (&["--d-max", "0.5,2"], "--d-max 2 is outside"),
        (&["--mu0", "0.5,-1"], "--mu0 -1 is outside"),
        (&["--mu0", "0:inf:3"], "--mu0"),
    ] {
        let m = bad(&[&["sweep", "--dry-run"][..], args].concat(), 2);
        assert!(m.contains(want), "{args:?}: {m}");
    }
}

/// A sweep in which every scene failed writes its file (each row says why) and exits 1; one
/// result among failures is a success (exit 0); the same per shard.
#[test]
fn a_sweep_with_no_result_exits_1_with_its_file() {
    let d = tmpdir("allfailed");
    // the closed forms exist only for the uniform rod
    let args = [
        "sweep", "--method", "analytic", "--taper", "0.5,0.8", "--points", "3", "--out", "f.csv",
    ];
    let m = bad_in(&d, &args, 1);
    assert_eq!(
        m,
        "error: every scene failed (2 of 2 rows have an error; the error column says why); written to f.csv"
    );
    let (h, rows) = csv(&std::fs::read_to_string(d.join("f.csv")).unwrap());
    assert_eq!(rows.len(), 2);
    for r in &rows {
        assert!(r.last().unwrap().contains("analytic"), "{r:?}");
        assert_eq!(
            r[h.iter().position(|c| c == "stop_reason").unwrap()],
            "error"
        );
    }
    assert_eq!(listing(&d), ["f.csv"], "no journal or temporary left");
    // one result: exit 0
    let o = run_in(
        &d,
        &[
            "sweep", "--method", "analytic", "--taper", "1,0.5", "--points", "3",
        ],
    );
    assert_eq!(o.code, 0, "{}", o.stderr);
    assert_eq!(csv(&o.stdout).1.len(), 2);
    // per shard: shard 2/2 holds only the failing scene
    let sharded = [
        "sweep", "--method", "analytic", "--taper", "1,0.5", "--points", "3", "--shard",
    ];
    let o = run(&[&sharded[..], &["2/2"]].concat());
    assert_eq!(o.code, 1);
    assert!(
        o.stderr
            .starts_with("error: every scene of shard 2/2 failed (1 of 1 rows"),
        "{}",
        o.stderr
    );
    assert_eq!(o.stdout.lines().count(), 1, "the row is written");
    assert_eq!(run(&[&sharded[..], &["1/2"]].concat()).code, 0);
}

/// The scene whose default scan ends in a solver failure (`--eta 0.9 --taper 0.8
/// --precurvature 0.5 --support-compliance 0.5`): its row never looks like a result. Whatever the
/// engine does with it, a row is either a result (empty `error`, a `stop_reason` that is an
/// event or d_max) or names its failure, and a failed scan's `mu_max` is empty or at a d the scan
/// reached.
#[test]
fn a_failed_scan_is_not_a_result_row() {
    let o = run(&[
        "sweep",
        "--eta",
        "0.9",
        "--taper",
        "0.8",
        "--precurvature",
        "-0.5,0.5",
        "--support-compliance",
        "0.5",
    ]);
    let (h, rows) = csv(&o.stdout);
    assert_eq!(rows.len(), 2, "{}", o.stderr);
    let cell = |r: &Vec<String>, c: &str| r[h.iter().position(|x| x == c).unwrap()].clone();
    let mut failed = 0;
    for r in &rows {
        let (stop, err) = (cell(r, "stop_reason"), cell(r, "error"));
        match stop.as_str() {
            "d_max" | "slip" | "lift_off" | "penetration" | "fold_in_d" => {
                assert!(err.is_empty(), "{r:?}")
            }
            "solver_failure" => {
                failed += 1;
                assert!(err.starts_with("solver failure after d = "), "{r:?}");
                let mu_max = cell(r, "mu_max");
                if !mu_max.is_empty() {
                    assert!(col(&h, r, "d_at_mu_max") <= col(&h, r, "d_end"), "{r:?}");
                }
            }
            "error" => {
                failed += 1;
                assert!(!err.is_empty(), "{r:?}");
            }
            other => panic!("stop_reason {other}: {r:?}"),
        }
    }
    assert_eq!(
        o.code,
        if failed == rows.len() { 1 } else { 0 },
        "{}",
        o.stderr
    );
}
