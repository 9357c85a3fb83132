//! The journal of a sweep written to a file: `FILE.journal` next to `--out FILE` holds what the
//! sweep is (its command line and its base scene) and the rows it has finished, in grid order,
//! each handed to the system as soon as it is written (synced to disk every few seconds). A
//! sweep that is killed (a cluster's time limit sends SIGTERM; Ctrl-C; an I/O error) leaves the
//! journal behind while its output file stays as it was (the output policy of `output_files`); the
//! same command then checks that the journal describes the same sweep, copies its rows and
//! computes only the rest, so the final file is byte-identical to an uninterrupted run. The
//! journal is removed once the output file is in place.
//!
//! Format (text): the line [`MAGIC`], one line `# KEY = "VALUE"` per item of the sweep's identity
//! (the value a JSON string), the line [`ROWS`], then the rows exactly as in the output (CSV, each
//! starting with its grid index). A last line without its line break (the process died while
//! writing it) is dropped when the journal is read.

use crate::error::{solve_fail, usage, Fail, Res};
use std::fs::{File, OpenOptions};
use std::io::{BufRead, BufReader, BufWriter, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// First line of a journal.
pub const MAGIC: &str = "# vibrissa sweep journal 1: the finished rows of a sweep; the same command resumes it, deleting this file starts it over";
/// The line after which the rows start.
pub const ROWS: &str = "# rows";
/// The rows are synced to disk at most this often (a killed process loses nothing written; a
/// crashed machine loses at most the rows of the last interval).
const SYNC_EVERY: Duration = Duration::from_secs(5);

/// What a sweep is: (key, value) pairs that must all be equal for a journal to be resumed.
pub type Identity = Vec<(String, String)>;

/// The journal of the output target `target` (a regular file): `target.journal`.
pub fn path_of(target: &Path) -> PathBuf {
    let mut name = target.file_name().unwrap_or_default().to_os_string();
    name.push(".journal");
    target.with_file_name(name)
}

/// The finished rows found in a journal.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Finished {
    /// rows, the first with index `lo`
    pub rows: u64,
    /// of which rows with an error (a non-empty last column)
    pub failed: u64,
}

/// An existing journal, checked against the sweep's identity, positioned at its first row.
pub struct Found {
    path: PathBuf,
    reader: BufReader<File>,
    /// byte offset of the first row
    offset: u64,
}

/// Open the journal at `path` if there is one, and check that it describes this sweep: every
/// item of `id` must be the same (the message names each one that differs). A file that is not
/// a journal is never touched: it is an error. Nothing is written.
pub fn find(path: &Path, id: &Identity) -> Res<Option<Found>> {
    let file = match File::open(path) {
        Ok(f) => f,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
        Err(e) => return Err(solve_fail(format!("cannot read {}: {e}", path.display()))),
    };
    let show = path.display();
    let read_err = |e: std::io::Error| solve_fail(format!("reading {show}: {e}"));
    let mut reader = BufReader::new(file);
    let mut offset = 0u64;
    let mut line = Vec::new();
    let mut saw: Vec<(String, String)> = Vec::new();
    let mut first = true;
    loop {
        line.clear();
        let n = reader.read_until(b'\n', &mut line).map_err(read_err)?;
        if n == 0 || line.last() != Some(&b'\n') {
            // the header was cut short (the process died while writing it): no row yet
            if first && n > 0 && !MAGIC.as_bytes().starts_with(&line) {
                return Err(not_a_journal(path));
            }
            break;
        }
        offset += n as u64;
        let text = String::from_utf8_lossy(&line[..n - 1]).into_owned();
        if first {
            if text != MAGIC {
                return Err(not_a_journal(path));
            }
            first = false;
            continue;
        }
        if text == ROWS {
            return compare(path, id, &saw).map(|_| {
                Some(Found {
                    path: path.to_path_buf(),
                    reader,
                    offset,
                })
            });
        }
        let item = text
            .strip_prefix("# ")
            .and_then(|t| t.split_once(" = "))
            .and_then(|(k, v)| Some((k.to_string(), serde_json::from_str::<String>(v).ok()?)));
        match item {
            Some(kv) => saw.push(kv),
            None => return Err(damaged(path, "its header", &text)),
        }
    }
    // no row was written: whatever the header says, there is nothing to resume
    compare(path, id, &saw)?;
    Ok(Some(Found {
        path: path.to_path_buf(),
        reader,
        offset: u64::MAX,
    }))
}

