//! The output policy (src/output_files.rs), end to end: whole-command atomic files, symbolic links
//! written through, devices and FIFOs written in place, long names, permissions kept, cleanup
//! on SIGINT/SIGTERM, I/O errors that name the output, and a sweep that stops when its reader
//! goes away or its output fails.

mod common;
use common::*;
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

fn vib() -> Command {
    Command::new(env!("CARGO_BIN_EXE_vibrissa"))
}

fn temporaries(dir: &Path) -> Vec<String> {
    listing(dir)
        .into_iter()
        .filter(|n| n.ends_with(".part"))
        .collect()
}

#[test]
fn outputs_replace_together_or_not_at_all() {
    let d = tmpdir("atomic");
    std::fs::write(d.join("a.csv"), "old a\n").unwrap();
    std::fs::write(d.join("b.csv"), "old b\n").unwrap();
    // success: both replaced
    let o = run_in(
        &d,
        &[
            "scan", "--points", "3", "--out", "a.csv", "--shapes", "b.csv",
        ],
    );
    assert_eq!(o.code, 0, "{}", o.stderr);
    assert!(std::fs::read_to_string(d.join("a.csv"))
        .unwrap()
        .starts_with("d,mu"));
    assert!(std::fs::read_to_string(d.join("b.csv"))
        .unwrap()
        .starts_with("point,d"));
    // a failure after the first output was complete: neither changes
    std::fs::write(d.join("a.csv"), "old a\n").unwrap();
    let o = run_in(
        &d,
        &[
            "scan",
            "--points",
            "3",
            "--out",
            "a.csv",
            "--shapes",
            "/dev/full",
        ],
    );
    assert_eq!(o.code, 1);
    assert!(o.stderr.contains("--shapes /dev/full"), "{}", o.stderr);
    assert_eq!(std::fs::read_to_string(d.join("a.csv")).unwrap(), "old a\n");
    assert_eq!(listing(&d), ["a.csv", "b.csv"]);
}

#[cfg(unix)]
#[test]
fn symlinks_are_written_through_and_permissions_kept() {
    use std::os::unix::fs::PermissionsExt;
    let d = tmpdir("links");
    std::fs::create_dir(d.join("real")).unwrap();
    std::fs::write(d.join("real/target.csv"), "old\n").unwrap();
    std::fs::set_permissions(
        d.join("real/target.csv"),
        std::fs::Permissions::from_mode(0o640),
    )
    .unwrap();
    std::os::unix::fs::symlink("real/target.csv", d.join("link.csv")).unwrap();
    // a dangling link: the file it names is created
    std::os::unix::fs::symlink("real/new.csv", d.join("dangling.csv")).unwrap();
    let o = run_in(
        &d,
        &[
            "scan",
            "--points",
            "3",
            "--out",
            "link.csv",
            "--shapes",
            "dangling.csv",
        ],
    );
    assert_eq!(o.code, 0, "{}", o.stderr);
    for (link, target) in [
        ("link.csv", "real/target.csv"),
        ("dangling.csv", "real/new.csv"),
    ] {
        let m = std::fs::symlink_metadata(d.join(link)).unwrap();
        assert!(m.file_type().is_symlink(), "{link} was replaced by a file");
        assert_eq!(std::fs::read_link(d.join(link)).unwrap(), Path::new(target));
        assert!(std::fs::read_to_string(d.join(target)).unwrap().len() > 100);
    }
    let mode = std::fs::metadata(d.join("real/target.csv"))
        .unwrap()
        .permissions()
        .mode();
    assert_eq!(mode & 0o777, 0o640, "permissions of the replaced file");
    assert_eq!(listing(&d.join("real")), ["new.csv", "target.csv"]);
}

