//! The output policy, one for every command.
//!
//! - Every output file of a command is written to a temporary file next to its target and
//!   renamed into place only when the whole command has succeeded ([`commit_all`], called by
//!   `main` after the command returned); on any error, panic, SIGINT, SIGTERM or SIGHUP the
//!   temporaries are removed ([`abort_all`]) and no existing file has changed.
//! - Two outputs with the same target (after following symbolic links and canonicalizing the
//!   directory) are an error before any work.
//! - A symbolic link is written through: the link stays, its target is replaced.
//! - Device nodes, FIFOs and sockets (`/dev/null`, `/dev/stdout`, a named pipe) are written in
//!   place, without a temporary; `-` is stdout.
//! - Temporary names are short (`.NAME.PID.N.part` with NAME cut to 100 bytes), so any legal
//!   target name works.
//! - Every I/O error names the user's flag and path and the operation.
//! - One file outlives a failure on purpose: the journal of `sweep --out FILE` (`journal`), kept
//!   on error and on a signal, removed after the commit ([`remove_after_commit`]).

use crate::error::{solve_fail, usage, Res};
use std::fs::{File, OpenOptions};
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Mutex, Once};

/// How an output is written.
#[derive(Debug)]
enum Kind {
    /// a temporary renamed onto `target` at commit
    Temp { tmp: PathBuf, target: PathBuf },
    /// written in place (device, FIFO, socket)
    InPlace,
}

#[derive(Debug)]
struct Slot {
    /// the flag and the path as the user typed them, for messages
    label: String,
    /// the path as given (lookup key of [`open`])
    given: PathBuf,
    /// the canonical target (duplicate detection)
    canon: PathBuf,
    kind: Kind,
    /// until a writer takes it
    file: Option<File>,
    /// written completely ([`Out::finish`])
    ready: bool,
}

static SLOTS: Mutex<Vec<Slot>> = Mutex::new(Vec::new());
/// Files to remove once every output is in place (a sweep's journal).
static AFTER_COMMIT: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());
/// A line for stderr when a signal ends the process (where a sweep's finished rows are kept).
static SIGNAL_NOTE: Mutex<Option<String>> = Mutex::new(None);
static COUNTER: AtomicU64 = AtomicU64::new(0);
static SIGNALS: Once = Once::new();

fn slots() -> std::sync::MutexGuard<'static, Vec<Slot>> {
    // a panic while holding the lock leaves the list usable
    SLOTS.lock().unwrap_or_else(|p| p.into_inner())
}

fn label(flag: &str, path: &Path) -> String {
    if flag.is_empty() {
        path.display().to_string()
    } else {
        format!("{flag} {}", path.display())
    }
}

/// The target after following symbolic links, and whether it is a special file (device, FIFO,
/// socket: written in place through the path as given, which also serves `/dev/stderr`, whose
/// link names no file).
fn resolve(lab: &str, path: &Path) -> Res<(PathBuf, bool)> {
    if path.as_os_str().is_empty() {
        return Err(usage(format!("{lab}: an empty file name")));
    }
    match std::fs::metadata(path) {
        Ok(m) if m.is_dir() => Err(usage(format!("{lab} is a directory; give a file name"))),
        Ok(m) if !m.is_file() => Ok((path.to_path_buf(), true)),
        Ok(_) => std::fs::canonicalize(path)
            .map(|p| (p, false))
            .map_err(|e| solve_fail(format!("cannot resolve {lab}: {e}"))),
        Err(e) if e.kind() == io::ErrorKind::NotFound => {
            // a new file, or a link to one: follow the links by hand (up to 40)
            let mut p = path.to_path_buf();
            for _ in 0..40 {
                match std::fs::symlink_metadata(&p) {
                    Ok(m) if m.file_type().is_symlink() => {
                        let t = std::fs::read_link(&p)
                            .map_err(|e| solve_fail(format!("cannot read the link {lab}: {e}")))?;
                        p = match p.parent() {
                            Some(dir) if !t.is_absolute() => dir.join(t),
                            _ => t,
                        };
                    }
                    _ => return Ok((p, false)),
                }
            }
            Err(usage(format!("{lab}: too many levels of symbolic links")))
        }
        Err(e) => Err(solve_fail(format!("cannot write {lab}: {e}"))),
    }
}

/// Directory and file name of a (resolved) target, the directory canonicalized.
fn split(lab: &str, p: &Path) -> Res<(PathBuf, std::ffi::OsString)> {
    let name = match p.file_name() {
        Some(n) if !p.as_os_str().to_string_lossy().ends_with('/') => n.to_os_string(),
        _ => return Err(usage(format!("{lab} is not a file name"))),
    };
    let dir = match p.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let dir = std::fs::canonicalize(&dir).map_err(|e| {
        solve_fail(format!(
            "cannot write {lab}: directory {}: {e}",
            dir.display()
        ))
    })?;
    Ok((dir, name))
}