fn not_a_journal(path: &Path) -> Fail {
    usage(format!(
        "{} exists but is not a sweep journal (its first line is not the journal's); it is where the sweep keeps its finished rows: move it away",
        path.display()
    ))
}

fn damaged(path: &Path, what: &str, line: &str) -> Fail {
    let mut l: String = line.chars().take(60).collect();
    if l.len() < line.len() {
        l.push_str("...");
    }
    usage(format!(
        "{} is damaged ({what}: {l:?}); delete it to start the sweep over",
        path.display()
    ))
}

/// Every item of `id` against the journal's (items of a header cut short are not there).
fn compare(path: &Path, id: &Identity, saw: &[(String, String)]) -> Res<()> {
    let mut diffs = Vec::new();
    for (k, v) in id {
        if let Some((_, old)) = saw.iter().find(|(j, _)| j == k) {
            if old != v {
                let show = |s: &str| {
                    if s.is_empty() {
                        "not given".to_string()
                    } else {
                        s.to_string()
                    }
                };
                diffs.push(format!("{k} was {}, now {}", show(old), show(v)));
            }
        }
    }
    for (k, _) in saw {
        if !id.iter().any(|(j, _)| j == k) {
            diffs.push(format!("{k} is unknown to this program"));
        }
    }
    if diffs.is_empty() {
        return Ok(());
    }
    Err(usage(format!(
        "{} holds the finished rows of a different sweep ({}); rerun that sweep to resume it, or delete {} to start this one",
        path.display(),
        diffs.join("; "),
        path.display()
    )))
}

impl Found {
    /// Read the rows (indices `lo`, `lo + 1`, ... below `hi`), handing each complete one to
    /// `row`; returns what was found and the length of the journal up to its last complete row.
    pub fn rows(
        &mut self,
        lo: u64,
        hi: u64,
        mut row: impl FnMut(&str) -> Res<()>,
    ) -> Res<(Finished, u64)> {
        let mut f = Finished::default();
        if self.offset == u64::MAX {
            return Ok((f, 0));
        }
        let mut len = self.offset;
        let mut line = Vec::new();
        loop {
            line.clear();
            let n = self
                .reader
                .read_until(b'\n', &mut line)
                .map_err(|e| solve_fail(format!("reading {}: {e}", self.path.display())))?;
            if n == 0 || line.last() != Some(&b'\n') {
                // the end, or the row being written when the process died
                return Ok((f, len));
            }
            let text = String::from_utf8_lossy(&line);
            let want = lo + f.rows;
            let index_ok = text
                .split_once(',')
                .is_some_and(|(i, _)| i.parse::<u64>() == Ok(want));
            if !index_ok || want >= hi {
                let what = format!("row {} should have index {want}", f.rows + 1);
                return Err(damaged(&self.path, &what, text.trim_end()));
            }
            row(&text)?;
            f.rows += 1;
            f.failed += !text.ends_with(",\n") as u64;
            len += n as u64;
        }
    }
}

/// A journal open for appending rows.
pub struct Journal {
    path: PathBuf,
    w: BufWriter<File>,
    synced: Instant,
}

impl Journal {
    /// Continue the journal at `path` after its first `len` bytes (its header and complete rows,
    /// from [`Found::rows`]), or start a new one with the header of `id` when `len` is 0.
    pub fn open(path: &Path, id: &Identity, len: u64) -> Res<Journal> {
        let fail = |e: std::io::Error| solve_fail(format!("writing {}: {e}", path.display()));
        let mut file = OpenOptions::new()
            .write(true)
            .create(true)
            .truncate(false)
            .open(path)
            .map_err(fail)?;
        // drop a row cut short, or a header without rows
        file.set_len(len).map_err(fail)?;
        file.seek(SeekFrom::End(0)).map_err(fail)?;
        let mut j = Journal {
            path: path.to_path_buf(),
            w: BufWriter::new(file),
            synced: Instant::now(),
        };
        if len == 0 {
            let mut head = format!("{MAGIC}\n");
            for (k, v) in id {
                // a JSON string: one line whatever the value
                let v = serde_json::to_string(v).unwrap_or_default();
                head.push_str(&format!("# {k} = {v}\n"));
            }
            head.push_str(ROWS);
            head.push('\n');
            j.w.write_all(head.as_bytes()).map_err(fail)?;
            j.w.flush().map_err(fail)?;
            j.w.get_ref().sync_all().map_err(fail)?;
        }
        Ok(j)
    }

