//! A hang guard that counts the CPU time of the thread it watches, not the wall clock: the
//! tests run two at a time on two cores, often beside a build, and a drag that takes 5 s of CPU
//! can take 30 s of wall time then (CI on a15f669, run beside a release build: two named cases
//! of `contact_forces` cancelled at d ≈ 1e-11, in their presses).

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{self, RecvTimeoutError};
use std::sync::Arc;
use std::time::{Duration, Instant};

/// Clock ticks per second of `/proc`'s times (`sysconf(_SC_CLK_TCK)`, 100 on Linux).
const TICKS: f64 = 100.0;

/// The CPU seconds (user + system) of the thread at `/proc/self/task/<tid>/stat`, where
/// readable.
fn cpu_seconds(stat: &str) -> Option<f64> {
    let text = std::fs::read_to_string(stat).ok()?;
    // (the fields after the command's closing parenthesis: state is field 3, utime 14, stime 15)
    let rest = &text[text.rfind(')')? + 1..];
    let f: Vec<&str> = rest.split_whitespace().collect();
    let ticks = f.get(11)?.parse::<f64>().ok()? + f.get(12)?.parse::<f64>().ok()?;
    Some(ticks / TICKS)
}

/// Runs `work` on this thread and sets `flag` once `work` has used `hang` seconds of the
/// thread's CPU (of wall time where the thread's CPU time cannot be read, or after ten times
/// `hang` of wall time in any case).
pub fn guarded<T>(flag: Arc<AtomicBool>, hang: u64, work: impl FnOnce() -> T) -> T {
    // (the thread's stat file and its CPU time so far: a property test runs its cases one
    // after another on the thread)
    let probe = std::fs::read_link("/proc/thread-self")
        .ok()
        .map(|p| format!("/proc/{}/stat", p.display()))
        .and_then(|p| cpu_seconds(&p).map(|spent| (p, spent)));
    let (done, wait) = mpsc::channel::<()>();
    let guard = std::thread::spawn(move || {
        let start = Instant::now();
        let limit = Duration::from_secs(hang);
        loop {
            let (over, poll) = match &probe {
                Some((p, spent)) => (
                    cpu_seconds(p).is_some_and(|s| s - spent > hang as f64)
                        || start.elapsed() > 10 * limit,
                    Duration::from_millis(250),
                ),
                None => (
                    start.elapsed() > limit,
                    limit.saturating_sub(start.elapsed()),
                ),
            };
            if over {
                flag.store(true, Ordering::Relaxed);
                return;
            }
            match wait.recv_timeout(poll) {
                Err(RecvTimeoutError::Timeout) => continue,
                _ => return,
            }
        }
    });
    let out = work();
    drop(done);
    guard.join().unwrap();
    out
}