/// A short temporary name next to the target: `.NAME.PID.N.part`, NAME cut to 100 bytes at a
/// character boundary (names may be up to NAME_MAX = 255 bytes).
fn temp_name(name: &std::ffi::OsStr) -> String {
    let s = name.to_string_lossy();
    let mut cut = s.len().min(100);
    while !s.is_char_boundary(cut) {
        cut -= 1;
    }
    format!(
        ".{}.{}.{}.part",
        &s[..cut],
        std::process::id(),
        COUNTER.fetch_add(1, Ordering::Relaxed)
    )
}

/// The file a regular-file output ends up in (links followed, the directory canonical, as
/// [`plan`] resolves it); `None` for devices, FIFOs and sockets, which are written in place.
pub fn file_target(flag: &str, path: &Path) -> Res<Option<PathBuf>> {
    let lab = label(flag, path);
    let (target, special) = resolve(&lab, path)?;
    if special {
        return Ok(None);
    }
    let (dir, name) = split(&lab, &target)?;
    Ok(Some(dir.join(name)))
}

/// Remove `path` once every output of the command is in place ([`commit_all`] succeeded); on
/// failure or a signal it stays.
pub fn remove_after_commit(path: PathBuf) {
    AFTER_COMMIT
        .lock()
        .unwrap_or_else(|p| p.into_inner())
        .push(path);
}

/// Print `line` on stderr if a signal ends the process (after the temporaries are removed).
pub fn note_on_signal(line: String) {
    *SIGNAL_NOTE.lock().unwrap_or_else(|p| p.into_inner()) = Some(line);
}

/// Plan the outputs of a command before any work: resolve each, refuse duplicates, and (unless
/// `check_only`) create the temporaries and open the special files. On error nothing is left.
pub fn plan(outs: &[(&str, &Path)], check_only: bool) -> Res<()> {
    let mut planned: Vec<Slot> = Vec::new();
    {
        let existing = slots();
        for &(flag, path) in outs {
            let lab = label(flag, path);
            let (target, special) = resolve(&lab, path)?;
            let canon = if special {
                std::fs::canonicalize(&target).unwrap_or(target.clone())
            } else {
                let (dir, name) = split(&lab, &target)?;
                dir.join(name)
            };
            if let Some(other) = planned
                .iter()
                .chain(existing.iter())
                .find(|s| s.canon == canon)
            {
                return Err(usage(format!(
                    "{lab} and {} are the same file ({}); each output needs its own file",
                    other.label,
                    canon.display()
                )));
            }
            planned.push(Slot {
                label: lab,
                given: path.to_path_buf(),
                canon,
                kind: if special {
                    Kind::InPlace
                } else {
                    Kind::Temp {
                        tmp: PathBuf::new(),
                        target,
                    }
                },
                file: None,
                ready: false,
            });
        }
    }
    if check_only {
        return Ok(());
    }
    for s in planned {
        create(s)?;
    }
    Ok(())
}

/// Create the temporary (or open the special file) of a planned slot and register it.
fn create(mut s: Slot) -> Res<()> {
    let mut reg = slots();
    match &mut s.kind {
        Kind::InPlace => {
            let f = OpenOptions::new()
                .write(true)
                .open(&s.canon)
                .map_err(|e| solve_fail(format!("cannot open {} for writing: {e}", s.label)))?;
            s.file = Some(f);
        }
        Kind::Temp { tmp, target } => {
            install_signal_cleanup();
            let dir = s.canon.parent().unwrap_or(Path::new(".")).to_path_buf();
            let name = s.canon.file_name().unwrap_or_default().to_os_string();
            let mut o = OpenOptions::new();
            o.write(true).create_new(true);
            #[cfg(unix)]
            {
                use std::os::unix::fs::{OpenOptionsExt, PermissionsExt};
                // a replaced file keeps its permissions
                let mode = std::fs::metadata(&*target).map_or(0o666, |m| m.permissions().mode());
                o.mode(mode & 0o7777);
            }
            let _ = target;
            let t = dir.join(temp_name(&name));
            let f = o.open(&t).map_err(|e| {
                solve_fail(format!(
                    "cannot create a temporary file in {} for {}: {e}",
                    dir.display(),
                    s.label
                ))
            })?;
            *tmp = t;
            s.file = Some(f);
        }
    }
    reg.push(s);
    Ok(())
}

/// A file being written: buffered, errors name the output; [`Out::finish`] marks it complete.
pub struct Out {
    w: BufWriter<File>,
    label: String,
    temp: bool,
    canon: PathBuf,
}