    /// Append one finished row (a CSV line with its line break) and hand it to the system.
    pub fn append(&mut self, row: &str) -> std::io::Result<()> {
        self.w.write_all(row.as_bytes())?;
        self.w.flush()?;
        if self.synced.elapsed() >= SYNC_EVERY {
            self.w.get_ref().sync_data()?;
            self.synced = Instant::now();
        }
        Ok(())
    }

    /// Where it is.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Sync it (the sweep is complete); it is removed once the output is in place.
    pub fn close(mut self) -> Res<()> {
        let fail = |e: std::io::Error| solve_fail(format!("writing {}: {e}", self.path.display()));
        self.w.flush().map_err(fail)?;
        self.w.get_ref().sync_data().map_err(fail)?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn id(eta: &str) -> Identity {
        vec![
            ("--eta".to_string(), eta.to_string()),
            ("--timing".to_string(), String::new()),
        ]
    }

    fn dir(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("journal-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    fn read(p: &Path, id: &Identity, lo: u64, hi: u64) -> Res<Option<(Finished, u64, String)>> {
        let Some(mut found) = find(p, id)? else {
            return Ok(None);
        };
        let mut text = String::new();
        let (f, len) = found.rows(lo, hi, |r| {
            text.push_str(r);
            Ok(())
        })?;
        Ok(Some((f, len, text)))
    }

    #[test]
    fn rows_survive_and_a_cut_row_is_dropped() {
        let d = dir("rows");
        let p = d.join("out.csv.journal");
        assert_eq!(path_of(&d.join("out.csv")), p);
        assert!(read(&p, &id("0.7"), 5, 9).unwrap().is_none());
        let mut j = Journal::open(&p, &id("0.7"), 0).unwrap();
        j.append("5,0.7,x,\n").unwrap();
        j.append("6,0.7,y,\"an error\"\n").unwrap();
        drop(j);
        // a row cut short by a kill
        let mut f = OpenOptions::new().append(true).open(&p).unwrap();
        f.write_all(b"7,0.7,z").unwrap();
        let (f, len, text) = read(&p, &id("0.7"), 5, 9).unwrap().unwrap();
        assert_eq!(f, Finished { rows: 2, failed: 1 });
        assert_eq!(text, "5,0.7,x,\n6,0.7,y,\"an error\"\n");
        // continuing drops the cut row
        let mut j = Journal::open(&p, &id("0.7"), len).unwrap();
        j.append("7,0.7,z,\n").unwrap();
        j.close().unwrap();
        let (f, _, text) = read(&p, &id("0.7"), 5, 9).unwrap().unwrap();
        assert_eq!(f.rows, 3);
        assert!(text.ends_with("6,0.7,y,\"an error\"\n7,0.7,z,\n"), "{text}");
    }

    #[test]
    fn another_sweep_or_another_file_is_refused() {
        let d = dir("refuse");
        let p = d.join("j");
        Journal::open(&p, &id("0.6:0.9:5"), 0).unwrap();
        let e = read(&p, &id("0.6:0.9:4"), 0, 5).err().unwrap().message();
        assert!(
            e.contains("--eta was 0.6:0.9:5, now 0.6:0.9:4") && e.contains("delete"),
            "{e}"
        );
        // a row with the wrong index
        let mut j = Journal::open(&p, &id("0.6:0.9:5"), 0).unwrap();
        j.append("0,a,\n").unwrap();
        j.append("2,b,\n").unwrap();
        drop(j);
        let e = read(&p, &id("0.6:0.9:5"), 0, 5).err().unwrap().message();
        assert!(e.contains("damaged") && e.contains("index 1"), "{e}");
        // rows beyond the shard
        let e = read(&p, &id("0.6:0.9:5"), 0, 1).err().unwrap().message();
        assert!(e.contains("damaged"), "{e}");
        // not a journal: never touched
        std::fs::write(&p, "index,eta\n0,0.7\n").unwrap();
        let e = read(&p, &id("0.7"), 0, 5).err().unwrap().message();
        assert!(e.contains("not a sweep journal"), "{e}");
        // empty, or a header cut short: nothing to resume, and it may be rewritten
        for cut in [0, 10, MAGIC.len() + 5] {
            let full = format!("{MAGIC}\n# --eta = \"0.7\"\n");
            std::fs::write(&p, &full[..cut]).unwrap();
            let (f, len, _) = read(&p, &id("0.7"), 0, 5).unwrap().unwrap();
            assert_eq!((f.rows, len), (0, 0), "cut at {cut}");
        }
    }
}