#[cfg(unix)]
#[test]
fn devices_and_fifos_are_written_in_place() {
    use std::os::unix::fs::FileTypeExt;
    let o = run(&[
        "scan",
        "--points",
        "3",
        "--out",
        "/dev/null",
        "--shapes",
        "/dev/stderr",
    ]);
    assert_eq!(o.code, 0, "{}", o.stderr);
    assert!(
        o.stderr.contains("point,d,s"),
        "shapes went to stderr in place"
    );
    let m = std::fs::metadata("/dev/null").unwrap();
    assert!(
        m.file_type().is_char_device(),
        "/dev/null is no longer a device"
    );
    // a FIFO: a reader gets the CSV, the FIFO stays a FIFO
    let d = tmpdir("fifo");
    let fifo = d.join("pipe.csv");
    let st = Command::new("mkfifo").arg(&fifo).status().unwrap();
    assert!(st.success());
    let f2 = fifo.clone();
    let reader = std::thread::spawn(move || std::fs::read_to_string(f2).unwrap());
    let o = run(&["scan", "--points", "3", "--out", fifo.to_str().unwrap()]);
    assert_eq!(o.code, 0, "{}", o.stderr);
    let text = reader.join().unwrap();
    assert!(text.starts_with("d,mu,alpha"), "{text:?}");
    assert_eq!(text.lines().count(), 4);
    assert!(std::fs::metadata(&fifo).unwrap().file_type().is_fifo());
    assert_eq!(listing(&d), ["pipe.csv"]);
    // the device reports a full disk: the error names the output
    let o = run(&["scan", "--points", "3", "--out", "/dev/full"]);
    assert_eq!(o.code, 1);
    assert!(
        o.stderr.contains("writing --out /dev/full: No space left"),
        "{}",
        o.stderr
    );
    // stdout on a full device, for every command that prints to it
    for args in [
        &["scan", "--points", "3"][..],
        &["scan", "--points", "3", "--json"],
        &["solve", "--alpha", "0", "--phi1", "0.3"],
        &["infer", "--d0", "0.05", "--points", "5"],
        &["sweep", "--eta", "0.7", "--points", "3"],
    ] {
        let full = std::fs::OpenOptions::new()
            .write(true)
            .open("/dev/full")
            .unwrap();
        let o = vib().args(args).stdout(Stdio::from(full)).output().unwrap();
        assert_eq!(o.status.code(), Some(1), "{args:?}");
        let e = String::from_utf8_lossy(&o.stderr);
        assert!(e.contains("writing stdout: No space left"), "{args:?}: {e}");
    }
    // stderr on a full device: warnings and summaries are lost, never a panic
    for (args, code) in [
        (&["scan", "--points", "3", "--eta", "0.6"][..], 0),
        (&["scan", "--eta", "0.3"], 2),
        (&["sweep", "--eta", "0.7", "--dry-run"], 0),
    ] {
        let full = std::fs::OpenOptions::new()
            .write(true)
            .open("/dev/full")
            .unwrap();
        let o = vib()
            .args(args)
            .stdout(Stdio::null())
            .stderr(Stdio::from(full))
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(code), "{args:?}");
    }
}

