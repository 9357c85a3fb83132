//! Helpers shared by the end-to-end tests: run the built binary, check the error contract.
#![allow(dead_code)]

use std::path::PathBuf;
use std::process::{Child, Command};
use std::time::{Duration, Instant};

pub struct Out {
    pub code: i32,
    pub stdout: String,
    pub stderr: String,
}

pub fn run(args: &[&str]) -> Out {
    output(Command::new(env!("CARGO_BIN_EXE_vibrissa")).args(args))
}

/// Runs `cmd` to its end and collects its exit code and output.
fn output(cmd: &mut Command) -> Out {
    let o = cmd.output().expect("run vibrissa");
    Out {
        code: o.status.code().unwrap_or(-1),
        stdout: String::from_utf8_lossy(&o.stdout).into_owned(),
        stderr: String::from_utf8_lossy(&o.stderr).into_owned(),
    }
}

pub fn ok(args: &[&str]) -> Out {
    let o = run(args);
    assert_eq!(
        o.code, 0,
        "vibrissa {args:?} failed: {}\n{}",
        o.stderr, o.stdout
    );
    o
}

/// A bad invocation: non-zero exit, exactly one line on stderr starting with `error:`, no panic.
pub fn bad(args: &[&str], code: i32) -> String {
    let o = run(args);
    assert_eq!(o.code, code, "vibrissa {args:?}: stderr {:?}", o.stderr);
    let lines: Vec<&str> = o.stderr.lines().collect();
    assert_eq!(lines.len(), 1, "vibrissa {args:?}: stderr {:?}", o.stderr);
    assert!(lines[0].starts_with("error: "), "{:?}", lines[0]);
    assert!(!o.stderr.contains("panicked"), "{:?}", o.stderr);
    assert!(!o.stdout.contains("NaN"), "{:?}", o.stdout);
    lines[0].to_string()
}

pub fn tmpdir(name: &str) -> PathBuf {
    // Under target/ (not /tmp), so repeated runs leave nothing behind outside the build directory.
    let d = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("cli-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Parse a CSV with a header into (header, rows).
pub fn csv(text: &str) -> (Vec<String>, Vec<Vec<String>>) {
    let mut r = csv::ReaderBuilder::new()
        .has_headers(true)
        .from_reader(text.as_bytes());
    let h = r.headers().unwrap().iter().map(String::from).collect();
    let rows = r
        .records()
        .map(|x| x.unwrap().iter().map(String::from).collect())
        .collect();
    (h, rows)
}

pub fn col(h: &[String], row: &[String], name: &str) -> f64 {
    let i = h
        .iter()
        .position(|c| c == name)
        .unwrap_or_else(|| panic!("no column {name} in {h:?}"));
    row[i]
        .parse()
        .unwrap_or_else(|_| panic!("column {name}: {:?}", row[i]))
}

pub fn json(text: &str) -> serde_json::Value {
    serde_json::from_str(text).unwrap_or_else(|e| panic!("bad JSON {e}: {text}"))
}

pub fn close(a: f64, b: f64, tol: f64, what: &str) {
    assert!(
        (a - b).abs() <= tol,
        "{what}: {a} vs {b} (|diff| = {:e} > {tol:e})",
        (a - b).abs()
    );
}

/// Run the program in directory `dir`.
pub fn run_in(dir: &std::path::Path, args: &[&str]) -> Out {
    output(
        Command::new(env!("CARGO_BIN_EXE_vibrissa"))
            .args(args)
            .current_dir(dir),
    )
}

/// The names in a directory, sorted (hidden ones included: a temporary left behind shows).
pub fn listing(dir: &std::path::Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

/// Wait for `child` at most `secs` seconds; kill it and fail the test if it does not end.
pub fn wait_at_most(mut child: Child, secs: u64, what: &str) -> std::process::Output {
    let t0 = Instant::now();
    loop {
        if child.try_wait().unwrap().is_some() {
            return child.wait_with_output().unwrap();
        }
        if t0.elapsed() > Duration::from_secs(secs) {
            let _ = child.kill();
            let _ = child.wait();
            panic!("{what}: still running after {secs} s");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
}

/// Run with `input` written to stdin (`None`: stdin is empty), for at most 60 s.
pub fn run_fed(args: &[&str], input: Option<&str>) -> Out {
    use std::io::Write;
    use std::process::Stdio;
    let mut c = Command::new(env!("CARGO_BIN_EXE_vibrissa"))
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut stdin = c.stdin.take().unwrap();
    if let Some(text) = input {
        stdin.write_all(text.as_bytes()).unwrap();
    }
    drop(stdin);
    let o = wait_at_most(c, 60, &format!("vibrissa {args:?}"));
    Out {
        code: o.status.code().unwrap_or(-1),
        stdout: String::from_utf8_lossy(&o.stdout).into_owned(),
        stderr: String::from_utf8_lossy(&o.stderr).into_owned(),
    }
}