/// The writer of the output `path`: planned by [`plan`], or planned now (outputs a command
/// discovers as it goes, e.g. the files of `figures`).
pub fn open(path: &Path) -> Res<Out> {
    let find = |reg: &mut Vec<Slot>| {
        reg.iter_mut()
            .find(|s| s.given == path && s.file.is_some())
            .map(|s| {
                (
                    s.file.take(),
                    s.label.clone(),
                    matches!(s.kind, Kind::Temp { .. }),
                    s.canon.clone(),
                )
            })
    };
    let mut got = find(&mut slots());
    if got.is_none() {
        plan(&[("", path)], false)?;
        got = find(&mut slots());
    }
    match got {
        Some((Some(f), label, temp, canon)) => Ok(Out {
            w: BufWriter::with_capacity(64 * 1024, f),
            label,
            temp,
            canon,
        }),
        _ => Err(solve_fail(format!(
            "internal error: output {} is not open",
            path.display()
        ))),
    }
}

impl Out {
    /// Open `path` (see [`open`]).
    pub fn create(path: &Path) -> Res<Out> {
        open(path)
    }

    /// Flush and sync; the file is renamed into place when the whole command succeeded.
    pub fn finish(mut self) -> Res<()> {
        self.w
            .flush()
            .map_err(|e| solve_fail(format!("writing {}: {e}", self.label)))?;
        if self.temp {
            self.w
                .get_ref()
                .sync_all()
                .map_err(|e| solve_fail(format!("writing {} (sync): {e}", self.label)))?;
        }
        if let Some(s) = slots().iter_mut().find(|s| s.canon == self.canon) {
            s.ready = true;
        }
        Ok(())
    }

    /// Same as [`Out::finish`] (the name the figure code uses).
    pub fn commit(self) -> Res<()> {
        self.finish()
    }
}

/// An I/O error that names what was being written (the kind is kept: a broken pipe stays one).
pub fn named(label: &str, e: io::Error) -> io::Error {
    io::Error::new(e.kind(), format!("writing {label}: {e}"))
}

impl Write for Out {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        self.w.write(buf).map_err(|e| named(&self.label, e))
    }
    fn write_all(&mut self, buf: &[u8]) -> io::Result<()> {
        self.w.write_all(buf).map_err(|e| named(&self.label, e))
    }
    fn flush(&mut self) -> io::Result<()> {
        self.w.flush().map_err(|e| named(&self.label, e))
    }
}

/// Rename every completed temporary onto its target (the command succeeded); temporaries of
/// outputs that were never completed are removed. The first failure is reported (naming the
/// output) after the remaining temporaries are removed.
pub fn commit_all() -> Res<()> {
    let mut reg = slots();
    let mut first_err = None;
    for s in reg.drain(..) {
        drop(s.file);
        if let Kind::Temp { tmp, target } = s.kind {
            if s.ready && first_err.is_none() {
                if let Err(e) = std::fs::rename(&tmp, &target) {
                    let _ = std::fs::remove_file(&tmp);
                    first_err = Some(solve_fail(format!(
                        "cannot put {} in place (rename from {}): {e}",
                        s.label,
                        tmp.display()
                    )));
                }
            } else {
                let _ = std::fs::remove_file(&tmp);
            }
        }
    }
    let after: Vec<PathBuf> = AFTER_COMMIT
        .lock()
        .unwrap_or_else(|p| p.into_inner())
        .drain(..)
        .collect();
    if first_err.is_none() {
        for p in after {
            if let Err(e) = std::fs::remove_file(&p) {
                crate::progress::warn(&format!("cannot remove {}: {e}", p.display()));
            }
        }
    }
    first_err.map_or(Ok(()), Err)
}

/// Remove every temporary; no target is touched.
pub fn abort_all() {
    let mut reg = slots();
    for s in reg.drain(..) {
        if let Kind::Temp { tmp, .. } = &s.kind {
            let _ = std::fs::remove_file(tmp);
        }
    }
}

/// On SIGINT, SIGTERM and SIGHUP: remove the temporaries, then die of the signal as the
/// default action would (a shell sees 130 for Ctrl-C). Installed with the first temporary.
fn install_signal_cleanup() {
    SIGNALS.call_once(|| {
        use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
        let Ok(mut sigs) = signal_hook::iterator::Signals::new([SIGINT, SIGTERM, SIGHUP]) else {
            return;
        };
        std::thread::spawn(move || {
            if let Some(sig) = sigs.forever().next() {
                abort_all();
                let note = SIGNAL_NOTE.try_lock().ok().and_then(|n| n.clone());
                if let Some(n) = note {
                    crate::progress::eprint(&n);
                }
                crate::progress::stop();
                let _ = signal_hook::low_level::emulate_default_handler(sig);
                std::process::exit(128 + sig);
            }
        });
    });
}

/// [`abort_all`] unless the list is locked (from a panic hook: the panicking thread may hold it).
pub fn abort_if_free() {
    if let Ok(mut reg) = SLOTS.try_lock() {
        for s in reg.drain(..) {
            if let Kind::Temp { tmp, .. } = &s.kind {
                let _ = std::fs::remove_file(tmp);
            }
        }
    }
}
