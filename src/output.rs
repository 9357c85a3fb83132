//! Output helpers: number formatting, CSV rows, files that appear only when complete.

use crate::error::{solve_fail, Res};
use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};

/// Shortest round-trip representation (`1e-10`, `0.5`, `1.0`); non-finite values become an empty
/// field (never `NaN` in a result file).
pub fn num(v: f64) -> String {
    if v.is_finite() {
        // + 0.0 turns -0 into 0; zmij: ~8× fewer instructions than `{:?}` (measured on a scan's
        // CSV, docs/dependencies.md), same round-trip guarantee
        zmij::Buffer::new().format_finite(v + 0.0).to_owned()
    } else {
        String::new()
    }
}

/// Optional number: empty field when absent.
pub fn opt(v: Option<f64>) -> String {
    v.map(num).unwrap_or_default()
}

/// A file written under a temporary name in the same directory and renamed to its final name by
/// [`AtomicFile::commit`]; dropped without commit, the temporary file is removed.
pub struct AtomicFile {
    tmp: PathBuf,
    dest: PathBuf,
    w: Option<BufWriter<File>>,
}

impl AtomicFile {
    /// Create the temporary file next to `dest`.
    pub fn create(dest: &Path) -> Res<AtomicFile> {
        let name = dest
            .file_name()
            .ok_or_else(|| solve_fail(format!("{}: not a file name", dest.display())))?
            .to_string_lossy()
            .into_owned();
        let dir = match dest.parent() {
            Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
            _ => PathBuf::from("."),
        };
        let tmp = dir.join(format!(".{name}.part-{}", std::process::id()));
        let f = File::create(&tmp)
            .map_err(|e| solve_fail(format!("cannot create {}: {e}", dest.display())))?;
        Ok(AtomicFile {
            tmp,
            dest: dest.to_path_buf(),
            w: Some(BufWriter::new(f)),
        })
    }

    /// Flush, sync and rename to the final name.
    pub fn commit(mut self) -> Res<()> {
        if let Some(w) = self.w.take() {
            let f = w
                .into_inner()
                .map_err(|e| solve_fail(format!("writing {}: {e}", self.dest.display())))?;
            f.sync_all()?;
        }
        std::fs::rename(&self.tmp, &self.dest)
            .map_err(|e| solve_fail(format!("cannot rename to {}: {e}", self.dest.display())))?;
        Ok(())
    }
}

impl Write for AtomicFile {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        match &mut self.w {
            Some(w) => w.write(buf),
            None => Err(io::Error::other("file already committed")),
        }
    }
    fn flush(&mut self) -> io::Result<()> {
        match &mut self.w {
            Some(w) => w.flush(),
            None => Ok(()),
        }
    }
}

impl Drop for AtomicFile {
    fn drop(&mut self) {
        if self.w.take().is_some() {
            let _ = std::fs::remove_file(&self.tmp);
        }
    }
}

/// Where a table goes: a file (atomic) or stdout.
pub enum Sink {
    /// standard output, block-buffered (stdout alone is line-buffered: one system call per row)
    Stdout(BufWriter<io::StdoutLock<'static>>),
    /// a file renamed into place on [`Sink::finish`]
    File(AtomicFile),
}

impl Sink {
    /// Open `path`, or stdout when `None`.
    pub fn open(path: Option<&Path>) -> Res<Sink> {
        Ok(match path {
            Some(p) => Sink::File(AtomicFile::create(p)?),
            None => Sink::Stdout(BufWriter::new(io::stdout().lock())),
        })
    }

    /// Complete the output (rename the file into place).
    pub fn finish(self) -> Res<()> {
        match self {
            Sink::Stdout(mut s) => Ok(s.flush()?),
            Sink::File(f) => f.commit(),
        }
    }
}

impl Write for Sink {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        match self {
            Sink::Stdout(s) => s.write(buf),
            Sink::File(f) => f.write(buf),
        }
    }
    fn flush(&mut self) -> io::Result<()> {
        match self {
            Sink::Stdout(s) => s.flush(),
            Sink::File(f) => f.flush(),
        }
    }
}

/// Write one CSV line (fields are numbers or simple names; fields with commas, quotes or line
/// breaks are quoted).
pub fn csv_line<W: Write, S: AsRef<str>>(w: &mut W, fields: &[S]) -> Res<()> {
    let mut line = String::new();
    for (i, f) in fields.iter().enumerate() {
        if i > 0 {
            line.push(',');
        }
        let f = f.as_ref();
        if f.contains([',', '"', '\n', '\r']) {
            line.push('"');
            line.push_str(&f.replace('"', "\"\""));
            line.push('"');
        } else {
            line.push_str(f);
        }
    }
    line.push('\n');
    w.write_all(line.as_bytes())?;
    Ok(())
}