#[test]
fn help_to_a_full_device_is_an_error() {
    let full = std::fs::OpenOptions::new()
        .write(true)
        .open("/dev/full")
        .unwrap();
    let o = vib()
        .arg("--help")
        .stdout(Stdio::from(full))
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(1));
    let e = String::from_utf8_lossy(&o.stderr);
    assert_eq!(e.lines().count(), 1, "{e}");
    assert!(
        e.starts_with("error: ") && e.contains("No space left"),
        "{e}"
    );
    // a reader that stops early is not an error
    let mut c = vib()
        .args(["scan", "--help"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(c.stdout.take());
    let o = c.wait_with_output().unwrap();
    assert_eq!(o.status.code(), Some(0), "{:?}", o);
}

#[test]
fn long_names_work() {
    let d = tmpdir("long");
    // 255 bytes, NAME_MAX on Linux file systems: the temporary name must be shorter
    for len in [249, 255] {
        let name = format!("{}.csv", "a".repeat(len - 4));
        let o = run_in(&d, &["scan", "--points", "3", "--out", &name]);
        assert_eq!(o.code, 0, "{len}: {}", o.stderr);
        assert!(d.join(&name).exists());
    }
    assert!(temporaries(&d).is_empty());
}

#[cfg(unix)]
#[test]
fn signals_remove_temporaries() {
    for sig in ["TERM", "INT", "HUP"] {
        let d = tmpdir(&format!("sig{sig}"));
        std::fs::write(d.join("out.csv"), "precious\n").unwrap();
        // a sweep long enough to be interrupted (thousands of scans)
        let child = vib()
            .args(["sweep", "--eta", "0.6:0.9:5000", "--out", "out.csv"])
            .current_dir(&d)
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        // wait until the temporary exists, then signal
        let t0 = Instant::now();
        while temporaries(&d).is_empty() {
            assert!(
                t0.elapsed() < Duration::from_secs(60),
                "no temporary appeared"
            );
            std::thread::sleep(Duration::from_millis(10));
        }
        let st = Command::new("sh")
            .args(["-c", &format!("kill -{sig} {}", child.id())])
            .status()
            .unwrap();
        assert!(st.success());
        let o = wait_at_most(child, 60, "signalled sweep");
        assert!(!o.status.success(), "SIG{sig}: {:?}", o.status);
        // the sweep's journal of finished rows stays (tests/cluster_runs.rs resumes one)
        let left: Vec<String> = listing(&d)
            .into_iter()
            .filter(|n| n != "out.csv.journal")
            .collect();
        assert_eq!(left, ["out.csv"], "SIG{sig} left a temporary");
        assert_eq!(
            std::fs::read_to_string(d.join("out.csv")).unwrap(),
            "precious\n"
        );
    }
}

#[test]
fn sweep_stops_when_its_reader_goes_away_or_its_output_fails() {
    use std::io::{BufRead, BufReader};
    // 10^6 scenes would take hours: the sweep must stop soon after the reader closes
    let mut child = vib()
        .args(["sweep", "--eta", "0.6:0.9:1000000", "--points", "21"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut header = String::new();
    BufReader::new(child.stdout.take().unwrap())
        .read_line(&mut header)
        .unwrap();
    assert!(header.starts_with("index,eta"), "{header:?}");
    let o = wait_at_most(child, 120, "sweep after its reader closed");
    assert_eq!(o.status.code(), Some(0));
    assert!(
        o.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    // a failing output: exit 1 with the output named, long before the grid is done
    let child = vib()
        .args([
            "sweep",
            "--eta",
            "0.6:0.9:1000000",
            "--points",
            "21",
            "--out",
            "/dev/full",
        ])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let o = wait_at_most(child, 120, "sweep with a failing output");
    assert_eq!(o.status.code(), Some(1));
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(e.contains("--out /dev/full"), "{e}");
}

#[test]
fn jobs_are_capped_with_a_warning() {
    let o = run(&["sweep", "--eta", "0.7,0.8", "--jobs", "4096", "--dry-run"]);
    assert_eq!(o.code, 0, "{}", o.stderr);
    assert!(o.stderr.contains("warning: --jobs 4096"), "{}", o.stderr);
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    // capped at 4 per core, then at the number of scenes (2)
    assert!(
        o.stderr.contains(&format!("using {}", 4 * cores)) && o.stderr.contains("2 threads"),
        "{}",
        o.stderr
    );
}

#[test]
fn dash_is_stdout() {
    let d = tmpdir("dash");
    let o = run_in(&d, &["scan", "--points", "3", "--out", "-"]);
    assert_eq!(o.code, 0, "{}", o.stderr);
    assert!(o.stdout.starts_with("d,mu,alpha"), "{}", o.stdout);
    assert_eq!(o.stdout.lines().count(), 4, "only the table on stdout");
    let o = run_in(
        &d,
        &["sweep", "--eta", "0.7", "--points", "3", "--out", "-"],
    );
    assert_eq!(o.code, 0, "{}", o.stderr);
    assert!(o.stdout.starts_with("index,eta"), "{}", o.stdout);
    assert!(listing(&d).is_empty(), "{:?}", listing(&d));
}
