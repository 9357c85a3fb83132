//! Progress on stderr, only when stderr is a terminal (never on a pipe or in a file): a spinner
//! with the elapsed time for single computations that take longer than a second, and the sweep's
//! bar (in `sweep`). Anything the program prints to the terminal first clears the spinner, so a
//! line of output never shares the spinner's line.

use std::io::IsTerminal;
use std::sync::mpsc::{self, RecvTimeoutError, Sender};
use std::sync::Mutex;
use std::thread::JoinHandle;
use std::time::Duration;

/// A computation shorter than this shows nothing.
pub const DELAY: Duration = Duration::from_secs(1);

struct Active {
    stop: Sender<()>,
    thread: JoinHandle<()>,
}

static SPINNER: Mutex<Option<Active>> = Mutex::new(None);

/// Start the spinner for `label` (shown after [`DELAY`], if stderr is a terminal). `lines`:
/// print a full line every few seconds instead of redrawing one line, for commands whose output
/// this module cannot clear the spinner before (`figures`).
pub fn start(label: &str, lines: bool) {
    if !std::io::stderr().is_terminal() {
        return;
    }
    stop();
    let (tx, rx) = mpsc::channel::<()>();
    let label = label.to_string();
    let thread = std::thread::spawn(move || {
        if rx.recv_timeout(DELAY) != Err(RecvTimeoutError::Timeout) {
            return;
        }
        let t0 = std::time::Instant::now() - DELAY;
        if lines {
            let mut next = 0u64;
            loop {
                let s = t0.elapsed().as_secs();
                if s >= next {
                    eprint(&format!("{label}: still computing, {s} s"));
                    next = s + 10;
                }
                if rx.recv_timeout(Duration::from_millis(500)) != Err(RecvTimeoutError::Timeout) {
                    return;
                }
            }
        }
        let bar = indicatif::ProgressBar::new_spinner();
        if let Ok(st) = indicatif::ProgressStyle::with_template("{spinner} {msg} {elapsed}") {
            bar.set_style(st);
        }
        bar.set_message(format!("{label}: computing"));
        bar.tick();
        while rx.recv_timeout(Duration::from_millis(120)) == Err(RecvTimeoutError::Timeout) {
            bar.tick();
        }
        bar.finish_and_clear();
    });
    if let Ok(mut g) = SPINNER.lock() {
        *g = Some(Active { stop: tx, thread });
    }
}

/// Clear the spinner (if any) and wait until its line is gone.
pub fn stop() {
    let active = SPINNER.lock().ok().and_then(|mut g| g.take());
    if let Some(a) = active {
        let _ = a.stop.send(());
        let _ = a.thread.join();
    }
}

/// A warning on stderr (one line, `warning: ...`), after clearing the spinner.
pub fn warn(msg: &str) {
    note(&format!("warning: {}", crate::error::one_line(msg)));
}

/// A line on stderr, after clearing the spinner. A stderr that cannot be written (a full
/// device, a closed pipe) is ignored: it is where errors would be reported.
pub fn note(line: &str) {
    stop();
    eprint(line);
}

/// A line on stderr, ignoring failures (`eprintln!` would panic).
pub fn eprint(line: &str) {
    use std::io::Write;
    let _ = writeln!(std::io::stderr(), "{line}");
}
