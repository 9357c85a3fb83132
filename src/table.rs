//! Output helpers: number formatting, CSV rows, the table sink (stdout or a file of the output
//! policy in `output_files`).

use crate::error::Res;
use crate::output_files::{self, Out};
use std::io::{self, BufWriter, Write};
use std::path::Path;

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

/// A file output of the program, written by the output policy (see `output_files`): a temporary
/// renamed into place when the whole command succeeded, or a device written in place.
pub type AtomicFile = Out;

/// Where a table goes: a file (see `output_files`) or stdout.
pub enum Sink {
    /// standard output, block-buffered (stdout alone is line-buffered: one system call per row)
    Stdout(BufWriter<io::StdoutLock<'static>>),
    /// a file
    File(Out),
}

impl Sink {
    /// Open `path`, or stdout when `None` or `-` (clears the progress spinner first).
    pub fn open(path: Option<&Path>) -> Res<Sink> {
        Ok(match path {
            Some(p) if p.as_os_str() != "-" => Sink::File(output_files::open(p)?),
            _ => {
                crate::progress::stop();
                Sink::Stdout(BufWriter::with_capacity(64 * 1024, io::stdout().lock()))
            }
        })
    }

    /// Complete the output (the file is renamed into place when the command succeeded).
    pub fn finish(self) -> Res<()> {
        match self {
            Sink::Stdout(mut s) => Ok(s.flush().map_err(|e| output_files::named("stdout", e))?),
            Sink::File(f) => f.finish(),
        }
    }
}

/// Writes a table (its header, then a row per item) to `path` or stdout (see [`Sink::open`]).
pub fn write_table<T>(
    path: Option<&Path>,
    header: &[&str],
    items: &[T],
    row: impl Fn(&T) -> Vec<String>,
) -> Res<()> {
    let mut sink = Sink::open(path)?;
    csv_line(&mut sink, header)?;
    for p in items {
        csv_line(&mut sink, &row(p))?;
    }
    sink.finish()
}

impl Write for Sink {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        match self {
            Sink::Stdout(s) => s.write(buf).map_err(|e| output_files::named("stdout", e)),
            Sink::File(f) => f.write(buf),
        }
    }
    fn write_all(&mut self, buf: &[u8]) -> io::Result<()> {
        match self {
            Sink::Stdout(s) => s
                .write_all(buf)
                .map_err(|e| output_files::named("stdout", e)),
            Sink::File(f) => f.write_all(buf),
        }
    }
    fn flush(&mut self) -> io::Result<()> {
        match self {
            Sink::Stdout(s) => s.flush().map_err(|e| output_files::named("stdout", e)),
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
